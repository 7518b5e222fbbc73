#!/usr/bin/python3
"""The plots of `fogradar sweep` (docs/sweep.md), read back as SVG from small sweeps:

- comparison.svg: every line has its own pair of mark shape and dash pattern, every point is
  marked, the legend is titled with the swept key; ratios that are all positive are in dB;
- limits.svg with one axis: limits are whole numbers drawn as marks and steps (no sloped piece);
  a limit not reached is its sensor's mark in a row above the last step (one per point of
  limits.csv with no limit), named in the legend; with two axes: every sensor's heat map has the
  same colour key, whole numbers only, and a value has the same colour in every panel;
- envelope.svg: a statistic's panel names in its legend only what it draws (no band where every
  setup gives the same value); the references and values keep off the frame (padded axes); the
  titles are words, not column names.

Usage: test_sweep_plots.py FOGRADAR"""
import csv
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

fogradar = sys.argv[1]
failures = []
NS = "{http://www.w3.org/2000/svg}"


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def sweep(sweep_file, out):
    done = subprocess.run([fogradar, "sweep", "--sweep", sweep_file, "--out", out, "--threads", "2"],
                          capture_output=True, text=True)
    check(done.returncode == 0, f"sweep {sweep_file}: exit {done.returncode}, {done.stderr.strip()}")


def panels(path):
    """The nested <svg> panels of a stacked plot, each a list of its elements in document order."""
    root = ET.parse(path).getroot()
    return [list(panel.iter()) for panel in root.findall(NS + "svg")]


def of_class(elements, tag, cls):
    return [e for e in elements if e.tag == NS + tag and e.get("class") == cls]


def texts(elements, cls):
    return [e.text or "" for e in of_class(elements, "text", cls)]


def path_ys(element):
    return [float(p.split(",")[1]) for p in re.findall(r"-?[\d.]+,-?[\d.]+", element.get("d"))]


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


