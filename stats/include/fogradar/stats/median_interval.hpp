// Distribution-free confidence intervals for a median and for a shift between two series.
//
// Median: the order statistics x_(l) <= x_(n+1-l) cover the population median with probability
//   gamma = 1 - 2 P(B <= l - 1),  B ~ Binomial(n, 1/2)
// for any continuous distribution (Thompson 1936, Ann. Math. Statist. 7, 122-128; Conover 1999,
// Practical Nonparametric Statistics, 3rd ed., §3.2).
// l is the largest integer with gamma >= confidence, found from the binomial quantile.
//
// Shift: the Hodges-Lehmann estimator (Hodges & Lehmann 1963, Ann. Math. Statist. 34, 598-611:
// median of all n_x n_y differences x_i - y_j) and its interval from the order statistics of
// those differences, [d_(C), d_(n_x n_y + 1 - C)], with C from the null distribution of the
// Mann-Whitney U (Bauer 1972, JASA 67, 687-690; Hollander, Wolfe & Chicken 2014, Nonparametric
// Statistical Methods, 3rd ed., §4.3; R's wilcox.test(conf.int = TRUE)). It inverts the same
// test as mann_whitney_u, so the interval excludes 0 essentially when that test rejects.
//
// When the sample is too small for the requested confidence (e.g. a median with n < 6 at 95 %),
// no interval of order statistics reaches it and the result is (-inf, +inf).
#pragma once

#include <span>

namespace fogradar::stats {

struct Interval {
  double low;
  double high;
};

// Order-statistic interval for the median of an ascending-sorted, finite, non-empty sample.
// Throws InvalidParameter naming "sorted" or "confidence" (must be in (0, 1)).
Interval median_confidence_interval(std::span<const double> sorted, double confidence);

// Standard error of the sample median from the distribution-free interval (McKean & Schrader
// 1984, Commun. Statist. B 13, 751-773; Price & Bonett 2001, J. Statist. Comput. Simul. 68,
// 295-305): SE = (x_(n+1-l) - x_(l)) / (2 z), z = Phi^-1((1 + gamma) / 2), with l the 95 %
// interval's order statistic and gamma its achieved coverage (l = 1 when n < 6).
// NaN for n < 2. Throws InvalidParameter naming "values" (a value not finite).
double median_standard_error(std::span<const double> values);

// Hodges-Lehmann shift estimate: median of the differences x_i - y_j.
// Throws InvalidParameter naming "x" or "y" (empty or a value not finite).
double hodges_lehmann_shift(std::span<const double> x, std::span<const double> y);

// Distribution-free interval for the shift Delta in x ~ y + Delta, C chosen as in
// mann_whitney_u:
//  - exact (both samples shorter than mann_whitney_exact_limit and no ties): C is the largest
//    integer with P(U <= C - 1) <= alpha / 2, so the coverage 1 - 2 P(U <= C - 1) >= 1 - alpha
//    (R's exact conf.int);
//  - otherwise C = floor(n_x n_y / 2 + 1/2 - z_(1-alpha/2) sigma), sigma the tie-corrected
//    standard deviation of U: Hollander, Wolfe & Chicken's large-sample C = n_x n_y / 2 -
//    z sigma rounded to the nearest integer (R instead solves the corrected z for the shift by
//    root finding, which lands between the order statistics).
// Memory O(n_x + n_y): the order statistics of the differences are selected without forming them
// (bisection on the value with an O(n_x + n_y) count per step).
// Throws InvalidParameter naming "x", "y" or "confidence".
Interval median_shift_interval(std::span<const double> x, std::span<const double> y,
                               double confidence);

}  // namespace fogradar::stats
