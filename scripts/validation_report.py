#!/usr/bin/python3
"""The validation report (docs/validation.md) from GoogleTest's JSON output: every check a test
recorded through tests/support/validation.hpp ("validation:<id>" properties) into validation.json
(one object per check, with the suite and test that made it) and validation.html (one
self-contained page: a table per group, reference against value against tolerance, and the plots
the checks name, drawn inline as SVG by matplotlib).

Usage: validation_report.py OUT_DIR GTEST_JSON...
Exit status 1 when a check fails, a test failed or no check was found."""
import datetime
import html
import io
import json
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402

matplotlib.rcParams.update({"svg.fonttype": "path", "font.size": 10, "svg.hashsalt": "fogradar"})

GROUP_ORDER = ["physics: water", "physics: droplets", "physics: fog", "physics: chamber",
               "radar: SNR", "radar: CFAR", "radar: detection", "radar: RCS", "radar: Doppler",
               "radar: signal processing", "lidar", "camera", "experiment: paper comparison",
               "experiment: geometry and Doppler", "experiment: statistics"]
COLUMNS = ('<colgroup><col class="id"><col class="q"><col class="c"><col class="r">'
           '<col class="s"><col class="v"><col class="t"><col class="p"></colgroup>')
PLOTS = {
    "p840_frequency": ("Water's specific attenuation against frequency: ITU-R P.840 and fogradar",
                       "log", "log"),
    "p840_temperature": ("Water's specific attenuation against temperature: ITU-R P.840 and "
                         "fogradar", "linear", "linear"),
    "mie_miev0": ("Mie efficiencies: Wiscombe's MIEV0 cases and fogradar", "log", "linear"),
    "cfar_pfa": ("CFAR false-alarm probability: realised against design", "log", "log"),
    "swerling0_pd": ("Detection probability, Swerling 0: closed form and fogradar", "linear",
                     "linear"),
    "swerling1_pd": ("Detection probability, Swerling 1: closed form and fogradar", "linear",
                     "linear"),
    "paper_comparison": ("The paper scenario against the study's published numbers", "linear",
                         "linear"),
}


def read_checks(paths):
    checks, tests, failed_tests = [], 0, []
    for path in paths:
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
        for suite in report.get("testsuites", []):
            for case in suite.get("testsuite", []):
                tests += 1
                name = f"{suite['name']}.{case['name']}"
                if case.get("failures"):
                    failed_tests.append(name)
                for key, value in case.items():
                    if key.startswith("validation:"):
                        check = json.loads(value)
                        check["test"] = name
                        check["binary"] = os.path.basename(path)
                        checks.append(check)
    return checks, tests, failed_tests


def number(value, digits=6):
    if value is None:
        return "—"
    if value == 0 or (1e-3 <= abs(value) < 1e6):
        return f"{value:.{digits}g}"
    return f"{value:.{digits - 1}e}"


def tolerance_text(check):
    kind = check["tolerance_kind"]
    if kind == "statistical":
        low, high = check.get("interval", [None, None])
        return (f"in [{number(low)}, {number(high)}] ({html.escape(check.get('confidence', ''))}"
                f", n = {check.get('samples', 0)})")
    symbol = {"relative": "± rel.", "absolute": "±", "at_most": "≤ ref. +",
              "at_least": "≥ ref. −"}
    return f"{symbol[kind]} {number(check['tolerance'], 3)}"


def svg_of(figure):
    buffer = io.StringIO()
    figure.savefig(buffer, format="svg", bbox_inches="tight", metadata={"Date": None})
    plt.close(figure)
    text = buffer.getvalue()
    return text[text.index("<svg"):]


