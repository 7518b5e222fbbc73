#!/usr/bin/python3
"""`fogradar sweep` on MPI ranks (docs/scale-out.md): parallel efficiency from 1 to 2 ranks, rank
0's bookkeeping per point, and the numbers the scale model takes.

- Speed-up: a 16-point sweep of the paper scenario (measurements_per_step = 600, one thread per
  rank, about 9 s on one rank), timed whole (mpirun included) as `mpirun -n 1` and `mpirun -n 2`,
  and as one process without MPI, in turn, round by round; the speed-up t(-n 1) / t(-n 2) per
  round as median [min, max]. The contract: at least 1.85 on this 2-core machine. mpirun's start (a few tenths of a
  second, the difference between `-n 1` and no MPI) is not divided: a shorter sweep gains less.
- Bookkeeping: rank 0's time per message of a worker (receiving the point's piece, committing it
  with its fsyncs, answering with the next point), as the command prints it, from a sweep of 48
  cheap points on 2 ranks (one message every few milliseconds).
- The model: points per second on R ranks = min(R / (t_point + t_wait), 1 / t_message), with
  t_point the single rank's time per point, t_message rank 0's time per message and t_wait a
  worker's wait for its next point: t_message plus half of rank 0's 2 ms polling period.

Usage: bench/mpi_scaling.py [-n ROUNDS] [--fogradar PATH] [--mpiexec PATH] [--ranks R]"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import tempfile
import time

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser()
parser.add_argument("-n", "--rounds", type=int, default=3)
parser.add_argument("--fogradar", default=os.path.join(root, "build/release/cli/fogradar"))
parser.add_argument("--mpiexec", default="mpiexec")
parser.add_argument("--ranks", type=int, default=2, help="the largest job (default 2)")
args = parser.parse_args()
launcher = [args.mpiexec, "--oversubscribe", "--bind-to", "none"]
if os.geteuid() == 0:
    launcher.append("--allow-run-as-root")


def timed(command):
    start = time.perf_counter()
    done = subprocess.run(command, check=True, capture_output=True, text=True)
    return time.perf_counter() - start, done.stdout


def summary(values, digits=3):
    return (f"{statistics.median(values):.{digits}f} "
            f"[{min(values):.{digits}f}, {max(values):.{digits}f}]")


work = tempfile.mkdtemp(prefix="fogradar-mpi-scaling-")
try:
    def write(name, text):
        path = os.path.join(work, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    write("base.toml", "[radar]\nmeasurements_per_step = 600\n")
    points = 16
    values = ", ".join("%.1f" % (300.0 + 50.0 * i) for i in range(points))
    heavy = write("heavy.toml", f"[sweep]\nbase = \"base.toml\"\n[[axis]]\n"
                  f"key = \"fog.extinction_per_km\"\nvalues = [{values}]\n")
    cheap_values = ", ".join("%.1f" % (300.0 + 10.0 * i) for i in range(48))
    write("cheap_base.toml", "[experiment]\nsensors = [\"radar\"]\n"
          "max_active_layers = 1\n[radar]\nchirps_per_frame = 16\nmeasurements_per_step = 4\n")
    cheap = write("cheap.toml", f"[sweep]\nbase = \"cheap_base.toml\"\n[[axis]]\n"
                  f"key = \"fog.extinction_per_km\"\nvalues = [{cheap_values}]\n")

    def sweep(sweep_file, ranks):
        out = os.path.join(work, f"out{ranks}")
        shutil.rmtree(out, ignore_errors=True)
        command = [args.fogradar, "sweep", "--sweep", sweep_file, "--out", out, "--threads", "1"]
        return timed(command if ranks == 0 else launcher + ["-n", str(ranks)] + command)

    rank_counts = sorted({1, 2, args.ranks})
    times = {r: [] for r in [0] + rank_counts}
    speed_up = {r: [] for r in rank_counts if r > 1}
    bookkeeping = []
    for _ in range(args.rounds):
        for r in [0] + rank_counts:
            seconds, stdout = sweep(heavy, r)
            times[r].append(seconds)
        for r in speed_up:
            speed_up[r].append(times[1][-1] / times[r][-1])
        _, stdout = sweep(cheap, 2)
        bookkeeping.append(float(re.search(r"rank 0 spent ([0-9.e+-]+) ms", stdout).group(1)))
    print(f"{args.rounds} rounds, {points} points, one thread per rank; "
          "wall seconds median [min, max]:")
    print(f"  one process without MPI: {summary(times[0])}")
    for r in rank_counts:
        print(f"  mpirun -n {r}: {summary(times[r])}")
    for r, values in speed_up.items():
        print(f"  speed-up 1 -> {r} ranks: {summary(values)} "
              f"(parallel efficiency {statistics.median(values) / r:.3f})")
    print(f"  mpirun -n 1 / no MPI: {summary([a / b for a, b in zip(times[1], times[0])])}")
    t_point = statistics.median(times[1]) / points
    t_message = statistics.median(bookkeeping) / 1e3
    t_wait = t_message + 1e-3
    print("rank 0's bookkeeping per message (48 cheap points on 2 ranks): "
          f"{summary(bookkeeping)} ms")
    print(f"model, t_point = {t_point:.3f} s (the single rank's wall time / {points}), "
          f"t_message = {t_message * 1e3:.3f} ms, t_wait = {t_wait * 1e3:.3f} ms:")
    print("  ranks  points/s  efficiency")
    for r in (1, 2, 16, 64, 256, 1024, 4096):
        rate = min(r / (t_point + t_wait), 1 / t_message)
        print(f"  {r:5d}  {rate:8.1f}  {rate * t_point / r:10.3f}")
finally:
    shutil.rmtree(work, ignore_errors=True)
