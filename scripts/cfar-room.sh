#!/usr/bin/env bash
# The table of docs/radar.md §7.1, "Zero-Doppler clutter beside a slow target": runs
# examples/room_clutter.toml (the EVT at 10 m, a concrete back wall 1 m behind it, two rain barrels
# 1.2 m in front of it in the beam, no fog) for each CFAR shape x kind and the target at 0, 1, 2, 3
# and 5 Doppler bins (one bin lambda / (2 N_c T) = 0.594 m/s), and prints one row per case: the
# target's detection rate and median RCS (radar_summary.csv, target-origin detections in the gate)
# and, per frame, the detections of each other origin counted from radar_detections.csv. First
# writes docs/figures/room_clutter_origins.svg (below).
# Usage: scripts/cfar-room.sh [FOGRADAR_BINARY]   (default build/release/cli/fogradar)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
fogradar=${1:-"$root/build/release/cli/fogradar"}
[ -x "$fogradar" ] || { echo "build the tool first: scripts/run.sh" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# lambda / (2 N_c T_i) of the paper radar (77 GHz, 64 chirps of 51.2 us)
bin=$(awk 'BEGIN { printf "%.9g", 299792458 / 77e9 / (2 * 64 * 51.2e-6) }')

# docs/figures/room_clutter_origins.svg: the scenario with the target at 2 bins and the paper's four
# fog layers switched on one by one, the default CFAR (range CA): its origins plot.
sed 's/^max_active_layers = 0 .*/max_active_layers = 4/' "$root/examples/room_clutter.toml" >"$work/origins.toml"
printf '\n[target]\nradial_velocity_m_per_s = %s\n' \
  "$(awk -v b="$bin" 'BEGIN { printf "%.9g", 2 * b }')" >>"$work/origins.toml"
"$fogradar" run --scenario "$work/origins.toml" --out "$work/origins" >/dev/null
cp "$work/origins/radar_origins.svg" "$root/docs/figures/room_clutter_origins.svg"
echo "| shape | kind | Doppler bin (m/s) | target detected | median RCS (dBsm) | room /frame | multipath /frame | sidelobe /frame | noise /frame |"
echo "|---|---|---|---|---|---|---|---|---|"
for shape in range range_doppler; do
  for kind in ca go so os; do
    for bins in 0 1 2 3 5; do
      velocity=$(awk -v b="$bin" -v k="$bins" 'BEGIN { printf "%.9g", b * k }')
      { cat "$root/examples/room_clutter.toml"
        printf '\n[target]\nradial_velocity_m_per_s = %s\n' "$velocity"
        printf '[radar.processing.cfar]\nshape = "%s"\nkind = "%s"\n' "$shape" "$kind"
      } >"$work/case.toml"
      rm -rf "$work/out"
      "$fogradar" run --scenario "$work/case.toml" --out "$work/out" >/dev/null
      summary=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
        $col["active_layers"] == 0 {
          median = $col["median_dbsm"] == "" ? "–" : sprintf("%.2f", $col["median_dbsm"])
          printf "%.0f %% | %s | %s", 100 * $col["detection_rate"], median, $col["n"] }' \
        "$work/out/radar_summary.csv")
      frames=${summary##* | }
      awk -F, -v frames="$frames" -v row="| $shape | $kind | $bins ($(printf '%.3f' "$velocity")) | ${summary% | *} |" \
        'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
        { ++count[$col["origin"]] }
        END { printf "%s %.2f | %.2f | %.2f | %.2f |\n", row, count["room"] / frames,
                count["multipath"] / frames, count["sidelobe"] / frames, count["noise"] / frames }' \
        "$work/out/radar_detections.csv"
    done
  done
done
