#!/usr/bin/env bash
# End-to-end checks of `fogradar room`: its text and JSON outputs against values written here
# (ITU-R P.2040-3 Table 3's concrete evaluated by hand, and numpy's Fresnel coefficients, as in
# tests/propagation/test_materials.cpp), and bad input -> exit status 2 with one message naming the
# option as written, the value and the allowed range.
# Usage: test_room.sh FOGRADAR_BINARY SOURCE_DIR
. "$(dirname "$0")/cli_test_support.sh"

# --- outputs -------------------------------------------------------------------------------------
# Concrete at 77 GHz: eps' = 5.24, sigma = 0.0462 * 77^0.7822 = 1.3812 S/m, eps'' = 0.322518; at
# 30 deg grazing numpy gives |TE| = 0.618788 (phase -178.975 deg), |TM| = 0.106797 (6.81111 deg).
"$fogradar" room --material concrete --frequency-ghz 77 --grazing-deg 30 >"$work/text" 2>&1 \
  || fail "room concrete failed: $(cat "$work/text")"
for line in 'source             ITU-R P.2040-3 Table 3, valid 1-100 GHz' \
  'conductivity       1.3812 S/m' \
  'permittivity       5.24 + 0.322518i' \
  'Gamma TE (horiz.)  |G| = 0.618788, phase = -178.975 deg' \
  'Gamma TM (vert.)   |G| = 0.106797, phase = 6.81111 deg'; do
  grep -qF -- "$line" "$work/text" && pass || fail "room text lacks '$line': $(cat "$work/text")"
done

"$fogradar" room --material concrete --frequency-ghz 77 --grazing-deg 30 --json >"$work/json" 2>&1 \
  || fail "room --json failed: $(cat "$work/json")"
if [ -x /usr/bin/python3 ]; then
  /usr/bin/python3 - "$work/json" <<'PY' && pass || fail "room --json values: $(cat "$work/json")"
import json, sys
o = json.load(open(sys.argv[1]))
close = lambda a, b, tol=1e-9: abs(a - b) <= tol * max(1.0, abs(b))
assert o["material"] == "concrete" and o["valid_frequency_ghz"] == [1.0, 100.0], o
assert close(o["permittivity"]["real"], 5.24) and close(o["permittivity"]["imag"], 0.3225180186), o
assert close(o["conductivity_s_per_m"], 1.381195074), o
assert close(o["te"]["real"], -0.618689385437426) and close(o["te"]["imag"], -0.011067378330502115)
assert close(o["tm"]["real"], 0.10604318396805577) and close(o["tm"]["imag"], 0.012665738981663503)
assert close(o["tm"]["magnitude"], 0.10679689981471631) and close(o["te"]["phase_deg"], -178.9751780803285)
PY
fi

# Optical: aluminium at 1550 nm (Rakic's model, numpy m = 1.53554 + 15.3304i); at normal incidence
# |TE| = |TM| = |(1 - m) / (1 + m)| = 0.987199.
"$fogradar" room --material metal --wavelength-nm 1550 --grazing-deg 90 >"$work/metal" 2>&1 \
  || fail "room metal optical failed: $(cat "$work/metal")"
for line in 'refractive index   1.53554 + 15.3304i' 'Gamma TE (horiz.)  |G| = 0.987199' \
  'Gamma TM (vert.)   |G| = 0.987199'; do
  grep -qF -- "$line" "$work/metal" && pass || fail "room metal lacks '$line': $(cat "$work/metal")"
done
# Brewster for fused silica at 587.56 nm (n_d = 1.4585): psi_B = atan(1 / n) = 34.44 deg.
"$fogradar" room --material glass --wavelength-nm 587.56 --grazing-deg 34.4365 --json >"$work/glass" 2>&1 \
  || fail "room glass failed: $(cat "$work/glass")"
if [ -x /usr/bin/python3 ]; then
  /usr/bin/python3 -c 'import json,sys; o=json.load(open(sys.argv[1])); assert o["tm"]["magnitude"] < 1e-4 < o["te"]["magnitude"], o' \
    "$work/glass" && pass || fail "glass at Brewster's angle: $(cat "$work/glass")"
fi

# --- bad input -----------------------------------------------------------------------------------
expect_bad "unknown material" "--material = 'steel'" "one of concrete, brick, plasterboard, wood, glass" \
  room --material steel --frequency-ghz 77 --grazing-deg 30
expect_bad "material outside its fit" "--frequency-ghz = '77'" "in [1, 40] for material 'brick'" \
  room --material brick --frequency-ghz 77 --grazing-deg 30
expect_bad "floorboard below its fit" "--frequency-ghz = '24'" "in [50, 100] for material 'floorboard'" \
  room --material floorboard --frequency-ghz 24 --grazing-deg 30
expect_bad "frequency not a number" "--frequency-ghz = '77x'" "in [0.001, 1000]" \
  room --material concrete --frequency-ghz 77x --grazing-deg 30
expect_bad "grazing 0" "--grazing-deg = '0'" "in (0, 90]" \
  room --material concrete --frequency-ghz 77 --grazing-deg 0
expect_bad "grazing over 90" "--grazing-deg = '90.5'" "in (0, 90]" \
  room --material concrete --frequency-ghz 77 --grazing-deg 90.5
expect_bad "grazing empty" "--grazing-deg = ''" "in (0, 90]" \
  room --material concrete --frequency-ghz 77 --grazing-deg ''
expect_bad "both frequency and wavelength" "--frequency-ghz" "--wavelength-nm" \
  room --material water --frequency-ghz 77 --wavelength-nm 905 --grazing-deg 30
expect_bad "neither frequency nor wavelength" "--frequency-ghz" "give exactly one of them" \
  room --material water --grazing-deg 30
expect_bad "no optical data" "--material = 'concrete'" "one of water, glass, metal with --wavelength-nm" \
  room --material concrete --wavelength-nm 905 --grazing-deg 30
expect_bad "wavelength outside the fit" "--wavelength-nm = '5000'" "in [210, 3710] for material 'glass'" \
  room --material glass --wavelength-nm 5000 --grazing-deg 30
expect_bad "no material" "--material" "required" room --frequency-ghz 77 --grazing-deg 30

finish
