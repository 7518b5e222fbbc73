// The threshold-factor root finder shared by the independent-cell (cfar.cpp) and the
// correlated-cell (cfar_design.cpp) CFAR designs.
#pragma once

#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>

#include "fogradar/core/error.hpp"

namespace fogradar::radar {

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
  std::uintmax_t max_iterations = 200;
  const auto [lower, upper] = boost::math::tools::toms748_solve(
      residual, low, high, f_low, f_high, boost::math::tools::eps_tolerance<double>(50),
      max_iterations);
  FOGRADAR_CHECK(max_iterations < 200);
  return 0.5 * (lower + upper);
}

}  // namespace fogradar::radar
