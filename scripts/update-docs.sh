#!/usr/bin/env bash
# Writes the generated blocks of the docs anew from the binary that declares them: every block
#   <!-- generated: fogradar ARGS -->
#   ...
#   <!-- end generated -->
# in docs/*.md gets the output of `fogradar ARGS` (e.g. `scenario --keys radar`: the key table of
# [radar] from the keys' declarations). With --check nothing is written: it names each stale file
# and fails (the test cli.scenario runs it so).
# Usage: scripts/update-docs.sh [--check] [FOGRADAR_BINARY]  (default: build/release/cli/fogradar)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
check=0
if [ "${1:-}" = --check ]; then
  check=1
  shift
fi
fogradar=${1:-$root/build/release/cli/fogradar}
stale=0
[ -x "$fogradar" ] || { echo "update-docs.sh: no fogradar binary at $fogradar (build it first)" >&2; exit 2; }
for doc in "$root"/docs/*.md; do
  grep -q '^<!-- generated: fogradar ' "$doc" || continue
  out=$(mktemp)
  skipping=0
  while IFS= read -r line || [ -n "$line" ]; do
    if [[ $line =~ ^\<!--\ generated:\ fogradar\ (.*)\ --\>$ ]]; then
      printf '%s\n' "$line" >>"$out"
      # shellcheck disable=SC2086  # the arguments are words of the marker
      "$fogradar" ${BASH_REMATCH[1]} >>"$out"
      skipping=1
    elif [[ $line == '<!-- end generated -->' ]]; then
      printf '%s\n' "$line" >>"$out"
      skipping=0
    elif [ "$skipping" -eq 0 ]; then
      printf '%s\n' "$line" >>"$out"
    fi
  done <"$doc"
  if cmp -s "$out" "$doc"; then
    rm -f "$out"
  elif [ "$check" -eq 1 ]; then
    echo "stale generated blocks in ${doc#"$root"/} (run scripts/update-docs.sh):" >&2
    diff "$doc" "$out" >&2 || true
    rm -f "$out"
    stale=1
  else
    mv "$out" "$doc"
    echo "updated ${doc#"$root"/}"
  fi
done
exit "$stale"
