#!/usr/bin/python3
"""What the room costs (docs/performance.md): the paper scenario as shipped (its hall: a concrete
floor, a wall on the left, four barrels) and a full room over it (the paper's hall plus a right
wall, a ceiling, a back wall and a metal plate: all five planes, every second-order image path)
against the paper scenario in an empty hall (no floor, walls or objects), whole processes at one
thread, run in turn empty, paper, full, round by round. Prints each one's CPU seconds (user +
system of the child process: at one thread its wall time on a quiet machine, and less disturbed by
other work on a shared one) and wall seconds, and the ratios paper/empty and full/empty of each
taken round by round, as median [min, max]. The contract: the paper's room at most 1.3 x the empty
hall.

Usage: bench/room_cost.py [-n ROUNDS] [--fogradar PATH] [--threads N]"""
import argparse
import os
import resource
import statistics
import subprocess
import tempfile
import time

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser()
parser.add_argument("-n", "--rounds", type=int, default=15)
parser.add_argument("--fogradar", default=os.path.join(root, "build/release/cli/fogradar"))
parser.add_argument("--threads", default="1")
args = parser.parse_args()

EMPTY = """[chamber]
objects = []
[chamber.room]
floor = false
left_wall = false
"""
FULL = """[chamber.room]
right_wall = { distance_m = 3.0, material = "concrete" }
ceiling = { height_m = 5.0, material = "concrete" }
back_wall = { distance_m = 14.0, material = "concrete" }
[[chamber.objects]]
shape = "plate"
x_m = 6.0
y_m = 2.0
material = "metal"
"""


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(command):
    cpu, wall = children_cpu(), time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return children_cpu() - cpu, time.perf_counter() - wall


def summary(values, unit=""):
    return f"{statistics.median(values):.4f}{unit} [{min(values):.4f}, {max(values):.4f}]"


with tempfile.TemporaryDirectory() as work:
    commands = {}
    for name, text in (("empty", EMPTY), ("paper", None), ("full", FULL)):
        command = [args.fogradar, "run", "--threads", args.threads,
                   "--out", os.path.join(work, name)]
        if text is not None:
            path = os.path.join(work, name + ".toml")
            with open(path, "w") as f:
                f.write(text)
            command += ["--scenario", path]
        commands[name] = command
    for command in commands.values():
        timed(command)  # warm-up: the binary and its data in the page cache
    times = {name: [] for name in commands}
    for _ in range(args.rounds):
        for name, command in commands.items():
            times[name].append(timed(command))
for name, values in times.items():
    print(f"{name:6s} CPU {summary([v[0] for v in values], ' s')}  "
          f"wall {summary([v[1] for v in values], ' s')}")
for name in ("paper", "full"):
    pairs = list(zip(times[name], times["empty"]))
    print(f"{name}/empty CPU {summary([x[0] / y[0] for x, y in pairs])}  "
          f"wall {summary([x[1] / y[1] for x, y in pairs])}  ({args.rounds} rounds)")
