#include "fogradar/stats/shift_test.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <numeric>

#include "detail.hpp"
#include "fogradar/stats/box_plot.hpp"

namespace fogradar::stats {

namespace {

void require_two_samples(std::span<const double> x, std::span<const double> y,
                         std::size_t min_size) {
  detail::require_min_size("x", x, min_size);
  detail::require_finite_values("x", x);
  detail::require_min_size("y", y, min_size);
  detail::require_finite_values("y", y);
}

// Two-sided exact p-value from the permutation distribution of U, summing the nearer tail
// directly (no 1 - cdf cancellation): R's wilcox.test with exact = TRUE.
double exact_p_value(double u, std::size_t m, std::size_t n) {
  const std::vector<double> counts = detail::u_null_counts(m, n);
  const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
  const auto u_index = static_cast<std::size_t>(std::llround(u));
  const double half = 0.5 * static_cast<double>(m * n);
  const double tail =
      u > half ? std::accumulate(counts.begin() + static_cast<std::ptrdiff_t>(u_index),
                                 counts.end(), 0.0)
               : std::accumulate(counts.begin(),
                                 counts.begin() + static_cast<std::ptrdiff_t>(u_index) + 1, 0.0);
  return std::min(1.0, 2.0 * tail / total);
}

// Normal approximation with tie and continuity correction (R's wilcox.test, correct = TRUE).
double normal_p_value(double u, std::size_t m, std::size_t n, double tie_term) {
  const double sigma = detail::u_null_sigma(m, n, tie_term);
  // Every value tied: U = m n / 2 exactly, no evidence of a shift.
  if (sigma == 0.0) return 1.0;
  const double distance = std::abs(u - 0.5 * static_cast<double>(m * n));
  const double z = (distance - (distance > 0.0 ? 0.5 : 0.0)) / sigma;
  return 2.0 * boost::math::cdf(boost::math::complement(boost::math::normal_distribution<>(), z));
}

double sample_mean(std::span<const double> v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double sample_variance(std::span<const double> v, double mean) {
  double sum_sq = 0.0;
  for (const double value : v) sum_sq += (value - mean) * (value - mean);
  return sum_sq / static_cast<double>(v.size() - 1);
}

}  // namespace

ShiftTestResult mann_whitney_u(std::span<const double> x, std::span<const double> y) {
  require_two_samples(x, y, 1);
  const detail::RankSum statistic = detail::rank_sum(x, y);
  const bool exact = detail::use_exact_distribution(x.size(), y.size(), statistic.tie_term);
  const double p_value = exact
                             ? exact_p_value(statistic.u, x.size(), y.size())
                             : normal_p_value(statistic.u, x.size(), y.size(), statistic.tie_term);
  return {statistic.u, p_value, median(x) - median(y),
          exact ? mann_whitney_exact_method : mann_whitney_normal_method};
}

WelchResult welch_t_test(std::span<const double> x, std::span<const double> y) {
  require_two_samples(x, y, 2);
  const double mean_x = sample_mean(x);
  const double mean_y = sample_mean(y);
  // Squared standard errors of the two means.
  const double se2_x = sample_variance(x, mean_x) / static_cast<double>(x.size());
  const double se2_y = sample_variance(y, mean_y) / static_cast<double>(y.size());
  const double se2 = se2_x + se2_y;
  if (se2 == 0.0) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, mean_x - mean_y};
  }
  const double t = (mean_x - mean_y) / std::sqrt(se2);
  const double nu = se2 * se2 /
                    (se2_x * se2_x / static_cast<double>(x.size() - 1) +
                     se2_y * se2_y / static_cast<double>(y.size() - 1));
  const double p_value = 2.0 * boost::math::cdf(boost::math::complement(
                                   boost::math::students_t_distribution<>(nu), std::abs(t)));
  return {t, nu, p_value, mean_x - mean_y};
}

}  // namespace fogradar::stats
