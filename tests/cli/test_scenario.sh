#!/usr/bin/env bash
# End-to-end checks of `fogradar scenario` and of the command line itself (docs/cli.md): the
# printed scenario, the docs' key tables against the keys' declarations, an unknown subcommand or
# section -> exit status 2.
# Usage: test_scenario.sh FOGRADAR_BINARY SOURCE_DIR
. "$(dirname "$0")/cli_test_support.sh"

expect_bad unknown-subcommand "unknown subcommand 'frob'" "one of run, scenario, fog" frob
"$fogradar" scenario | grep -q '^\[experiment\]' && pass || fail "fogradar scenario prints no [experiment]"
# The key tables of the docs are the keys' declarations as `fogradar scenario --keys` prints them.
"$src/scripts/update-docs.sh" --check "$fogradar" 2>"$work/stale" && pass || fail "$(cat "$work/stale")"
expect_bad keys-unknown-section "--keys" "a section of the scenario: chamber, fog, target, experiment, radar" scenario --keys radr


finish