with tempfile.TemporaryDirectory() as work:
    def write(name, text):
        path = os.path.join(work, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    write("small.toml", "[radar]\nmeasurements_per_step = 12\n[lidar]\n"
          "scans_per_step = 6\n[camera]\nframes_per_step = 3\n")

    # One axis: comparison.svg and limits.svg as a line plot.
    one = os.path.join(work, "one")
    sweep(write("one.toml", "[sweep]\nbase = \"small.toml\"\n[[axis]]\n"
                "key = \"fog.extinction_per_km\"\nvalues = [100.0, 900.0, 3000.0]\n"), one)
    for panel in panels(os.path.join(one, "comparison.svg")):
        title = texts(panel, "title")[0]
        styles, current = [], None
        for e in panel:
            if e.tag == NS + "polyline" and e.get("class") == "series":
                current = [e.get("stroke-dasharray", ""), None]
                styles.append(current)
            elif e.tag == NS + "path" and (e.get("class") or "").startswith("point-"):
                if current[1] is None:
                    current[1] = e.get("class")
        check(len(styles) == 3, f"{title}: {len(styles)} lines")
        check(all(s[1] for s in styles), f"{title}: a line without marks {styles}")
        check(len({tuple(s) for s in styles}) == len(styles),
              f"{title}: two lines share mark and dash {styles}")
        marks = [e for e in panel if (e.get("class") or "").startswith("point-")]
        check(len(marks) == 3 * 5, f"{title}: {len(marks)} marks for 3 lines of 5 steps")
        check(texts(panel, "legend-title") == ["fog.extinction_per_km"],
              f"{title}: legend title {texts(panel, 'legend-title')}")
        check(texts(panel, "legend-text") == ["100.0", "900.0", "3000.0"],
              f"{title}: legend {texts(panel, 'legend-text')}")
        ys = [float(v) for line in of_class(panel, "polyline", "series")
              for v in re.findall(r",(-?[\d.]+)", line.get("points"))]
        check(len(ys) == 15, f"{title}: {len(ys)} vertices")
    # The radar's ratios are all positive (its RCS barely moves): drawn in dB.
    radar = panels(os.path.join(one, "comparison.svg"))[0]
    y_label = [e.text for e in of_class(radar, "text", "y-label")][0]
    check(y_label.endswith("(dB)"), f"radar comparison y label {y_label!r}")

    limits = rows(os.path.join(one, "limits.csv"))
    missing = {}
    for r in limits:
        if r["layers_to_failure"] == "":
            missing[r["sensor"]] = missing.get(r["sensor"], 0) + 1
    check(missing.get("radar") == 3 and missing.get("lidar", 0) >= 1,
          f"the sweep should leave limits unreached: {missing}")
    (panel,) = panels(os.path.join(one, "limits.svg"))
    frame_top = float(of_class(panel, "rect", "frame")[0].get("y"))
    beyond = [e for e in panel if e.tag == NS + "path" and (e.get("class") or "").startswith("beyond-")]
    check(len(beyond) == sum(missing.values()),
          f"{len(beyond)} 'not reached' marks for {sum(missing.values())} unreached limits")
    for e in beyond:
        check(max(path_ys(e)) < frame_top, f"'not reached' mark {e.get('d')} not above {frame_top}")
    check(texts(panel, "beyond-label") == ["not reached"], "the row of 'not reached' is unnamed")
    check(texts(panel, "legend-beyond") == ["top row: not reached"],
          f"legend of 'not reached': {texts(panel, 'legend-beyond')}")
    ticks = [t for t in of_class(panel, "text", "tick") if float(t.get("x")) < 84.0]
    check([t.text for t in ticks] == ["0", "1", "2", "3", "4"],
          f"layer ticks {[t.text for t in ticks]}")
    top_tick_y = float(ticks[-1].get("y")) - 4.0
    check(abs(top_tick_y - frame_top) < 0.01, "the last step is not the top of the axis")
    for line in of_class(panel, "polyline", "series"):
        vertices = [tuple(map(float, p.split(","))) for p in line.get("points").split()]
        for a, b in zip(vertices, vertices[1:]):
            check(a[0] == b[0] or a[1] == b[1], f"a sloped piece {a} -> {b} in limits.svg")
    reached = sum(1 for r in limits if r["layers_to_failure"] != "")
    marks = [e for e in panel if (e.get("class") or "").startswith("point-")]
    check(len(marks) == reached, f"{len(marks)} limit marks for {reached} limits reached")

    # Two axes: heat maps on one colour scale.
    two = os.path.join(work, "two")
    sweep(write("two.toml", "[sweep]\nbase = \"small.toml\"\n[[axis]]\n"
                "key = \"fog.extinction_per_km\"\nvalues = [100.0, 900.0, 3000.0]\n[[axis]]\n"
                "key = \"radar.centre_frequency_hz\"\nvalues = [77e9, 79e9]\n"), two)
    maps = panels(os.path.join(two, "limits.svg"))
    check(len(maps) == 3, f"{len(maps)} heat maps")
    keys = [[(e.get("fill"), t) for e, t in zip(of_class(m, "rect", "key"), texts(m, "key-text"))]
            for m in maps]
    check(all(k == keys[0] for k in keys), f"heat maps with different keys {keys}")
    check([t for _, t in keys[0]] == ["4", "3", "2", "1", "0", "not reached"],
          f"heat map key {keys[0]}")
    colours = {}
    for m in maps:
        for cell, label in zip(of_class(m, "rect", "cell"), of_class(m, "text", "cell-text")):
            colours.setdefault(label.text, set()).add(cell.get("fill"))
    check(all(len(c) == 1 for c in colours.values()), f"a value with several colours {colours}")
    check(all(v == "not reached" or re.fullmatch(r"\d+", v) for v in colours),
          f"cell values {sorted(colours)}")

    # The envelope: one statistic per axis, a legend that covers what is drawn, padded axes.
    env = os.path.join(work, "env")
    sweep(write("env.toml", """[sweep]
base = "small.toml"
[uncertain]
setups = 3
[uncertain.keys."radar.height_m"]
distribution = "uniform"
low = 0.45
high = 0.55
[[uncertain.plot]]
sensor = "radar"
statistic = "mean_dbsm"
box = ["whisker_low_dbsm", "q1_dbsm", "median_dbsm", "q3_dbsm", "whisker_high_dbsm"]
y_label = "target RCS (dBsm)"
references = [{ active_layers = 0, value = 14.97 }]
reference_label = "the study (Fig. 4, mean)"
[[uncertain.plot]]
sensor = "camera"
statistic = "mean_grey"
y_label = "ROI mean grey level"
references = [{ active_layers = 0, value = 46.0 }]
reference_label = "the study (Fig. 7)"
"""), env)
    radar_values, radar_boxes, camera = panels(os.path.join(env, "envelope.svg"))
    for panel in (radar_values, radar_boxes, camera):
        title = texts(panel, "title")[0]
        check("_" not in title, f"a column name in the title {title!r}")
        frame = of_class(panel, "rect", "frame")[0]
        top, height = float(frame.get("y")), float(frame.get("height"))
        drawn = [float(e.get("y1")) for e in panel if e.tag == NS + "line" and
                 e.get("class") in ("value", "median", "whisker")]
        drawn += [0.5 * (float(e.get("y1")) + float(e.get("y2"))) for e in of_class(panel, "line", "reference")]
        for y in drawn:
            check(top + 0.03 * height < y < top + 0.97 * height,
                  f"{title}: a mark at y = {y} on the frame [{top}, {top + height}]")
        legend = texts(panel, "legend-text")
        has_band = bool(of_class(panel, "rect", "band"))
        check(("5-95 % of the setups" in legend) == has_band, f"{title}: legend {legend}, band {has_band}")
        has_value = bool(of_class(panel, "line", "value"))
        check(("the nominal run" in legend) == has_value, f"{title}: legend {legend}")
        check(("box: quartiles Q1 to Q3" in legend) == bool(of_class(panel, "rect", "box")),
              f"{title}: legend {legend}")
    check(of_class(radar_values, "rect", "band") and not of_class(radar_values, "rect", "box"),
          "the radar's statistic panel: bands and values, no box")
    check(not of_class(camera, "rect", "band"), "the camera: a band although every setup is alike")
    check(any("no key of [uncertain] changes it" in c for c in texts(camera, "caption")),
          f"the camera's caption {texts(camera, 'caption')}")

if failures:
    print(f"{len(failures)} failures")
    sys.exit(1)
print("all sweep plot checks passed")
