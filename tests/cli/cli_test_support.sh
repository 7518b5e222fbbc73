#!/usr/bin/env bash
# Shared by the `fogradar` command's end-to-end checks, one script per subcommand (test_run.sh,
# test_fog.sh, test_scenario.sh, test_room.sh): the arguments, a scratch directory, the pass/fail
# counts and the bad-input checks. Sourced, with the checks' arguments FOGRADAR_BINARY SOURCE_DIR.
set -u
fogradar=$(realpath "$1")  # absolute: some cases run it from another directory
src=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0
pass() { passes=$((passes + 1)); }
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# --- bad input -----------------------------------------------------------------------------------
# One message (a CLI11 usage error adds the "run 'fogradar --help'" line) naming the argument or key,
# and the allowed range or set.
check_message() {
  local name=$1 rc=$2 key=$3 allowed=$4
  if [ "$rc" -ne 2 ]; then fail "$name: exit $rc, expected 2 ($(cat "$work/stderr"))"; return 1; fi
  if ! grep -qF -- "$key" "$work/stderr"; then fail "$name: message does not name '$key': $(cat "$work/stderr")"; return 1; fi
  if ! grep -qF -- "$allowed" "$work/stderr"; then fail "$name: message does not state '$allowed': $(cat "$work/stderr")"; return 1; fi
  if [ "$(grep -vc "^(run 'fogradar --help' for usage)$" "$work/stderr")" -ne 1 ]; then
    fail "$name: not exactly one message: $(cat "$work/stderr")"; return 1
  fi
  # Nothing but the message: no estimate line or table before it.
  if [ -s "$work/stdout" ]; then fail "$name: printed besides its message: $(cat "$work/stdout")"; return 1; fi
  return 0
}
# expect_bad NAME KEY ALLOWED ARGS...: a command that writes no results (fog, a bad subcommand, a bad
# --out).
expect_bad() {
  local name=$1 key=$2 allowed=$3
  shift 3
  timeout 20 "$fogradar" "$@" >"$work/stdout" 2>"$work/stderr"
  check_message "$name" $? "$key" "$allowed" && pass
}

# The counts, and the exit status: 0 only when nothing failed.
finish() {
  echo "$passes passed, $failures failed"
  [ "$failures" -eq 0 ]
}
