#include "fogradar/stats/histogram.hpp"

#include <cmath>

#include "fogradar/core/error.hpp"

namespace fogradar::stats {
namespace {

std::uint64_t total(std::span<const std::uint64_t> counts) {
  std::uint64_t n = 0;
  for (const std::uint64_t c : counts) n += c;
  if (n == 0) throw_invalid("counts", 0.0, "a histogram holding at least one value");
  return n;
}

// The j-th smallest value (0-based) of the expanded sample.
double order_statistic(std::span<const std::uint64_t> counts, std::uint64_t j) {
  std::uint64_t below = 0;
  for (std::size_t v = 0; v < counts.size(); ++v) {
    below += counts[v];
    if (j < below) return static_cast<double>(v);
  }
  return static_cast<double>(counts.size() - 1);
}

}  // namespace

HistogramSummary histogram_summary(std::span<const std::uint64_t> counts) {
  HistogramSummary summary;
  summary.n = total(counts);
  double sum = 0.0;
  for (std::size_t v = 0; v < counts.size(); ++v) {
    sum += static_cast<double>(v) * static_cast<double>(counts[v]);
  }
  summary.mean = sum / static_cast<double>(summary.n);
  // Two-pass: squared deviations from the mean, no cancellation.
  double squares = 0.0;
  for (std::size_t v = 0; v < counts.size(); ++v) {
    const double d = static_cast<double>(v) - summary.mean;
    squares += d * d * static_cast<double>(counts[v]);
  }
  summary.std_dev = summary.n > 1 ? std::sqrt(squares / static_cast<double>(summary.n - 1)) : 0.0;
  return summary;
}

double histogram_quantile_type7(std::span<const std::uint64_t> counts, double p) {
  const std::uint64_t n = total(counts);
  require_in_range("p", p, 0.0, 1.0);
  const double h = static_cast<double>(n - 1) * p;
  const double lo = std::floor(h);
  const auto j = static_cast<std::uint64_t>(lo);
  const double x_lo = order_statistic(counts, j);
  if (h == lo) return x_lo;
  return x_lo + (h - lo) * (order_statistic(counts, j + 1) - x_lo);
}

}  // namespace fogradar::stats
