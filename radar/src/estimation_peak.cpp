// The DTFT peak numerics: the maximum of |X| between bins, bracketed on Dirichlet sums and refined
// by Newton steps on the time signal; the Dirichlet kernel and its tables.
#include "estimation_peak.hpp"

#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <complex>
#include <cstring>
#include <limits>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/radar/estimation.hpp"

namespace fogradar::radar {
namespace estimation_peak {
namespace {

using detail::f64x4;

// Brent's bracket of the peak (2^-24 bin), then at most a few Newton steps within 2^-20 bin of it
// (find_peak); Newton converges quadratically from there, so three steps reach rounding level.
constexpr int brent_bits = 24;
constexpr double newton_neighbourhood_bins = 0x1p-20;
constexpr int max_newton_steps = 4;
// The true maximum of a tone lies within half a bin of the largest cell; a little margin lets
// Brent's method find it when two cells are nearly equal.
constexpr double peak_search_half_width_bins = 0.75;

// sum_m (re[m] + i im[m]) / (sin_j[m] cos_delta + cos_j[m] sin_delta): the Dirichlet sum of one
// fractional bin (dirichlet_kernel in estimation.hpp), four lanes of partial sums.
FOGRADAR_SIMD_CLONES
std::complex<double> sum_over_sines(const double* re, const double* im, const double* sin_j,
                                    const double* cos_j, std::size_t n, double cos_delta,
                                    double sin_delta) {
  f64x4 sum_re{}, sum_im{};
  std::size_t m = 0;
  for (; m + 4 <= n; m += 4) {
    const f64x4 inverse =
        1.0 / (detail::load4(sin_j + m) * cos_delta + detail::load4(cos_j + m) * sin_delta);
    sum_re += detail::load4(re + m) * inverse;
    sum_im += detail::load4(im + m) * inverse;
  }
  double tail_re = 0.0, tail_im = 0.0;
  for (; m < n; ++m) {
    const double inverse = 1.0 / (sin_j[m] * cos_delta + cos_j[m] * sin_delta);
    tail_re += re[m] * inverse;
    tail_im += im[m] * inverse;
  }
  return {detail::sum_lanes(sum_re) + tail_re, detail::sum_lanes(sum_im) + tail_im};
}

// |X(k + f)|^2 of a DFT for f in [-w, w] around bin k (0 <= k < N): the rotated values
// X[m] e^{i pi j/N} and the table entries of j = k - m are gathered once, so each evaluation is
// three sines and one sum_over_sines.
class FractionalBinPower {
 public:
  FractionalBinPower(std::span<const std::complex<double>> values, std::size_t k,
                     const DirichletTable& table, EstimationWorkspace& ws)
      : n_(values.size()), centre_(values[k]), ws_(ws) {
    ws.rotated_re.resize(n_);
    ws.rotated_im.resize(n_);
    ws.sin_j.resize(n_);
    ws.cos_j.resize(n_);
    for (std::size_t m = 0, j = k; m < n_;
         ++m, j = previous_index(j, 2 * n_)) {  // j = (k - m) mod 2N
      const double c = table.cos_pi_j_over_n(j), s = table.sin_pi_j_over_n(j);
      ws.sin_j[m] = s;
      ws.cos_j[m] = c;
      ws.rotated_re[m] = values[m].real() * c - values[m].imag() * s;
      ws.rotated_im[m] = values[m].real() * s + values[m].imag() * c;
    }
  }

  double operator()(double f) const {
    if (f == 0.0) return std::norm(centre_);
    const double nd = static_cast<double>(n_);
    const double delta = pi * f / nd;
    const std::complex<double> sum =
        sum_over_sines(ws_.rotated_re.data(), ws_.rotated_im.data(), ws_.sin_j.data(),
                       ws_.cos_j.data(), n_, std::cos(delta), std::sin(delta));
    const double scale = std::sin(pi * f) / nd;
    return scale * scale * std::norm(sum);
  }

