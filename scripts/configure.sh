#!/usr/bin/env bash
# Sourced by run.sh and test.sh (which set $root): `fogradar_configure DIR [cmake options...]` configures DIR for this
# source tree with Ninja. Every option the caller cares about is passed explicitly, so the result does
# not depend on what an earlier run of either script (or a hand-made build) left in DIR's cache. A
# cache made for another source tree or with another generator cannot be reconfigured; it is removed.
fogradar_configure() {
  local dir=$1
  shift
  local cache="$dir/CMakeCache.txt"
  if [ -f "$cache" ]; then
    local home generator
    home=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$cache")
    generator=$(sed -n 's/^CMAKE_GENERATOR:INTERNAL=//p' "$cache")
    if [ "$home" != "$root" ] || [ "$generator" != "Ninja" ]; then
      echo "note: $dir was configured for '$home' with '$generator'; configuring it anew" >&2
      rm -rf "$dir"
    fi
  fi
  cmake -S "$root" -B "$dir" -G Ninja "$@" >/dev/null
}

# The options of build/release, shared by run.sh and test.sh so that either may run first on one
# build tree without rebuilding what the other built. With CI=true warnings are errors.
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
release_options=(-DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS= -DFOGRADAR_SANITIZE=OFF
  -DFOGRADAR_BUILD_TESTS=ON -DFOGRADAR_BUILD_BENCHMARKS=ON -DFOGRADAR_BUILD_EXAMPLES=ON
  -DFOGRADAR_BUILD_PYTHON=ON -DFOGRADAR_WITH_MPI=ON -DFOGRADAR_WARNINGS_AS_ERRORS=$werror)
