#!/usr/bin/env python3
"""Where a `fogradar run` spends its time, stage by stage (docs/performance.md, "Where the time goes").

Samples one run with `perf record` (Debian package linux-perf; on a VM without hardware counters perf
falls back to cpu-clock samples), then sums the samples of each function into the chain's stages by
function and library name. Prints each stage's share of all samples and, given --ratio (the run's
end to end over its FFT floor, from bench/throughput), that share times the ratio: the stage's cost
in units of the floor.

Usage:
  bench/stage_profile.py --fogradar build/release/cli/fogradar --scenario examples/bench_small.toml \
      [--measurements 1000] [--threads 1] [--frequency 5000] [--ratio 2.2] [--show-other 10]

--measurements rewrites radar.measurements_per_step in a copy of the scenario, to collect more
samples from a small frame. The grouping is by name only: a function shared by two stages (libm's
sine and cosine serve the scene's paths and the peak searches) counts where the table below puts it.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

# (stage, pattern on "library symbol"), first match wins; the order matters where names overlap.
STAGES = [
    ("FFTW codelets (range and Doppler FFTs)", r"^libfftw3"),
    ("Doppler column-block gather and write-back", r"memmove|memcpy|ColumnBlockFft"),
    ("thermal noise", r"complex_normal|finish_slow|ComplexNormalGenerator"),
    ("tone synthesis", r"add_tone|fill_tone_powers|tone_step|synthesize_frame|beat_frequency_hz|doppler_shift_hz"),
    ("scene paths (scene_tones and its libm calls)",
     r"scene_tones|received_power_w|two_way|backscatter_cross_section|gaussian_beam|RandomStream"
     r"|^libm\S* .*(sincos|pow|exp|log|atan|hypot|sin|cos)"),
    ("|X|^2 (with the first window-sum pass)", r"squared_magnitudes|interleave_norms"),
    ("CFAR", r"Cfar|cfar|interior_thresholds|add_cells|accumulate_cells|reference_cells|window_sums"
             r"|two_sided_detect|scan_cells"),
    ("row interpolation", r"rows_times_kernels|interpolate_rows|dirichlet_weights"),
    ("peak searches, grouping, RCS",
     r"find_peak|sum_over_sines|dtft_derivatives|take_object|estimate_detections|brent|FractionalBinPower"
     r"|TimeSignalDtft|WindowSpectrum|OriginClassifier|attribution|InverseDft"),
    ("start-up (Mie sums, plans, workspaces, CFAR design)",
     r"mie_|__divdc3|Chamber::|Fog::|RangeDopplerProcessor::RangeDopplerProcessor|make_workspace"
     r"|design_cfar|chirp_plan_with_batch_bits|FftPlan::FftPlan|Eigen::|SegelsteinTable|_dl_|^ld-linux"),
    ("statistics and result files", r"stats::|hodges_lehmann|median_shift|write_|json|toml"),
    ("kernel", r"^\[kernel"),
]


def with_measurements(scenario, measurements):
    text = open(scenario, encoding="utf-8").read()
    text, count = re.subn(r"(?m)^measurements_per_step\s*=.*$", f"measurements_per_step = {measurements}", text)
    if count != 1:
        sys.exit(f"stage_profile.py: {scenario} has no single measurements_per_step line to rewrite")
    handle = tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False)
    handle.write(text)
    handle.close()
    return handle.name


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fogradar", required=True)
    parser.add_argument("--scenario", required=True)
    parser.add_argument("--measurements", type=int)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--frequency", type=int, default=5000)
    parser.add_argument("--ratio", type=float, help="end to end / floor of the run, from bench/throughput")
    parser.add_argument("--show-other", type=int, default=0, metavar="N",
                        help="also list the N largest functions no stage claims")
    args = parser.parse_args()

    scenario = with_measurements(args.scenario, args.measurements) if args.measurements else args.scenario
    with tempfile.TemporaryDirectory() as work:
        data = os.path.join(work, "perf.data")
        subprocess.run(["perf", "record", "-q", "-F", str(args.frequency), "-o", data, args.fogradar, "run",
                        "--scenario", scenario, "--out", os.path.join(work, "out"), "--threads",
                        str(args.threads)], check=True, stdout=subprocess.DEVNULL)
        # Sample counts (-n), not perf's rounded percentages: a stripped library such as FFTW shows
        # every sampled address as its own entry, thousands of them under 0.01 %.
        report = subprocess.run(["perf", "report", "-i", data, "--no-children", "-n", "--sort", "dso,sym",
                                 "--stdio", "--percent-limit", "0"], check=True, capture_output=True,
                                text=True).stdout
    if args.measurements:
        os.unlink(scenario)

    shares = {stage: 0.0 for stage, _ in STAGES}
    shares["other"] = 0.0
    unclaimed = []
    line_pattern = re.compile(r"^\s*[\d.]+%\s+(\d+)\s+(\S+)\s+\[[.k]\]\s+(.*)$")
    entries = []
    for line in report.splitlines():
        match = line_pattern.match(line)
        if match:
            entries.append((int(match.group(1)), match.group(2), match.group(3).strip()))
    total = sum(count for count, _, _ in entries)
    if total == 0:
        sys.exit("stage_profile.py: perf recorded no samples")
    for count, library, symbol in entries:
        share = 100.0 * count / total
        key = f"{library} {symbol}"
        stage = next((name for name, pattern in STAGES if re.search(pattern, key)), "other")
        shares[stage] += share
        if stage == "other":
            unclaimed.append((share, key))

    print(f"{args.scenario}, {args.threads} thread(s), perf at {args.frequency} Hz, {total} samples; "
          f"load {open('/proc/loadavg').read().strip()}")
    header = f"  {'stage':<52} {'share':>7}"
    if args.ratio:
        header += f" {'x floor':>8}"
    print(header)
    for stage, share in sorted(shares.items(), key=lambda item: -item[1]):
        row = f"  {stage:<52} {share:6.1f}%"
        if args.ratio:
            row += f" {share / 100.0 * args.ratio:8.2f}"
        print(row)
    for share, key in sorted(unclaimed, reverse=True)[: args.show_other]:
        print(f"    other: {share:5.2f}%  {key}")


if __name__ == "__main__":
    main()