 private:
  std::size_t n_;
  std::complex<double> centre_;
  const EstimationWorkspace& ws_;
};

// P = |g|^2 and its first two derivatives in f for g(f) = sum_n y[n] e^{i f w_n}, w_n = -2 pi (n -
// c)/N: phases about the centre c = (N-1)/2 (|g| and its derivatives do not depend on it, and the
// derivative weights w_n stay small). Four lanes, lane l summing n = l mod 4 with its own phasor
// recurrence (N/4 steps, error ~ N/4 eps), so the recurrences do not wait on each other.
struct DtftDerivatives {
  double power, slope, curvature;  // P, dP/df, d2P/df2
};

FOGRADAR_SIMD_CLONES
DtftDerivatives dtft_derivatives(const std::complex<double>* signal, std::size_t count, double f) {
  using detail::load4;
  const double* y = reinterpret_cast<const double*>(signal);  // layout-compatible with double[2]
  const double nd = static_cast<double>(count);
  const double centre = 0.5 * (nd - 1.0);
  const double radians_per_sample = -2.0 * pi / nd;
  const auto phasor = [&](double sample_offset) {
    return std::polar(1.0, f * sample_offset * radians_per_sample);
  };
  f64x4 offset{-centre, 1.0 - centre, 2.0 - centre, 3.0 - centre};  // n - c, exact
  f64x4 p_re, p_im;
  for (int l = 0; l < 4; ++l) {
    const std::complex<double> start = phasor(offset[l]);
    p_re[l] = start.real();
    p_im[l] = start.imag();
  }
  const std::complex<double> step = phasor(4.0);
  f64x4 g_re{}, g_im{}, g1_re{}, g1_im{}, g2_re{}, g2_im{};
  std::size_t n = 0;
  for (; n + 4 <= count; n += 4) {
    const f64x4 first = load4(y + 2 * n), second = load4(y + 2 * n + 4);
    const f64x4 y_re = __builtin_shufflevector(first, second, 0, 2, 4, 6);
    const f64x4 y_im = __builtin_shufflevector(first, second, 1, 3, 5, 7);
    const f64x4 w = offset * radians_per_sample;  // d/df of the phase
    const f64x4 term_re = y_re * p_re - y_im * p_im;
    const f64x4 term_im = y_re * p_im + y_im * p_re;
    g_re += term_re;
    g_im += term_im;
    g1_re -= w * term_im;  // i w term
    g1_im += w * term_re;
    g2_re -= w * w * term_re;
    g2_im -= w * w * term_im;
    const f64x4 next_re = p_re * step.real() - p_im * step.imag();
    p_im = p_re * step.imag() + p_im * step.real();
    p_re = next_re;
    offset += 4.0;
  }
  std::complex<double> g(detail::sum_lanes(g_re), detail::sum_lanes(g_im));
  std::complex<double> g1(detail::sum_lanes(g1_re), detail::sum_lanes(g1_im));
  std::complex<double> g2(detail::sum_lanes(g2_re), detail::sum_lanes(g2_im));
  for (; n < count; ++n) {
    const double sample_offset = static_cast<double>(n) - centre;
    const double w = sample_offset * radians_per_sample;
    const std::complex<double> term = signal[n] * phasor(sample_offset);
    g += term;
    g1 += std::complex<double>(-w * term.imag(), w * term.real());  // i w term
    g2 -= w * w * term;
  }
  return {std::norm(g), 2.0 * (g.real() * g1.real() + g.imag() * g1.imag()),
          2.0 * (std::norm(g1) + (g.real() * g2.real() + g.imag() * g2.imag()))};
}

// The DTFT around bin k from the time signal: g(f) = X(k + f) = sum_n y[n] e^{-i 2 pi f n / N},
// y[n] = x[n] e^{-i 2 pi k n / N}, x = IDFT(X), with its first two derivatives in f. Unlike the
// Dirichlet sum, nothing here is singular at f = 0, so the stationarity condition
// dP/df = 2 Re(conj(g) g') = 0 of P = |g|^2 can be solved to rounding level, where searching on
// values of P alone stalls at ~sqrt(eps) (P is flat to second order at its maximum).
class TimeSignalDtft {
 public:
  TimeSignalDtft(std::span<const std::complex<double>> values, std::size_t k,
                 const DirichletTable& table, InverseDft& inverse)
      : n_(values.size()), y_(inverse.signal) {
    inverse.prepare(n_);
    inverse.plan->execute(values, y_);
    const double nd = static_cast<double>(n_);
    // j = 2 k n mod 2N: e^{-i 2 pi k n / N} = e^{-i pi j / N}.
    for (std::size_t n = 0, j = 0; n < n_; ++n, j = next_index(j, 2 * k, 2 * n_)) {
      y_[n] *= std::complex<double>(table.cos_pi_j_over_n(j), -table.sin_pi_j_over_n(j)) / nd;
    }
  }

