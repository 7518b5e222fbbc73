#!/usr/bin/env bash
# Peak memory of the real `fogradar run` on the bench workload (examples/bench.toml, 128 chirps x
# 1024 samples, 5 layer steps) at two numbers of measurements per step (default 200 and 2000), to
# check the performance contract (docs/architecture.md): memory must not grow with the number of measurements beyond the stored per-
# measurement records (frames are streamed, one per worker thread). Each run uses a temporary copy of
# bench.toml in which only [radar] measurements_per_step is changed, writes its result files
# into a temporary directory (removed afterwards), and is measured with GNU time's
# `/usr/bin/time -v` ("Maximum resident set size", KiB).
#
# Usage: bench/peak_memory.sh [FOGRADAR_BINARY] [MEASUREMENTS_A] [MEASUREMENTS_B]
#   FOGRADAR_BINARY  default build/perf/cli/fogradar (cmake --build build/perf --target fogradar)
# Extra `fogradar run` options can be given in FOGRADAR_RUN_ARGS, e.g. FOGRADAR_RUN_ARGS="--threads 1".
# Needs GNU time: Debian/Ubuntu `apt-get install time` (the shell builtin `time` has no -v).
# 2000 measurements per step are 10000 frames: about 10 x the time of one bench run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
binary=${1:-$root/build/perf/cli/fogradar}
counts=("${2:-200}" "${3:-2000}")
scenario=$root/examples/bench.toml

if [[ ! -x /usr/bin/time ]]; then
  echo "peak_memory.sh: /usr/bin/time (GNU time) not found; install it with: apt-get install time" >&2
  exit 2
fi
if [[ ! -x $binary ]]; then
  echo "peak_memory.sh: $binary not found; build it with:" >&2
  echo "  cmake -S . -B build/perf -G Ninja -DCMAKE_BUILD_TYPE=Release && cmake --build build/perf --target fogradar" >&2
  exit 2
fi
if ! grep -q '^measurements_per_step *=' "$scenario"; then
  echo "peak_memory.sh: $scenario has no measurements_per_step line to override" >&2
  exit 2
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "fogradar peak memory: $binary run --scenario <bench.toml with measurements_per_step = N> ${FOGRADAR_RUN_ARGS:-}"
echo "  CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'); $(nproc) cores; load average $(cut -d' ' -f1-3 /proc/loadavg)"
declare -A rss_kib
for n in "${counts[@]}"; do
  sed "s/^measurements_per_step *=.*/measurements_per_step = $n/" "$scenario" >"$work/bench_$n.toml"
  # shellcheck disable=SC2086  # FOGRADAR_RUN_ARGS is meant to split into options
  /usr/bin/time -v -o "$work/time_$n.txt" "$binary" run --scenario "$work/bench_$n.toml" \
    --out "$work/out_$n" ${FOGRADAR_RUN_ARGS:-} >"$work/stdout_$n.txt" 2>"$work/stderr_$n.txt" || {
    echo "peak_memory.sh: fogradar run failed for measurements_per_step = $n:" >&2
    cat "$work/stderr_$n.txt" "$work/time_$n.txt" >&2
    exit 1
  }
  rss_kib[$n]=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time_$n.txt")
  wall=$(awk -F': ' '/Elapsed \(wall clock\) time/ {print $2}' "$work/time_$n.txt")
  frames=$((5 * n))
  printf '  measurements_per_step %6d (%6d frames): maximum resident set size %8d KiB = %7.1f MiB (wall %s)\n' \
    "$n" "$frames" "${rss_kib[$n]}" "$(awk -v k="${rss_kib[$n]}" 'BEGIN {print k / 1024}')" "$wall"
done
a=${counts[0]}
b=${counts[1]}
diff_kib=$((rss_kib[$b] - rss_kib[$a]))
printf '  difference (%d - %d per step): %d KiB = %.2f MiB, %.1f bytes per extra measurement\n' \
  "$b" "$a" "$diff_kib" "$(awk -v k="$diff_kib" 'BEGIN {print k / 1024}')" \
  "$(awk -v k="$diff_kib" -v a="$a" -v b="$b" 'BEGIN {print k * 1024 / (5 * (b - a))}')"
