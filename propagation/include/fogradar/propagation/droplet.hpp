// Scattering by one spherical water droplet in air: Rayleigh closed forms and the full Mie
// solution. Index convention m = n + i k, k >= 0 (Bohren & Huffman 1983). Backscatter is the radar
// backscattering cross section sigma_b = 4 pi dsigma/dOmega(180 deg).
#pragma once

#include <complex>

namespace fogradar::propagation {

// Efficiencies Q = sigma / (pi a^2), dimensionless.
struct MieEfficiencies {
  double extinction = 0.0;
  double scattering = 0.0;
  double absorption = 0.0;
  double backscatter = 0.0;  // Q_b = |sum (2n+1)(-1)^n (a_n - b_n)|^2 / x^2
  double asymmetry = 0.0;    // g = <cos theta>
};

struct CrossSections {
  double extinction_m2 = 0.0;
  double scattering_m2 = 0.0;
  double absorption_m2 = 0.0;
  double backscatter_m2 = 0.0;
};

// Clausius-Mossotti factor K = (m^2 - 1) / (m^2 + 2).
std::complex<double> clausius_mossotti(std::complex<double> m);

// Size parameter x = pi D / lambda.
double size_parameter(double diameter_m, double wavelength_m);

// Full Mie solution (Bohren & Huffman 1983 ch. 4; Wiscombe 1980 NCAR/TN-140 for the series length
// and downward recurrence of the logarithmic derivative). Accurate for 1e-6 <= x <= 2e4.
// Throws InvalidParameter for x <= 0, non-finite input, Re(m) <= 0 or Im(m) < 0.
MieEfficiencies mie_efficiencies(double size_parameter, std::complex<double> m);

// The complex recurrence steps mie_efficiencies takes: the downward ratio recurrence of m x from
// its start, then one step per order of the series (the real recurrence of x is cheaper and left
// out). The unit of the Mie cost model of the run-time estimate.
std::size_t mie_recurrence_steps(double size_parameter, std::complex<double> m);

// Mie cross sections of a droplet of diameter D at wavelength lambda.
CrossSections mie_cross_sections(double diameter_m, double wavelength_m, std::complex<double> m);

// Rayleigh (small particle, x << 1, |m| x << 1) cross sections (Bohren & Huffman eq. 5.7-5.8;
// Battan 1973 for backscatter):
//   absorption   sigma_a = pi^2 D^3 / lambda * Im(K)        (Im(K) > 0 in this index convention)
//   scattering   sigma_s = 2 pi^5 D^6 / (3 lambda^4) |K|^2
//   backscatter  sigma_b = pi^5 D^6 / lambda^4 |K|^2
//   extinction   sigma_a + sigma_s
CrossSections rayleigh_cross_sections(double diameter_m, double wavelength_m,
                                      std::complex<double> m);

}  // namespace fogradar::propagation
