#include "fogradar/radar/noise_correlation.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"

namespace fogradar::radar {

double NoiseCorrelation::at(std::ptrdiff_t lag) const noexcept {
  const std::size_t m = static_cast<std::size_t>(lag < 0 ? -lag : lag);
  return m < coefficients.size() ? coefficients[m] : 0.0;
}

bool NoiseCorrelation::white() const noexcept {
  for (std::size_t m = 1; m < coefficients.size(); ++m) {
    if (coefficients[m] != 0.0) return false;
  }
  return true;
}

void NoiseCorrelation::validate() const {
  if (coefficients.empty() || coefficients[0] != 1.0) {
    throw_invalid("noise_correlation.coefficients", coefficients.empty() ? 0.0 : coefficients[0],
                  "rho(0) = 1 (a correlation coefficient)");
  }
  for (double rho : coefficients) {
    if (!(std::abs(rho) <= 1.0))
      throw_invalid("noise_correlation.coefficients", rho, "finite and in [-1, 1]");
  }
}

NoiseCorrelation window_noise_correlation(std::span<const double> window, std::size_t max_lag) {
  const std::size_t n = window.size();
  if (n == 0) throw_invalid("window", 0.0, "at least one sample");
  double energy = 0.0;
  for (double w : window) energy += w * w;
  if (!(energy > 0.0) || !std::isfinite(energy))
    throw_invalid("window", energy, "finite samples, not all zero (sum w^2)");
  const std::size_t lags = std::min(max_lag, n - 1) + 1;
  NoiseCorrelation result;
  result.coefficients.assign(lags, 0.0);
  result.coefficients[0] = 1.0;
  // The twiddles e^{-i 2 pi k / N} for k = m j mod N (which keeps the argument in [0, 2 pi) at full
  // precision), tabulated once: a lag costs N multiply-adds, not N sines and cosines.
  std::vector<double> cosines(n), sines(n), power(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double phase = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
    cosines[k] = std::cos(phase);
    sines[k] = std::sin(phase);
    power[k] = window[k] * window[k];
  }
  for (std::size_t m = 1; m < lags; ++m) {
    double real = 0.0;
    double imaginary = 0.0;
    std::size_t k = 0;  // m j mod N
    for (std::size_t j = 0; j < n; ++j) {
      real += power[j] * cosines[k];
      imaginary += power[j] * sines[k];
      k += m;
      if (k >= n) k -= n;
    }
    // DFT-even windows have vanishing sine sums up to rounding (N eps of the energy).
    if (std::abs(imaginary) > 1e-10 * energy) {
      throw_invalid("window", imaginary / energy,
                    "DFT-even (w[n] = w[N-n]): the imaginary part of rho(" + std::to_string(m) +
                        ") must vanish");
    }
    // The sums carry a rounding error of about N eps of the energy: where rho vanishes analytically
    // (every lag of the rectangular window, Hann and Hamming beyond 2) they are set to exact zeros,
    // so that white noise is recognised as such. A true |rho| this small (< 8 N eps) changes a P_fa
    // by O(rho^2).
    const double rho = real / energy;
    result.coefficients[m] =
        std::abs(rho) <= 8.0 * static_cast<double>(n) * std::numeric_limits<double>::epsilon()
            ? 0.0
            : rho;
  }
  while (result.coefficients.size() > 1 && result.coefficients.back() == 0.0)
    result.coefficients.pop_back();
  return result;
}

}  // namespace fogradar::radar
