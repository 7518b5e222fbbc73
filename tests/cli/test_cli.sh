#!/usr/bin/env bash
# End-to-end checks of the fogradar command (README, docs/scenario.md, docs/architecture.md Contracts): outputs, byte-identical results for 1 and
# 2 threads, and bad input -> exit status 2, one message naming the argument or key, no files left.
# Usage: test_cli.sh FOGRADAR_BINARY SOURCE_DIR
set -u
fogradar=$(realpath "$1")  # absolute: some cases run it from another directory
src=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0
pass() { passes=$((passes + 1)); }
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# --- outputs and determinism -------------------------------------------------------------------
"$fogradar" run --scenario "$src/tests/cli/small.toml" --out "$work/t1" --threads 1 >"$work/t1.log" 2>&1 \
  || fail "small run (1 thread) failed: $(cat "$work/t1.log")"
"$fogradar" run --scenario "$src/tests/cli/small.toml" --out "$work/t2" --threads 2 >/dev/null 2>&1 \
  || fail "small run (2 threads) failed"
for f in samples.csv summary.csv summary.json rcs_boxplot.svg scenario.toml; do
  if [ -s "$work/t1/$f" ] && cmp -s "$work/t1/$f" "$work/t2/$f"; then pass; else fail "$f missing or differs between 1 and 2 threads"; fi
done
head -1 "$work/t1/samples.csv" | grep -qx 'active_layers,measurement,detected,range_m,rcs_dbsm,snr_db,origin,fog_detections,false_alarms' && pass \
  || fail "samples.csv header"
head -1 "$work/t1/summary.csv" | grep -qx 'active_layers,n,detections,detection_rate,mean_dbsm,std_db,min_dbsm,q1_dbsm,median_dbsm,q3_dbsm,max_dbsm,whisker_low_dbsm,whisker_high_dbsm,outliers,median_shift_db,p_value,median_shift_ci95_low_db,median_shift_ci95_high_db,median_snr_db,two_way_attenuation_db,confusion_rate,false_association_rate,false_alarms_per_frame,fog_detections_per_frame' \
  && pass || fail "summary.csv header"
[ "$(wc -l <"$work/t1/samples.csv")" -eq 31 ] && pass || fail "samples.csv should have 5 x 6 rows"
grep -q '"sensor_limit_layers"' "$work/t1/summary.json" && pass || fail "summary.json lacks sensor_limit_layers"
grep -q '<svg' "$work/t1/rcs_boxplot.svg" && pass || fail "no svg element"
# An XML parser independent of the C++ tests' checker, where Python is installed.
if command -v python3 >/dev/null; then
  python3 -c 'import sys, xml.etree.ElementTree as ET; ET.parse(sys.argv[1])' "$work/t1/rcs_boxplot.svg" && pass \
    || fail "rcs_boxplot.svg is not well-formed XML"
fi
# The resolved scenario reproduces the run exactly.
"$fogradar" run --scenario "$work/t1/scenario.toml" --out "$work/t3" >/dev/null 2>&1 || fail "rerun from scenario.toml"
cmp -s "$work/t1/samples.csv" "$work/t3/samples.csv" && pass || fail "scenario.toml does not reproduce the run"
ls -A "$work/t1" | grep -q '\.tmp' && fail "temporary files left behind" || pass

# --- the result set is replaced whole or not at all (README, docs/scenario.md Results) ---------------
# Each case works in a parent of its own so that "no temporary files" means an empty listing besides DIR.
small="$src/tests/cli/small.toml"
# The paper scenario with 5000 measurements per step runs for many seconds: still going when signalled.
printf '[experiment]\nmeasurements_per_step = 5000\n' >"$work/long.toml"
digest() { (cd "$1" && sha256sum -- * 2>&1); }
leftovers() { ls -A "$1" | grep -v -x "$2"; }  # anything in parent $1 besides the result directory $2
# wait_for_staging PARENT: until the run has created its staging directory (at most 5 s).
wait_for_staging() {
  for _ in $(seq 100); do
    ls -A "$1" | grep -q '\.tmp-' && return 0
    sleep 0.05
  done
  return 1
}

