#!/usr/bin/python3
"""`fogradar sweep` end to end (docs/sweep.md), against independent references:

- a fog-density sweep (paper scenario, beta550 = 100, 300, 900, 2000 /km): the lidar's layers to
  failure never rise with density; the radar's two-way loss of one layer in results.csv equals
  `fogradar fog`'s for each density (relative 1e-9);
- a frequency sweep (24.125 / 77 / 94 GHz zipped with 250 MHz / 1 GHz / 1 GHz): the radar's two-way
  loss per layer follows ITU-R P.840-8's frequency dependence, K_l(f) / K_l(77 GHz) with K_l from
  its double-Debye permittivity of water (written out below), within 1 % (the fog's 1 um droplets
  are Rayleigh scatterers at these frequencies: absorption dominates and is K_l x LWC);
- results.csv, limits.csv and points.csv byte-identical for threads 1 and 2, for a sweep killed by
  SIGKILL at a random instant and resumed, and for the values listed in reverse order; after a
  value is added to an axis and the sweep resumed, every point computed before is reused and the
  tables equal a fresh sweep's;
- with every [uncertain] key collapsed to one value (the base's own), the envelope's quantiles are
  the single run's values exactly; with the fog's extinction drawn uniformly (Latin hypercube), the
  quantiles of the radar's loss lie within the bounds the strata give (`fogradar fog` at the edges);
- a bad sweep file: exit 2, one message with file and line, nothing written; a sweep over the memory
  or time limit: exit 2, nothing written; a file of the user's in the output directory, or a file
  as --out: refused, kept; every refusal prints its one message and nothing on stdout.

Usage: test_sweep_cli.py FOGRADAR SOURCE_DIR"""
import csv
import json
import math
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

fogradar, source = sys.argv[1], sys.argv[2]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def sweep(sweep_file, out, *extra, expect=0):
    done = subprocess.run([fogradar, "sweep", "--sweep", sweep_file, "--out", out, *extra],
                          capture_output=True, text=True)
    check(done.returncode == expect, f"sweep {sweep_file} {extra}: exit {done.returncode}, "
                                     f"{done.stderr.strip()}")
    return done


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def same_tables(a, b, what):
    for name in ("points.csv", "results.csv", "limits.csv"):
        with open(os.path.join(a, name), "rb") as x, open(os.path.join(b, name), "rb") as y:
            check(x.read() == y.read(), f"{what}: {name} differs")


def p840_kl(f_ghz, t_c):
    """ITU-R P.840-8 eq. (2)-(9): specific attenuation coefficient K_l, (dB/km)/(g/m^3)."""
    theta = 300.0 / (t_c + 273.15)
    e0 = 77.66 + 103.3 * (theta - 1.0)
    e1 = 0.0671 * e0
    e2 = 3.52
    fp = 20.20 - 146.0 * (theta - 1.0) + 316.0 * (theta - 1.0) ** 2
    fs = 39.8 * fp
    e_im = f_ghz * (e0 - e1) / (fp * (1 + (f_ghz / fp) ** 2)) + \
        f_ghz * (e1 - e2) / (fs * (1 + (f_ghz / fs) ** 2))
    e_re = (e0 - e1) / (1 + (f_ghz / fp) ** 2) + (e1 - e2) / (1 + (f_ghz / fs) ** 2) + e2
    eta = (2 + e_re) / e_im
    return 0.819 * f_ghz / (e_im * (1 + eta ** 2))


