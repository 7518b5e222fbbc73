#!/usr/bin/python3
"""The raw-data file of `fogradar run --raw` (docs/data-out.md) read back with h5py, Debian's
independent HDF5 reader, against NumPy and against the run's own CSV files:

- /radar/range_doppler equals |X|^2 of the windowed 2-D DFT of /radar/beat recomputed with NumPy
  (periodic Hann windows, numpy.fft.fft2): pocketfft and FFTW both round in double precision, so
  the two agree to about N log2 N eps of the peak; the tolerance is 1e-11 of each map's peak;
- the gate detection in /radar/detections (associated = 1) is radar_samples.csv's row, every number
  the same double, and each frame has as many detections as radar_detections.csv's rows for it;
- the sum of a step's /camera/images histograms is camera_histograms.csv's counts, exactly;
- /lidar/echoes holds lidar_echoes.csv's echoes (ranges to the CSV's 4 decimals, origins and
  layers);
- every origin, the radar's and the lidar's, is one HDF5 enumeration with names: noise 0, target 1,
  fog 2, background 3, clipping 4, sidelobe 5, multipath 6, room 7 (sensor/origin.hpp);
- the ground truth on request: /radar/origins, an enumerated map whose cell at each detection's
  peak (its range_cell, doppler_cell) holds that detection's origin, and /radar/origin_layers,
  int16, whose cell there holds its layer (-1 where not fog); /lidar/origins, whose stretch holding
  each echo's attributed_range_m holds that echo's origin and layer; the room's origins among them
  (examples/room_clutter.toml: the target's ghost, multipath, and the back wall's and barrels' own
  echoes, room, in every frame);
- the layout: shapes [active_layers, item, ...], one item per chunk, dimension scales attached,
  units, the resolved scenario as the root attribute (scenario.toml's text);
- one name for the step and one for the item everywhere: every CSV file of the result set and
  every HDF5 dataset, table field and `dimensions` attribute say `active_layers` and `item`, never
  `step`, `measurement`, `scan` or `frame`.

Usage: raw_h5_check.py FOGRADAR_BINARY SOURCE_DIR
"""
import csv
import os
import subprocess
import sys
import tempfile
from collections import Counter, defaultdict

import h5py
import numpy as np

fogradar, source = sys.argv[1], sys.argv[2]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def hann(n):
    return 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(n) / n)


