#!/usr/bin/env bash
# End-to-end checks of the fogradar command (README, docs/scenario.md, docs/architecture.md Contracts): outputs, byte-identical results for 1 and
# 2 threads, and bad input -> exit status 2, one message naming the argument or key and the allowed
# range, no fresh output directory created and an earlier result left unchanged.
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
# small.toml runs the paper scenario's three sensors: every sensor's files.
for f in radar_samples.csv radar_detections.csv radar_summary.csv radar_summary.json radar_rcs_boxplot.svg summary.json scenario.toml \
  lidar_echoes.csv lidar_summary.csv lidar_summary.json lidar_intensity_boxplot.svg lidar_scans.svg \
  camera_histograms.csv camera_summary.csv camera_summary.json camera_histograms.svg benchmark.svg; do
  if [ -s "$work/t1/$f" ] && cmp -s "$work/t1/$f" "$work/t2/$f"; then pass; else fail "$f missing or differs between 1 and 2 threads"; fi
done
[ "$(ls -A "$work/t1" | wc -l)" -eq 18 ] && pass || fail "result set is not the 17 files and their record: $(ls -A "$work/t1")"
# The set's record of its files (.fogradar-files): their names, sorted bytewise, one a line.
[ "$(cat "$work/t1/.fogradar-files")" = "$(LC_ALL=C ls "$work/t1")" ] && pass \
  || fail "the set's record is not its files: $(cat "$work/t1/.fogradar-files")"
# One table per sensor, then the benchmark: layers to failure (or not reached) per sensor.
for sensor in radar lidar camera; do
  grep -qx "$sensor" "$work/t1.log" && pass || fail "no $sensor table: $(cat "$work/t1.log")"
  grep -q "^$sensor *layers to failure: " "$work/t1.log" && pass || fail "no benchmark line for $sensor"
done
head -1 "$work/t1/lidar_echoes.csv" | grep -qx 'active_layers,item,angle_deg,echo,range_m,intensity,origin,layer' && pass \
  || fail "lidar_echoes.csv header: $(head -1 "$work/t1/lidar_echoes.csv")"
head -1 "$work/t1/camera_histograms.csv" | grep -qx 'active_layers,grey_level,count' && pass \
  || fail "camera_histograms.csv header: $(head -1 "$work/t1/camera_histograms.csv")"
head -1 "$work/t1/camera_summary.csv" | grep -q '^active_layers,frames,' && pass \
  || fail "camera_summary.csv header: $(head -1 "$work/t1/camera_summary.csv")"
if [ -x /usr/bin/python3 ]; then
  /usr/bin/python3 - "$work/t1/summary.json" <<'PY' && pass || fail "summary.json lacks a sensor's limit"
import json, sys
sensors = json.load(open(sys.argv[1]))["sensors"]
assert sorted(sensors) == ["camera", "lidar", "radar"], sensors
for name, entry in sensors.items():
    assert "sensor_limit_layers" in entry and entry["criterion"], name
PY
fi
head -1 "$work/t1/radar_samples.csv" | grep -qx 'active_layers,item,detected,range_m,rcs_dbsm,snr_db,origin,fog_detections,false_alarms,velocity_m_per_s' && pass \
  || fail "radar_samples.csv header"
head -1 "$work/t1/radar_detections.csv" | grep -qx 'active_layers,item,range_m,velocity_m_per_s,power_dbm,snr_db,rcs_dbsm,origin,in_gate,associated,layer' && pass \
  || fail "radar_detections.csv header"
head -1 "$work/t1/radar_summary.csv" | grep -qx 'active_layers,n,detections,detection_rate,mean_dbsm,std_db,min_dbsm,q1_dbsm,median_dbsm,q3_dbsm,max_dbsm,whisker_low_dbsm,whisker_high_dbsm,outliers,median_shift_db,p_value,median_shift_ci95_low_db,median_shift_ci95_high_db,median_snr_db,two_way_attenuation_db,radome_two_way_loss_db,target_film_loss_db,confusion_rate,false_association_rate,false_alarms_per_frame,fog_detections_per_frame,adc_clipped_fraction,clipping_detections_per_frame,sidelobe_detections_per_frame' \
  && pass || fail "radar_summary.csv header"
[ "$(wc -l <"$work/t1/radar_samples.csv")" -eq 31 ] && pass || fail "radar_samples.csv should have 5 x 6 rows"
grep -q '"sensor_limit_layers"' "$work/t1/summary.json" && pass || fail "summary.json lacks sensor_limit_layers"
grep -q '<svg' "$work/t1/radar_rcs_boxplot.svg" && pass || fail "no svg element"
# An XML parser independent of the C++ tests' checker, where Python is installed.
if [ -x /usr/bin/python3 ]; then
  for svg in radar_rcs_boxplot.svg lidar_intensity_boxplot.svg lidar_scans.svg camera_histograms.svg benchmark.svg; do
    /usr/bin/python3 -c 'import sys, xml.etree.ElementTree as ET; ET.parse(sys.argv[1])' "$work/t1/$svg" && pass \
      || fail "$svg is not well-formed XML"
  done
fi
# The resolved scenario reproduces the run exactly.
"$fogradar" run --scenario "$work/t1/scenario.toml" --out "$work/t3" >/dev/null 2>&1 || fail "rerun from scenario.toml"
diff -r "$work/t1" "$work/t3" >/dev/null && pass || fail "scenario.toml does not reproduce the run"
ls -A "$work/t1" | grep -q '\.tmp' && fail "temporary files left behind" || pass
# The camera alone with its ROI images (camera_roi_<step>.pgm, binary PGM): a result set a later run
# of other sensors replaces whole.
printf '[experiment]\nsensors = ["camera"]\n[camera]\nframes_per_step = 2\nwrite_roi_images = true\n' >"$work/roi.toml"
"$fogradar" run --scenario "$work/roi.toml" --out "$work/roi" >/dev/null 2>&1 || fail "camera run with ROI images failed"
[ "$(ls "$work/roi" | grep -c '^camera_roi_[0-4]\.pgm$')" -eq 5 ] && [ "$(head -c 2 "$work/roi/camera_roi_0.pgm")" = P5 ] \
  && [ ! -e "$work/roi/radar_samples.csv" ] && pass || fail "camera ROI set: $(ls "$work/roi")"
"$fogradar" run --scenario "$src/tests/cli/small.toml" --out "$work/roi" >/dev/null 2>&1 && ! ls "$work/roi" | grep -q pgm \
  && pass || fail "ROI images not replaced by the next set: $(ls "$work/roi")"
