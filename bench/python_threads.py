#!/usr/bin/python3
"""What releasing the GIL gives the Python module (docs/python.md, docs/performance.md): the wall
time of two Python threads measuring radar frames in parallel (each half of them, one Simulator
shared) over that of one thread measuring all of them, interleaved round by round, as
median [min, max]. The contract: at most 0.6 on 2 cores.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_threads.py [-n ROUNDS]
        [--frames N] [--scenario FILE]
"""
import argparse
import statistics
import threading
import time

import fogradar


def measure(sim, indices, keep):
    for i in indices:
        sim.measure("radar", 0, i, keep=keep)


def timed(sim, groups, keep):
    threads = [threading.Thread(target=measure, args=(sim, g, keep)) for g in groups]
    start = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return time.perf_counter() - start


def summary(values):
    return f"{statistics.median(values):.4f} [{min(values):.4f}, {max(values):.4f}]"


parser = argparse.ArgumentParser()
parser.add_argument("-n", "--rounds", type=int, default=9)
parser.add_argument("--frames", type=int, default=400)
parser.add_argument("--scenario", default=None, help="default: the paper scenario's radar")
args = parser.parse_args()
scenario = (fogradar.Scenario.from_file(args.scenario) if args.scenario
            else fogradar.Scenario.paper())
scenario = scenario.with_overrides({"experiment.sensors": ["radar"],
                                    "radar.measurements_per_step": args.frames})
sim = fogradar.Simulator(scenario)
keep = ("range_doppler", "detections")
frames = list(range(args.frames))
one, two = [frames], [frames[0::2], frames[1::2]]
timed(sim, one, keep)  # warm-up
ones, twos = [], []
for _ in range(args.rounds):
    ones.append(timed(sim, one, keep))
    twos.append(timed(sim, two, keep))
print(f"{args.frames} frames of {sim.scenario.to_dict()['radar']['chirps_per_frame']} chirps, "
      f"kept {', '.join(keep)}")
print(f"one thread   {summary(ones)} s")
print(f"two threads  {summary(twos)} s")
print(f"two / one    {summary([b / a for a, b in zip(ones, twos)])} ({args.rounds} rounds)")
