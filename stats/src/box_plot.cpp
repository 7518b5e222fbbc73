#include "fogradar/stats/box_plot.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "detail.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::stats {

namespace detail {

// Hyndman & Fan (1996) definition 7, written as R's quantile.default computes it:
// index = (n - 1) p, Q = (1 - h) x[lo] + h x[hi], lo = floor(index), hi = ceil(index), h = index -
// lo.
double quantile_type7_unchecked(std::span<const double> sorted, double p) {
  const double index = static_cast<double>(sorted.size() - 1) * p;
  const double lo = std::floor(index);
  const auto lo_i = static_cast<std::size_t>(lo);
  const auto hi_i = static_cast<std::size_t>(std::ceil(index));
  const double h = index - lo;
  if (h == 0.0 || sorted[lo_i] == sorted[hi_i]) return sorted[lo_i];
  return (1.0 - h) * sorted[lo_i] + h * sorted[hi_i];
}

}  // namespace detail

double quantile_type7(std::span<const double> sorted, double p) {
  detail::require_sorted_sample("sorted", sorted);
  require_in_range("p", p, 0.0, 1.0);
  return detail::quantile_type7_unchecked(sorted, p);
}

double median(std::span<const double> values) {
  detail::require_min_size("values", values, 1);
  detail::require_finite_values("values", values);
  return detail::quantile_type7_unchecked(detail::sorted_copy(values), 0.5);
}

BoxPlot box_plot(std::span<const double> values) {
  detail::require_finite_values("values", values);
  BoxPlot box;
  box.n = values.size();
  if (values.empty()) return box;

  const std::vector<double> sorted = detail::sorted_copy(values);
  const auto n = static_cast<double>(sorted.size());

  // Mean and sample standard deviation (two-pass, divisor n - 1).
  box.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / n;
  if (sorted.size() > 1) {
    double sum_sq = 0.0;
    for (const double v : sorted) sum_sq += (v - box.mean) * (v - box.mean);
    box.std_dev = std::sqrt(sum_sq / (n - 1.0));
  }

  // Five-number summary with type-7 quartiles.
  box.min = sorted.front();
  box.max = sorted.back();
  box.q1 = detail::quantile_type7_unchecked(sorted, 0.25);
  box.median = detail::quantile_type7_unchecked(sorted, 0.5);
  box.q3 = detail::quantile_type7_unchecked(sorted, 0.75);

  // Tukey fences at 1.5 IQR; whiskers end at the most extreme values inside them.
  const double iqr = box.q3 - box.q1;
  const double fence_low = box.q1 - 1.5 * iqr;
  const double fence_high = box.q3 + 1.5 * iqr;
  const auto inside_begin = std::lower_bound(sorted.begin(), sorted.end(), fence_low);
  const auto inside_end = std::upper_bound(sorted.begin(), sorted.end(), fence_high);
  box.whisker_low = *inside_begin;
  box.whisker_high = *(inside_end - 1);
  box.outliers.assign(sorted.begin(), inside_begin);
  box.outliers.insert(box.outliers.end(), inside_end, sorted.end());
  return box;
}

}  // namespace fogradar::stats