# A file of the user's under a name the camera's ROI images could have (the set was written with
# them off, or the camera never writes the name) is not the set's: refused naming it, never deleted.
for mine in camera_roi_1.pgm camera_roi_01.pgm camera_roi_999.pgm; do
  echo mine >"$work/roi/$mine"
  "$fogradar" run --scenario "$src/tests/cli/small.toml" --out "$work/roi" >/dev/null 2>"$work/err"
  rc=$?
  [ "$rc" -eq 2 ] && grep -qF -- "--out = '$work/roi'" "$work/err" && grep -qF "'$mine' is not one" "$work/err" \
    && [ "$(cat "$work/roi/$mine")" = mine ] && pass || fail "user's $mine: exit $rc, $(cat "$work/err")"
  rm -f "$work/roi/$mine"
done

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
mkdir -p "$work/foreign-extra/radar_samples.csv/keep" && rm -f "$parent/out/radar_samples.csv" && mv "$work/foreign-extra/radar_samples.csv" "$parent/out/"
before=$(digest "$parent/out")
"$fogradar" run --scenario "$small" --seed 2 --out "$parent/out" >/dev/null 2>"$work/err"
expect_kept foreign-file "$parent" "$before" $? "$work/err" 2 "--out"
[ -d "$parent/out/radar_samples.csv/keep" ] && pass || fail "the user's directory was touched"
# Writing fails half-way (the file-size limit, EFBIG, also binds root; SIGXFSZ ignored so write()
# reports it): the first set stays.
make_old write-fails
(ulimit -f 1; trap '' XFSZ; exec "$fogradar" run --scenario "$small" --seed 2 --out "$parent/out" >/dev/null 2>"$work/err")
expect_kept write-fails "$parent" "$before" $? "$work/err" 2 "--out"
# A run that fails after measuring leaves no parent of --out it created.
(ulimit -f 1; trap '' XFSZ; exec "$fogradar" run --scenario "$small" --out "$work/new-parent/deeper/out" >/dev/null 2>"$work/err")
rc=$?
[ "$rc" -eq 2 ] && grep -qF -- "--out" "$work/err" && [ ! -e "$work/new-parent" ] && pass \
  || fail "failed run into a new parent: exit $rc, $(cat "$work/err"), left $(ls -A "$work/new-parent" 2>&1)"

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