# (a) A second run replaces the first's set whole: every file equals a fresh run's byte for byte.
mkdir -p "$work/a" "$work/a-fresh"
"$fogradar" run --scenario "$small" --seed 1 --out "$work/a/out" >/dev/null 2>&1 || fail "replace: first run failed"
"$fogradar" run --scenario "$small" --seed 2 --out "$work/a/out" >/dev/null 2>&1 || fail "replace: second run failed"
"$fogradar" run --scenario "$small" --seed 2 --out "$work/a-fresh/out" >/dev/null 2>&1 || fail "replace: fresh run failed"
[ "$(digest "$work/a/out")" = "$(digest "$work/a-fresh/out")" ] && pass || fail "replaced set differs from a fresh run"
[ -z "$(leftovers "$work/a" out)" ] && pass || fail "replace left $(leftovers "$work/a" out)"

# expect_kept NAME PARENT BEFORE RC STDERR_FILE EXPECTED_RC EXPECTED_TEXT: the run failed as expected and
# left the previous set byte-identical and nothing else in PARENT.
expect_kept() {
  local name=$1 parent=$2 before=$3 rc=$4 err=$5 want_rc=$6 text=$7
  if [ "$rc" -ne "$want_rc" ]; then fail "$name: exit $rc, expected $want_rc ($(cat "$err"))"; return; fi
  if ! grep -qF -- "$text" "$err"; then fail "$name: message lacks '$text': $(cat "$err")"; return; fi
  if [ "$(wc -l <"$err")" -ne 1 ]; then fail "$name: not one message: $(cat "$err")"; return; fi
  if [ "$(digest "$parent/out")" != "$before" ]; then fail "$name: previous set changed"; return; fi
  if [ -n "$(leftovers "$parent" out)" ]; then fail "$name: left $(leftovers "$parent" out)"; return; fi
  pass
}
# make_old NAME: PARENT=$work/NAME holding out/, the set of a seed-1 run; BEFORE its digest.
make_old() {
  parent="$work/$1"
  mkdir -p "$parent"
  "$fogradar" run --scenario "$small" --seed 1 --out "$parent/out" >/dev/null 2>&1 || fail "$1: first run failed"
  before=$(digest "$parent/out")
}

# (b) A set fogradar may not replace: a file of the user's (here a non-empty directory under a result
# file's name, which no one, root included, can replace by a file) is refused before the run, exit 2.
make_old foreign
mkdir -p "$work/foreign-extra/samples.csv/keep" && rm -f "$parent/out/samples.csv" && mv "$work/foreign-extra/samples.csv" "$parent/out/"
before=$(digest "$parent/out")
"$fogradar" run --scenario "$small" --seed 2 --out "$parent/out" >/dev/null 2>"$work/err"
expect_kept foreign-file "$parent" "$before" $? "$work/err" 2 "--out"
[ -d "$parent/out/samples.csv/keep" ] && pass || fail "the user's directory was touched"
# Writing fails half-way (the file-size limit, EFBIG, also binds root; SIGXFSZ ignored so write()
# reports it): the first set stays.
make_old write-fails
(ulimit -f 1; trap '' XFSZ; exec "$fogradar" run --scenario "$small" --seed 2 --out "$parent/out" >/dev/null 2>"$work/err")
expect_kept write-fails "$parent" "$before" $? "$work/err" 2 "--out"

# (c) SIGTERM and SIGINT while measuring: exit 128 + signal, one message, previous set and nothing else.
# Job control (set -m) keeps bash from starting the background run with SIGINT ignored.
for sig in TERM INT; do
  make_old "signal-$sig"
  set -m
  "$fogradar" run --scenario "$work/long.toml" --threads 1 --out "$parent/out" >/dev/null 2>"$work/err" &
  pid=$!
  set +m
  if wait_for_staging "$parent"; then
    sleep 0.2
    kill -s "$sig" "$pid"
    wait "$pid"
    rc=$?
    want=$([ "$sig" = TERM ] && echo 143 || echo 130)
    expect_kept "signal-$sig" "$parent" "$before" "$rc" "$work/err" "$want" "interrupted by SIG$sig"
  else
    kill -s KILL "$pid"; wait "$pid"
    fail "signal-$sig: the run never started"
  fi
done

