#!/usr/bin/env bash
# bench/throughput for the three frame sizes of docs/performance.md, one after the other: 64 x 512
# (examples/bench_small.toml), 128 x 1024 (examples/bench.toml) and 256 x 2048
# (examples/bench_long.toml), each with the whole `fogradar run` process timed beside the in-process
# run. `uptime` before and after each size.
#
# Usage: bench/throughput_sizes.sh [BUILD_DIR] [REPEATS]
#   BUILD_DIR  a Release build with the targets throughput and fogradar (default build/release)
#   REPEATS    repeats of each interleaved measurement (default 5)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build/release}
repeats=${2:-5}
for binary in "$build/bench/throughput" "$build/cli/fogradar"; do
  if [[ ! -x $binary ]]; then
    echo "throughput_sizes.sh: $binary not found; build it with:" >&2
    echo "  cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release && ninja -C build/release throughput fogradar" >&2
    exit 2
  fi
done
for scenario in bench_small bench bench_long; do
  echo "== $scenario: uptime $(uptime)"
  "$build/bench/throughput" --scenario "$root/examples/$scenario.toml" --repeats "$repeats" \
    --fogradar "$build/cli/fogradar"
  echo "== $scenario done: uptime $(uptime)"
  echo
done
