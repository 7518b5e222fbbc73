#!/usr/bin/python3
"""The validation report (docs/validation.md) from GoogleTest's JSON output: every check a test
recorded through tests/support/validation.hpp ("validation:<id>" properties) into validation.json
(one object per check, with the suite and test that made it) and validation.html (one
self-contained page: the paper comparison first, then a table per group, reference against value
against tolerance, the checks of one loop folded into one row, and the plots the checks name, drawn
inline as SVG by matplotlib).

Usage: validation_report.py OUT_DIR GTEST_JSON...
Exit status 1 when a check fails, a test failed or no check was found."""
import datetime
import html
import io
import json
import math
import os
import re
import subprocess
import sys
import textwrap

import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402

matplotlib.rcParams.update({"svg.fonttype": "path", "font.size": 10, "svg.hashsalt": "fogradar"})

PAPER = "paper comparison"
GROUP_ORDER = [PAPER, "physics: water", "physics: materials", "physics: room", "physics: droplets",
               "physics: fog", "physics: chamber", "physics: sensor bands", "radar: SNR",
               "radar: CFAR", "radar: detection", "radar: RCS", "radar: Doppler",
               "radar: signal processing", "lidar", "lidar: optics", "camera",
               "experiment: geometry and Doppler", "experiment: layers", "experiment: statistics"]
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
    "paper_comparison": ("The study's numbers against the paper scenario: Fig. 4 (radar), "
                         "Fig. 6 (lidar), Fig. 7 (camera)", "linear", "linear"),
}
# The paper comparison's abscissa: the study's steps, 0 to 4 active fog layers.
PAPER_LAYERS = range(0, 5)
# Beyond this many checks a loop's row lists them in validation.json only, not on the page.
LISTED_MEMBERS = 20


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
    """A value as a reader would write it: 6 significant digits, an exponent only where needed."""
    if value is None:
        return "—"
    return f"{value:.{digits}g}"


def tolerance_text(check):
    kind = check["tolerance_kind"]
    if kind in ("statistical", "disagreement"):
        low, high = check.get("interval", [None, None])
        what = (f"({html.escape(check.get('confidence', ''))}, n = {check.get('samples', 0)})")
        if kind == "disagreement":
            return f"outside fogradar's band [{number(low)}, {number(high)}] {what}"
        return f"in [{number(low)}, {number(high)}] {what}"
    tolerance = check["tolerance"]
    bound = {"at_most": ("≤ ref.", "+"), "at_least": ("≥ ref.", "−"), "above": ("> ref.", "+")}
    if kind in bound:
        relation, sign = bound[kind]
        return relation if tolerance == 0 else f"{relation} {sign} {number(tolerance, 3)}"
    symbol = {"relative": "± rel.", "absolute": "±"}
    return f"{symbol[kind]} {number(tolerance, 3)}"


def verdict(check):
    """The result cell's class and text: a known disagreement is neither a pass nor a failure while
    it holds as documented."""
    if check["tolerance_kind"] == "disagreement":
        return ("disagree", "known disagreement") if check["pass"] else \
            ("fail", "fail: inside the band")
    return ("pass", "pass") if check["pass"] else ("fail", "fail")


def svg_of(figure):
    buffer = io.StringIO()
    figure.savefig(buffer, format="svg", bbox_inches="tight", metadata={"Date": None})
    plt.close(figure)
    text = buffer.getvalue()
    return text[text.index("<svg"):]


def padded_limits(values, log):
    """Axis limits that show `values` with a margin, and a span a reader can see where they are
    (nearly) one value: ±10 % of it, or ±0.5 around 0."""
    low, high = min(values), max(values)
    if log:
        return low / 1.6, high * 1.6
    span = high - low
    if span <= 1e-9 * max(abs(low), abs(high), 1.0):
        half = 0.1 * abs(low) if low != 0 else 0.5
        return low - half, high + half
    return low - 0.08 * span, high + 0.08 * span


def plot(name, checks):
    """plot_figure() as inline SVG, or "" where no check of the plot has an abscissa."""
    figure = plot_figure(name, checks)
    return "" if figure is None else svg_of(figure)