def plot(name, checks):
    """The checks of one plot against their abscissa (bounds only in the tables): the reference
    as squares on a line (or bars where several share an x), fogradar's values as circles,
    statistical intervals as whiskers, failures as red crosses; one panel per quantity where the
    quantities differ (the paper comparison)."""
    title, x_scale, y_scale = PLOTS.get(name, (name, "linear", "linear"))
    series = {}
    for c in checks:
        if c.get("x") is None or c["value"] is None or c["reference"] is None or \
                c["tolerance_kind"] in ("at_most", "at_least"):
            continue  # a bound is a row of its table, not a point on a curve
        series.setdefault((c["quantity"], c["unit"]), []).append(c)
    panels = [[key] for key in sorted(series)] if name == "paper_comparison" else [sorted(series)]
    if not panels or not panels[0]:
        return ""
    figure, axes_list = plt.subplots(len(panels), 1, figsize=(12.0, 1.0 + 3.4 * len(panels)),
                                     squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for axes, keys in zip(axes_list[:, 0], panels):
        members_all = []
        for i, key in enumerate(keys):
            quantity, unit = key
            members = sorted(series[key], key=lambda c: c["x"])
            members_all += members
            colour = colours[i % len(colours)]
            xs = [c["x"] for c in members]
            label = quantity if unit in ("", "1") else f"{quantity} ({unit})"
            unique = len(set(xs)) == len(xs)
            axes.plot(xs, [c["reference"] for c in members], "-s" if unique else "_",
                      color=colour, alpha=0.45, linewidth=2.0, markersize=6 if unique else 14,
                      label=f"{label}: reference")
            axes.plot(xs, [c["value"] for c in members], "o", color=colour, markersize=4.5,
                      markerfacecolor="none", label=f"{label}: fogradar")
            for c in members:
                if c["tolerance_kind"] == "statistical" and c.get("interval"):
                    low, high = c["interval"]
                    if low is not None and high is not None:
                        axes.plot([c["x"], c["x"]], [low, high], "-", color=colour,
                                  linewidth=0.8)
                if not c["pass"]:
                    axes.plot([c["x"]], [c["value"]], "x", color="#c00000", markersize=10,
                              markeredgewidth=2)
        positive = all(v > 0 for c in members_all for v in (c["x"], c["value"], c["reference"]))
        axes.set_xscale(x_scale if positive else "linear")
        axes.set_yscale(y_scale if positive else "linear")
        axes.set_xlabel(checks[0].get("x_label", "") or "x")
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize=8, loc="best")
    axes_list[0, 0].set_title(title)
    figure.tight_layout()
    return svg_of(figure)


def margin_used(c):
    """How much of its tolerance a check uses (1: on the limit)."""
    if c["value"] is None or c["reference"] is None:
        return math.inf
    error = abs(c["value"] - c["reference"])
    kind, tolerance = c["tolerance_kind"], c["tolerance"]
    if kind == "relative":
        allowed = tolerance * abs(c["reference"])
    elif kind == "statistical":
        low, high = c.get("interval") or [None, None]
        if low is None or high is None or high <= low:
            return 0.0
        return abs(c["value"] - (low + high) / 2) / ((high - low) / 2)
    elif kind in ("at_most", "at_least"):
        allowed = tolerance if tolerance > 0 else abs(c["reference"])
        error = c["value"] - c["reference"] if kind == "at_most" else c["reference"] - c["value"]
        return (error + allowed) / allowed if allowed else 0.0
    else:
        allowed = tolerance
    return error / allowed if allowed else (0.0 if error == 0 else math.inf)


def row(c):
    unit = "" if c["unit"] in ("", "1") else " " + html.escape(c["unit"])
    result = "pass" if c["pass"] else "fail"
    return (f"<tr class=\"{result}\" id=\"{html.escape(c['id'])}\">"
            f"<td title=\"{html.escape(c['test'])}\">{html.escape(c['id'])}</td>"
            f"<td>{html.escape(c['quantity'])}{unit}</td>"
            f"<td>{html.escape(c['conditions'])}</td>"
            f"<td class=\"n\">{number(c['reference'])}</td>"
            f"<td>{html.escape(c['source'])}</td>"
            f"<td class=\"n\">{number(c['value'])}</td>"
            f"<td>{tolerance_text(c)}</td><td class=\"{result}\">{result}</td></tr>")


