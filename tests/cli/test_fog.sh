#!/usr/bin/env bash
# End-to-end checks of `fogradar fog` (docs/cli.md, docs/physics.md): its values against formulas
# written out here, its JSON keys, and bad options -> exit status 2 with one message naming the
# option, the value as typed and the allowed range.
# Usage: test_fog.sh FOGRADAR_BINARY SOURCE_DIR
. "$(dirname "$0")/cli_test_support.sh"

expect_bad fog-lwc "--lwc = '-1'" "[0, 100]" fog --lwc -1
expect_bad fog-lwc-empty "--lwc = ''" "[0, 100]" fog --lwc ""
expect_bad fog-lwc-text "--lwc = 'wet'" "[0, 100]" fog --lwc wet
expect_bad fog-extinction-empty "--extinction-per-km = ''" "[0, 1e6]" fog --extinction-per-km ""
expect_bad fog-visibility-inf "--visibility-m = 'inf'" "[0.001, 1e7]" fog --visibility-m inf
expect_bad fog-diameter-empty "--diameter-um = ''" "[0.01, 1000]" fog --diameter-um ""
expect_bad fog-temperature-empty "--temperature-c = ''" "[-20, 50] with --water-model liebe" fog --temperature-c ""
expect_bad fog-frequency-empty "--frequency-ghz = ''" "[0.03, 1000] with --water-model liebe" fog --frequency-ghz ""
expect_bad fog-model --water-model "one of liebe, segelstein" fog --water-model mie
expect_bad fog-model-empty "--water-model = ''" "one of liebe, segelstein" fog --water-model ""
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
# --- fog --json carries the documented keys (docs/cli.md) ----------------------------------------------------------
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
# --- fog: optical models, Kunkel, the virtual layer model, drop size distributions ----------------
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
expect_bad fog-b-mean-radius "--b-per-um-gamma = 0.001" \
  "mean radius Gamma((alpha + 2)/gamma) / (b^(1/gamma) Gamma((alpha + 1)/gamma)) <= 500 um" \
  fog --distribution modified_gamma --b-per-um-gamma 0.001
expect_bad fog-b-mean-radius-alpha-0 "--b-per-um-gamma = 1e-300" "mean radius" \
  fog --distribution modified_gamma --alpha 0 --b-per-um-gamma 1e-300
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

finish
