#!/usr/bin/python3
"""What writing raw data costs a run, against the time the disk takes to write the same bytes.

Runs, in turn and RUNS times over: `fogradar run` without --raw, the same run with --raw FILE and
the given selection, and a plain write of as many bytes as that FILE holds (os.write in 8 MiB
blocks, then fsync, as fogradar's file is synced before it is published), all into the same
directory. Prints each one's wall seconds and, taken round by round, the raw data's extra time
(with - without) over the plain write time, as median [min, max]. The contract
(docs/performance.md): at most 1.1.

Usage: bench/raw_cost.py [-n RUNS] [--fogradar PATH] [--scenario FILE] [--threads N]
                         [--select KINDS] [--items LIST] [--dir DIR]"""
import argparse
import os
import shutil
import statistics
import subprocess
import tempfile
import time


def timed(command):
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def timed_write(path, size):
    block = b"\0" * (8 << 20)
    start = time.perf_counter()
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    try:
        left = size
        while left > 0:
            left -= os.write(fd, block[: min(left, len(block))])
        os.fsync(fd)
    finally:
        os.close(fd)
    return time.perf_counter() - start


def summary(values, unit=""):
    return f"{statistics.median(values):.4f}{unit} [{min(values):.4f}, {max(values):.4f}]"


root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser()
parser.add_argument("-n", "--runs", type=int, default=7)
parser.add_argument("--fogradar", default=os.path.join(root, "build/release/cli/fogradar"))
parser.add_argument("--scenario", default=os.path.join(root, "examples/bench.toml"))
parser.add_argument("--threads", default="2")
parser.add_argument("--select", default="radar.beat,radar.range_doppler")
parser.add_argument("--items", default=None,
                    help="--raw-items (default: fogradar's, the first ten)")
parser.add_argument("--dir", default=None, help="where the files go (default: a new one in /tmp)")
args = parser.parse_args()

work = tempfile.mkdtemp(prefix="fogradar-raw-cost-", dir=args.dir)
try:
    raw = os.path.join(work, "raw.h5")
    plain = os.path.join(work, "plain.bin")
    base = [args.fogradar, "run", "--scenario", args.scenario, "--threads", args.threads]
    without = base + ["--out", os.path.join(work, "out-without")]
    with_raw = base + ["--out", os.path.join(work, "out-with"), "--raw", raw,
                       "--raw-select", args.select]
    if args.items is not None:
        with_raw += ["--raw-items", args.items]
    timed(without)  # warm-up: page cache, FFTW wisdom
    timed(with_raw)
    size = os.path.getsize(raw)
    times = {"without": [], "with": [], "write": []}
    for _ in range(args.runs):
        times["without"].append(timed(without))
        times["with"].append(timed(with_raw))
        times["write"].append(timed_write(plain, size))
    print(f"raw file {size} bytes ({size / (1 << 20):.1f} MiB): {args.select}")
    for name, values in times.items():
        print(f"{name:8s} {summary(values, ' s')}")
    extra = [w - o for w, o in zip(times["with"], times["without"])]
    print(f"extra    {summary(extra, ' s')}")
    print(f"extra / write {summary([e / t for e, t in zip(extra, times['write'])])} "
          f"({args.runs} rounds)")
finally:
    shutil.rmtree(work)