def page(checks, tests, failed_tests, commit):
    failing = [c for c in checks if not c["pass"]]
    groups = {}
    for c in checks:
        groups.setdefault(c["group"], []).append(c)
    order = [g for g in GROUP_ORDER if g in groups] + sorted(g for g in groups
                                                             if g not in GROUP_ORDER)
    plots = {}
    for c in checks:
        if c.get("plot"):
            plots.setdefault(c["plot"], []).append(c)
    # A plot stands in the group most of its checks are in; the paper comparison in its own.
    plot_group = {name: max(sorted({c["group"] for c in members}),
                            key=lambda g: sum(c["group"] == g for c in members))
                  for name, members in plots.items()}
    if "paper_comparison" in plots:
        plot_group["paper_comparison"] = "experiment: paper comparison"
        groups.setdefault("experiment: paper comparison", [])
        order = [g for g in GROUP_ORDER if g in groups] + sorted(g for g in groups
                                                                 if g not in GROUP_ORDER)
    out = ["<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">",
           "<title>fogradar validation report</title><style>",
           "body{font-family:sans-serif;margin:24px auto;max-width:1400px;color:#222}",
           "table{border-collapse:collapse;width:100%;font-size:13px;margin-bottom:18px;"
           "table-layout:fixed}td,th{overflow-wrap:anywhere}",
           "col.id{width:19%}col.q{width:13%}col.c{width:14%}col.r{width:8%}col.s{width:20%}"
           "col.v{width:8%}col.t{width:12%}col.p{width:6%}",
           "th,td{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top}",
           "th{background:#eee}td.n{text-align:right;font-family:monospace}",
           "tr.fail td{background:#fdd}td.pass{color:#070;font-weight:bold}",
           "td.fail{color:#c00;font-weight:bold}.summary{font-size:16px}",
           "figure{margin:12px 0}svg{max-width:100%;height:auto}</style></head><body>",
           "<h1>fogradar validation report</h1>"]
    status = "all passing" if not failing and not failed_tests else \
        f"<b style=\"color:#c00\">{len(failing)} failing</b>"
    out.append(f"<p class=\"summary\">{len(checks)} checks against independent references, "
               f"{status}; from {tests} tests of the GoogleTest suites "
               f"({len(failed_tests)} failed). Commit {html.escape(commit)}, generated "
               f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC by "
               "<code>scripts/validate.sh</code> (docs/validation.md).</p>")
    if failing:
        out.append("<h2>Failing checks</h2><ul>")
        for c in failing:
            out.append(f"<li><a href=\"#{html.escape(c['id'])}\">{html.escape(c['id'])}</a>: "
                       f"{html.escape(c['quantity'])} = {number(c['value'])} against "
                       f"{number(c['reference'])}</li>")
        out.append("</ul>")
    out.append("<h2>Groups</h2><ul>")
    for g in order:
        bad = sum(not c["pass"] for c in groups[g])
        out.append(f"<li><a href=\"#{html.escape(g)}\">{html.escape(g)}</a>: {len(groups[g])} "
                   f"checks{'' if not bad else f', {bad} failing'}</li>")
    out.append("</ul>")
    for g in order:
        out.append(f"<h2 id=\"{html.escape(g)}\">{html.escape(g)}</h2>")
        for name, members in plots.items():
            if plot_group[name] == g:
                out.append(f"<figure>{plot(name, members)}</figure>")
        if not groups[g]:
            continue
        out.append("<table>" + COLUMNS + "<tr><th>check</th><th>quantity</th><th>conditions</th>"
                   "<th>reference</th><th>source</th><th>fogradar</th><th>tolerance</th>"
                   "<th>result</th></tr>")
        # The checks of one loop (one test, quantity, source and kind of tolerance) beyond a few
        # are one row, the worst of them shown, the others a click away.
        families = {}
        for c in groups[g]:
            key = (c["test"], c["quantity"], c["unit"], c["source"], c["tolerance_kind"])
            families.setdefault(key, []).append(c)
        for members in families.values():
            if len(members) <= 4:
                out.extend(row(c) for c in members)
                continue
            worst = max(members, key=lambda c: (not c["pass"], margin_used(c)))
            bad = sum(not c["pass"] for c in members)
            result = "fail" if bad else "pass"
            out.append(f"<tr class=\"{result}\"><td colspan=\"8\"><details><summary>"
                       f"{len(members)} checks of {html.escape(worst['test'])}: "
                       f"{html.escape(worst['quantity'])}, {bad} failing; the closest to its "
                       f"tolerance: {html.escape(worst['id'])}</summary><table>{COLUMNS}")
            out.extend(row(c) for c in members)
            out.append("</table></details></td></tr>")
            out.append(row(worst))
        out.append("</table>")
    out.append("</body></html>\n")
    return "\n".join(out)


def main():
    out_dir, paths = sys.argv[1], sys.argv[2:]
    checks, tests, failed_tests = read_checks(paths)
    ids = [c["id"] for c in checks]
    duplicates = sorted({i for i in ids if ids.count(i) > 1})
    problems = [f"check {c['id']} has no {field}" for c in checks
                for field in ("source", "quantity", "group") if not c.get(field)]
    problems += [f"check id {i} recorded more than once" for i in duplicates]
    try:
        commit = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(__file__)),
                                 "describe", "--always", "--dirty"], capture_output=True,
                                text=True).stdout.strip() or "unknown"
    except OSError:
        commit = "unknown"
    os.makedirs(out_dir, exist_ok=True)
    checks.sort(key=lambda c: c["id"])
    with open(os.path.join(out_dir, "validation.json"), "w", encoding="utf-8") as f:
        json.dump({"commit": commit, "tests": tests, "failed_tests": failed_tests,
                   "checks": checks}, f, indent=1, allow_nan=False)
        f.write("\n")
    with open(os.path.join(out_dir, "validation.html"), "w", encoding="utf-8") as f:
        f.write(page(checks, tests, failed_tests, commit))
    failing = [c["id"] for c in checks if not c["pass"]]
    print(f"validation: {len(checks)} checks, {len(failing)} failing, {tests} tests "
          f"({len(failed_tests)} failed); {os.path.join(out_dir, 'validation.html')}, "
          f"{os.path.join(out_dir, 'validation.json')}")
    for line in problems + [f"failing: {i}" for i in failing] + \
            [f"failed test: {t}" for t in failed_tests]:
        print("  " + line)
    return 1 if failing or failed_tests or problems or not checks else 0


if __name__ == "__main__":
    sys.exit(main())