with tempfile.TemporaryDirectory() as work:
    out, raw = os.path.join(work, "out"), os.path.join(work, "r.h5")
    subprocess.run([fogradar, "run", "--scenario", os.path.join(source, "tests/cli/small.toml"),
                    "--out", out, "--raw", raw, "--raw-steps", "0,4", "--raw-items", "0-3",
                    "--threads", "2"], check=True, stdout=subprocess.DEVNULL)
    with h5py.File(raw, "r") as f:
        # Layout.
        beat, rd = f["/radar/beat"], f["/radar/range_doppler"]
        check(beat.shape == (2, 4, 16, 512) and beat.dtype == np.complex128, f"beat {beat.shape} {beat.dtype}")
        check(beat.chunks == (1, 1, 16, 512), f"beat chunks {beat.chunks}")
        check(rd.shape == (2, 4, 16, 512) and rd.dtype == np.float64, f"range_doppler {rd.shape}")
        check(list(f["/radar/active_layers"][:]) == [0, 4]
              and list(f["/radar/item"][:]) == [0, 1, 2, 3], "active_layers and item scales")
        check(rd.dims[3][0].name == "/radar/range_m" and rd.dims[2][0].name == "/radar/velocity_m_per_s",
              "range_doppler's axes attached")
        check(rd.attrs["units"].decode().startswith("W"), "range_doppler's units")
        with open(os.path.join(out, "scenario.toml"), "rb") as toml:
            check(f.attrs["scenario"] == toml.read(), "the root attribute is scenario.toml")
        check(f.attrs["raw_format"] == 2, "raw_format")

        # One name for the step and the item in every file.
        other_names = {"step", "measurement", "scan", "frame"}
        for name in sorted(os.listdir(out)):
            if name.endswith(".csv"):
                with open(os.path.join(out, name)) as table:
                    header = next(csv.reader(table))
                check(not other_names & set(header) and header.count("active_layers") <= 1,
                      f"{name}'s header names the step and item active_layers and item: {header}")
        for name in ("radar_samples.csv", "radar_detections.csv", "lidar_echoes.csv"):
            with open(os.path.join(out, name)) as table:
                header = next(csv.reader(table))
            check(header[:2] == ["active_layers", "item"],
                  f"{name} starts with active_layers, item: {header}")

        def names_of(path, node):
            names = [path.rsplit("/", 1)[-1]]
            if isinstance(node, h5py.Dataset):
                names += list(node.dtype.names or ())
                if "dimensions" in node.attrs:
                    names += node.attrs["dimensions"].decode().split(", ")
                if node.dtype.names:
                    check(list(node.dtype.names[:2]) == ["active_layers", "item"],
                          f"{path}'s rows start with active_layers, item")
                elif node.ndim >= 2 and "dimensions" in node.attrs:
                    check(node.attrs["dimensions"].decode().startswith("active_layers, item"),
                          f"{path} is indexed [active_layers, item, ...]")
            check(not other_names & set(names), f"{path} names the step or item otherwise: {names}")
        f.visititems(names_of)

        # The map from the beat.
        window = hann(16)[:, None] * hann(512)[None, :]
        worst = 0.0
        for s in range(2):
            for i in range(4):
                power = np.abs(np.fft.fft2(beat[s, i] * window)) ** 2
                worst = max(worst, np.max(np.abs(power - rd[s, i])) / np.max(rd[s, i]))
        check(worst < 1e-11, f"range_doppler against numpy: {worst:.1e} of the peak")
        print(f"[ measured ] |numpy - range_doppler| <= {worst:.1e} of each map's peak")
        noise = rd.attrs["thermal_noise_level"]
        median_cell = np.median(rd[0, 0])
        # Median of chi-square(2)/2 noise: ln 2 of its mean; target and clutter cells are few.
        check(0.5 * noise < median_cell < 1.5 * noise,
              f"median cell {median_cell:.3e} against the stated thermal noise level {noise:.3e}")

        # The gate detection is radar_samples.csv's row; every frame's detections.
        detections = f["/radar/detections"][:]
        origins = h5py.check_enum_dtype(detections.dtype["origin"])
        label = {v: k for k, v in origins.items()}
        with open(os.path.join(out, "radar_samples.csv")) as samples_file:
            samples = {(int(r["active_layers"]), int(r["item"])): r
                       for r in csv.DictReader(samples_file)}
        with open(os.path.join(out, "radar_detections.csv")) as detections_file:
            csv_count = Counter((int(r["active_layers"]), int(r["item"]))
                                for r in csv.DictReader(detections_file))
        h5_count = Counter((int(r["active_layers"]), int(r["item"])) for r in detections)
        compared = 0
        for step in (0, 4):
            for item in range(4):
                check(h5_count[(step, item)] == csv_count[(step, item)],
                      f"detections of ({step}, {item}): {h5_count[(step, item)]} against the CSV's "
                      f"{csv_count[(step, item)]}")
                gate = [r for r in detections if r["active_layers"] == step
                        and r["item"] == item and r["associated"] == 1]
                row = samples[(step, item)]
                check(len(gate) == (1 if row["origin"] else 0), f"gate detection of ({step}, {item})")
                if gate:
                    g = gate[0]
                    for column in ("range_m", "rcs_dbsm", "snr_db", "velocity_m_per_s"):
                        check(float(row[column]) == g[column], f"{column} of ({step}, {item})")
                    check(label[g["origin"]] == row["origin"], f"origin of ({step}, {item})")
                    compared += 1
        check(compared == 8, f"{compared} gate detections compared")

        # The camera's images make its histograms.
        images = f["/camera/images"]
        check(images.shape == (2, 2, 120, 160) and images.dtype == np.uint8, f"images {images.shape}")
        histograms = defaultdict(lambda: np.zeros(256, dtype=np.int64))
        with open(os.path.join(out, "camera_histograms.csv")) as histogram_file:
            for r in csv.DictReader(histogram_file):
                histograms[int(r["active_layers"])][int(r["grey_level"])] = int(r["count"])
        for s, step in enumerate((0, 4)):
            counts = sum(np.bincount(images[s, i].ravel(), minlength=256) for i in range(2))
            check(np.array_equal(counts, histograms[step]), f"camera histogram of step {step}")

        # The lidar's echoes.
        echoes = f["/lidar/echoes"][:]
        with open(os.path.join(out, "lidar_echoes.csv")) as echo_file:
            listed = [r for r in csv.DictReader(echo_file)
                      if int(r["active_layers"]) in (0, 4) and int(r["item"]) < 4]
        check(len(listed) == len(echoes), f"{len(echoes)} echoes against the CSV's {len(listed)}")
        table = {"noise": 0, "target": 1, "fog": 2, "background": 3, "clipping": 4,
                 "sidelobe": 5, "multipath": 6, "room": 7}
        check(h5py.check_enum_dtype(echoes.dtype["origin"]) == table, "the lidar's origin codes")
        check(h5py.check_enum_dtype(f["/radar/detections"].dtype["origin"]) == table,
              "the radar's origin codes")
        lidar_labels = {v: k for k, v in h5py.check_enum_dtype(echoes.dtype["origin"]).items()}
        for row, echo in zip(listed, echoes):
            check(int(row["active_layers"]) == echo["active_layers"]
                  and int(row["item"]) == echo["item"]
                  and abs(float(row["range_m"]) - echo["range_m"]) <= 5e-5
                  and row["origin"] == lidar_labels[echo["origin"]]
                  and int(row["layer"]) == echo["layer"], f"echo {row}")
        waveforms = f["/lidar/waveforms"]
        check(waveforms.shape[:2] == (2, 4) and waveforms.shape[2] == len(f["/lidar/angle_deg"]),
              f"waveforms {waveforms.shape}")

