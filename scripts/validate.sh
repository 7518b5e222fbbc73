#!/usr/bin/env bash
# The validation report (docs/validation.md): runs the GoogleTest suites of build/release (built
# here first if needed, with the README's options) with JSON output and turns every check they
# record against an independent reference into OUT/validation.json and OUT/validation.html
# (default OUT: build/release/validation). Prints the count of checks and failures; exit status 1
# when a check or a test fails.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/build/release/validation}
"$root/scripts/install-deps.sh"
# shellcheck source=scripts/configure.sh
. "$root/scripts/configure.sh"
dir="$root/build/release"
fogradar_configure "$dir" "${release_options[@]}"
cmake --build "$dir"
mkdir -p "$out"
# The suites run side by side, one per core; each leaves its exit status beside its report, and
# the suites' own failures are counted by the report; their output is kept out of the way.
reports=()
for binary in "$dir"/tests/test_*; do
  [ -x "$binary" ] && [ -f "$binary" ] || continue
  name=$(basename "$binary")
  report="$out/gtest_$name.json"
  rm -f "$report" "$out/$name.status"
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do
    wait -n || true
  done
  {
    code=0
    "$binary" --gtest_output="json:$report" --gtest_brief=1 >"$out/$name.log" 2>&1 || code=$?
    echo "$code" >"$out/$name.status"
  } &
  reports+=("$report")
done
wait
status=0
for report in "${reports[@]}"; do
  name=${report#"$out/gtest_"}
  name=${name%.json}
  [ "$(cat "$out/$name.status")" = 0 ] || status=1
done
/usr/bin/python3 "$root/scripts/validation_report.py" "$out" "${reports[@]}" || status=1
exit $status