# (d) Two runs into one directory: while the first holds it, the second is refused naming --out; the
# first, stopped, leaves the previous set; run one after the other, both succeed.
make_old concurrent
"$fogradar" run --scenario "$work/long.toml" --threads 1 --out "$parent/out" >/dev/null 2>&1 &
pid=$!
if wait_for_staging "$parent"; then
  "$fogradar" run --scenario "$small" --seed 2 --out "$parent/out" >/dev/null 2>"$work/err2"
  rc=$?
  kill -s TERM "$pid"
  wait "$pid"
  [ "$rc" -eq 2 ] && grep -qF -- "--out" "$work/err2" && grep -q 'locked' "$work/err2" && pass \
    || fail "concurrent: second run exit $rc: $(cat "$work/err2")"
  [ "$(digest "$parent/out")" = "$before" ] && [ -z "$(leftovers "$parent" out)" ] && pass \
    || fail "concurrent: previous set changed or files left: $(leftovers "$parent" out)"
else
  kill -s KILL "$pid"; wait "$pid"
  fail "concurrent: the first run never started"
fi
"$fogradar" run --scenario "$small" --seed 2 --out "$parent/out" >/dev/null 2>&1 \
  && [ "$(digest "$parent/out")" = "$(digest "$work/a-fresh/out")" ] && pass || fail "concurrent: serial rerun"

# The working directory is never the result set: swapping it away would strand the caller's shell.
mkdir -p "$work/cwd"
(cd "$work/cwd" && exec "$fogradar" run --scenario "$small" --out . >/dev/null 2>"$work/err")
rc=$?
[ "$rc" -eq 2 ] && grep -qF -- "--out" "$work/err" && [ -z "$(ls -A "$work/cwd")" ] && pass \
  || fail "--out . : exit $rc, $(cat "$work/err"), left $(ls -A "$work/cwd")"

# (e) A full filesystem: a 64 KiB tmpfs, filled after the first set is in place. Needs mount rights.
mkdir -p "$work/full"
if mount -t tmpfs -o size=64k tmpfs "$work/full" 2>/dev/null; then
  make_old full
  dd if=/dev/zero of="$parent/filler" bs=1k count=64 2>/dev/null
  before=$(digest "$parent/out")
  "$fogradar" run --scenario "$small" --seed 2 --out "$parent/out" >/dev/null 2>"$work/err"
  rc=$?
  rm -f "$parent/filler"
  expect_kept full-disk "$parent" "$before" "$rc" "$work/err" 2 "--out"
  umount "$work/full"
else
  echo "SKIP full-disk case: cannot mount a tmpfs here (needs privileges)"
fi

