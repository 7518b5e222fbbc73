// Descriptive statistics of one series of plain numbers: sample quantiles and the Tukey box plot.
//
// Quantiles: Hyndman & Fan (1996), "Sample quantiles in statistical packages", The American
// Statistician 50(4), 361-365, definition 7 (R's default quantile(type = 7), NumPy's default
// "linear"): for the sorted sample x_(1) <= ... <= x_(n) and probability p,
//   h = (n - 1) p,  j = floor(h),  Q(p) = (1 - (h - j)) x_(j+1) + (h - j) x_(j+2)   (x_(n+1) :=
//   x_(n))
// Box plot: Tukey (1977), Exploratory Data Analysis, with the quartiles taken as type-7 quantiles
// (R's boxplot.stats uses Tukey's hinges, fivenum(), instead; the two agree for n = 4k + 1 and
// n = 4k + 3 and differ slightly otherwise).
#pragma once

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace fogradar::stats {

// Type-7 sample quantile of an ascending-sorted, finite, non-empty sample; p in [0, 1].
// Throws InvalidParameter naming "sorted" (empty, non-finite or not ascending) or "p".
double quantile_type7(std::span<const double> sorted, double p);

// Type-7 median (p = 1/2) of any finite, non-empty sample (sorts a copy).
// Throws InvalidParameter naming "values".
double median(std::span<const double> values);

// Tukey box plot of one series, in the unit of the values (e.g. dBsm).
// For n = 0 every statistic is NaN and there are no outliers; for n = 1 std_dev is NaN.
struct BoxPlot {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();

  std::size_t n = 0;
  double mean = nan;
  double std_dev = nan;  // sample standard deviation, divisor n - 1
  double min = nan;
  double q1 = nan;      // type-7 quantile at p = 0.25
  double median = nan;  // type-7 quantile at p = 0.5
  double q3 = nan;      // type-7 quantile at p = 0.75
  double max = nan;
  double whisker_low = nan;      // smallest value >= q1 - 1.5 (q3 - q1)
  double whisker_high = nan;     // largest value <= q3 + 1.5 (q3 - q1)
  std::vector<double> outliers;  // values < whisker_low or > whisker_high, ascending
};

// The box plot of `values` (any order). Throws InvalidParameter naming "values" if a value is
// not finite.
BoxPlot box_plot(std::span<const double> values);

}  // namespace fogradar::stats
