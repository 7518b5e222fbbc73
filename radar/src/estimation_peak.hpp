// The DTFT peak numerics (estimation_peak.cpp) that the estimation of detections (estimation.cpp)
// calls, and the Dirichlet weights both evaluate. Built, as both files are, with -ffp-contract=off.
#pragma once

#include <cmath>
#include <complex>
#include <cstddef>
#include <span>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/radar/estimation.hpp"

namespace fogradar::radar::estimation_peak {

// (j - 1) mod period and (j + step) mod period for 0 <= j, step < period: the table index of the
// next column, without a division per column.
inline std::size_t previous_index(std::size_t j, std::size_t period) {
  return j == 0 ? period - 1 : j - 1;
}
inline std::size_t next_index(std::size_t j, std::size_t step, std::size_t period) {
  return j >= period - step ? j - (period - step) : j + step;
}

// nu = k + f with k the nearest integer, reduced modulo 2N (the period of e^{i pi j/N}), and f.
struct SplitBin {
  std::size_t k_mod_2n;
  double fraction;
};

inline SplitBin split_bin(double nu, std::size_t n) {
  const double k = std::nearbyint(nu);
  const double two_n = 2.0 * static_cast<double>(n);
  double k_mod = std::fmod(k, two_n);
  if (k_mod < 0.0) k_mod += two_n;
  return {static_cast<std::size_t>(k_mod), nu - k};
}

// Calls sink(m, K(nu - m)) for m = 0..N-1 (the evaluation described at dirichlet_kernel).
template <class Sink>
void dirichlet_weights(double nu, const DirichletTable& table, Sink sink) {
  const std::size_t n = table.length();
  FOGRADAR_CHECK(n > 0);
  const auto [k, f] = split_bin(nu, n);
  const double nd = static_cast<double>(n);
  // An integer nu: 1 at bin nu and its aliases (j a multiple of N), 0 elsewhere.
  if (f == 0.0) {
    for (std::size_t m = 0; m < n; ++m) sink(m, (k + 2 * n - m) % n == 0 ? 1.0 : 0.0);
    return;
  }
  const double delta = pi * f / nd;
  const double cos_delta = std::cos(delta), sin_delta = std::sin(delta);
  const std::complex<double> a = std::polar(std::sin(pi * f) / nd, -pi * f * (nd - 1.0) / nd);
  for (std::size_t m = 0, j = k; m < n; ++m, j = previous_index(j, 2 * n)) {  // j = (k - m) mod 2N
    const double c = table.cos_pi_j_over_n(j), s = table.sin_pi_j_over_n(j);
    sink(m, a * std::complex<double>(c, s) / (s * cos_delta + c * sin_delta));
  }
}

// Fractional offset in [-w, w] around bin `centre` that maximises |X(centre + offset)|, and the
// maximum |X|^2. Brent's method on the Dirichlet sums brackets the maximum robustly to 2^-24 bin;
// Newton steps on dP/df = 0 from the time signal then take it to rounding level. A Newton step
// that is not at a maximum (d2P/df2 >= 0) or that leaves the 2^-20-bin neighbourhood of Brent's
// point is not taken.
struct Peak {
  double offset;
  double power;
};

Peak find_peak(std::span<const std::complex<double>> values, std::size_t centre,
               const DirichletTable& table, InverseDft& inverse, EstimationWorkspace& ws);

}  // namespace fogradar::radar::estimation_peak