  DtftDerivatives at(double f) const { return dtft_derivatives(y_.data(), n_, f); }

 private:
  std::size_t n_;
  ComplexVector& y_;
};

}  // namespace

Peak find_peak(std::span<const std::complex<double>> values, std::size_t centre,
               const DirichletTable& table, InverseDft& inverse, EstimationWorkspace& ws) {
  if (values.size() == 1) return {0.0, std::norm(values[0])};
  const FractionalBinPower power(values, centre, table, ws);
  const double bracketed =
      boost::math::tools::brent_find_minima([&power](double offset) { return -power(offset); },
                                            -peak_search_half_width_bins,
                                            peak_search_half_width_bins, brent_bits)
          .first;
  const TimeSignalDtft dtft(values, centre, table, inverse);
  double offset = bracketed;
  DtftDerivatives at = dtft.at(offset);
  for (int iteration = 0; iteration < max_newton_steps && at.curvature < 0.0; ++iteration) {
    const double next = offset - at.slope / at.curvature;
    if (!(std::abs(next - bracketed) <= newton_neighbourhood_bins)) break;
    const bool converged = std::abs(next - offset) <= 4.0 * std::numeric_limits<double>::epsilon();
    offset = next;
    at = dtft.at(offset);
    if (converged) break;
  }
  return {offset, at.power};
}

}  // namespace estimation_peak

using estimation_peak::dirichlet_weights;

void InverseDft::prepare(std::size_t n) {
  if (plan && signal.size() == n) return;
  plan.emplace(n, FftDirection::inverse, FftOptions{.alignment = FftAlignment::unaligned});
  signal.resize(n);
}

void DirichletTable::prepare(std::size_t n) {
  if (n == n_) return;
  n_ = n;
  cos_.resize(2 * n);
  sin_.resize(2 * n);
  // The second half by symmetry, so sin(pi j/N) is exactly 0 at j = N as at j = 0: the Dirichlet
  // denominator sin(pi j/N) cos(pi f/N) + ... must vanish with f there, not leave 1e-16.
  for (std::size_t j = 0; j < n; ++j) {
    const double angle = pi * static_cast<double>(j) / static_cast<double>(n);
    cos_[j] = std::cos(angle);
    sin_[j] = std::sin(angle);
    cos_[j + n] = -cos_[j];
    sin_[j + n] = -sin_[j];
  }
}

void dirichlet_kernel(double nu, std::size_t n, std::span<std::complex<double>> kernel) {
  dirichlet_kernel(nu, DirichletTable(n), kernel);
}

void dirichlet_kernel(double nu, const DirichletTable& table,
                      std::span<std::complex<double>> kernel) {
  FOGRADAR_CHECK(kernel.size() >= table.length());
  dirichlet_weights(nu, table,
                    [&kernel](std::size_t m, std::complex<double> weight) { kernel[m] = weight; });
}

}  // namespace fogradar::radar
