// The threshold-factor root finder and log-space sum shared by the independent-cell
// (cfar_theory.cpp) and the correlated-cell (cfar_correlated.cpp) CFAR designs.
#pragma once

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

#include "fogradar/core/error.hpp"

namespace fogradar::radar {

// Accumulates sum(exp(log_term)) without overflow or underflow (running log-sum-exp).
class LogSum {
 public:
  void add(double log_term) {
    if (log_term == -std::numeric_limits<double>::infinity()) return;
    if (log_term > max_) {
      scaled_sum_ = scaled_sum_ * std::exp(max_ - log_term) + 1.0;
      max_ = log_term;
    } else {
      scaled_sum_ += std::exp(log_term - max_);
    }
  }
  double log() const { return max_ + std::log(scaled_sum_); }

 private:
  double max_ = -std::numeric_limits<double>::infinity();
  double scaled_sum_ = 0.0;
};

// Solves log_pfa(alpha) = log(design) for the threshold factor alpha, starting from `start`:
// log_pfa is continuous and decreasing, so the root is bracketed by halving/doubling from start
// and refined by TOMS 748 (Alefeld, Potra & Shi 1995) to a few ulps.
template <class LogPfa>
double solve_threshold_factor(const LogPfa& log_pfa, double design, double start) {
  const double target = std::log(design);
  const auto residual = [&](double alpha) { return log_pfa(alpha) - target; };
  double low = start;
  double high = start;
  double f_low = residual(low);
  double f_high = f_low;
  while (f_low < 0.0) {
    high = low;
    f_high = f_low;
    low *= 0.5;
    f_low = residual(low);
    FOGRADAR_CHECK(low > 1e-300);
  }
  while (f_high > 0.0) {
    low = high;
    f_low = f_high;
    high *= 2.0;
    f_high = residual(high);
    FOGRADAR_CHECK(std::isfinite(high));
  }
  if (f_low == 0.0) return low;
  if (f_high == 0.0) return high;
  // TOMS 748 converges in a few steps on a smooth residual; where log_pfa is flat to rounding
  // near the root (a residual of ~700 whose ulp exceeds its change over one ulp of alpha, P_fa
  // below ~1e-300) it may stall, and bisection of its last bracket ends the solve.
  std::uintmax_t max_iterations = 200;
  auto [lower, upper] = boost::math::tools::toms748_solve(
      residual, low, high, f_low, f_high, boost::math::tools::eps_tolerance<double>(50),
      max_iterations);
  if (max_iterations >= 200) {
    double f_lower = residual(lower);
    for (int step = 0; step < 200 && upper - lower > 4.0 * 0x1p-52 * upper; ++step) {
      const double middle = 0.5 * (lower + upper);
      const double f_middle = residual(middle);
      if (f_middle == 0.0) return middle;
      if ((f_middle > 0.0) == (f_lower > 0.0)) {
        lower = middle;
        f_lower = f_middle;
      } else {
        upper = middle;
      }
    }
  }
  return 0.5 * (lower + upper);
}

// The same root for an estimate whose evaluations are expensive and whose own error is far above
// `tolerance` (relative, in alpha): log P_fa is smooth and close to linear in log alpha, so the
// secant method on u = log alpha from start and a point 2 % beside it needs 3-4 more evaluations.
// Once the root is bracketed a secant step that leaves the bracket is replaced by bisection;
// before, steps are limited to a factor 2.
template <class LogPfa>
double solve_smooth_threshold_factor(const LogPfa& log_pfa, double design, double start,
                                     double tolerance) {
  const double target = std::log(design);
  const auto residual = [&](double u) { return log_pfa(std::exp(u)) - target; };
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  double below = -kInfinity, above = kInfinity;  // residual(below) > 0 > residual(above)
  const auto note = [&](double u, double f) { (f > 0.0 ? below : above) = u; };
  double u0 = std::log(start), f0 = residual(u0);
  if (f0 == 0.0) return start;
  note(u0, f0);
  double u1 = u0 + (f0 > 0.0 ? 0.02 : -0.02), f1 = residual(u1);
  note(u1, f1);
  for (int step = 0; step < 100 && f1 != 0.0; ++step) {
    double u2 = u1 - f1 * (u1 - u0) / (f1 - f0);
    if (!std::isfinite(u2)) u2 = u1 + (f1 > 0.0 ? 0.7 : -0.7);  // a flat or infinite residual
    if (std::isfinite(below) && std::isfinite(above)) {
      if (!(u2 > std::min(below, above) && u2 < std::max(below, above))) u2 = 0.5 * (below + above);
    } else {
      u2 = std::clamp(u2, u1 - 0.7, u1 + 0.7);
    }
    if (std::abs(u2 - u1) < tolerance) return std::exp(u2);
    u0 = u1;
    f0 = f1;
    u1 = u2;
    f1 = residual(u1);
    FOGRADAR_CHECK(std::isfinite(f1) || f1 == -kInfinity);
    note(u1, f1);
  }
  return std::exp(u1);
}

}  // namespace fogradar::radar
