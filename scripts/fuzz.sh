#!/usr/bin/env bash
# Fuzzes the scenario reader and the set-up before a run's first frame (tests/fuzz/fuzz_scenario.cpp,
# docs/architecture.md "Fuzzing") for SECONDS (default 120, as CI runs it). Installs clang-14 and
# libclang-rt-14-dev if missing, builds build/fuzz (clang, libFuzzer + ASan + UBSan) and fuzzes from a
# seed corpus of examples/*.toml with the dictionary tests/fuzz/scenario.dict. Fails on any crash,
# sanitizer report, failed check, input slower than 10 s or over 2 GiB; the input that did it is kept
# as build/fuzz/crash-* / timeout-* / oom-* (rerun one: build/fuzz/tests/fuzz/fuzz_scenario FILE).
# The corpus grown here (build/fuzz/corpus) is kept for the next run.
set -euo pipefail
seconds=${1:-120}
if ! [[ $seconds =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
  echo "scripts/fuzz.sh: SECONDS must be a whole number >= 1, got '$seconds'" >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh" clang-14 libclang-rt-14-dev
# shellcheck source=scripts/configure.sh
. "$root/scripts/configure.sh"
dir="$root/build/fuzz"
# The vector loops' baseline version only (-DFOGRADAR_SIMD_CLONES=): the other clones are the same
# source, and tests cover them.
CXX=clang++-14 fogradar_configure "$dir" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS=-DFOGRADAR_SIMD_CLONES=" -DFOGRADAR_BUILD_FUZZERS=ON -DFOGRADAR_SANITIZE=OFF \
  -DFOGRADAR_BUILD_TESTS=OFF -DFOGRADAR_BUILD_EXAMPLES=OFF -DFOGRADAR_BUILD_BENCHMARKS=OFF \
  -DFOGRADAR_WARNINGS_AS_ERRORS="$werror"
cmake --build "$dir" --target fuzz_scenario
mkdir -p "$dir/corpus" "$dir/seeds"
cp "$root"/examples/*.toml "$root"/tests/cli/*.toml "$dir/seeds/"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd "$dir"
# -timeout: an input slower than 10 s is a hang; -rss_limit_mb above the target's own 512 MiB
# chain limit; -workers/-jobs 1: one process, its exit status is the verdict.
"$dir/tests/fuzz/fuzz_scenario" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -dict="$root/tests/fuzz/scenario.dict" -max_len=8192 -print_final_stats=1 "$dir/corpus" "$dir/seeds"
echo "scripts/fuzz.sh: no finding in $seconds s"
