#!/usr/bin/env bash
# Quick start (1): installs missing packages, builds Release, runs the main job.
# With arguments they go to the fogradar command instead, e.g. `scripts/run.sh fog --lwc 0.5`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
# shellcheck source=scripts/configure.sh
. "$root/scripts/configure.sh"
# The same configuration as scripts/test.sh (only the tool is built here), so the two commands can run
# in either order on one build tree.
fogradar_configure "$root/build/release" "${release_options[@]}"
cmake --build "$root/build/release" --target fogradar
if (($#)); then
  exec "$root/build/release/cli/fogradar" "$@"
fi
exec "$root/build/release/cli/fogradar" run
