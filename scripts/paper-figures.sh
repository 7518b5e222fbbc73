#!/usr/bin/env bash
# Regenerates the figures and tables of docs/paper-comparison.md from the current build
# (scripts/run.sh builds it): the paper scenario's summary and figures of all three sensors (seed 1)
# into docs/figures/, the run under the study's other fog reading (V = 5.74 m),
# the seed 2 and 3 shifts, and the baseline decomposition (the model's parts switched on one at a
# time, 0 active layers, 200 measurements each). Prints what the page quotes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
fogradar="$root/build/release/cli/fogradar"
[ -x "$fogradar" ] || { echo "build the tool first: scripts/run.sh" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$fogradar" run --out "$work/seed1" >"$work/seed1.txt"
cp "$work/seed1/radar_summary.csv" "$root/docs/figures/paper_summary.csv"
cp "$work/seed1/radar_rcs_boxplot.svg" "$root/docs/figures/paper_rcs_boxplot.svg"
for figure in lidar_intensity_boxplot lidar_scans camera_histograms benchmark; do
  cp "$work/seed1/$figure.svg" "$root/docs/figures/paper_$figure.svg"
done
grep -v "^results in" "$work/seed1.txt"

# The study's other fog reading: visibility 5.74 m instead of beta = 900 /km, the camera calibrated
# on the study's 0- and 2-layer means for that reading (docs/camera.md §6-7).
cat >"$work/visibility.toml" <<'TOML'
[fog]
visibility_m = 5.74
[camera.exposure]
ambient_level = 0.05788
[camera.roi.target]
median_reflectance = 0.2643
TOML
echo "== the visibility reading (V = 5.74 m)"
"$fogradar" run --scenario "$work/visibility.toml" --out "$work/visibility" | grep -v "^results in"
for seed in 2 3; do
  "$fogradar" run --seed "$seed" --out "$work/seed$seed" >/dev/null
  printf 'seed %s Hodges-Lehmann shifts (dB), steps 1-4:' "$seed"
  awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    $1 > 0 { printf " %+.3f", $col["median_shift_db"] } END { print "" }' "$work/seed$seed/radar_summary.csv"
done

# One baseline variant: `decompose NAME TOML` runs 200 measurements at 0 layers with the TOML text
# (sections of its own, never [experiment]) over the paper scenario and prints the median and IQR of
# the radar's RCS.
decompose() {
  printf '%s\n[experiment]\nmax_active_layers = 0\nsensors = ["radar"]\n' "$2" >"$work/variant.toml"
  "$fogradar" run --scenario "$work/variant.toml" --out "$work/variant" >/dev/null
  awk -F, -v name="$1" 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    $col["detections"] == 0 { printf "| %s | – | – | 0 %% |\n", name; next }
    { printf "| %s | %.3f | %.3f | %.1f %% |\n", name, $col["median_dbsm"],
        $col["q3_dbsm"] - $col["q1_dbsm"], 100 * $col["detection_rate"] }' \
    "$work/variant/radar_summary.csv"
}
empty=$'[chamber]\nobjects = []\n[chamber.room]\nfloor = false\nleft_wall = false'
bare=$'[chamber]\nobjects = []\n[chamber.room]\nleft_wall = false'
still=$'[target]\nmicro_motion_std_m = 0.0'
point=$'[radar.target]\nmodel = "point"'
echo "| model | median (dBsm) | IQR (dB) | target detected |"
echo "|---|---|---|---|"
decompose "point target 10 dBsm, empty hall, no micro-motion" "$empty"$'\n'"$still"$'\n'"$point"
decompose "EVT, empty hall, no micro-motion" "$empty"$'\n'"$still"
decompose "EVT, empty hall, 0.2 mm micro-motion" "$empty"
decompose "EVT, floor of coefficient -0.7 alone" "$bare"$'\n[chamber.room.floor]\nreflection_coefficient = -0.7'
decompose "EVT, concrete floor alone, horizontal" "$bare"
decompose "EVT, concrete floor alone, vertical" "$bare"$'\n[radar]\npolarisation = "vertical"'
decompose "EVT, concrete floor, wall and barrels (the paper scenario)" ""
decompose "the paper scenario, vertical" $'[radar]\npolarisation = "vertical"'
decompose "the paper scenario, metal wall" $'[chamber.room.left_wall]\nmaterial = "metal"'
for resolution in 0.2 0.6 1.8; do
  bandwidth=$(awk -v r="$resolution" 'BEGIN { printf "%.6g", 299792458 / (2 * r) }')
  decompose "the paper scenario, range resolution $resolution m" $'[radar]\nsweep_bandwidth_hz = '"$bandwidth"
done
# What the study's unnamed radar's beam would do (not among the envelope's keys: its own row each).
for width in 30 60; do
  decompose "the paper scenario, azimuth beam $width deg" $'[radar]\nazimuth_beamwidth_deg = '"$width"
done
decompose "EVT, concrete floor alone, azimuth beam 60 deg" "$bare"$'\n[radar]\nazimuth_beamwidth_deg = 60'
decompose "EVT, empty hall, azimuth beam 60 deg" "$empty"$'\n[radar]\nazimuth_beamwidth_deg = 60'
decompose "the paper scenario, azimuth beam 60 deg, metal wall" \
  $'[radar]\nazimuth_beamwidth_deg = 60\n[chamber.room.left_wall]\nmaterial = "metal"'
for h in 0.50 0.55 0.60 0.70; do
  decompose "point target, concrete floor, no micro-motion, target at $h m" \
    "$bare"$'\n'"$still"$'\n'"$point"$'\nheight_m = '"$h"
done
