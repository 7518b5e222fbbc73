#!/usr/bin/env bash
# Quick start (2): installs missing packages, builds everything (Release), runs the test suite.
# `scripts/test.sh --sanitize` builds and runs the same suite under ASan + UBSan instead, unoptimised
# (Debug), which also covers the code paths an -O0 build takes (nothing inlined that is not forced).
# With CI=true warnings are errors.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
if [ "${1:-}" = "--sanitize" ]; then
  dir="$root/build/sanitize"
  cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
    -DFOGRADAR_SANITIZE=ON -DFOGRADAR_WARNINGS_AS_ERRORS=$werror -DFOGRADAR_BUILD_BENCHMARKS=OFF >/dev/null
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
else
  dir="$root/build/release"
  cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DFOGRADAR_WARNINGS_AS_ERRORS=$werror >/dev/null
fi
cmake --build "$dir"
ctest --test-dir "$dir" --output-on-failure -j "$(nproc)"
