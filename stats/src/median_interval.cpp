#include "fogradar/stats/median_interval.hpp"

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <vector>

#include "detail.hpp"

namespace fogradar::stats {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr Interval unbounded{-infinity, infinity};

// Round-down discrete quantile: the largest k with P(B <= k) <= p (or 0 when there is none).
using RoundDown = boost::math::policies::policy<
    boost::math::policies::discrete_quantile<boost::math::policies::integer_round_down>>;
using Binomial = boost::math::binomial_distribution<double, RoundDown>;

// The largest k with P(B <= k) <= alpha_half, B ~ Binomial(n, 1/2), if there is one:
// [x_(k+1), x_(n-k)] (1-based) then covers the median with probability 1 - 2 P(B <= k).
std::optional<std::size_t> median_order_statistic(std::size_t n, double alpha_half) {
  const Binomial b(static_cast<double>(n), 0.5);
  const double k = boost::math::quantile(b, alpha_half);
  if (boost::math::cdf(b, k) > alpha_half) return std::nullopt;
  return static_cast<std::size_t>(k);
}

void require_two_samples(std::span<const double> x, std::span<const double> y) {
  detail::require_min_size("x", x, 1);
  detail::require_finite_values("x", x);
  detail::require_min_size("y", y, 1);
  detail::require_finite_values("y", y);
}

// Order statistics of the m n differences x_i - y_j without forming them (memory O(m + n), so
// long series do not grow the run's memory quadratically): the k-th smallest by bisection on the
// value, each step counting the differences <= t with two pointers over the sorted samples.
// fl(x_i - y_j) is monotone in x_i and in -y_j, so the count is exact for the computed differences
// and the result is exactly the element a full sort would give.
class PairwiseDifferences {
 public:
  PairwiseDifferences(std::span<const double> x, std::span<const double> y)
      : x_(detail::sorted_copy(x)), y_(detail::sorted_copy(y)) {}

  std::size_t size() const { return x_.size() * y_.size(); }

  // The k-th smallest difference, k in [1, size()].
  double kth_smallest(std::size_t k) const {
    double lo = x_.front() - y_.back();  // the smallest difference
    double hi = x_.back() - y_.front();  // the largest
    if (count_at_most(lo) >= k) return lo;
    // Invariant count(lo) < k <= count(hi); it ends with lo and hi adjacent doubles, and the only
    // difference in (lo, hi] is then hi itself.
    for (;;) {
      const double mid = lo + 0.5 * (hi - lo);
      if (mid <= lo || mid >= hi) return hi;
      (count_at_most(mid) >= k ? hi : lo) = mid;
    }
  }

  // Type-7 quantile of the differences (Hyndman & Fan 1996).
  double quantile_type7(double p) const {
    const double h = static_cast<double>(size() - 1) * p;
    const auto j = static_cast<std::size_t>(std::floor(h));
    const double low = kth_smallest(j + 1);
    return h == static_cast<double>(j)
               ? low
               : low + (h - static_cast<double>(j)) * (kth_smallest(j + 2) - low);
  }

 private:
  // #{(i, j) : x_i - y_j <= t}; for ascending x_i the qualifying j form a shrinking-from-the-left
  // suffix of the ascending y.
  std::size_t count_at_most(double t) const {
    std::size_t count = 0, j = 0;
    for (const double xi : x_) {
      while (j < y_.size() && xi - y_[j] > t) ++j;
      count += y_.size() - j;
    }
    return count;
  }

  std::vector<double> x_;
  std::vector<double> y_;
};

// Exact: the largest C with P(U <= C - 1) <= alpha / 2, i.e. the smallest C with
// P(U <= C) > alpha / 2 (R's qwilcox uses >=, which differs only when P(U <= C) equals alpha / 2
// exactly); 0 if no interval of differences reaches the confidence.
std::size_t exact_shift_rank(std::size_t m, std::size_t n, double alpha_half) {
  const std::vector<double> counts = detail::u_null_counts(m, n);
  const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
  double cumulative = 0.0;
  std::size_t c = 0;
  while ((cumulative += counts[c]) / total <= alpha_half) ++c;
  return c;
}

// Large samples: C = floor(m n / 2 + 1/2 - z sigma) (0 if below 1).
std::size_t normal_shift_rank(std::size_t m, std::size_t n, double tie_term, double alpha_half) {
  const double z = boost::math::quantile(
      boost::math::complement(boost::math::normal_distribution<>(), alpha_half));
  const double c =
      std::floor(0.5 * static_cast<double>(m * n) + 0.5 - z * detail::u_null_sigma(m, n, tie_term));
  return c < 1.0 ? 0 : static_cast<std::size_t>(c);
}

}  // namespace

Interval median_confidence_interval(std::span<const double> sorted, double confidence) {
  detail::require_sorted_sample("sorted", sorted);
  detail::require_confidence(confidence);
  const auto k = median_order_statistic(sorted.size(), 0.5 * (1.0 - confidence));
  if (!k) return unbounded;
  return {sorted[*k], sorted[sorted.size() - 1 - *k]};
}

double median_standard_error(std::span<const double> values) {
  detail::require_finite_values("values", values);
  const std::size_t n = values.size();
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> sorted = detail::sorted_copy(values);
  // The 95 % order statistics, or the extremes when n is too small for 95 %.
  const std::size_t k = median_order_statistic(n, 0.025).value_or(0);
  const Binomial b(static_cast<double>(n), 0.5);
  const double coverage = 1.0 - 2.0 * boost::math::cdf(b, static_cast<double>(k));
  const double z =
      boost::math::quantile(boost::math::normal_distribution<>(), 0.5 * (1.0 + coverage));
  return (sorted[n - 1 - k] - sorted[k]) / (2.0 * z);
}

double hodges_lehmann_shift(std::span<const double> x, std::span<const double> y) {
  require_two_samples(x, y);
  return PairwiseDifferences(x, y).quantile_type7(0.5);
}

Interval median_shift_interval(std::span<const double> x, std::span<const double> y,
                               double confidence) {
  require_two_samples(x, y);
  detail::require_confidence(confidence);
  const std::size_t m = x.size();
  const std::size_t n = y.size();
  const double alpha_half = 0.5 * (1.0 - confidence);
  const double tie_term = detail::rank_sum(x, y).tie_term;
  const std::size_t c = detail::use_exact_distribution(m, n, tie_term)
                            ? exact_shift_rank(m, n, alpha_half)
                            : normal_shift_rank(m, n, tie_term, alpha_half);
  if (c == 0) return unbounded;
  // [d_(C), d_(mn + 1 - C)], 1-based order statistics of the differences.
  const PairwiseDifferences differences(x, y);
  return {differences.kth_smallest(c), differences.kth_smallest(m * n + 1 - c)};
}

}  // namespace fogradar::stats
