#!/usr/bin/env bash
# Quick start (1): installs missing packages, builds Release, runs the main job.
# With arguments they go to the fogradar command instead, e.g. `scripts/run.sh fog --lwc 0.5`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$root/build/release" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DFOGRADAR_BUILD_TESTS=OFF -DFOGRADAR_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$root/build/release" --target fogradar
if (($#)); then
  exec "$root/build/release/cli/fogradar" "$@"
fi
exec "$root/build/release/cli/fogradar" run
