// Statistics of a sample given as a histogram of integer values 0, 1, ..., bins - 1 (e.g. 8-bit
// grey levels): the same numbers box_plot.hpp gives for the expanded sample, without expanding it.
#pragma once

#include <cstdint>
#include <span>

namespace fogradar::stats {

struct HistogramSummary {
  std::uint64_t n = 0;
  double mean = 0.0;
  double std_dev = 0.0;  // sample standard deviation, divisor n - 1 (0 for n = 1)
};
// Throws InvalidParameter naming "counts" when every count is zero.
HistogramSummary histogram_summary(std::span<const std::uint64_t> counts);

// Type-7 quantile (Hyndman & Fan 1996, box_plot.hpp) of the sample in which value v occurs
// counts[v] times. Throws InvalidParameter naming "counts" (all zero) or "p" (outside [0, 1]).
double histogram_quantile_type7(std::span<const std::uint64_t> counts, double p);

}  // namespace fogradar::stats
