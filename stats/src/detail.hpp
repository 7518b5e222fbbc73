// Internals shared by the stats sources: input checks, the unchecked type-7 quantile and the
// Mann-Whitney U machinery (mid-ranks, tie term, exact null distribution).
#pragma once

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

namespace fogradar::stats::detail {

// Throws InvalidParameter naming `field`: "<field>[i] = nan: must be a finite number".
void require_finite_values(std::string_view field, std::span<const double> values);
// Throws InvalidParameter naming `field` if `values` has fewer than `min_size` elements.
void require_min_size(std::string_view field, std::span<const double> values, std::size_t min_size);
// Non-empty, finite, ascending; throws InvalidParameter naming `field`.
void require_sorted_sample(std::string_view field, std::span<const double> sorted);
// Throws InvalidParameter naming "confidence" unless 0 < confidence < 1.
void require_confidence(double confidence);

std::vector<double> sorted_copy(std::span<const double> values);

// Hyndman & Fan definition 7 on a sorted, non-empty sample; p in [0, 1] (not checked).
double quantile_type7_unchecked(std::span<const double> sorted, double p);

struct RankSum {
  double u;         // U = R_x - m (m + 1) / 2 with mid-ranks
  double tie_term;  // sum over groups of tied values of t^3 - t
};

// Mid-rank sum statistic of x in the pooled sample (x, y).
RankSum rank_sum(std::span<const double> x, std::span<const double> y);

// True when the exact null distribution is used: m, n < mann_whitney_exact_limit, no ties.
bool use_exact_distribution(std::size_t m, std::size_t n, double tie_term);

// c(u; m, n) for u = 0..m n: the number of the C(m + n, m) equally likely arrangements with U = u
// (Mann & Whitney 1947 recursion). Doubles: exact up to 2^53, then relative error ~1e-16.
std::vector<double> u_null_counts(std::size_t m, std::size_t n);

// Null standard deviation of U with tie correction (Hollander, Wolfe & Chicken 2014, §4.1):
//   sigma^2 = (m n / 12) ((N + 1) - tie_term / (N (N - 1))),  N = m + n.
double u_null_sigma(std::size_t m, std::size_t n, double tie_term);

}  // namespace fogradar::stats::detail
