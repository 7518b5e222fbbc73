#!/usr/bin/python3
"""The run-time estimate against the measured wall and CPU time, for every example.

Runs `fogradar run` on each examples/*.toml at --threads 1 and 2 and `fogradar sweep` on each
examples/sweeps/*.toml at --threads 1 and 2, parses the estimate each prints on its first line,
times the whole process (start to exit, results written: wall time, and user + system CPU time of
all its threads) and prints estimate / measured for both. The estimate's CPU time is its set-up
plus every item (`run`: "set-up and files" plus each sensor's items x item time; `sweep`: "of
CPU"). Medians of --repeats runs. On a machine shared with other work the wall ratio falls below 1
by the share of the cores the run did not get; the CPU ratio does not depend on it. The load
average is printed before and after.

    /usr/bin/python3 bench/estimate_ratio.py [--fogradar build/release/cli/fogradar] [--repeats 3]
    /usr/bin/python3 bench/estimate_ratio.py --property-seeds 0-49

--property-seeds FIRST-LAST runs, instead of the examples, the property checker's random scenarios
of those seeds (tests/property/scenario_generator.cpp, printed by the property_scenario program of
the same build, --property-scenario) with `fogradar run` at --threads 1 and 2.

Exit status 1 when a wall ratio lies outside [0.5, 2] (docs/scenario.md, "Time limit").
"""
import argparse
import os
import pathlib
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6}
NUMBER = r"([0-9.e+-]+) (s|ms|us)"
RUN_ESTIMATE = re.compile(r"estimated time: " + NUMBER + r" on .*\((.*); set-up and files " + NUMBER + r"\)")
RUN_PART = re.compile(r"[a-z]+ ([0-9]+) x " + NUMBER)
SWEEP_ESTIMATE = re.compile(r"; about " + NUMBER + r" \(cost models; " + NUMBER + r" of CPU\)")


def seconds(number, unit):
    return float(number) * UNITS[unit]


def estimates(command, stdout):
    match = (RUN_ESTIMATE if command == "run" else SWEEP_ESTIMATE).search(stdout)
    if match is None:
        sys.exit(f"no estimate in the output of fogradar {command}:\n{stdout[:300]}")
    wall = seconds(match.group(1), match.group(2))
    if command == "sweep":
        return wall, seconds(match.group(3), match.group(4))
    cpu = seconds(match.group(4), match.group(5))
    for items, number, unit in RUN_PART.findall(match.group(3)):
        cpu += int(items) * seconds(number, unit)
    return wall, cpu


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(command, out):
    """(stdout, wall seconds, CPU seconds) of one run of `command`."""
    shutil.rmtree(out, ignore_errors=True)
    cpu = children_cpu()
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"{' '.join(map(str, command))} failed ({done.returncode}):\n{done.stderr}")
    return done.stdout, wall, children_cpu() - cpu


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fogradar", default=str(ROOT / "build/release/cli/fogradar"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--only", default="", help="run only the examples whose path contains this")
    parser.add_argument("--property-seeds", metavar="FIRST-LAST",
                        help="the property checker's scenarios of these seeds instead of the examples")
    parser.add_argument("--property-scenario",
                        default=str(ROOT / "build/release/tests/property_scenario"))
    args = parser.parse_args()
    scratch_dir = tempfile.TemporaryDirectory()
    cases = []
    if args.property_seeds:
        match = re.fullmatch(r"([0-9]+)-([0-9]+)", args.property_seeds)
        if match is None or int(match.group(1)) > int(match.group(2)):
            print(f"--property-seeds {args.property_seeds!r}: must be FIRST-LAST with "
                  "0 <= FIRST <= LAST", file=sys.stderr)
            return 2
        for seed in range(int(match.group(1)), int(match.group(2)) + 1):
            toml = pathlib.Path(scratch_dir.name) / f"seed_{seed}.toml"
            toml.write_text(subprocess.run([args.property_scenario, str(seed)], check=True,
                                           capture_output=True, text=True).stdout)
            cases += [(toml, threads, "run") for threads in (1, 2)]
    else:
        for toml in sorted((ROOT / "examples").glob("*.toml")):
            cases += [(toml, threads, "run") for threads in (1, 2)]
        for toml in sorted((ROOT / "examples/sweeps").glob("*.toml")):
            cases += [(toml, threads, "sweep") for threads in (1, 2)]
    print(f"load average before: {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    print(f"{'example':<40} {'threads':>7} {'est wall':>9} {'wall':>8} {'ratio':>6}"
          f" {'est CPU':>9} {'CPU':>8} {'ratio':>6}")
    ratios, cpu_ratios = [], []
    with scratch_dir, tempfile.TemporaryDirectory() as scratch:
        out = pathlib.Path(scratch) / "out"
        for toml, threads, command in cases:
            name = toml.stem if args.property_seeds else str(toml.relative_to(ROOT))
            if args.only not in name:
                continue
            flag = "--scenario" if command == "run" else "--sweep"
            runs = [timed([args.fogradar, command, flag, str(toml), "--out", str(out),
                           "--threads", str(threads)], out) for _ in range(args.repeats)]
            est_wall, est_cpu = estimates(command, runs[0][0])
            wall = statistics.median(w for _, w, _ in runs)
            cpu = statistics.median(c for _, _, c in runs)
            ratios.append(est_wall / wall)
            cpu_ratios.append(est_cpu / cpu)
            print(f"{name:<40} {threads:>7} {est_wall:>9.3f} {wall:>8.3f} {est_wall / wall:>6.2f}"
                  f" {est_cpu:>9.3f} {cpu:>8.3f} {est_cpu / cpu:>6.2f}", flush=True)
    print(f"load average after: {os.getloadavg()[0]:.2f}")
    if ratios:
        print(f"wall ratios in [{min(ratios):.2f}, {max(ratios):.2f}], "
              f"CPU ratios in [{min(cpu_ratios):.2f}, {max(cpu_ratios):.2f}]")
    return 0 if all(0.5 <= r <= 2.0 for r in ratios) else 1


if __name__ == "__main__":
    sys.exit(main())
