// Two-sample tests of a shift of one series x against a baseline y (two-sided).
//
// The primary test is Mann-Whitney U (Wilcoxon rank-sum). RCS in dBsm is not normally
// distributed: Rayleigh-like fading makes the dB values skewed with a long low tail, and the
// experiment compares the medians of box plots. A rank test is distribution-free (its null
// distribution holds for any continuous distribution), invariant to monotone transforms (dB or
// linear gives the same answer) and robust to the outliers the box plot shows. Welch's t-test is
// provided for comparison and documentation only.
#pragma once

#include <cstddef>
#include <span>

namespace fogradar::stats {

// Both samples shorter than this and no ties anywhere: the exact null distribution is used
// (R's wilcox.test default, exact = NULL).
inline constexpr std::size_t mann_whitney_exact_limit = 50;

inline constexpr const char* mann_whitney_exact_method = "Wilcoxon rank sum exact test";
inline constexpr const char* mann_whitney_normal_method =
    "Wilcoxon rank sum test with continuity correction";

struct ShiftTestResult {
  double u_statistic;   // U = R_x - n_x (n_x + 1) / 2, R_x the mid-rank sum of x (R's W)
  double p_value;       // two-sided
  double median_shift;  // median(x) - median(y), type-7 medians, in the unit of the values
  const char* method;   // mann_whitney_exact_method or mann_whitney_normal_method
};

// Mann & Whitney (1947), Ann. Math. Statist. 18, 50-60; identical to R's
// wilcox.test(x, y, exact = NULL, correct = TRUE). Ranks are mid-ranks for ties.
//  - exact (n_x, n_y < mann_whitney_exact_limit and no ties): U's permutation distribution by the
//    counting recursion c(u; m, n) = c(u - n; m - 1, n) + c(u; m, n - 1);
//    p = min(1, 2 P(U <= u)) if u <= m n / 2, else min(1, 2 P(U >= u)).
//  - otherwise the normal approximation with tie and continuity correction:
//    z = (U - m n / 2 - sign(U - m n / 2) / 2) / sigma,
//    sigma^2 = (m n / 12) ((N + 1) - sum_ties (t^3 - t) / (N (N - 1))),  N = m + n,
//    p = 2 (1 - Phi(|z|)); p = 1 when every value is tied (sigma = 0, U = m n / 2).
// Throws InvalidParameter naming "x" or "y" (empty or a value not finite).
ShiftTestResult mann_whitney_u(std::span<const double> x, std::span<const double> y);

struct WelchResult {
  double t_statistic;         // (mean(x) - mean(y)) / sqrt(s_x^2 / n_x + s_y^2 / n_y)
  double degrees_of_freedom;  // Welch-Satterthwaite
  double p_value;             // two-sided, Student t with non-integer degrees of freedom
  double mean_shift;          // mean(x) - mean(y)
};

// Welch (1947), Biometrika 34, 28-35; R's t.test(x, y) (var.equal = FALSE):
//   nu = (s_x^2/n_x + s_y^2/n_y)^2 / ((s_x^2/n_x)^2/(n_x-1) + (s_y^2/n_y)^2/(n_y-1)).
// If both samples are constant the statistic is undefined: t, nu and p are NaN.
// Throws InvalidParameter naming "x" or "y" (fewer than 2 values or a value not finite).
WelchResult welch_t_test(std::span<const double> x, std::span<const double> y);

}  // namespace fogradar::stats