# The beat's two parts, kept only when named: signal + noise is the beat, exactly (static paths).
with tempfile.TemporaryDirectory() as work:
    out, raw = os.path.join(work, "out"), os.path.join(work, "parts.h5")
    subprocess.run([fogradar, "run", "--scenario", os.path.join(source, "tests/cli/small.toml"),
                    "--out", out, "--raw", raw, "--raw-select",
                    "radar.beat,radar.signal,radar.noise", "--raw-steps", "2",
                    "--raw-items", "1"], check=True, stdout=subprocess.DEVNULL)
    with h5py.File(raw) as f:
        check(sorted(f["/radar"]) == sorted(["beat", "signal", "noise", "active_layers", "item",
                                             "chirp_time_s", "sample_time_s"]),
              f"parts file: {sorted(f['/radar'])}")
        f.visititems(names_of)
        beat, signal, noise = (f[f"/radar/{k}"][0, 0] for k in ("beat", "signal", "noise"))
        check(np.array_equal(signal + noise, beat), "signal + noise == beat")

def radar_truth_seen(f):
    """Checks every radar detection of the open raw file against /radar/origins and
    /radar/origin_layers at its peak cell; returns the count of detections of each origin code."""
    truth = f["/radar/origins"]
    check(h5py.check_enum_dtype(truth.dtype) == table, "the radar map's origin codes")
    rows, columns = truth.shape[2:]
    bin_m, velocity_bin = truth.attrs["range_bin_m"], truth.attrs["velocity_bin_m_per_s"]
    coupling = truth.attrs["range_coupling_s"]
    radar_seen = Counter()
    layers = f["/radar/origin_layers"]
    check(layers.dtype == np.int16 and layers.shape == truth.shape, "the radar's layer map")
    for d in f["/radar/detections"][:]:
        s, i = list(f["/radar/active_layers"][:]).index(d["active_layers"]), d["item"]
        row, column = d["doppler_cell"], d["range_cell"]
        check(truth[s, i, row, column] == d["origin"], f"radar truth at {d}")
        check(layers[s, i, row, column] == d["layer"], f"radar layer at {d}")
        check((d["layer"] >= 0) == (d["origin"] == table["fog"]), f"radar layer of {d}")
        # From range and velocity alone: the peak cell to within one (the estimate's offset).
        near_column = (d["range_m"] + coupling * d["velocity_m_per_s"]) / bin_m
        near_row = d["velocity_m_per_s"] / velocity_bin
        check(abs(near_column - column) <= 1.0, f"radar range cell of {d}")
        check(abs((near_row - row + rows / 2) % rows - rows / 2) <= 1.0,
              f"radar Doppler cell of {d}")
        radar_seen[int(d["origin"])] += 1
    return radar_seen


