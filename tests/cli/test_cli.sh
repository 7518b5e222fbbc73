#!/usr/bin/env bash
# End-to-end checks of the fogradar command (README, docs/scenario.md, docs/architecture.md Contracts): outputs, byte-identical results for 1 and
# 2 threads, and bad input -> exit status 2, one message naming the argument or key, no files left.
# Usage: test_cli.sh FOGRADAR_BINARY SOURCE_DIR
set -u
fogradar=$1
src=$2
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

# --- memory limit (docs/scenario.md, "Memory limit"): refused up front, before any frame exists -----
printf '[radar]\nsamples_per_chirp = 65536\nchirps_per_frame = 16384\nchirp_duration_s = 6.5536e-3\nchirp_interval_s = 6.5536e-3\n' \
  >"$work/huge.toml"
for key in radar.samples_per_chirp radar.chirps_per_frame experiment.measurements_per_step --threads; do
  start=$(date +%s)
  expect_bad "huge-$key" "$key" run --scenario "$work/huge.toml" --out "$work/bad-huge-$key" --memory-limit-mib 8192
  [ $(($(date +%s) - start)) -le 5 ] && pass || fail "65536 x 16384 refused only after more than 5 s"
done
# The default limit, half the physical memory, where that is below the 17 GiB one frame takes.
half_mib=$(($(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 2048))
if [ "$half_mib" -lt 17000 ]; then
  expect_bad huge-default "radar.chirps_per_frame" run --scenario "$work/huge.toml" --out "$work/bad-huge-default" --threads 1
fi
expect_bad small-over-limit "--memory-limit-mib" run --scenario "$src/tests/cli/small.toml" --out "$work/bad-small-over-limit" \
  --memory-limit-mib 1
expect_bad memory-limit-range "--memory-limit-mib" run --scenario "$src/tests/cli/small.toml" --out "$work/bad-memory-limit-range" \
  --memory-limit-mib 0
"$fogradar" run --scenario "$src/tests/cli/small.toml" --out "$work/t-limit" --memory-limit-mib 64 >/dev/null 2>&1 && pass \
  || fail "small.toml refused under a 64 MiB limit"

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
