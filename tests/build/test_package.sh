#!/usr/bin/env bash
# The installed CMake package works for a C++ program: installs BUILD_DIR (`cmake --install`) into
# a temporary prefix, configures tests/build/package_consumer — `project(... LANGUAGES CXX)`, C++
# alone, as an application would — against that prefix alone, builds it with fogradar's libraries
# (propagation, experiment, raw_file with libhdf5, sweep with MPI where the build has it) and runs
# it. The references are independent of fogradar: the study's eq. 6 in closed form, V = -ln(0.02) /
# beta, at beta = 0.9 /m (4.346692 m, printed to 6 decimals); the study's four fog layers (the
# compiled-in paper scenario); and the build's own FOGRADAR_WITH_MPI.
# A sanitizer build's libraries need the sanitizers' runtime: the consumer links with them too.
# Usage: test_package.sh BUILD_DIR SOURCE_DIR CXX_COMPILER WITH_MPI(0|1) SANITIZE(0|1)
set -euo pipefail
build=$1 source=$2 cxx=$3 with_mpi=$4 sanitize=$5
link_flags=
[ "$sanitize" = 1 ] && link_flags=-fsanitize=address,undefined
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" 2>&1 ||
  { cat "$work/install.log" >&2; fail "cmake --install $build"; }
# The package registry and the system prefixes are left out: only the fresh prefix may answer.
cmake -S "$source/tests/build/package_consumer" -B "$work/consumer" -G Ninja \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_EXE_LINKER_FLAGS="$link_flags" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF \
  >"$work/configure.log" 2>&1 || { cat "$work/configure.log" >&2; fail "configuring the consumer"; }
found=$(sed -n 's/^fogradar_DIR:PATH=//p' "$work/consumer/CMakeCache.txt")
[ "$found" = "$work/prefix/lib/cmake/fogradar" ] ||
  fail "found fogradar in '$found', not the prefix"
grep -q '^CMAKE_C_COMPILER' "$work/consumer/CMakeCache.txt" && fail "the consumer enabled C"
cmake --build "$work/consumer" >"$work/build.log" 2>&1 ||
  { cat "$work/build.log" >&2; fail "building the consumer"; }
output=$("$work/consumer/consumer") || fail "the consumer exited with status $?"
expected=$(printf 'visibility_m %s\nlayers 4\nraw_file 1\nmpi %s' \
  "$(awk 'BEGIN { printf "%.6f", -log(0.02) / 0.9 }')" "$with_mpi")
if [ "$output" != "$expected" ]; then
  printf 'FAIL: the consumer printed\n%s\nexpected\n%s\n' "$output" "$expected" >&2
  exit 1
fi
echo "PASS: a C++-only project found, built and ran against the installed package (MPI $with_mpi)"