with tempfile.TemporaryDirectory() as work:
    def write(name, text):
        path = os.path.join(work, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    # Fog density: the paper scenario at four densities.
    densities = [100.0, 300.0, 900.0, 2000.0]
    fog_file = write("fog.toml", "[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = [" +
                     ", ".join(map(str, densities)) + "]\n")
    fog_out = os.path.join(work, "fog")
    sweep(fog_file, fog_out, "--threads", "2")
    limits = rows(os.path.join(fog_out, "limits.csv"))
    lidar = [int(r["layers_to_failure"] or 99) for r in limits if r["sensor"] == "lidar"]
    check(len(lidar) == 4 and all(a >= b for a, b in zip(lidar, lidar[1:])),
          f"lidar layers to failure rise with density: {lidar}")
    results = rows(os.path.join(fog_out, "results.csv"))
    for point, beta in enumerate(densities):
        loss = [float(r["two_way_attenuation_db"]) for r in results
                if r["sensor"] == "radar" and r["point"] == str(point) and r["active_layers"] == "1"]
        fog = json.loads(subprocess.run([fogradar, "fog", "--extinction-per-km", str(beta), "--json"],
                                        capture_output=True, text=True, check=True).stdout)
        expected = fog["sensors"]["radar"]["two_way_loss_db_per_layer"]
        check(len(loss) == 1 and abs(loss[0] / expected - 1) < 1e-9,
              f"beta {beta}: radar loss per layer {loss} against fogradar fog's {expected}")

    # Frequency, zipped with bandwidth: P.840's frequency dependence.
    freq_file = write("freq.toml", """
[[axis]]
keys = ["radar.centre_frequency_hz", "radar.sweep_bandwidth_hz"]
values = [[94e9, 1e9], [24.125e9, 250e6], [77e9, 1e9]]
[sweep]
base = "radar_only.toml"
""")
    write("radar_only.toml", "[experiment]\nsensors = [\"radar\"]\n"
          "max_active_layers = 1\n[radar]\nchirps_per_frame = 16\nmeasurements_per_step = 5\n")
    freq_out = os.path.join(work, "freq")
    sweep(freq_file, freq_out)
    points = rows(os.path.join(freq_out, "points.csv"))
    loss = {float(p["radar.centre_frequency_hz"]): float(r["two_way_attenuation_db"])
            for p in points for r in rows(os.path.join(freq_out, "results.csv"))
            if r["point"] == p["point"] and r["active_layers"] == "1"}
    check(sorted(loss) == [24.125e9, 77e9, 94e9], f"frequency points {sorted(loss)}")
    for f_hz, value in loss.items():
        expected = p840_kl(f_hz / 1e9, 20.0) / p840_kl(77.0, 20.0)
        measured = value / loss[77e9]
        check(abs(measured / expected - 1) < 0.01,
              f"{f_hz / 1e9} GHz: loss ratio {measured:.5f} against P.840's {expected:.5f}")
        print(f"{f_hz / 1e9:g} GHz: loss / loss(77 GHz) {measured:.5f}, P.840 {expected:.5f}")

    # Threads, a SIGKILL and a resume, the values reversed: the same tables.
    small = write("small.toml", "[radar]\nmeasurements_per_step = 12\n[lidar]\n"
                  "scans_per_step = 6\n[camera]\nframes_per_step = 3\n")
    axis = "[sweep]\nbase = \"small.toml\"\n[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = "
    forward = write("forward.toml", axis + "[150.0, 300.0, 600.0, 900.0, 1500.0, 2500.0]\n")
    backward = write("backward.toml", axis + "[2500.0, 1500.0, 900.0, 600.0, 300.0, 150.0]\n")
    one, two = os.path.join(work, "t1"), os.path.join(work, "t2")
    start = time.monotonic()
    sweep(forward, one, "--threads", "1")
    whole = time.monotonic() - start
    sweep(forward, two, "--threads", "2")
    same_tables(one, two, "threads 1 and 2")
    sweep(backward, os.path.join(work, "back"), "--threads", "2")
    same_tables(one, os.path.join(work, "back"), "values reversed")
    killed = os.path.join(work, "killed")
    delay = random.Random().uniform(0.1, 0.9) * whole
    child = subprocess.Popen([fogradar, "sweep", "--sweep", forward, "--out", killed, "--threads", "1"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(delay)
    child.send_signal(signal.SIGKILL)
    child.wait()
    committed = len(os.listdir(os.path.join(killed, ".sweep"))) \
        if os.path.isdir(os.path.join(killed, ".sweep")) else 0
    resumed = sweep(forward, killed, "--resume")
    print(f"killed after {delay:.2f} s with {committed} points committed; resumed: "
          f"{resumed.stdout.strip().splitlines()[-1]}")
    same_tables(one, killed, f"resumed after SIGKILL at {delay:.2f} s")

    # A value added to an axis moves the points after it in the grid; resumed, every point computed
    # before is reused (committed by its resolved scenario, not its index) and the tables are a
    # fresh sweep's byte for byte.
    grid = ("[sweep]\nbase = \"small.toml\"\n[[axis]]\nkey = \"fog.extinction_per_km\"\n"
            "values = {}\n[[axis]]\nkey = \"radar.processing.cfar.training_cells\"\nvalues = [8, 16]\n")
    before = write("before.toml", grid.format("[300.0, 900.0]"))
    extended = write("extended.toml", grid.format("[300.0, 600.0, 900.0]"))
    grown, kept = os.path.join(work, "grown"), os.path.join(work, "kept")
    sweep(before, grown)
    sweep(before, kept, "--keep-points")
    resumed = sweep(extended, grown, "--resume").stdout
    check("2 points computed, 4 committed before" in resumed,
          f"a value added to an axis: {resumed.strip().splitlines()[-1]}")
    fresh = os.path.join(work, "fresh")
    sweep(extended, fresh)
    same_tables(fresh, grown, "a value added to an axis, resumed")
    check(sorted(os.listdir(os.path.join(grown, ".sweep"))) ==
          sorted(os.listdir(os.path.join(fresh, ".sweep"))), "the committed pieces of 6 points")
    # With --keep-points, points/<i>/ must be point i's: the two points that moved are made again.
    resumed = sweep(extended, kept, "--resume", "--keep-points").stdout
    check("4 points computed, 2 committed before" in resumed,
          f"a value added to an axis, --keep-points: {resumed.strip().splitlines()[-1]}")
    same_tables(fresh, kept, "a value added to an axis, resumed with --keep-points")
    for point in rows(os.path.join(kept, "points.csv")):
        with open(os.path.join(kept, "points", point["point"], "scenario.toml")) as f:
            text = f.read()
        check(f"extinction_per_km = {point['fog.extinction_per_km']}\n" in text and
              f"training_cells = {point['radar.processing.cfar.training_cells']}\n" in text,
              f"points/{point['point']}/scenario.toml is another point's")
    # Resumed without --keep-points: the result sets of points that moved are removed, not left
    # under another point's index (points 0 and 1 stayed where they were).
    unkept = os.path.join(work, "unkept")
    sweep(before, unkept, "--keep-points")
    sweep(extended, unkept, "--resume")
    left = sorted(os.listdir(os.path.join(unkept, "points")))
    check(left == ["0", "1"], f"points/ after a resume that moved points 2 and 3: {left}")

    # [uncertain] collapsed to the base's own values: the envelope is the single run.
    collapsed = write("collapsed.toml", """
[sweep]
base = "small.toml"
[uncertain]
setups = 3
[uncertain.keys."radar.height_m"]
distribution = "discrete"
values = [0.5]
[uncertain.keys."chamber.room.floor.material"]
distribution = "discrete"
values = ["concrete"]
[uncertain.keys."radar.polarisation"]
distribution = "discrete"
values = ["horizontal"]
""")
    envelope_out = os.path.join(work, "envelope")
    sweep(collapsed, envelope_out)
    nominal = {(r["sensor"], r["active_layers"]): r for r in rows(os.path.join(envelope_out, "results.csv"))}
    envelope = rows(os.path.join(envelope_out, "envelope.csv"))
    check(len(envelope) > 50, f"{len(envelope)} envelope rows")
    for e in envelope:
        value = nominal[(e["sensor"], e["active_layers"])][e["statistic"]]
        if value == "" or not math.isfinite(float(value)):
            check(e["p50"] == "" or e["setups"] == "0" or not math.isfinite(float(e["p50"])),
                  f"envelope of a missing value {e}")
            continue
        check(all(float(e[q]) == float(value) for q in ("p05", "p25", "p50", "p75", "p95")),
              f"collapsed envelope {e} against the run's {value}")
    for r in rows(os.path.join(envelope_out, "envelope_limits.csv")):
        check(r["setups"] == "3" and r["fraction"] == "1", f"collapsed limits {r}")

    # A known distribution: fog.extinction_per_km uniform on [200, 1000] /km in 40 Latin-hypercube
    # setups. The radar's loss rises with the extinction, so the envelope's type-7 q-quantile of the
    # loss is the loss at the sample's q-quantile of the extinction, and with one draw per stratum
    # (of width 20 /km) that lies between the strata's edges around position h = 39 q:
    # [200 + 20 floor(h), 200 + 20 (floor(h) + 2)], the loss at each edge from `fogradar fog`.
    known = write("known.toml", """
[sweep]
base = "radar_only.toml"
[uncertain]
setups = 40
[uncertain.keys."fog.extinction_per_km"]
distribution = "uniform"
low = 200.0
high = 1000.0
""")
    known_out = os.path.join(work, "known")
    sweep(known, known_out)
    loss_row = [e for e in rows(os.path.join(known_out, "envelope.csv"))
                if e["sensor"] == "radar" and e["active_layers"] == "1"
                and e["statistic"] == "two_way_attenuation_db"]
    check(len(loss_row) == 1 and loss_row[0]["setups"] == "40", f"loss envelope rows {loss_row}")

    def fog_loss(beta):
        done = subprocess.run([fogradar, "fog", "--extinction-per-km", repr(beta), "--json"],
                              capture_output=True, text=True, check=True)
        return json.loads(done.stdout)["sensors"]["radar"]["two_way_loss_db_per_layer"]

    for column, q in (("p05", 0.05), ("p25", 0.25), ("p50", 0.5), ("p75", 0.75), ("p95", 0.95)):
        h = math.floor(39 * q)
        low, high = fog_loss(200.0 + 20.0 * h), fog_loss(200.0 + 20.0 * (h + 2))
        value = float(loss_row[0][column]) if loss_row else math.nan
        check(low <= value <= high, f"envelope {column} {value} outside [{low}, {high}]")
        print(f"envelope {column} of the loss: {value:.5f} dB in [{low:.5f}, {high:.5f}]")

    # Bad input: one message with file and line, exit 2, nothing written; the user's file kept.
    bad = write("bad.toml", "[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = [900.0, -5.0]\n")
    nowhere = os.path.join(work, "nowhere")
    done = sweep(bad, nowhere, expect=2)
    check(done.stderr.startswith(f"fogradar: {bad}:1: axis[0] value -5.0 of fog.extinction_per_km")
          and done.stderr.count("\n") == 1, f"bad sweep message: {done.stderr!r}")
    check(not os.path.exists(nowhere), "a refused sweep created its directory")
    done = sweep(forward, nowhere, "--memory-limit-mib", "1", expect=2)
    check(done.stdout == "" and "--memory-limit-mib" in done.stderr and not os.path.exists(nowhere),
          f"over the memory limit: {done.stdout!r} {done.stderr!r}")
    mine = os.path.join(work, "mine")
    os.makedirs(mine)
    with open(os.path.join(mine, "notes.txt"), "w") as f:
        f.write("mine")
    done = sweep(forward, mine, expect=2)
    check("--out" in done.stderr and "notes.txt" in done.stderr, f"user's file: {done.stderr!r}")
    check(os.listdir(mine) == ["notes.txt"], f"the user's directory now holds {os.listdir(mine)}")
    # A refused sweep prints its one message and nothing else: no estimate line before it.
    check(done.stdout == "" and done.stderr.count("\n") == 1,
          f"refused --out with the user's file printed {done.stdout!r} {done.stderr!r}")
    a_file = os.path.join(work, "a-file")
    with open(a_file, "w") as f:
        f.write("mine")
    done = sweep(forward, a_file, expect=2)
    check(done.stdout == "" and done.stderr.count("\n") == 1
          and f"--out = '{a_file}'" in done.stderr and "a directory" in done.stderr,
          f"--out naming a file: {done.stdout!r} {done.stderr!r}")
    done = sweep(forward, nowhere, "--time-limit", "0.001", expect=2)
    check(done.stdout == "" and done.stderr.count("\n") == 1 and "--time-limit" in done.stderr
          and not os.path.exists(nowhere), f"over the time limit: {done.stdout!r} {done.stderr!r}")

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
