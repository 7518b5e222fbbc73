// ITU-R P.840's specific attenuation coefficient of fog, written out for the tests independently
// of propagation/water.cpp: the reference the fog's radar attenuation is checked against.
#pragma once

namespace fogradar::testing {

// P.840's K_l written out from ITU-R P.840-8 eqs. (2)-(9) (theta = 300/T; eps0 = 77.66 +
// 103.3 (theta - 1), eps1 = 0.0671 eps0, eps2 = 3.52; f_p = 20.20 - 146 (theta - 1) + 316 (theta -
// 1)^2, f_s = 39.8 f_p; eps', eps'' of the double Debye sum; eta = (2 + eps')/eps'';
// K_l = 0.819 f / (eps'' (1 + eta^2))), independently of water.cpp. At 77 GHz it gives
// 3.5374 (dB/km)/(g/m^3) at 0 C and 2.7130 at 20 C (evaluated in Python from the same formulas).
inline double p840_k_l(double frequency_ghz, double temperature_c) {
  const double theta = 300.0 / (temperature_c + 273.15);
  const double eps0 = 77.66 + 103.3 * (theta - 1.0), eps1 = 0.0671 * eps0, eps2 = 3.52;
  const double fp = 20.20 - 146.0 * (theta - 1.0) + 316.0 * (theta - 1.0) * (theta - 1.0),
               fs = 39.8 * fp;
  const double f = frequency_ghz;
  const double eps_im = f * (eps0 - eps1) / (fp * (1.0 + (f / fp) * (f / fp))) +
                        f * (eps1 - eps2) / (fs * (1.0 + (f / fs) * (f / fs)));
  const double eps_re = (eps0 - eps1) / (1.0 + (f / fp) * (f / fp)) +
                        (eps1 - eps2) / (1.0 + (f / fs) * (f / fs)) + eps2;
  const double eta = (2.0 + eps_re) / eps_im;
  return 0.819 * f / (eps_im * (1.0 + eta * eta));
}

}  // namespace fogradar::testing
