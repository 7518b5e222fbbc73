#!/usr/bin/python3
"""scripts/validation_report.py on GoogleTest JSON made here, whose answers are known by
construction: a loop's checks are one row of its table (a parameterised test's too), the paper
comparison holds the study's numbers and shows a known disagreement as one, never as a pass, and
fails it when the study's value comes inside fogradar's band; a subnormal reference (a stand-in
for "above 0") is refused; the plots' legends lie outside their axes, and an axis of one value is
padded to a visible span (the paper comparison's abscissa is the study's 0-4 layers).

Usage: test_validation_report.py SOURCE_DIR"""
import importlib.util
import json
import os
import re
import subprocess
import sys
import tempfile

SOURCE = sys.argv[1]
SCRIPT = os.path.join(SOURCE, "scripts", "validation_report.py")


def load_report():
    spec = importlib.util.spec_from_file_location("validation_report", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def check(id_, **fields):
    record = {"id": id_, "group": "radar: signal processing", "quantity": "DFT bin", "unit": "1",
              "conditions": id_, "reference": 0.0, "source": "closed form", "value": 0.0,
              "tolerance": 1e-12, "tolerance_kind": "absolute", "pass": True}
    record.update(fields)
    return record


def gtest_json(path, tests):
    """tests: {"Suite.Name": [check, ...]}, as GoogleTest's JSON output carries them."""
    suites = {}
    for name, checks in tests.items():
        suite, case = name.split(".", 1)  # "Instance/Suite" and "Test/param" for TEST_P
        entry = {"name": case}
        entry.update({f"validation:{c['id']}": json.dumps(c) for c in checks})
        suites.setdefault(suite, []).append(entry)
    with open(path, "w", encoding="utf-8") as f:
        json.dump({"testsuites": [{"name": s, "testsuite": cases} for s, cases in
                                  suites.items()]}, f)


def disagreement(reference, low, high):
    return check("paper.radar.fig4.mean_rcs", group="paper comparison",
                 quantity="EVT's mean RCS at 0 layers", unit="dBsm", reference=reference,
                 value=(low + high) / 2, tolerance=0.0, tolerance_kind="disagreement",
                 samples=64, interval=[low, high], confidence="the setups' 5-95 % band",
                 source="the study's Fig. 4", plot="paper_comparison", x=0.0,
                 x_label="active fog layers",
                 **{"pass": not low <= reference <= high})


def run(tests):
    with tempfile.TemporaryDirectory() as out:
        path = os.path.join(out, "gtest_test_x.json")
        gtest_json(path, tests)
        done = subprocess.run([sys.executable, SCRIPT, out, path], capture_output=True,
                              text=True)
        with open(os.path.join(out, "validation.html"), encoding="utf-8") as f:
            return done.returncode, done.stdout, f.read()


def table_rows(page, group):
    section = page[page.index(f'<h2 id="{group}">'):]
    section = section[:section.index("</table>\n")]
    section = re.sub(r"<details>.*?</details>", "", section, flags=re.S)  # a short loop's cases
    return re.findall(r"<tr class=\"([^\"]*)\"[^>]*>(.*?)</tr>", section)


def test_a_loop_is_one_row():
    loop = [check(f"radar.window.hann.dft_bin.k{k}", value=1e-14 * k) for k in range(30)]
    parameterised = {f"Windows/Shape.IsSymmetric/{w}": [check(f"radar.window.{w}.symmetry",
                                                               quantity="w[j] - w[N-1-j]")]
                     for w in ("hann", "hamming", "blackman")}
    status, stdout, page = run({"Window.HannDft": loop, **parameterised})
    assert status == 0, stdout
    rows = [r for r in table_rows(page, "radar: signal processing") if r[0] != "cases"]
    assert len(rows) == 2, rows
    first = rows[0][1] if "dft_bin" in rows[0][1] else rows[1][1]
    assert "radar.window.hann.dft_bin.* (30 checks)" in first, first
    # The worst case is shown: k = 29, value 2.9e-13.
    assert "2.9e-13" in first and "pass, 30 of 30" in first, first
    # The thirty cases are in validation.json; the page names the worst alone (its conditions).
    assert page.count("radar.window.hann.dft_bin.k") == 1
    assert "33 checks against independent references in 2 rows" in page, page[:2000]
    assert "3 checks" in [r for r in rows if "symmetry" in r[1]][0][1]


def test_a_known_disagreement_is_shown_as_one():
    agree = check("lidar.paper.fig6.sensor_limit", group="paper comparison",
                  quantity="lidar sensor limit", unit="layers", reference=1.0, value=1.0,
                  tolerance=0.0, source="the study's Fig. 6", plot="paper_comparison", x=1.0,
                  x_label="active fog layers")
    status, stdout, page = run({"Paper.Radar": [disagreement(14.97, 5.64, 12.75)],
                                "Paper.Lidar": [agree]})
    assert status == 0, stdout
    assert "1 known disagreement with published values" in stdout, stdout
    classes = [r[0] for r in table_rows(page, "paper comparison")]
    assert sorted(classes) == ["disagree", "pass"], classes
    radar = [r[1] for r in table_rows(page, "paper comparison") if r[0] == "disagree"][0]
    assert "known disagreement" in radar and ">pass<" not in radar, radar
    assert "outside fogradar's band [5.64, 12.75]" in radar, radar
    assert "the study's value lies 2.22 dB above fogradar's band" in page
    assert "1 known disagreement with published values" in page
    # The paper comparison is the first section.
    assert page.index("<h2 id=") == page.index('<h2 id="paper comparison">')


def test_a_disagreement_that_no_longer_holds_fails():
    status, stdout, page = run({"Paper.Radar": [disagreement(10.0, 5.64, 12.75)]})
    assert status == 1, stdout
    assert "failing: paper.radar.fig4.mean_rcs" in stdout, stdout
    assert "now lies inside fogradar's band" in page


def test_a_subnormal_reference_is_refused():
    tiny = check("lidar.paper.intensity", reference=5e-324, tolerance_kind="at_least",
                 tolerance=0.0, value=571.0)
    status, stdout, _ = run({"Lidar.Intensity": [tiny]})
    assert status == 1 and "subnormal reference" in stdout, stdout
    above = check("lidar.paper.intensity", reference=0.0, tolerance_kind="above",
                  tolerance=0.0, value=571.0)
    status, stdout, page = run({"Lidar.Intensity": [above]})
    assert status == 0, stdout
    assert "&gt; ref." in page or "> ref." in page


def overlaps(a, b):
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_plots_keep_legends_off_the_data_and_axes_open():
    report = load_report()
    # Agg lays the figure out as the SVG does and gives the extents of what it drew.
    report.plt.switch_backend("agg")
    one_point = [check("camera.paper.mean_grey.2layers", group="paper comparison",
                       quantity="mean grey value", unit="grey level", reference=64.0,
                       value=63.93, tolerance=1.5, source="the study's Fig. 7",
                       plot="paper_comparison", x=2.0, x_label="active fog layers"),
                 disagreement(14.97, 5.64, 12.75)]
    curve = [check(f"p840.k{f}", quantity="K_l", unit="dB/km", reference=0.1 * f,
                   value=0.1 * f, plot="p840_frequency", x=float(f), x_label="GHz",
                   tolerance_kind="relative", tolerance=0.01) for f in (10, 35, 77, 94)]
    single = [check("swerling.pd.10dB", quantity="P_d", reference=0.5, value=0.5,
                    plot="swerling0_pd", x=10.0, x_label="SNR (dB)")]
    for name, checks in (("paper_comparison", one_point), ("p840_frequency", curve),
                         ("swerling0_pd", single)):
        figure = report.plot_figure(name, checks)
        figure.canvas.draw()
        renderer = figure.canvas.get_renderer()
        for axes in figure.axes:
            legend = axes.get_legend()
            assert legend is not None, name
            assert not overlaps(legend.get_window_extent(renderer),
                                axes.get_window_extent(renderer)), name
            for low, high in (axes.get_xlim(), axes.get_ylim()):
                assert high - low > 1e-6 * max(abs(low), abs(high), 1.0), (name, low, high)
        if name == "paper_comparison":
            # Every panel shows the study's steps, 0 to 4 layers.
            for axes in figure.axes:
                low, high = axes.get_xlim()
                assert low < 0 and high > 4, (low, high)
        if name == "swerling0_pd":
            low, high = figure.axes[0].get_ylim()
            assert high - low >= 0.09, (low, high)  # ±10 % of 0.5


def main():
    tests = [value for key, value in globals().items() if key.startswith("test_")]
    for test in tests:
        test()
        print(f"PASS {test.__name__}")


if __name__ == "__main__":
    main()
