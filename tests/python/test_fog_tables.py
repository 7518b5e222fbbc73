"""The fog tables of `fogradar fog` from Python: the optical models at one wavelength and the
virtual layer model, against their formulas written out here (paper eq. 1-4, 6; Kim, McArthur &
Korevaar 2001) and against the command's own output for the same fog."""
import json
import math
import os
import subprocess

import pytest

import fogradar

KOSCHMIEDER = 3.912023005428146  # -ln 0.02, eq. 6


def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * abs(b)


def test_optical_models_are_eq1_with_kruse_and_kim_q():
    # V = 3 km at 905 nm: Kruse q = 0.585 V^(1/3) (eq. 2), Kim q = 0.16 V + 0.34; eq. 1
    # beta = 3.912 / V (lambda / 550)^-q; 1e-12 relative (the same formula in another order).
    table = fogradar.optical_model_table(1.25, 3000.0, 905.0)
    assert list(table.index) == ["mie", "kruse", "kim"]
    assert table.loc["mie", "extinction_per_km"] == 1.25
    for model, q in (("kruse", 0.585 * 3.0 ** (1 / 3)), ("kim", 0.16 * 3.0 + 0.34)):
        assert close(table.loc[model, "q"], q), (model, table.loc[model, "q"], q)
        beta = KOSCHMIEDER / 3.0 * (905.0 / 550.0) ** -q
        assert close(table.loc[model, "extinction_per_km"], beta), (model, table.loc[model])
    # Kim alone, and no water: eq. 1 as V grows without bound gives no extinction and no q.
    clear = fogradar.optical_model_table(0.0, math.inf, 905.0, models="kim")
    assert list(clear.index) == ["mie", "kim"]
    assert clear.loc["kim", "extinction_per_km"] == 0.0
    assert clear.loc["kim", "q"] is None or math.isnan(clear.loc["kim", "q"])


def test_optical_models_match_the_command():
    cli = os.environ.get("FOGRADAR_CLI")
    if not cli:
        pytest.skip("FOGRADAR_CLI not set")
    out = json.loads(subprocess.run([cli, "fog", "--visibility-m", "800", "--wavelength-nm",
                                     "1550", "--json"], check=True, capture_output=True,
                                    text=True).stdout)
    models = out["optical_models"]
    table = fogradar.optical_model_table(models["mie"]["extinction_per_km"], out["visibility_m"],
                                         1550.0)
    for model, row in table.iterrows():
        assert row["extinction_per_km"] == models[model]["extinction_per_km"], model


def test_layer_model_rows_are_eq3_and_eq4_written_out():
    # Eq. 3 with the Narayana numbers for kappa = 1, 3, 5, 7 and eq. 4 rho_obj tau^(2k); 1e-12.
    tau, rho, rho_obj = 0.8, 0.05, 0.6
    table = fogradar.layer_model_table(tau, rho, 3, rho_obj)
    eq3 = [rho, rho * tau**2, rho * tau**4 + rho**3 * tau**2,
           rho * tau**6 + 3 * rho**3 * tau**4 + rho**5 * tau**2]
    assert list(table.index) == [0, 1, 2, 3]
    for k, row in table.iterrows():
        assert row["kappa"] == 2 * k + 1
        assert close(row["fog_intensity_per_i0"], eq3[k]), (k, row)
        assert close(row["object_intensity_per_i0"], rho_obj * tau ** (2 * k)), (k, row)


def test_longest_layer_is_the_larger_root():
    # Newton's method on f(d) = exp(-alpha d) + eta d - 1 from d = 1 / eta: f is convex and
    # positive there, so the iterates fall monotonically onto the larger root; 1e-12 relative.
    for alpha, eta in ((2.0, 1.0), (0.9, 0.09), (1e-2, 1e-3)):
        d = 1.0 / eta
        for _ in range(100):
            d -= (math.exp(-alpha * d) + eta * d - 1.0) / (eta - alpha * math.exp(-alpha * d))
        assert close(fogradar.longest_layer_m(alpha, eta), d), (alpha, eta, d)


def test_bad_input_names_the_argument():
    with pytest.raises(fogradar.InvalidParameter) as error:
        fogradar.optical_model_table(1.0, 1000.0, 905.0, models=("kruse", "foo"))
    assert error.value.key == "models" and "one of mie, kruse, kim" in str(error.value)
    with pytest.raises(fogradar.InvalidParameter):
        fogradar.layer_model_table(0.9, 0.2, 3)  # tau + rho > 1
    with pytest.raises(fogradar.InvalidParameter) as error:
        fogradar.longest_layer_m(1.0, 2.0)  # eta >= alpha: no layer fits
    assert error.value.key == "eta_m2_per_m3"