def plot_figure(name, checks):
    """The checks of one plot against their abscissa, a panel per unit: the reference as squares on
    a line (bars where several share an x; points alone in the paper comparison, whose abscissa
    counts layers), fogradar's values as circles, statistical intervals as
    whiskers, a bound as a triangle pointing where the value may lie, a known disagreement as
    fogradar's band (a bar) beside the reference (a star), failures as red crosses. Legends stand
    beside the axes, never over the data; an axis with one value is padded to a visible span."""
    title, x_scale, y_scale = PLOTS.get(name, (name, "linear", "linear"))
    paper = name == "paper_comparison"
    reference = "the study" if paper else "reference"
    series = {}
    for c in checks:
        if c.get("x") is None or c["value"] is None or c["reference"] is None:
            continue
        series.setdefault(c["unit"], {}).setdefault(c["quantity"], []).append(c)
    if not series:
        return None

    def figure_of(unit):  # the study's figure a panel of the paper comparison shows
        found = [re.search(r"Fig\. (\d+)", c["source"]) for q in series[unit].values() for c in q]
        return min((int(m.group(1)) for m in found if m), default=99)
    units = sorted(series, key=lambda u: (figure_of(u), u) if paper else (0, u))
    figure, axes_list = plt.subplots(len(units), 1, figsize=(9.0, 0.8 + 3.0 * len(units)),
                                     squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    bound_marker = {"at_least": "^", "above": "^", "at_most": "v"}
    for axes, unit in zip(axes_list[:, 0], units):
        xs_all, ys_all = [], []
        for i, quantity in enumerate(sorted(series[unit])):
            members = sorted(series[unit][quantity], key=lambda c: c["x"])
            colour = colours[i % len(colours)]
            label = textwrap.fill(quantity, 48)
            curve = [c for c in members if c["tolerance_kind"] not in bound_marker]
            xs = [c["x"] for c in curve]
            unique = len(set(xs)) == len(xs)
            if curve and not any(c["tolerance_kind"] == "disagreement" for c in curve):
                # The study's steps are counts of layers: its numbers are points, not a curve.
                style = ("s" if paper else "-s") if unique else "_"
                axes.plot(xs, [c["reference"] for c in curve], style,
                          color=colour, alpha=0.45, linewidth=2.0, markersize=6 if unique else 14,
                          label=f"{label}: {reference}")
            for kind, marker in bound_marker.items():
                bounds = [c for c in members if c["tolerance_kind"] == kind]
                if bounds:
                    axes.plot([c["x"] for c in bounds], [c["reference"] for c in bounds], marker,
                              color=colour, alpha=0.6, markersize=8,
                              label=f"{label}: {reference}, a bound ({kind.replace('_', ' ')})")
            for c in members:
                if c["tolerance_kind"] == "disagreement":
                    low, high = c["interval"]
                    axes.plot([c["x"], c["x"]], [low, high], "-", color=colour, linewidth=6,
                              alpha=0.5, solid_capstyle="butt",
                              label=f"{label}: fogradar, {c.get('confidence', 'band')}")
                    axes.plot([c["x"]], [c["reference"]], "*", color="#d07000", markersize=13,
                              label=f"{label}: the study (known disagreement)")
                    ys_all += [low, high]
                elif c["tolerance_kind"] == "statistical" and c.get("interval"):
                    low, high = c["interval"]
                    if low is not None and high is not None:
                        axes.plot([c["x"], c["x"]], [low, high], "-", color=colour,
                                  linewidth=0.8)
                if not c["pass"]:
                    axes.plot([c["x"]], [c["value"]], "x", color="#c00000", markersize=10,
                              markeredgewidth=2)
            axes.plot([c["x"] for c in members], [c["value"] for c in members], "o",
                      color=colour, markersize=4.5, markerfacecolor="none",
                      label=f"{label}: fogradar")
            xs_all += [c["x"] for c in members]
            ys_all += [v for c in members for v in (c["value"], c["reference"])]
        log_x = x_scale == "log" and all(x > 0 for x in xs_all)
        log_y = y_scale == "log" and all(y > 0 for y in ys_all)
        axes.set_xscale("log" if log_x else "linear")
        axes.set_yscale("log" if log_y else "linear")
        layers = (min(PAPER_LAYERS) - 0.5, max(PAPER_LAYERS) + 0.5)
        if paper:
            axes.set_xlim(*layers)
            axes.set_xticks(list(PAPER_LAYERS))
            axes.set_title(f"the study's Fig. {figure_of(unit)}", fontsize=9, loc="left")
        else:
            axes.set_xlim(*padded_limits(xs_all, log_x))
        if paper and unit == "layers":
            axes.set_ylim(*layers)
            axes.set_yticks(list(PAPER_LAYERS))
        else:
            axes.set_ylim(*padded_limits(ys_all, log_y))
        axes.set_xlabel(checks[0].get("x_label", "") or "x")
        if unit not in ("", "1"):
            axes.set_ylabel(unit)
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    figure.suptitle(title, y=1.0 + 0.03 / len(units))
    figure.tight_layout()
    return figure


def margin_used(c):
    """How much of its tolerance a check uses (1: on the limit)."""
    if c["value"] is None or c["reference"] is None:
        return math.inf
    error = abs(c["value"] - c["reference"])
    kind, tolerance = c["tolerance_kind"], c["tolerance"]
    if kind == "disagreement":
        return 0.0
    if kind == "above":
        kind = "at_least"
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


def with_unit(c):
    quantity = html.escape(c["quantity"])
    return quantity if c["unit"] in ("", "1") else f"{quantity} ({html.escape(c['unit'])})"


def row(c):
    result, text = verdict(c)
    return (f"<tr class=\"{result}\" id=\"{html.escape(c['id'])}\">"
            f"<td title=\"{html.escape(c['test'])}\">{html.escape(c['id'])}</td>"
            f"<td>{with_unit(c)}</td>"
            f"<td>{html.escape(c['conditions'])}</td>"
            f"<td class=\"n\">{number(c['reference'])}</td>"
            f"<td>{html.escape(c['source'])}</td>"
            f"<td class=\"n\">{number(c['value'])}</td>"
            f"<td>{tolerance_text(c)}</td><td class=\"{result}\">{text}</td></tr>")


def loops(checks):
    """The checks of one loop: one test's (over all its parameters) checks of one quantity against
    one source with one kind of tolerance, in the order recorded."""
    families = {}
    for c in checks:
        # A parameterised test ("Instance/Suite.Test/param") is one loop over its parameters.
        test = re.sub(r"^[^/.]+/", "", re.sub(r"/[^/.]+$", "", c["test"]))
        key = (test, c["quantity"], c["unit"], c["source"], c["tolerance_kind"])
        families.setdefault(key, []).append(c)
    return list(families.values())


def id_pattern(ids):
    """What the ids of a loop share, up to the last separator, with a wildcard for the rest."""
    prefix = os.path.commonprefix(ids)
    cut = max(prefix.rfind("."), prefix.rfind("/"))
    return (prefix[:cut + 1] if cut >= 0 else prefix) + "*"


def folded_row(members):
    """A loop's checks as one row: how many, the case closest to its tolerance (reference, value and
    tolerance), and how many failed; the failing cases follow as rows of their own, and a short
    loop's cases are a click away."""
    worst = max(members, key=lambda c: (not c["pass"], margin_used(c)))
    bad = [c for c in members if not c["pass"]]
    result = "fail" if bad else "pass"
    tolerances = {tolerance_text(c) for c in members}
    tolerance = tolerance_text(worst) + ("" if len(tolerances) == 1 else
                                         " (this case's; each case has its own)")
    listed = len(members) <= LISTED_MEMBERS
    ids = id_pattern([c["id"] for c in members])
    passed = f"{result}, {len(members) - len(bad)} of {len(members)}"
    out = [f"<tr class=\"{result} loop\">"
           f"<td title=\"{html.escape(worst['test'])}\">{html.escape(ids)}"
           f" ({len(members)} checks)</td>"
           f"<td>{with_unit(worst)}</td>"
           f"<td>{len(members)} cases{'' if listed else ' (each in validation.json)'}; the closest "
           f"to its tolerance: {html.escape(worst['conditions'])}</td>"
           f"<td class=\"n\">{number(worst['reference'])}</td>"
           f"<td>{html.escape(worst['source'])}</td>"
           f"<td class=\"n\">{number(worst['value'])}</td>"
           f"<td>{tolerance}</td>"
           f"<td class=\"{result}\">{passed}</td></tr>"]
    out.extend(row(c) for c in bad)
    if listed:
        out.append(f"<tr class=\"cases\"><td colspan=\"8\"><details><summary>the {len(members)} "
                   f"cases</summary><table>{COLUMNS}")
        out.extend(row(c) for c in members)
        out.append("</table></details></td></tr>")
    return out


def paper_summary(checks):
    """The paper comparison's opening: what it holds, and each known disagreement in numbers."""
    agree = [c for c in checks if c["tolerance_kind"] != "disagreement"]
    known = [c for c in checks if c["tolerance_kind"] == "disagreement"]
    out = [f"<p>The study's published numbers (its Fig. 4 to 7 and their text) against the paper "
           f"scenario: {len(agree)} checks of what fogradar reproduces, and {len(known)} known "
           f"disagreement{'s' if len(known) != 1 else ''} — a published number fogradar does not "
           "reproduce, shown with fogradar's band and not counted as a pass; "
           "docs/paper-comparison.md gives the reasons.</p>"]
    if known:
        out.append("<ul>")
        for c in known:
            low, high = c["interval"]
            # A difference of levels in dBsm, dBm, ... is in dB.
            unit = "dB" if c["unit"].startswith("dB") else html.escape(c["unit"])
            side = f"{number(c['reference'] - high, 3)} {unit} above" if c["reference"] > high \
                else f"{number(low - c['reference'], 3)} {unit} below"
            state = (f"the study's value lies {side} fogradar's band" if c["pass"] else
                     "<b style=\"color:#c00\">the study's value now lies inside fogradar's band: "
                     "docs/paper-comparison.md and this check must be revised</b>")
            out.append(f"<li><a href=\"#{html.escape(c['id'])}\">{html.escape(c['quantity'])}</a>: "
                       f"the study {number(c['reference'])} {html.escape(c['unit'])}; fogradar "
                       f"{number(c['value'])} {html.escape(c['unit'])}, band "
                       f"[{number(low)}, {number(high)}] ({html.escape(c.get('confidence', ''))}, "
                       f"n = {c.get('samples', 0)}): {state}.</li>")
        out.append("</ul>")
    return out


def page(checks, tests, failed_tests, commit):
    failing = [c for c in checks if not c["pass"]]
    known = [c for c in checks if c["tolerance_kind"] == "disagreement" and c["pass"]]
    groups = {}
    for c in checks:
        groups.setdefault(c["group"], []).append(c)
    order = [g for g in GROUP_ORDER if g in groups] + sorted(g for g in groups
                                                             if g not in GROUP_ORDER)
    plots = {}
    for c in checks:
        if c.get("plot"):
            plots.setdefault(c["plot"], []).append(c)
    # A plot stands in the group most of its checks are in.
    plot_group = {name: max(sorted({c["group"] for c in members}),
                            key=lambda g: sum(c["group"] == g for c in members))
                  for name, members in plots.items()}
    rows = {g: len(loops(groups[g])) for g in order}
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
           "tr.disagree td{background:#fff0d8}td.disagree{color:#a05000;font-weight:bold}",
           "tr.loop td{background:#f6f8fb}tr.cases td{border-top:none}",
           "td.fail{color:#c00;font-weight:bold}.summary{font-size:16px}",
           "figure{margin:12px 0}svg{max-width:100%;height:auto}</style></head><body>",
           "<h1>fogradar validation report</h1>"]
    status = "all passing" if not failing and not failed_tests else \
        f"<b style=\"color:#c00\">{len(failing)} failing</b>"
    disagreements = "" if not known else \
        (f"; {len(known)} known disagreement{'s' if len(known) != 1 else ''} with published "
         f"values, shown as such in their sections")
    out.append(f"<p class=\"summary\">{len(checks)} checks against independent references in "
               f"{sum(rows.values())} rows (the checks of one loop are one row), {status}"
               f"{disagreements}; from {tests} tests of the GoogleTest suites "
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
        out.append(f"<li><a href=\"#{html.escape(g)}\">{html.escape(g)}</a>: {rows[g]} rows, "
                   f"{len(groups[g])} checks{'' if not bad else f', {bad} failing'}</li>")
    out.append("</ul>")
    for g in order:
        out.append(f"<h2 id=\"{html.escape(g)}\">{html.escape(g)}</h2>")
        if g == PAPER:
            out.extend(paper_summary(groups[g]))
        for name, members in plots.items():
            if plot_group[name] == g:
                out.append(f"<figure>{plot(name, members)}</figure>")
        out.append("<table>" + COLUMNS + "<tr><th>check</th><th>quantity</th><th>conditions</th>"
                   "<th>reference</th><th>source</th><th>fogradar</th><th>tolerance</th>"
                   "<th>result</th></tr>")
        for members in loops(groups[g]):
            if len(members) == 1:
                out.append(row(members[0]))
            else:
                out.extend(folded_row(members))
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
    # A reference is a number a reader can use: not a subnormal standing for "above 0" (a bound of
    # kind "above" says that).
    problems += [f"check {c['id']} has a subnormal {field} {c[field]!r}" for c in checks
                 for field in ("reference", "tolerance")
                 if c.get(field) is not None and 0 < abs(c[field]) < sys.float_info.min]
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
    known = sum(c["tolerance_kind"] == "disagreement" and c["pass"] for c in checks)
    print(f"validation: {len(checks)} checks, {len(failing)} failing, {known} known "
          f"disagreement{'' if known == 1 else 's'} with published values, {tests} tests "
          f"({len(failed_tests)} failed); {os.path.join(out_dir, 'validation.html')}, "
          f"{os.path.join(out_dir, 'validation.json')}")
    for line in problems + [f"failing: {i}" for i in failing] + \
            [f"failed test: {t}" for t in failed_tests]:
        print("  " + line)
    return 1 if failing or failed_tests or problems or not checks else 0


if __name__ == "__main__":
    sys.exit(main())
