#!/usr/bin/python3
"""Times two whole commands in turn, A B A B ..., and prints each one's wall seconds and the ratio
A/B taken pair by pair (pairing keeps the ratio meaningful when the shared machine's speed drifts),
as median [min, max]. What the commands print is thrown away.

Usage: bench/interleave.py [-n RUNS] [--warmup W] --a 'COMMAND A' --b 'COMMAND B'
(commands split as a shell splits words; no shell runs them)."""
import argparse
import shlex
import statistics
import subprocess
import time


def timed(command):
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def summary(values, unit=""):
    return f"{statistics.median(values):.4f}{unit} [{min(values):.4f}, {max(values):.4f}]"


parser = argparse.ArgumentParser()
parser.add_argument("-n", "--runs", type=int, default=11)
parser.add_argument("--warmup", type=int, default=1)
parser.add_argument("--a", required=True)
parser.add_argument("--b", required=True)
args = parser.parse_args()
a, b = shlex.split(args.a), shlex.split(args.b)
for _ in range(args.warmup):
    timed(a)
    timed(b)
times_a, times_b = [], []
for _ in range(args.runs):
    times_a.append(timed(a))
    times_b.append(timed(b))
print(f"A {summary(times_a, ' s')}  B {summary(times_b, ' s')}  ({args.runs} pairs)")
print(f"A/B {summary([x / y for x, y in zip(times_a, times_b)])}")
