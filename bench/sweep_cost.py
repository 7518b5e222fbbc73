#!/usr/bin/python3
"""What a sweep costs against running its points one by one (docs/sweep.md, docs/performance.md):
a 40-point sweep of the paper scenario, timed as `fogradar sweep` and as 40 `fogradar run`s of the
same points' scenarios, in turn, round by round; CPU seconds (user + system of the child processes)
and wall seconds, and their ratios sweep / runs as median [min, max]. Two sweeps: over
fog.extinction_per_km (every sensor's optics change from point to point) and over
radar.processing.cfar.training_cells (only the radar's CFAR changes: the lidar and the camera are made
once). The contract: at most 1.15 for the first, less for the second.

Usage: bench/sweep_cost.py [-n ROUNDS] [--fogradar PATH] [--threads N]"""
import argparse
import os
import resource
import shutil
import statistics
import subprocess
import tempfile
import time

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser()
parser.add_argument("-n", "--rounds", type=int, default=3)
parser.add_argument("--fogradar", default=os.path.join(root, "build/release/cli/fogradar"))
parser.add_argument("--threads", default="2")
args = parser.parse_args()


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(commands):
    cpu, wall = children_cpu(), time.perf_counter()
    for command in commands:
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return children_cpu() - cpu, time.perf_counter() - wall


def summary(values):
    return f"{statistics.median(values):.3f} [{min(values):.3f}, {max(values):.3f}]"


cases = {
    "fog.extinction_per_km": ["%.1f" % (100.0 + 50.0 * i) for i in range(40)],
    "radar.processing.cfar.training_cells": [str(8 + i) for i in range(40)],
}
work = tempfile.mkdtemp(prefix="fogradar-sweep-cost-")
try:
    for key, values in cases.items():
        section, name = key.rsplit(".", 1)
        sweep_file = os.path.join(work, "sweep.toml")
        with open(sweep_file, "w") as f:
            f.write(f"[[axis]]\nkey = \"{key}\"\nvalues = [{', '.join(values)}]\n")
        runs = []
        for i, value in enumerate(values):
            path = os.path.join(work, f"point{i}.toml")
            with open(path, "w") as f:
                f.write(f"[{section}]\n{name} = {value}\n")
            runs.append([args.fogradar, "run", "--scenario", path, "--out",
                         os.path.join(work, "run-out"), "--threads", args.threads])
        sweep = [[args.fogradar, "sweep", "--sweep", sweep_file, "--out",
                  os.path.join(work, "sweep-out"), "--threads", args.threads]]
        cpu_ratio, wall_ratio, sweep_cpu, runs_cpu = [], [], [], []
        for _ in range(args.rounds):
            s_cpu, s_wall = timed(sweep)
            r_cpu, r_wall = timed(runs)
            sweep_cpu.append(s_cpu)
            runs_cpu.append(r_cpu)
            cpu_ratio.append(s_cpu / r_cpu)
            wall_ratio.append(s_wall / r_wall)
        print(f"{key}, 40 points, --threads {args.threads}, {args.rounds} rounds:")
        print(f"  CPU s: sweep {summary(sweep_cpu)}, 40 runs {summary(runs_cpu)}")
        print(f"  sweep / runs: CPU {summary(cpu_ratio)}, wall {summary(wall_ratio)}")
finally:
    shutil.rmtree(work)
