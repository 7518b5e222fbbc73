#!/usr/bin/env bash
# Quick start (2): installs missing packages, builds everything (Release), runs the test suite.
# `scripts/test.sh --sanitize` builds and runs the same suite under ASan + UBSan instead, with
# assertions and line tables (Debug, -g1: a report's stack has its lines) at -O1, which
# AddressSanitizer's documentation advises for speed (at -O0 the suite's Eigen and Monte Carlo tests
# take most of CI's time), with the vector loops built for the x86-64 baseline only (no other
# clone, -DFOGRADAR_SIMD_CLONES=):
# the same tests, pinned noise samples included, then check that the version the loader picks on
# machines without AVX2 gives the same bits as the clone the release suite ran.
# `scripts/test.sh --baseline` builds the same baseline-only vector loops optimised (Release), for a
# check of the optimised baseline version; CI does not run it. The Python module is built and tested
# in the release and baseline trees; not under the sanitizers (Debian's python3 is not instrumented).
# With CI=true warnings are errors.
set -euo pipefail
mode=${1:-}
case "$mode" in
  "" | --sanitize | --baseline) ;;
  *)
    echo "scripts/test.sh: unknown argument '$mode'; allowed: none, --sanitize, --baseline" >&2
    exit 2
    ;;
esac
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
# shellcheck source=scripts/configure.sh
. "$root/scripts/configure.sh"
case "$mode" in
  "")
    dir="$root/build/release"
    fogradar_configure "$dir" "${release_options[@]}"
    ;;
  --sanitize)
    dir="$root/build/sanitize"
    fogradar_configure "$dir" -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS=-DFOGRADAR_SIMD_CLONES= -O1" \
      -DCMAKE_CXX_FLAGS_DEBUG=-g1 \
      -DFOGRADAR_BUILD_TESTS=ON -DFOGRADAR_BUILD_EXAMPLES=ON -DFOGRADAR_SANITIZE=ON \
      -DFOGRADAR_WARNINGS_AS_ERRORS=$werror -DFOGRADAR_BUILD_BENCHMARKS=OFF \
      -DFOGRADAR_BUILD_PYTHON=OFF
    export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    ;;
  --baseline)
    dir="$root/build/baseline"
    fogradar_configure "$dir" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=-DFOGRADAR_SIMD_CLONES=" \
      -DFOGRADAR_BUILD_TESTS=ON -DFOGRADAR_BUILD_EXAMPLES=ON -DFOGRADAR_SANITIZE=OFF \
      -DFOGRADAR_WARNINGS_AS_ERRORS=$werror -DFOGRADAR_BUILD_BENCHMARKS=OFF \
      -DFOGRADAR_BUILD_PYTHON=ON
    ;;
esac
cmake --build "$dir"
# --no-tests=error: a build tree without tests must fail, never pass as "0 tests".
ctest --test-dir "$dir" --output-on-failure --no-tests=error -j "$(nproc)"
