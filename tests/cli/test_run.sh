#!/usr/bin/env bash
# End-to-end checks of `fogradar run` (docs/cli.md, docs/scenario.md, docs/architecture.md
# Contracts): outputs, byte-identical results for 1 and 2 threads, the result set replaced whole or
# not at all, bad input -> exit status 2, one message naming the argument or key and the allowed
# range, no fresh output directory created and an earlier result left unchanged; the memory limit
# and the raw data.
# Usage: test_run.sh FOGRADAR_BINARY SOURCE_DIR
. "$(dirname "$0")/cli_test_support.sh"

# --- outputs and determinism -------------------------------------------------------------------
"$fogradar" run --scenario "$src/tests/cli/small.toml" --out "$work/t1" --threads 1 >"$work/t1.log" 2>&1 \
  || fail "small run (1 thread) failed: $(cat "$work/t1.log")"
"$fogradar" run --scenario "$src/tests/cli/small.toml" --out "$work/t2" --threads 2 >/dev/null 2>&1 \
  || fail "small run (2 threads) failed"
# small.toml runs the paper scenario's three sensors: every sensor's files.
for f in radar_samples.csv radar_detections.csv radar_summary.csv radar_summary.json radar_rcs_boxplot.svg radar_origins.svg summary.json scenario.toml \
  lidar_echoes.csv lidar_summary.csv lidar_summary.json lidar_intensity_boxplot.svg lidar_scans.svg \
  camera_histograms.csv camera_summary.csv camera_summary.json camera_histograms.svg benchmark.svg; do
  if [ -s "$work/t1/$f" ] && cmp -s "$work/t1/$f" "$work/t2/$f"; then pass; else fail "$f missing or differs between 1 and 2 threads"; fi
done
[ "$(ls -A "$work/t1" | wc -l)" -eq 19 ] && pass || fail "result set is not the 18 files and their record: $(ls -A "$work/t1")"
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
head -1 "$work/t1/radar_summary.csv" | grep -qx 'active_layers,n,detections,detection_rate,mean_dbsm,std_db,min_dbsm,q1_dbsm,median_dbsm,q3_dbsm,max_dbsm,whisker_low_dbsm,whisker_high_dbsm,outliers,median_shift_db,p_value,median_shift_ci95_low_db,median_shift_ci95_high_db,median_snr_db,two_way_attenuation_db,radome_two_way_loss_db,target_film_loss_db,confusion_rate,false_association_rate,false_alarms_per_frame,fog_detections_per_frame,adc_clipped_fraction,clipping_detections_per_frame,sidelobe_detections_per_frame,multipath_detections_per_frame,room_detections_per_frame' \
  && pass || fail "radar_summary.csv header"
[ "$(wc -l <"$work/t1/radar_samples.csv")" -eq 31 ] && pass || fail "radar_samples.csv should have 5 x 6 rows"
grep -q '"sensor_limit_layers"' "$work/t1/summary.json" && pass || fail "summary.json lacks sensor_limit_layers"
grep -q '<svg' "$work/t1/radar_rcs_boxplot.svg" && pass || fail "no svg element"
# An XML parser independent of the C++ tests' checker, where Python is installed.
if [ -x /usr/bin/python3 ]; then
  for svg in radar_rcs_boxplot.svg radar_origins.svg lidar_intensity_boxplot.svg lidar_scans.svg camera_histograms.svg benchmark.svg; do
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

# --- the result set is replaced whole or not at all (docs/cli.md, docs/scenario.md Results) ---------------
# Each case works in a parent of its own so that "no temporary files" means an empty listing besides DIR.
small="$src/tests/cli/small.toml"
# The paper scenario with 5000 measurements per step runs for many seconds: still going when signalled.
printf '[radar]\nmeasurements_per_step = 5000\n' >"$work/long.toml"
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
printf '[radar.processing.cfar]\ntraining_cells = 400\n' >"$work/cfar.toml"
printf '[radar]\ncentre_frequency_hz = 5e13\n' >"$work/freq.toml"
printf '[radar]\ncarrier_frequency_hz = 77e9\n' >"$work/carrier.toml"
printf '[fog]\nwater_model = "segelstein"\ntemperature_c = 0\n' >"$work/cold-table.toml"
printf '[fog]\nlwc_g_per_m3 = nan\n' >"$work/nan.toml"
printf '[radar\n' >"$work/malformed.toml"
printf '[radar.processing]\nwindow = ""\n' >"$work/empty-window.toml"
printf '[fog]\nwater_model = ""\n' >"$work/empty-water.toml"
printf '[radar]\nsamples_per_chirp = 5000000000\n' >"$work/huge-samples.toml"
printf '[radar]\nclutter_scatterers_per_bin = 65\n' >"$work/clutter.toml"
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
printf '[radar]\nsamples_per_chirp = 32\n[radar.processing.cfar]\nguard_cells = 20\n' >"$work/guard.toml"
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
expect_bad_run cfar-window "cfar.toml:2: radar.processing.cfar.training_cells = 400" "[1, 253]" --scenario "$work/cfar.toml"
expect_bad_run guard-fills-profile "guard.toml:4: radar.processing.cfar.guard_cells = 20" \
  "[0, 7] with radar.processing.cfar.training_cells = 8 and a profile of radar.samples_per_chirp = 32 cells" \
  --scenario "$work/guard.toml"
expect_bad_run target-beyond-range "far.toml:5: chamber.target_gap_m = 40" "radar.sample_rate_hz at line 2" \
  --scenario "$work/far.toml"
expect_bad_run frequency radar.centre_frequency_hz "[1000000000, 3e+11]" --scenario "$work/freq.toml"
expect_bad_run retired-carrier radar.centre_frequency_hz radar.sweep_direction --scenario "$work/carrier.toml"
expect_bad_run table-temperature "cold-table.toml:3: fog.temperature_c = 0" "liebe\" takes [-20, 50]" \
  --scenario "$work/cold-table.toml"
expect_bad_run nan-lwc "nan.toml:2: fog.lwc_g_per_m3 = nan" "[0, 100]" --scenario "$work/nan.toml"
expect_bad_run malformed malformed.toml:1 "malformed TOML" --scenario "$work/malformed.toml"
expect_bad_run empty-window "empty-window.toml:2: radar.processing.window = ''" "one of rectangular, hann" \
  --scenario "$work/empty-window.toml"
expect_bad_run empty-water-model "empty-water.toml:2: fog.water_model = ''" "one of liebe, segelstein" \
  --scenario "$work/empty-water.toml"
expect_bad_run integer-documented-range "radar.samples_per_chirp = 5000000000" "an integer in [16, 512]: the samples fit in the chirp" \
  --scenario "$work/huge-samples.toml"
expect_bad_run clutter-range "radar.clutter_scatterers_per_bin = 65" "an integer in [1, 64]" --scenario "$work/clutter.toml"
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
# The value as typed and the true range, for a value of the wrong type or a sub-table too.
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
# --- memory limit (docs/scenario.md, "Memory limit"): refused up front, before any frame exists -----
printf '[radar]\nsamples_per_chirp = 65536\nchirps_per_frame = 16384\nchirp_duration_s = 6.5536e-3\nchirp_interval_s = 6.5536e-3\n' \
  >"$work/huge.toml"
for key in radar.samples_per_chirp radar.chirps_per_frame radar.measurements_per_step --threads; do
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

finish