# --- bad input -----------------------------------------------------------------------------------
# expect_bad NAME EXPECTED_TEXT ARGS...: exit 2, stderr names EXPECTED_TEXT, the output dir stays empty.
expect_bad() {
  local name=$1 expected=$2
  shift 2
  local out="$work/bad-$name"
  "$fogradar" "$@" >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  if [ $rc -ne 2 ]; then fail "$name: exit $rc, expected 2 ($(cat "$work/stderr"))"; return; fi
  if ! grep -qF -- "$expected" "$work/stderr"; then fail "$name: message does not name '$expected': $(cat "$work/stderr")"; return; fi
  if [ "$(wc -l <"$work/stderr")" -gt 2 ]; then fail "$name: more than one message: $(cat "$work/stderr")"; return; fi
  if [ -d "$out" ] && [ -n "$(ls -A "$out")" ]; then fail "$name: files left in $out"; return; fi
  pass
}
printf '[radar]\ntx_power_w = 1\n' >"$work/unknown.toml"
printf '[radar]\ntx_power_dbm = "ten"\n' >"$work/type.toml"
printf '[chamber]\nlayer_count = 0\n' >"$work/zero.toml"
printf '[experiment]\nmax_active_layers = 9\n' >"$work/many.toml"
printf '[processing.cfar]\ntraining_cells = 400\n' >"$work/cfar.toml"
printf '[radar]\ncentre_frequency_hz = 5e13\n' >"$work/freq.toml"
printf '[radar]\ncarrier_frequency_hz = 77e9\n' >"$work/carrier.toml"
printf '[fog]\nwater_model = "segelstein"\ntemperature_c = 0\n' >"$work/cold-table.toml"
printf '[fog]\nlwc_g_per_m3 = nan\n' >"$work/nan.toml"
printf '[radar\n' >"$work/malformed.toml"
touch "$work/a-file"
expect_bad unknown-key radar.tx_power_w run --scenario "$work/unknown.toml" --out "$work/bad-unknown-key"
expect_bad wrong-type radar.tx_power_dbm run --scenario "$work/type.toml" --out "$work/bad-wrong-type"
expect_bad zero-layers chamber.layer_count run --scenario "$work/zero.toml" --out "$work/bad-zero-layers"
expect_bad too-many-active experiment.max_active_layers run --scenario "$work/many.toml" --out "$work/bad-too-many-active"
expect_bad cfar-window processing.cfar.training_cells run --scenario "$work/cfar.toml" --out "$work/bad-cfar-window"
expect_bad frequency radar.centre_frequency_hz run --scenario "$work/freq.toml" --out "$work/bad-frequency"
expect_bad retired-carrier radar.centre_frequency_hz run --scenario "$work/carrier.toml" --out "$work/bad-retired-carrier"
expect_bad table-temperature liebe run --scenario "$work/cold-table.toml" --out "$work/bad-table-temperature"
expect_bad nan-lwc fog.lwc_g_per_m3 run --scenario "$work/nan.toml" --out "$work/bad-nan-lwc"
expect_bad malformed malformed.toml:1 run --scenario "$work/malformed.toml" --out "$work/bad-malformed"
expect_bad missing-file --scenario run --scenario "$work/does-not-exist.toml" --out "$work/bad-missing-file"
expect_bad out-is-file --out run --scenario "$src/tests/cli/small.toml" --out "$work/a-file"
expect_bad out-unwritable --out run --scenario "$src/tests/cli/small.toml" --out /proc/fogradar-out
expect_bad threads-negative --threads run --threads -1 --out "$work/bad-threads-negative"
expect_bad threads-text --threads run --threads many --out "$work/bad-threads-text"
expect_bad seed-negative --seed run --seed -4 --out "$work/bad-seed-negative"
expect_bad unknown-option --frobnicate run --frobnicate --out "$work/bad-unknown-option"
expect_bad fog-lwc --lwc fog --lwc -1
expect_bad fog-model --water-model fog --water-model mie
expect_bad fog-two-densities --visibility-m fog --lwc 1 --visibility-m 3
expect_bad fog-frequency --frequency-ghz fog --frequency-ghz 1e9
expect_bad fog-liebe-frequency --frequency-ghz fog --frequency-ghz 2000
expect_bad fog-table-temperature --temperature-c fog --water-model segelstein --temperature-c 0
expect_bad fog-table-temperature-names-liebe liebe fog --water-model segelstein --temperature-c 20
expect_bad fog-liebe-temperature --temperature-c fog --temperature-c 60

# --- fog --json carries the documented keys (README) ----------------------------------------------------------
json=$("$fogradar" fog --frequency-ghz 77 --lwc 1 --temperature-c 20 --json)
for key in frequency_hz wavelength_m refractive_index_n refractive_index_k lwc_g_per_m3 \
  specific_attenuation_db_per_km volume_backscatter_m2_per_m3 optical_extinction_per_km visibility_m \
  water_model temperature_c optical_water_model optical_water_temperature_c; do
  echo "$json" | grep -q "\"$key\"" && pass || fail "fog --json lacks $key"
done
# The temperature the output states is the one the index used: 0 C moves the Liebe index; the
# table states its own 25 C, in JSON and in text.
cold=$("$fogradar" fog --lwc 1 --temperature-c 0 --json)
echo "$cold" | grep -q '"temperature_c": 0' && pass || fail "fog --json does not state 0 C: $cold"
[ "$(echo "$cold" | grep refractive_index_n)" != "$(echo "$json" | grep refractive_index_n)" ] && pass \
  || fail "0 C and 20 C give the same Liebe index"
table=$("$fogradar" fog --lwc 1 --water-model segelstein --json)
echo "$table" | grep -q '"water_model": "segelstein"' && echo "$table" | grep -q '"temperature_c": 25' && pass \
  || fail "fog --json does not state the table's 25 C: $table"
echo "$json" | grep -q '"optical_water_temperature_c": 25' && pass || fail "optical index temperature not stated"
"$fogradar" fog --lwc 1 --water-model segelstein | grep -q 'Segelstein table, for its own 25 C' && pass \
  || fail "fog text does not state the table's temperature"
"$fogradar" scenario | grep -q '^\[experiment\]' && pass || fail "fogradar scenario prints no [experiment]"

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