# (e) A full filesystem: a 1 MiB tmpfs (the three sensors' set is about 0.4 MB), filled after the first
# set is in place. Needs mount rights.
mkdir -p "$work/full"
if mount -t tmpfs -o size=1m tmpfs "$work/full" 2>/dev/null; then
  make_old full
  dd if=/dev/zero of="$parent/filler" bs=1k count=1024 2>/dev/null
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
# The result of an earlier run, which a refused run must leave as it is.
cp -r "$work/t1" "$work/earlier"
cp -r "$work/t1" "$work/earlier-pristine"
# expect_bad_run NAME KEY ALLOWED ARGS...: `fogradar run ARGS --out DIR` twice: a fresh DIR is not
# created, and an existing DIR holding an earlier result is unchanged.
expect_bad_run() {
  local name=$1 key=$2 allowed=$3
  shift 3
  local fresh="$work/bad-$name"
  timeout 20 "$fogradar" run "$@" --out "$fresh" >"$work/stdout" 2>"$work/stderr"
  check_message "$name" $? "$key" "$allowed" || return
  if [ -e "$fresh" ]; then fail "$name: created $fresh"; return; fi
  timeout 20 "$fogradar" run "$@" --out "$work/earlier" >"$work/stdout" 2>"$work/stderr"
  check_message "$name (existing --out)" $? "$key" "$allowed" || return
  if ! diff -r "$work/earlier-pristine" "$work/earlier" >/dev/null; then fail "$name: changed the earlier result"; return; fi
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
printf '[processing]\nwindow = ""\n' >"$work/empty-window.toml"
printf '[fog]\nwater_model = ""\n' >"$work/empty-water.toml"
printf '[radar]\nsamples_per_chirp = 5000000000\n' >"$work/huge-samples.toml"
printf '[fog]\nclutter_scatterers_per_bin = 65\n' >"$work/clutter.toml"
printf '[experiment]\nseed = -1\n' >"$work/seed.toml"
printf '[experiment]\nsensors = ["radar", "sonar"]\n' >"$work/sonar.toml"
printf '[experiment]\nsensors = []\n' >"$work/no-sensors.toml"
printf '[experiment]\nsensors = ["radar", "radar"]\n' >"$work/radar-twice.toml"
printf '[lidar]\npulse_width_ns = -5\n' >"$work/lidar-pulse.toml"
printf '[lidar]\nscans_per_step = 0\n' >"$work/lidar-scans.toml"
printf '[[lidar.background]]\nx0_m = 1\nx1_m = 2\nreflectivity = 2\n' >"$work/lidar-background.toml"
printf '[lidar]\nrange_m = 3\n' >"$work/lidar-unknown.toml"
printf '[camera.exposure]\nmode = "manual"\n' >"$work/camera-mode.toml"
printf '[camera.roi.target]\nlog_sigma = nan\n' >"$work/camera-sigma.toml"
printf '[camera]\nframes_per_step = 1.5\n' >"$work/camera-frames.toml"
printf '[radar]\nsamples_per_chirp = 32\n[processing.cfar]\nguard_cells = 20\n' >"$work/guard.toml"
printf '[radar]\nsample_rate_hz = 5e6\nsamples_per_chirp = 256\n[chamber]\ntarget_gap_m = 40\n' >"$work/far.toml"
printf '[chamber]\nlayer_count = 2\n[experiment]\nmax_active_layers = 3\n' >"$work/layers.toml"
printf '[fog]\nlwc_g_per_m3 = 0.1\nvisibility_m = 20\n' >"$work/two-densities.toml"
head -c 1048577 /dev/zero | tr '\0' '#' >"$work/too-big.toml"
mkdir "$work/a-directory"
mkfifo "$work/a-fifo"
touch "$work/a-file"
expect_bad_run unknown-key radar.tx_power_w "known keys of [radar]" --scenario "$work/unknown.toml"
expect_bad_run wrong-type-value "type.toml:2: radar.tx_power_dbm = 'ten'" "must be a number" --scenario "$work/type.toml"
expect_bad_run zero-layers "zero.toml:2: chamber.layer_count = 0" "[1, 1000]" --scenario "$work/zero.toml"
expect_bad_run too-many-active "many.toml:2: experiment.max_active_layers = 9" "[0, chamber.layer_count = 4]" \
  --scenario "$work/many.toml"
expect_bad_run too-many-active-given "layers.toml:4: experiment.max_active_layers = 3" \
  "[0, chamber.layer_count = 2] (chamber.layer_count at line 2)" --scenario "$work/layers.toml"
expect_bad_run cfar-window "cfar.toml:2: processing.cfar.training_cells = 400" "[1, 253]" --scenario "$work/cfar.toml"
expect_bad_run guard-fills-profile "guard.toml:4: processing.cfar.guard_cells = 20" \
  "[0, 7] with processing.cfar.training_cells = 8 and a profile of radar.samples_per_chirp = 32 cells" \
  --scenario "$work/guard.toml"
expect_bad_run target-beyond-range "far.toml:5: chamber.target_gap_m = 40" "radar.sample_rate_hz at line 2" \
  --scenario "$work/far.toml"
expect_bad_run frequency radar.centre_frequency_hz "[1000000000, 3e+11]" --scenario "$work/freq.toml"
expect_bad_run retired-carrier radar.centre_frequency_hz radar.sweep_direction --scenario "$work/carrier.toml"
expect_bad_run table-temperature "cold-table.toml:3: fog.temperature_c = 0" "liebe\" takes [-20, 50]" \
  --scenario "$work/cold-table.toml"
expect_bad_run nan-lwc "nan.toml:2: fog.lwc_g_per_m3 = nan" "[0, 100]" --scenario "$work/nan.toml"
expect_bad_run malformed malformed.toml:1 "malformed TOML" --scenario "$work/malformed.toml"
expect_bad_run empty-window "empty-window.toml:2: processing.window = ''" "one of rectangular, hann" \
  --scenario "$work/empty-window.toml"
expect_bad_run empty-water-model "empty-water.toml:2: fog.water_model = ''" "one of 'segelstein', 'liebe'" \
  --scenario "$work/empty-water.toml"
expect_bad_run integer-documented-range "radar.samples_per_chirp = 5000000000" "an integer in [16, 65536]" \
  --scenario "$work/huge-samples.toml"
expect_bad_run clutter-range "fog.clutter_scatterers_per_bin = 65" "an integer in [1, 64]" --scenario "$work/clutter.toml"
expect_bad_run scenario-seed "seed.toml:2: experiment.seed = -1" "an integer in [0, 9223372036854775807]" \
  --scenario "$work/seed.toml"
expect_bad_run unknown-sensor 'sonar.toml:2: experiment.sensors' '"sonar" is no sensor' --scenario "$work/sonar.toml"
expect_bad_run no-sensors 'no-sensors.toml:2: experiment.sensors = []' \
  'a non-empty array of distinct names from "radar", "lidar", "camera"' --scenario "$work/no-sensors.toml"
expect_bad_run sensor-twice 'radar-twice.toml:2: experiment.sensors' '"radar" is named twice' \
  --scenario "$work/radar-twice.toml"
expect_bad_run lidar-pulse 'lidar-pulse.toml:2: lidar.pulse_width_ns = -5' "[0.1, 1000]" --scenario "$work/lidar-pulse.toml"
expect_bad_run lidar-scans 'lidar-scans.toml:2: lidar.scans_per_step = 0' "an integer in [1, 100000]" \
  --scenario "$work/lidar-scans.toml"
expect_bad_run lidar-background 'lidar-background.toml:4: lidar.background[0].reflectivity = 2' "[0, 1]" \
  --scenario "$work/lidar-background.toml"
expect_bad_run lidar-unknown 'lidar.range_m' "known keys of [lidar]" --scenario "$work/lidar-unknown.toml"
expect_bad_run camera-mode "camera-mode.toml:2: camera.exposure.mode = 'manual'" "one of fixed, auto" \
  --scenario "$work/camera-mode.toml"
expect_bad_run camera-sigma 'camera-sigma.toml:2: camera.roi.target.log_sigma = nan' "[0, 3]" \
  --scenario "$work/camera-sigma.toml"
expect_bad_run camera-frames 'camera-frames.toml:2: camera.frames_per_step = 1.5' "an integer in [1, 100000]" \
  --scenario "$work/camera-frames.toml"
expect_bad_run two-densities "fog.lwc_g_per_m3 (line 2) and fog.visibility_m (line 3)" "at most one fog density" \
  --scenario "$work/two-densities.toml"
# Issue 27: the value as typed and the true range, for a value of the wrong type or a sub-table too.
printf '[experiment]\nmax_active_layers = -1\n' >"$work/active-negative.toml"
printf '[lidar]\nthreshold_reflectivity = true\n' >"$work/lidar-threshold-type.toml"
printf '[lidar]\nfog_fluctuation = 3\n' >"$work/fluctuation-value.toml"
printf '[camera]\nroi = 5\n' >"$work/roi-value.toml"
printf '[lidar]\nwavelength_m = 3e-7\n' >"$work/typed-wavelength.toml"
printf '[experiment]\nseed = 1e5\n' >"$work/typed-seed.toml"
expect_bad_run active-negative "active-negative.toml:2: experiment.max_active_layers = -1" \
  "must be an integer in [0, chamber.layer_count = 4]" --scenario "$work/active-negative.toml"
expect_bad_run wrong-type-range "lidar-threshold-type.toml:2: lidar.threshold_reflectivity = true" \
  "must be a number in (0, 1]" --scenario "$work/lidar-threshold-type.toml"
expect_bad_run sub-table-value "fluctuation-value.toml:2: lidar.fog_fluctuation = 3" \
  "must be a table [lidar.fog_fluctuation] with keys correlation_time_s, log_std" \
  --scenario "$work/fluctuation-value.toml"
expect_bad_run camera-roi-value "roi-value.toml:2: camera.roi = 5" \
  "must be a table [camera.roi] with keys background, cell_px, height_px, target" \
  --scenario "$work/roi-value.toml"
expect_bad_run typed-wavelength "typed-wavelength.toml:2: lidar.wavelength_m = 3e-7:" "[4e-07, 2e-06]" \
  --scenario "$work/typed-wavelength.toml"
expect_bad_run typed-seed "typed-seed.toml:2: experiment.seed = 1e5:" "an integer in [0, 9223372036854775807]" \
  --scenario "$work/typed-seed.toml"
expect_bad_run missing-file "--scenario = '$work/does-not-exist.toml'" "a readable regular TOML file" \
  --scenario "$work/does-not-exist.toml"
expect_bad_run scenario-directory "--scenario = '$work/a-directory'" "it is a directory" --scenario "$work/a-directory"
expect_bad_run scenario-fifo "--scenario = '$work/a-fifo'" "it is a FIFO" --scenario "$work/a-fifo"
expect_bad_run scenario-device "--scenario = '/dev/zero'" "it is a character device" --scenario /dev/zero
expect_bad_run scenario-too-big "--scenario = '$work/too-big.toml'" "at most 1048576 bytes (1 MiB); it holds 1048577" \
  --scenario "$work/too-big.toml"
expect_bad_run scenario-empty "--scenario = ''" "a path (not empty)" --scenario ""
expect_bad_run threads-negative "--threads = '-1'" "an integer in [0, 4096]" --threads -1
expect_bad_run threads-text "--threads = 'many'" "an integer in [0, 4096]" --threads many
expect_bad_run threads-empty "--threads = ''" "an integer in [0, 4096]" --threads ""
expect_bad_run threads-huge "--threads = '5000'" "an integer in [0, 4096]" --threads 5000
expect_bad_run seed-negative "--seed = '-4'" "an integer in [0, 9223372036854775807]" --seed -4
expect_bad_run seed-empty "--seed = ''" "an integer in [0, 9223372036854775807]" --seed ""
expect_bad_run seed-huge "--seed = '99999999999999999999'" "an integer in [0, 9223372036854775807]" \
  --seed 99999999999999999999
expect_bad_run seed-fraction "--seed = '1.5'" "an integer in [0, 9223372036854775807]" --seed 1.5
expect_bad_run unknown-option --frobnicate "not expected" --frobnicate
expect_bad out-empty "--out = ''" "a path (not empty)" run --scenario "$src/tests/cli/small.toml" --out ""
expect_bad out-is-file "--out = '$work/a-file'" "must be a directory" run --scenario "$src/tests/cli/small.toml" --out "$work/a-file"
expect_bad out-unwritable "--out = '/proc/fogradar-out'" "a directory whose parent is writable" run --scenario "$src/tests/cli/small.toml" --out /proc/fogradar-out
expect_bad unknown-subcommand "unknown subcommand 'frob'" "one of run, scenario, fog" frob
expect_bad fog-lwc "--lwc = '-1'" "[0, 100]" fog --lwc -1
expect_bad fog-lwc-empty "--lwc = ''" "[0, 100]" fog --lwc ""
expect_bad fog-lwc-text "--lwc = 'wet'" "[0, 100]" fog --lwc wet
expect_bad fog-extinction-empty "--extinction-per-km = ''" "[0, 1e6]" fog --extinction-per-km ""
expect_bad fog-visibility-inf "--visibility-m = 'inf'" "[1e-3, 1e7]" fog --visibility-m inf
# nan and inf as typed, signs included, in options and in scenario keys.
# Over the time limit: the estimate is the message, not a line before it.
expect_bad_run time-limit-exceeded "--time-limit = 1 ms" "raise --time-limit" --scenario "$src/tests/cli/small.toml" \
  --time-limit 0.001
expect_bad time-limit-nan "--time-limit = '-nan'" "[0.001, 1e9]" run --time-limit=-nan --out "$work/bad-time-nan"
expect_bad threads-inf "--threads = '+inf'" "[0, 4096]" run --threads=+inf --out "$work/bad-threads-inf"
printf '[radar]\ntx_power_dbm = +inf\n' >"$work/plus-inf.toml"
expect_bad_run plus-inf "plus-inf.toml:2: radar.tx_power_dbm = +inf:" "[-30, 50]" --scenario "$work/plus-inf.toml"
printf '[radar]\nchirp_interval_s = -nan\n' >"$work/minus-nan.toml"
expect_bad_run minus-nan "minus-nan.toml:2: radar.chirp_interval_s = -nan:" "[radar.chirp_duration_s = 5.12e-05, 1]" \
  --scenario "$work/minus-nan.toml"
expect_bad fog-diameter-empty "--diameter-um = ''" "[0.01, 1000]" fog --diameter-um ""
expect_bad fog-temperature-empty "--temperature-c = ''" "[-20, 50] with --water-model liebe" fog --temperature-c ""
expect_bad fog-frequency-empty "--frequency-ghz = ''" "[0.03, 1000] with --water-model liebe" fog --frequency-ghz ""
expect_bad fog-model --water-model "one of 'segelstein', 'liebe'" fog --water-model mie
expect_bad fog-model-empty "--water-model = ''" "one of 'segelstein', 'liebe'" fog --water-model ""
expect_bad fog-two-densities --visibility-m "excludes" fog --lwc 1 --visibility-m 3
expect_bad fog-frequency --frequency-ghz "[0.03, 1000] with --water-model liebe" fog --frequency-ghz 1e9
expect_bad fog-liebe-frequency "--frequency-ghz = '2000'" \
  "[0.03, 1000] with --water-model liebe (Liebe 1991 ends at 1 THz); --water-model segelstein covers [0.03, 2.99e7]" \
  fog --frequency-ghz 2000
expect_bad fog-liebe-frequency-typed "--frequency-ghz = '2e3'" "--water-model segelstein covers" fog --frequency-ghz 2e3
"$fogradar" fog --lwc 1 --frequency-ghz 2000 --water-model segelstein >/dev/null 2>&1 && pass \
  || fail "fog at 2000 GHz with the table refused"
expect_bad fog-table-temperature "--temperature-c = 0" "= 25 with --water-model segelstein" \
  fog --water-model segelstein --temperature-c 0
expect_bad fog-table-temperature-names-liebe "--temperature-c" "liebe takes [-20, 50]" \
  fog --water-model segelstein --temperature-c 20
expect_bad fog-liebe-temperature "--temperature-c = '60'" "[-20, 50]" fog --temperature-c 60
# The documented bounds themselves are accepted (checked in C, before the conversion to K).
"$fogradar" fog --lwc 1 --temperature-c -20 >/dev/null 2>&1 && pass || fail "fog at -20 C refused"
"$fogradar" fog --lwc 1 --temperature-c 50 >/dev/null 2>&1 && pass || fail "fog at 50 C refused"

# --- fog --json carries the documented keys (README) ----------------------------------------------------------
json=$("$fogradar" fog --frequency-ghz 77 --lwc 1 --temperature-c 20 --json)
for key in frequency_hz wavelength_m refractive_index_n refractive_index_k lwc_g_per_m3 \
  specific_attenuation_db_per_km volume_backscatter_m2_per_m3 optical_extinction_per_km visibility_m \
  water_model temperature_c optical_water_model optical_water_temperature_c; do
  echo "$json" | grep -q "\"$key\"" && pass || fail "fog --json lacks $key"
done
# The study's fog (beta = 900 /km at 550 nm, 1 um droplets) at the three sensors' bands through one
# 2 m layer. References: the radar's two-way loss is 2 A L with A the printed specific attenuation;
# the lidar's 10 log10(e) 2 alpha L (Beer-Lambert); the camera's photopic band-weighted extinction is
# within 2 % of the 550 nm value the fog was given by (V(lambda) peaks at 555 nm and beta of 1 um
# drops changes by a few % over its width), and its transmittance is exp(-beta_eff L).
if [ -x /usr/bin/python3 ]; then
  "$fogradar" fog --extinction-per-km 900 --layer-length-m 2 --json | /usr/bin/python3 -c '
import json, math, sys
j = json.load(sys.stdin)
s = j["sensors"]
assert abs(s["radar"]["two_way_loss_db_per_layer"] - 2 * j["specific_attenuation_db_per_km"] * 2e-3) < 1e-12, s
a = s["lidar"]["extinction_per_m"]
assert abs(s["lidar"]["two_way_loss_db_per_layer"] - 10 * math.log10(math.e) * 2 * a * 2) < 1e-9, s
assert s["lidar"]["wavelength_m"] == 905e-9 and s["lidar"]["backscatter_per_m_sr"] > 0, s
c = s["camera"]
assert abs(c["extinction_per_m"] / 0.9 - 1) < 0.02, c
assert abs(c["transmittance_per_layer"] - math.exp(-2 * c["extinction_per_m"])) < 1e-12, c
' && pass || fail "fog --json: sensors' bands"
fi
# --- fog: optical models, Kunkel, the virtual layer model, drop size distributions (issue 27) -----
# Each physics value is compared with its formula written out here, not computed by fogradar:
# Kruse (paper eq. 1, 2) and Kim (Kim, McArthur & Korevaar 2001) beta = 3.912 / V (lambda / 550)^-q
# with V the eq. 6 visibility in km; eq. 5 A = 10 log10(e) beta; eq. 9 d_m = -ln(0.05) / beta;
# Kunkel 1984 beta = 144.7 LWC^0.88; eq. 3 with the Narayana numbers p_i = N(m, i) and eq. 4
# I_obj = rho_obj tau^(2k). Tolerance 1e-12 relative where the same formula is evaluated in the same
# order (a few units in the last place), 1e-10 for eq. 3, which fogradar sums in log space.
for key in optical_models meteorological_visibility_m optical_wavelength_nm lwc_from \
  droplet_parameters; do
  echo "$json" | grep -q "\"$key\"" && pass || fail "fog --json lacks $key"
done
if [ -x /usr/bin/python3 ]; then
  for args in "--visibility-m 300" "--visibility-m 800 --wavelength-nm 1550" \
    "--visibility-m 3000" "--visibility-m 10000 --wavelength-nm 1550" "--visibility-m 60000" \
    "--extinction-per-km 900"; do
    # shellcheck disable=SC2086  # the arguments are words
    "$fogradar" fog $args --json | /usr/bin/python3 -c '
import json, math, sys
j = json.load(sys.stdin)
m = j["optical_models"]
v_km = j["visibility_m"] / 1000
lam = j["optical_wavelength_nm"]
beta550 = j["optical_extinction_per_km"]
def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * abs(b)
assert close(v_km, 3.912023005428146 / beta550), (v_km, beta550)
assert close(j["meteorological_visibility_m"], -math.log(0.05) / beta550 * 1000), j
if v_km > 50:
    q_kruse, q_kim = 1.6, 1.6
elif v_km > 6:
    q_kruse, q_kim = 1.3, 1.3
else:
    q_kruse = 0.585 * v_km ** (1 / 3)
    q_kim = 0.16 * v_km + 0.34 if v_km > 1 else (v_km - 0.5 if v_km > 0.5 else 0.0)
for name, q in (("kruse", q_kruse), ("kim", q_kim)):
    beta = 3.912023005428146 / v_km * (lam / 550) ** -q
    assert close(m[name]["q"], q) or m[name]["q"] == q, (name, m[name], q)
    assert close(m[name]["extinction_per_km"], beta), (name, m[name], beta)
for name, row in m.items():
    db = 10 * math.log10(math.e) * row["extinction_per_km"]
    assert close(row["specific_attenuation_db_per_km"], db), (name, row)
if lam == 905:
    assert close(m["mie"]["extinction_per_km"], j["sensors"]["lidar"]["extinction_per_m"] * 1e3)
' && pass || fail "fog --json $args: Kruse, Kim, eq. 5, eq. 9 against their formulas"
  done
  # At 550 nm eq. 1 is eq. 6 whatever q: Kruse, Kim and Mie give the fog's own extinction.
  "$fogradar" fog --visibility-m 2000 --wavelength-nm 550 --json | /usr/bin/python3 -c '
import json, sys
j = json.load(sys.stdin)
b = j["optical_extinction_per_km"]
assert all(abs(r["extinction_per_km"] - b) <= 1e-12 * b for r in j["optical_models"].values()), j
' && pass || fail "fog at 550 nm: the three models differ"
  # Kunkel both ways; the radar then sees Kunkel's LWC (the same numbers as --lwc with it), the
  # optical models the extinction.
  "$fogradar" fog --lwc-from kunkel --extinction-per-km 900 --json >"$work/kunkel.json"
  lwc=$(/usr/bin/python3 -c 'import json, sys; print(repr(json.load(sys.stdin)["lwc_g_per_m3"]))' \
    <"$work/kunkel.json")
  "$fogradar" fog --lwc "$lwc" --json >"$work/kunkel-lwc.json"
  /usr/bin/python3 - "$work/kunkel.json" "$work/kunkel-lwc.json" <<'EOF' && pass \
    || fail "fog --lwc-from kunkel"
import json, sys
k, by_lwc = (json.load(open(path)) for path in sys.argv[1:])
assert k["lwc_from"] == "kunkel", k
assert abs(k["lwc_g_per_m3"] - (900 / 144.7) ** (1 / 0.88)) <= 1e-12 * k["lwc_g_per_m3"], k
assert abs(k["optical_extinction_per_km"] - 900) <= 1e-12 * 900, k
for key in ("specific_attenuation_db_per_km", "volume_backscatter_m2_per_m3"):
    assert k[key] == by_lwc[key], (key, k[key], by_lwc[key])
assert k["sensors"]["radar"] == by_lwc["sensors"]["radar"], k["sensors"]
assert abs(k["optical_models"]["kim"]["extinction_per_km"] - 900) <= 1e-12 * 900, k
EOF
  for args in "--lwc 0.5" "--visibility-m 20"; do
    # shellcheck disable=SC2086
    "$fogradar" fog --lwc-from kunkel $args --json | /usr/bin/python3 -c '
import json, sys
j = json.load(sys.stdin)
beta, lwc = j["optical_extinction_per_km"], j["lwc_g_per_m3"]
assert abs(beta - 144.7 * lwc ** 0.88) <= 1e-12 * beta, (beta, lwc)
' && pass || fail "fog --lwc-from kunkel $args: beta != 144.7 LWC^0.88"
  done
  # The virtual layer model: tau = exp(-alpha d), rho = eta d of one layer at the wavelength (eta
  # = 4 pi beta_pi of the lidar's own report at 905 nm), eq. 3 and eq. 4 per row.
  for args in "--layer-model 12" "--layer-model 6 --diameter-um 3 --layer-length-m 2" \
    "--layer-model 4 --object-reflectivity 0.9 --wavelength-nm 1550"; do
    # shellcheck disable=SC2086
    "$fogradar" fog $args --json | /usr/bin/python3 -c '
import json, math, sys
j = json.load(sys.stdin)
lm = j["layer_model"]
d, alpha, eta = lm["layer_length_m"], lm["extinction_per_m"], lm["volume_backscatter_m2_per_m3"]
tau, rho, rho_obj = lm["transmittance_tau"], lm["reflectance_rho"], lm["object_reflectivity"]
assert abs(alpha - j["optical_models"]["mie"]["extinction_per_km"] / 1e3) <= 1e-12 * alpha, lm
if lm["wavelength_nm"] == 905:
    eta_lidar = 4 * math.pi * j["sensors"]["lidar"]["backscatter_per_m_sr"]
    assert abs(eta - eta_lidar) <= 1e-12 * eta, (eta, eta_lidar)
    assert rho_obj == 1.0 or "--object-reflectivity" in sys.argv[1], lm
assert abs(tau - math.exp(-alpha * d)) <= 1e-15 and abs(rho - eta * d) <= 1e-15 * rho, lm
def narayana(m, i):
    return math.comb(m, i) * math.comb(m, i - 1) // m
for row in lm["rows"]:
    k, kappa = row["layers"], row["kappa"]
    m = (kappa - 1) // 2
    assert kappa == 2 * k + 1, row
    eq3 = rho if m == 0 else sum(
        narayana(m, i) * rho ** (2 * i - 1) * tau ** (kappa + 1 - 2 * i) for i in range(1, m + 1))
    assert abs(row["fog_intensity_per_i0"] - eq3) <= 1e-10 * eq3, (row, eq3)
    eq4 = rho_obj * tau ** (2 * k)
    assert abs(row["object_intensity_per_i0"] - eq4) <= 1e-12 * eq4, (row, eq4)
written_out = {1: rho, 3: rho * tau**2, 5: rho * tau**4 + rho**3 * tau**2,
               7: rho * tau**6 + 3 * rho**3 * tau**4 + rho**5 * tau**2}
for row in lm["rows"][:4]:
    assert abs(row["fog_intensity_per_i0"] - written_out[row["kappa"]]) <= 1e-12 * rho, row
' "$args" && pass || fail "fog --json $args: eq. 3, 4 against their formulas"
  done
  # Limiting case: no water, tau = 1 and rho = 0: no fog echo, the object echo undimmed.
  "$fogradar" fog --lwc 0 --layer-model 3 --object-reflectivity 0.7 --json | /usr/bin/python3 -c '
import json, sys
lm = json.load(sys.stdin)["layer_model"]
assert lm["transmittance_tau"] == 1 and lm["reflectance_rho"] == 0, lm
assert [r["fog_intensity_per_i0"] for r in lm["rows"]] == [0] * 4, lm
assert [r["object_intensity_per_i0"] for r in lm["rows"]] == [0.7] * 4, lm
' && pass || fail "fog --lwc 0 --layer-model: not the clear-air limit"
  # Drop size distributions as the scenario's [fog.droplets] keys give them. N = LWC / (rho_w
  # (pi/6) <D^3>) with the closed-form moments: D^3 (monodisperse), D_med^3 exp(9 s^2 / 2)
  # (lognormal), 8 Gamma(alpha + 4) / (Gamma(alpha + 1) b^3) um^3 (modified gamma, gamma = 1);
  # 1e-12 for the single node of monodisperse, 1e-6 for the quadrature truncated at 1e-12 tails.
  for case in "monodisperse|--lwc 1 --diameter-um 10" \
    "monodisperse|--lwc 1 --distribution monodisperse --diameter-um 10" \
    "lognormal|--lwc 1 --distribution lognormal --median-diameter-um 2 --geometric-std 1.8" \
    "lognormal|--lwc 1" "modified_gamma|--lwc 1 --distribution advection" \
    "modified_gamma|--lwc 1 --distribution radiation" \
    "modified_gamma|--lwc 1 --distribution modified_gamma --alpha 4 --b-per-um-gamma 0.5"; do
    family=${case%%|*}
    # shellcheck disable=SC2086
    "$fogradar" fog ${case#*|} --json | /usr/bin/python3 -c '
import json, math, sys
j = json.load(sys.stdin)
p = j["droplet_parameters"]
assert j["droplets"] == sys.argv[1], j["droplets"]
if sys.argv[1] == "monodisperse":
    assert p == {"diameter_um": 10.0}, p
    d3_um3, tol = 10.0**3, 1e-12
elif sys.argv[1] == "lognormal":
    want = {"median_diameter_um": 2.0, "geometric_std": 1.8} if "--median-diameter-um" in \
        sys.argv[2] else {"median_diameter_um": 1.0, "geometric_std": 1.5}
    assert p == want, p
    d3_um3 = p["median_diameter_um"]**3 * math.exp(4.5 * math.log(p["geometric_std"])**2)
    tol = 1e-6
else:
    # Presets: Al Naboulsi et al. 2004, Table 1 (Shettle & Fenn).
    want = {"--distribution advection": {"alpha": 3.0, "gamma": 1.0, "b_per_um_gamma": 0.3},
            "--distribution radiation": {"alpha": 6.0, "gamma": 1.0, "b_per_um_gamma": 1.5}}
    given = {"alpha": 4.0, "gamma": 1.0, "b_per_um_gamma": 0.5}
    assert p == next((w for k, w in want.items() if k in sys.argv[2]), given), p
    a, b = p["alpha"], p["b_per_um_gamma"]
    d3_um3, tol = 8 * math.gamma(a + 4) / math.gamma(a + 1) / b**3, 1e-6
n_per_cm3 = 1.0 / (1e6 * math.pi / 6 * d3_um3 * 1e-18) * 1e-6
got = j["number_concentration_per_cm3"]
assert abs(got - n_per_cm3) <= tol * n_per_cm3, (got, n_per_cm3)
' "$family" "${case#*|}" && pass || fail "fog ${case#*|}: droplets or N off"
  done
  # The bound a refusal of --layer-length-m states is itself accepted.
  "$fogradar" fog --diameter-um 20 --layer-model 2 --layer-length-m 20 2>"$work/stderr" >/dev/null
  bound=$(sed -n 's/.*must be at most \([0-9.e+-]*\) with.*/\1/p' "$work/stderr")
  [ -n "$bound" ] && "$fogradar" fog --diameter-um 20 --layer-model 2 --layer-length-m "$bound" \
    >/dev/null 2>&1 && pass || fail "the stated longest layer ($bound) is refused"
fi
# Text: optical wavelengths in nm, radar ones in mm; the models and the layer table are printed.
"$fogradar" fog --frequency-ghz 3e5 --water-model segelstein | grep -q '(wavelength 999.308 nm)' \
  && pass || fail "an optical --frequency-ghz does not print its wavelength in nm"
"$fogradar" fog | grep -q '(wavelength 3.89341 mm)' && pass || fail "77 GHz not printed in mm"
text=$("$fogradar" fog --layer-model 3)
for line in '^CIE visibility (eq. 9)    3.32859 m' '^at 905 nm' '^  Mie  ' '^  Kruse (eq. 1, 2)  ' \
  '^  Kim (eq. 1)  ' '^  transmittance tau  ' '^  reflectance rho  ' '^         3  '; do
  echo "$text" | grep -q "$line" && pass || fail "fog --layer-model 3 text lacks '$line'"
done
"$fogradar" fog --optical-model kim | grep -c '^  \(Mie\|Kruse\|Kim\)' | grep -qx 2 && pass \
  || fail "--optical-model kim does not print Mie and Kim alone"
expect_bad fog-optical-model "--optical-model = 'foo'" "one of 'mie', 'kruse', 'kim'" \
  fog --optical-model kruse,foo
expect_bad fog-wavelength "--wavelength-nm = '300'" "in [400, 2000]" fog --wavelength-nm 300
expect_bad fog-wavelength-empty "--wavelength-nm = ''" "in [400, 2000]" fog --wavelength-nm ""
expect_bad fog-lwc-from "--lwc-from = 'liebe'" "one of 'mie', 'kunkel'" fog --lwc-from liebe
expect_bad fog-kunkel-extinction "--extinction-per-km = 9000" \
  "in [0, 8326.61] with --lwc-from kunkel" \
  fog --lwc-from kunkel --extinction-per-km 9000
expect_bad fog-kunkel-visibility "--visibility-m = 0.4" \
  "in [0.469822, 1e7] with --lwc-from kunkel" \
  fog --lwc-from kunkel --visibility-m 0.4
"$fogradar" fog --lwc-from kunkel --extinction-per-km 8326.61 >/dev/null 2>&1 \
  && "$fogradar" fog --lwc-from kunkel --visibility-m 0.469822 >/dev/null 2>&1 && pass \
  || fail "the stated Kunkel bounds are refused"
expect_bad fog-layer-model "--layer-model = '0'" "an integer in [1, 1000]" fog --layer-model 0
expect_bad fog-layer-model-many "--layer-model = '1001'" "an integer in [1, 1000]" \
  fog --layer-model 1001
expect_bad fog-layer-model-text "--layer-model = '2.5'" "an integer in [1, 1000]" \
  fog --layer-model 2.5
expect_bad fog-object-reflectivity "--object-reflectivity = '1.5'" "in [0, 1]" \
  fog --layer-model 2 --object-reflectivity 1.5
expect_bad fog-object-reflectivity-alone "--object-reflectivity" "requires --layer-model" \
  fog --object-reflectivity 0.5
expect_bad fog-layer-too-long "--layer-length-m = 20" "at most" \
  fog --diameter-um 20 --layer-model 2 --layer-length-m 20
expect_bad fog-distribution "--distribution = 'gamma'" \
  "one of 'lognormal', 'monodisperse', 'advection', 'radiation', 'modified_gamma'" \
  fog --distribution gamma
expect_bad fog-distribution-empty "--distribution = ''" "one of 'lognormal'" fog --distribution ""
expect_bad fog-median "--median-diameter-um = '2000'" "in [0.01, 1000]" \
  fog --median-diameter-um 2000
expect_bad fog-geometric-std "--geometric-std = '1'" "in [1.01, 3]" fog --geometric-std 1
expect_bad fog-alpha "--alpha = '21'" "in [0, 20]" fog --distribution advection --alpha 21
expect_bad fog-gamma "--gamma = '0.2'" "in [0.25, 4]" fog --distribution advection --gamma 0.2
expect_bad fog-b "--b-per-um-gamma = '0'" "finite and > 0" \
  fog --distribution advection --b-per-um-gamma 0
expect_bad fog-b-mode-radius "--b-per-um-gamma = 0.001" \
  "mode radius (alpha / (b gamma))^(1/gamma) <= 500 um" \
  fog --distribution modified_gamma --b-per-um-gamma 0.001
expect_bad fog-parameter-of-another-family "--geometric-std = 2" \
  'given only with --distribution = "lognormal"' \
  fog --distribution radiation --geometric-std 2
expect_bad fog-diameter-not-monodisperse "--diameter-um = 3" \
  'given only with --distribution = "monodisperse"' \
  fog --distribution lognormal --diameter-um 3
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
# The key tables of the docs are the keys' declarations as `fogradar scenario --keys` prints them.
"$src/scripts/update-docs.sh" --check "$fogradar" 2>"$work/stale" && pass || fail "$(cat "$work/stale")"
expect_bad keys-unknown-section "--keys" "a section of the scenario: radar, processing, target" scenario --keys radr

# --- memory limit (docs/scenario.md, "Memory limit"): refused up front, before any frame exists -----
printf '[radar]\nsamples_per_chirp = 65536\nchirps_per_frame = 16384\nchirp_duration_s = 6.5536e-3\nchirp_interval_s = 6.5536e-3\n' \
  >"$work/huge.toml"
for key in radar.samples_per_chirp radar.chirps_per_frame experiment.measurements_per_step --threads; do
  start=$(date +%s)
  expect_bad "huge-$key" "$key" "more than the limit of 8192 MiB" run --scenario "$work/huge.toml" \
    --out "$work/bad-huge-$key" --memory-limit-mib 8192
  [ $(($(date +%s) - start)) -le 5 ] && pass || fail "65536 x 16384 refused only after more than 5 s"
done
# The default limit, half the physical memory, where that is below the 17 GiB one frame takes.
half_mib=$(($(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 2048))
if [ "$half_mib" -lt 17000 ]; then
  expect_bad huge-default "radar.chirps_per_frame" "more than the limit of" run --scenario "$work/huge.toml" --out "$work/bad-huge-default" --threads 1
fi
expect_bad small-over-limit "--memory-limit-mib" "more than the limit of 1 MiB" run --scenario "$src/tests/cli/small.toml" --out "$work/bad-small-over-limit" \
  --memory-limit-mib 1
expect_bad memory-limit-range "--memory-limit-mib" "must be in [1, 1e9]" run --scenario "$src/tests/cli/small.toml" --out "$work/bad-memory-limit-range" \
  --memory-limit-mib 0
"$fogradar" run --scenario "$src/tests/cli/small.toml" --out "$work/t-limit" --memory-limit-mib 64 >/dev/null 2>&1 && pass \
  || fail "small.toml refused under a 64 MiB limit"

# --- raw data out (docs/data-out.md): checked before the run, written whole or not at all -----------
small="$src/tests/cli/small.toml"
expect_bad_run raw-select "--raw-select" "the running sensors' kinds: radar.beat, radar.range_doppler" \
  --scenario "$small" --raw "$work/x.h5" --raw-select radar.beat,radar.bogus
expect_bad_run raw-steps "--raw-steps" "ranges a-b in [0, 4]" --scenario "$small" --raw "$work/x.h5" --raw-steps 0,5
expect_bad_run raw-items "--raw-items" "(e.g. 0,4 or 0-2,4)" --scenario "$small" --raw "$work/x.h5" --raw-items 3-1
expect_bad_run raw-limit "--raw-limit-mib" "more than the limit of 1 MiB" --scenario "$small" --raw "$work/x.h5" \
  --raw-limit-mib 1
# The options not given are named with the defaults in force, those given as typed.
expect_bad_run raw-limit-defaults "--raw-limit-mib" "fewer kinds (--raw-select not given: every kind of the sensors that run, radar.beat," \
  --scenario "$small" --raw "$work/x.h5" --raw-limit-mib 1
expect_bad_run raw-limit-default-steps "--raw-select = 'radar.beat'" "steps (--raw-steps not given: every step, 0-4) or items (--raw-items = '0-5')" \
  --scenario "$small" --raw "$work/x.h5" --raw-limit-mib 1 --raw-select radar.beat --raw-items 0-5
expect_bad_run raw-needed "--raw" "--raw-select requires --raw" --scenario "$small" --raw-select radar.beat
"$fogradar" run --scenario "$small" --out "$work/raw-inside" --raw "$work/raw-inside/r.h5" >"$work/stdout" 2>"$work/stderr"
check_message raw-inside $? "--raw = '$work/raw-inside/r.h5'" "must be a file outside --out" \
  && [ ! -e "$work/raw-inside" ] && pass || fail "--raw inside --out: created $work/raw-inside"
[ ! -e "$work/x.h5" ] && pass || fail "a refused run created its --raw file"
# A file of the user's under the --raw name is never overwritten.
printf 'mine\n' >"$work/mine.h5"
"$fogradar" run --scenario "$small" --out "$work/raw-mine" --raw "$work/mine.h5" >"$work/stdout" 2>"$work/stderr"
check_message raw-mine $? "--raw = '$work/mine.h5'" "a new file or one fogradar wrote" \
  && [ "$(cat "$work/mine.h5")" = mine ] && [ ! -e "$work/raw-mine" ] \
  && pass || fail "--raw over a user's file: overwritten, or $work/raw-mine created"
# Written whole: a raw file fogradar wrote is replaced; a run with --raw gives the same result set as one
# without; a stopped run leaves neither the file nor its temporary.
"$fogradar" run --scenario "$small" --out "$work/raw-a" --raw "$work/raw/r.h5" --raw-items 0-1 >/dev/null 2>&1 \
  && "$fogradar" run --scenario "$small" --out "$work/raw-a" --raw "$work/raw/r.h5" >/dev/null 2>&1 \
  && pass || fail "a raw file fogradar wrote is not replaced"
"$fogradar" run --scenario "$small" --out "$work/raw-b" >/dev/null 2>&1
diff -r "$work/raw-a" "$work/raw-b" >/dev/null && pass || fail "--raw changed the result set"
command -v h5dump >/dev/null && { h5dump -H "$work/raw/r.h5" | grep -q 'DATASET "range_doppler"' && pass \
  || fail "h5dump finds no /radar/range_doppler"; }
set -m
"$fogradar" run --scenario "$work/long.toml" --threads 1 --out "$work/raw-stopped" --raw "$work/raw-stopped.h5" \
  >/dev/null 2>"$work/err" &
pid=$!
set +m
for _ in $(seq 100); do ls -A "$work" | grep -q '^\.raw-stopped\.h5\.tmp-' && break; sleep 0.05; done
sleep 0.2
kill -s TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 143 ] && [ ! -e "$work/raw-stopped.h5" ] && [ -z "$(ls -A "$work" | grep '^\.raw-stopped')" ] && pass \
  || fail "a stopped run with --raw: exit $rc, left $(ls -A "$work" | grep raw-stopped)"

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
