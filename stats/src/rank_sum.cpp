#include <algorithm>
#include <cmath>
#include <utility>

#include "detail.hpp"
#include "fogradar/stats/shift_test.hpp"

namespace fogradar::stats::detail {

RankSum rank_sum(std::span<const double> x, std::span<const double> y) {
  // Pool (value, from_x) and sort by value; each run of equal values shares its mid-rank.
  std::vector<std::pair<double, bool>> pooled;
  pooled.reserve(x.size() + y.size());
  for (const double v : x) pooled.emplace_back(v, true);
  for (const double v : y) pooled.emplace_back(v, false);
  std::sort(pooled.begin(), pooled.end());

  double rank_sum_x = 0.0;
  double tie_term = 0.0;
  for (std::size_t first = 0; first < pooled.size();) {
    std::size_t last = first;
    std::size_t from_x = 0;
    while (last < pooled.size() && pooled[last].first == pooled[first].first) {
      from_x += pooled[last].second ? 1 : 0;
      ++last;
    }
    // Ranks first + 1 .. last (1-based): mid-rank (first + 1 + last) / 2.
    const double mid_rank = 0.5 * static_cast<double>(first + 1 + last);
    const auto t = static_cast<double>(last - first);
    rank_sum_x += static_cast<double>(from_x) * mid_rank;
    tie_term += t * t * t - t;
    first = last;
  }
  const auto m = static_cast<double>(x.size());
  return {rank_sum_x - 0.5 * m * (m + 1.0), tie_term};
}

bool use_exact_distribution(std::size_t m, std::size_t n, double tie_term) {
  return m < mann_whitney_exact_limit && n < mann_whitney_exact_limit && tie_term == 0.0;
}

std::vector<double> u_null_counts(std::size_t m, std::size_t n) {
  // c(u; m, n) is symmetric in (m, n); recurse over the smaller one.
  if (m > n) std::swap(m, n);
  // row[j] = counts for (i, j) at the current i; start at i = 0, where U = 0 only.
  std::vector<std::vector<double>> row(n + 1, std::vector<double>{1.0});
  for (std::size_t i = 1; i <= m; ++i) {
    std::vector<std::vector<double>> next(n + 1);
    next[0] = {1.0};
    for (std::size_t j = 1; j <= n; ++j) {
      // The largest of the i + j values is a y (U unchanged, (i, j - 1)) or an x above all j
      // y's (U - j, (i - 1, j)).
      std::vector<double> counts(i * j + 1, 0.0);
      for (std::size_t u = 0; u < next[j - 1].size(); ++u) counts[u] += next[j - 1][u];
      for (std::size_t u = 0; u < row[j].size(); ++u) counts[u + j] += row[j][u];
      next[j] = std::move(counts);
    }
    row = std::move(next);
  }
  return row[n];
}

double u_null_sigma(std::size_t m, std::size_t n, double tie_term) {
  const auto md = static_cast<double>(m);
  const auto nd = static_cast<double>(n);
  const double big_n = md + nd;
  return std::sqrt(md * nd / 12.0 * ((big_n + 1.0) - tie_term / (big_n * (big_n - 1.0))));
}

}  // namespace fogradar::stats::detail