# The ground truth, asked for by name: each detection's and each echo's origin (and an echo's
# layer) is the one the truth holds where it is attributed: a detection's peak cell, an echo's
# attributed_range_m.
with tempfile.TemporaryDirectory() as work:
    out, raw = os.path.join(work, "out"), os.path.join(work, "truth.h5")
    subprocess.run([fogradar, "run", "--scenario", os.path.join(source, "tests/cli/small.toml"),
                    "--out", out, "--raw", raw, "--raw-select",
                    "radar.detections,radar.origins,radar.origin_layers,lidar.echoes,lidar.origins",
                    "--raw-steps",
                    "0,4", "--raw-items", "0-1"], check=True, stdout=subprocess.DEVNULL)
    with h5py.File(raw) as f:
        f.visititems(names_of)
        radar_seen = radar_truth_seen(f)
        check(sum(radar_seen.values()) > 0, "radar detections with truth")
        stretches = f["/lidar/origins"][:]
        check(h5py.check_enum_dtype(stretches.dtype["origin"]) == table, "lidar truth codes")
        lidar_seen = Counter()
        for e in f["/lidar/echoes"][:]:
            inside = stretches[(stretches["active_layers"] == e["active_layers"])
                               & (stretches["item"] == e["item"])
                               & (stretches["beam"] == e["beam"])
                               & (stretches["start_m"] <= e["attributed_range_m"])
                               & (e["attributed_range_m"] < stretches["end_m"])]
            expected = inside["origin"][0] if len(inside) else table["noise"]
            check(expected == e["origin"], f"lidar truth at {e}")
            check((inside["layer"][0] if len(inside) else -1) == e["layer"],
                  f"lidar truth's layer at {e}")
            lidar_seen[int(e["origin"])] += 1
        check(lidar_seen[table["background"]] > 0 and lidar_seen[table["target"]] > 0,
              f"lidar echoes with truth: {lidar_seen}")

# The room's origins in the ground truth: examples/room_clutter.toml (a back wall behind the target,
# two barrels in the beam) with the target at 2 Doppler bins, where every frame holds the target,
# its ghost off the back wall (multipath) and the wall's and barrels' own echo (room).
with tempfile.TemporaryDirectory() as work:
    out, raw, scenario = (os.path.join(work, name) for name in ("out", "room.h5", "room.toml"))
    with open(os.path.join(source, "examples/room_clutter.toml")) as base, open(scenario, "w") as s:
        s.write(base.read() + "\n[target]\nradial_velocity_m_per_s = 1.188\n")
    subprocess.run([fogradar, "run", "--scenario", scenario, "--out", out, "--raw", raw,
                    "--raw-select", "radar.detections,radar.origins,radar.origin_layers",
                    "--raw-items", "0-3"], check=True, stdout=subprocess.DEVNULL)
    with h5py.File(raw) as f:
        seen = radar_truth_seen(f)
        check(seen[table["multipath"]] >= 4 and seen[table["room"]] >= 4
              and seen[table["target"]] >= 4, f"the room's origins with truth: {seen}")

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
