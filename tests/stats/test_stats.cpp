// Statistics tests. References (each test names its own and its tolerance):
//   [HF96]  R. J. Hyndman, Y. Fan, "Sample quantiles in statistical packages", The American
//           Statistician 50(4), 361-365, 1996: definition 7, p_k = (k - 1)/(n - 1) hits x_(k).
//   [Rq]    R quantile() outputs: quantile(1:10, c(.25,.5,.75)) = 3.25 5.5 7.75;
//           quantile(1:9, seq(0, 1, .1)) = 1.0 1.8 ... 9.0 (TIBCO TERR quantile reference page);
//           quantile(mtcars$wt) = 1.51300 2.58125 3.32500 3.61000 5.42400 (w3schools "R
//           Percentiles", which lists the 32 values).
//   [Rbs]   R boxplot.stats(c(1:10, 50)): stats 1.0 3.5 6.0 8.5 10.0, out 50.
//   [Rw]    R wilcox.test outputs: x = c(1,5,9,24,56,21,3,7,21,4), y = c(12,15,5,9,9,14,56,22,3,7,
//           32,5): "W = 51.5, p-value = 0.5966" and with y = c(1233,4356,987,39999,1111,200000):
//           "W = 0, p-value = 0.001364" (continuity correction, ties; endmemo.com/r/wilcoxon.php);
//           the wilcox.test help example (Hollander & Wolfe depression data), alternative = "g":
//           "W = 35, p-value = 0.1272", i.e. two-sided 764/3003 = 0.2544 (full enumeration).
//   [Rt]    R t.test(extra ~ group, data = sleep): "t = -1.8608, df = 17.776, p-value = 0.07939".
//   [Bin]   Order-statistic median interval from Binomial(n, 1/2) sums written out here
//           (Conover 1999 §3.2): n = 10 -> (x_(2), x_(9)), n = 20 -> (x_(6), x_(15)).
// Monte Carlo tests use fixed-seed fogradar::RandomStream streams and 4-sigma binomial bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/median_interval.hpp"
#include "fogradar/stats/shift_test.hpp"

namespace fogradar::stats {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double kExactTol = 1e-12;  // values that are exact decimals or exact rationals

// mtcars$wt (R datasets), 1000 lbs, as listed by [Rq].
const std::vector<double> kMtcarsWt = {2.620, 2.875, 2.320, 3.215, 3.440, 3.460, 3.570, 3.190,
                                       3.150, 3.440, 3.440, 4.070, 3.730, 3.780, 5.250, 5.424,
                                       5.345, 2.200, 1.615, 1.835, 2.465, 3.520, 3.435, 3.840,
                                       3.845, 1.935, 2.140, 1.513, 3.170, 2.770, 3.570, 2.780};

// Hollander & Wolfe depression data from R's wilcox.test help page.
const std::vector<double> kDepressionX = {0.80, 0.83, 1.89, 1.04, 1.45,
                                          1.38, 1.91, 1.64, 0.73, 1.46};
const std::vector<double> kDepressionY = {1.15, 0.88, 0.90, 0.74, 1.21};

std::vector<double> sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v;
}

std::vector<double> normal_sample(RandomStream& rng, std::size_t n, double mean) {
  std::vector<double> v(n);
  for (double& x : v) x = mean + rng.normal();
  return v;
}

// Two-sided 4-sigma band of a binomial proportion with success probability p over `trials`.
double four_sigma(double p, int trials) { return 4.0 * std::sqrt(p * (1.0 - p) / trials); }

template <class F>
std::string expect_invalid(F&& f, const std::string& field) {
  try {
    f();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no InvalidParameter naming " << field;
  return {};
}

// --- Quantiles ----------------------------------------------------------------------------------

TEST(Quantile, MatchesROneToTen) {  // [Rq], exact decimals
  const std::vector<double> x = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  EXPECT_NEAR(quantile_type7(x, 0.25), 3.25, kExactTol);
  EXPECT_NEAR(quantile_type7(x, 0.50), 5.5, kExactTol);
  EXPECT_NEAR(quantile_type7(x, 0.75), 7.75, kExactTol);
}

TEST(Quantile, MatchesROneToNineDeciles) {  // [Rq], exact decimals
  const std::vector<double> x = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  const double expected[] = {1.0, 1.8, 2.6, 3.4, 4.2, 5.0, 5.8, 6.6, 7.4, 8.2, 9.0};
  for (int i = 0; i <= 10; ++i)
    EXPECT_NEAR(quantile_type7(x, i / 10.0), expected[i], kExactTol) << i;
}

TEST(Quantile, MatchesRMtcarsWeight) {  // [Rq], printed digits are exact
  const std::vector<double> wt = sorted(kMtcarsWt);
  const double p[] = {0.0, 0.25, 0.5, 0.75, 1.0};
  const double expected[] = {1.513, 2.58125, 3.325, 3.61, 5.424};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(quantile_type7(wt, p[i]), expected[i], kExactTol) << p[i];
}

TEST(Quantile, PlottingPositionsHitOrderStatistics) {
  // [HF96]: p_k = (k-1)/(n-1) -> x_(k). p_k is rounded to binary, so (n-1) p_k may miss k by an
  // ulp and interpolate a hair towards the neighbour (R's type 7 has no fuzz either):
  // tolerance 1e-14 on N(0, 1) data.
  RandomStream rng(7);
  const std::vector<double> x = sorted(normal_sample(rng, 23, 0.0));
  for (std::size_t k = 0; k < x.size(); ++k) {
    EXPECT_NEAR(quantile_type7(x, static_cast<double>(k) / 22.0), x[k], 1e-14) << k;
  }
}

TEST(Quantile, SmallSamples) {  // closed forms: n = 1 constant, n = 2 linear a + p (b - a)
  const std::vector<double> one = {4.5};
  for (const double p : {0.0, 0.3, 1.0}) EXPECT_EQ(quantile_type7(one, p), 4.5);
  const std::vector<double> two = {-1.0, 3.0};
  for (const double p : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    EXPECT_NEAR(quantile_type7(two, p), -1.0 + 4.0 * p, kExactTol) << p;
  }
  EXPECT_NEAR(median(std::vector<double>{5.0, -2.0, 9.0, 1.0}), 3.0, kExactTol);
}

// --- Box plot -----------------------------------------------------------------------------------

TEST(BoxPlot, TukeyOnOneToTenAndFifty) {
  // [Rbs] and by hand: type-7 quartiles of 11 values sit at h = 2.5, 5, 7.5 -> 3.5, 6, 8.5 (equal
  // to Tukey's hinges since n = 4k + 3); IQR 5, fences -4 and 16. Mean 105/11, sd by the
  // closed form sqrt((sum x^2 - n mean^2)/(n - 1)) with sum x^2 = 2885.
  std::vector<double> x = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 50};
  const BoxPlot b = box_plot(x);
  EXPECT_EQ(b.n, 11u);
  EXPECT_NEAR(b.min, 1.0, kExactTol);
  EXPECT_NEAR(b.q1, 3.5, kExactTol);
  EXPECT_NEAR(b.median, 6.0, kExactTol);
  EXPECT_NEAR(b.q3, 8.5, kExactTol);
  EXPECT_NEAR(b.max, 50.0, kExactTol);
  EXPECT_NEAR(b.whisker_low, 1.0, kExactTol);
  EXPECT_NEAR(b.whisker_high, 10.0, kExactTol);
  EXPECT_EQ(b.outliers, std::vector<double>{50.0});
  EXPECT_NEAR(b.mean, 105.0 / 11.0, kExactTol);
  EXPECT_NEAR(b.std_dev, std::sqrt((2885.0 - 105.0 * 105.0 / 11.0) / 10.0), kExactTol);
}

TEST(BoxPlot, LowerFenceIsInclusive) {
  // By hand, n = 11: sorted (v, 1, ..., 10) has q1 = (2 + 3)/2 = 2.5, median 5, q3 = 7.5,
  // IQR 5, lower fence -5: v = -6 is an outlier (whisker at 1), v = -5 sits on the fence and is
  // the whisker (whisker_low = smallest value >= q1 - 1.5 IQR).
  std::vector<double> x = {-6, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  BoxPlot b = box_plot(x);
  EXPECT_NEAR(b.q1, 2.5, kExactTol);
  EXPECT_NEAR(b.median, 5.0, kExactTol);
  EXPECT_NEAR(b.q3, 7.5, kExactTol);
  EXPECT_EQ(b.whisker_low, 1.0);
  EXPECT_EQ(b.whisker_high, 10.0);
  EXPECT_EQ(b.outliers, std::vector<double>{-6.0});
  x[0] = -5.0;
  b = box_plot(x);
  EXPECT_EQ(b.whisker_low, -5.0);
  EXPECT_TRUE(b.outliers.empty());
}

TEST(BoxPlot, TypeSevenDiffersFromTukeyHingesOnMtcarsWeight) {
  // By hand (n = 32): type-7 q1 = x_(8) + 0.75 (x_(9) - x_(8)) = 2.58125, q3 = x_(24) + 0.25
  // (x_(25) - x_(24)) = 3.61, IQR 1.02875, fences 1.038125 and 5.153125: whisker_high = 4.07 and
  // three outliers 5.25, 5.345, 5.424. R's boxplot.stats uses Tukey's hinges 2.5425 and 3.65
  // instead (fence 5.31125): whisker 5.25 and two outliers. Our box states type 7.
  const BoxPlot b = box_plot(kMtcarsWt);
  EXPECT_NEAR(b.q1, 2.58125, kExactTol);
  EXPECT_NEAR(b.q3, 3.61, kExactTol);
  EXPECT_NEAR(b.whisker_low, 1.513, kExactTol);
  EXPECT_NEAR(b.whisker_high, 4.07, kExactTol);
  EXPECT_EQ(b.outliers, (std::vector<double>{5.25, 5.345, 5.424}));
  EXPECT_NEAR(b.mean, 3.21725, kExactTol);  // sum 102.952 / 32
}

TEST(BoxPlot, EmptyAndSingleton) {
  const BoxPlot empty = box_plot(std::vector<double>{});
  EXPECT_EQ(empty.n, 0u);
  for (const double v : {empty.mean, empty.std_dev, empty.min, empty.q1, empty.median, empty.q3,
                         empty.max, empty.whisker_low, empty.whisker_high}) {
    EXPECT_TRUE(std::isnan(v));
  }
  EXPECT_TRUE(empty.outliers.empty());

  const BoxPlot one = box_plot(std::vector<double>{14.97});
  EXPECT_EQ(one.n, 1u);
  EXPECT_TRUE(std::isnan(one.std_dev));
  for (const double v : {one.mean, one.min, one.q1, one.median, one.q3, one.max, one.whisker_low,
                         one.whisker_high}) {
    EXPECT_EQ(v, 14.97);
  }
  EXPECT_TRUE(one.outliers.empty());
}

TEST(BoxPlot, IndependentOfInputOrder) {
  RandomStream rng(11);
  std::vector<double> x = normal_sample(rng, 200, 15.0);
  x.push_back(2.0);  // an outlier below
  const BoxPlot a = box_plot(x);
  std::reverse(x.begin(), x.end());
  std::rotate(x.begin(), x.begin() + 37, x.end());
  const BoxPlot b = box_plot(x);
  EXPECT_EQ(a.q1, b.q1);
  EXPECT_EQ(a.median, b.median);
  EXPECT_EQ(a.q3, b.q3);
  EXPECT_EQ(a.outliers, b.outliers);
  ASSERT_FALSE(a.outliers.empty());
  EXPECT_EQ(a.outliers.front(), 2.0);
  EXPECT_TRUE(std::is_sorted(a.outliers.begin(), a.outliers.end()));
  EXPECT_NEAR(a.mean, b.mean, 1e-12);
}

// --- Mann-Whitney U ----------------------------------------------------------------------------

TEST(MannWhitney, MatchesRWithTies) {  // [Rw]; R prints 4 significant digits of p
  const std::vector<double> x = {1, 5, 9, 24, 56, 21, 3, 7, 21, 4};
  const ShiftTestResult r =
      mann_whitney_u(x, std::vector<double>{12, 15, 5, 9, 9, 14, 56, 22, 3, 7, 32, 5});
  EXPECT_EQ(r.u_statistic, 51.5);
  EXPECT_NEAR(r.p_value, 0.5966, 5e-5);
  EXPECT_STREQ(r.method, mann_whitney_normal_method);
  EXPECT_NEAR(r.median_shift, 8.0 - 10.5, kExactTol);  // medians 8 and 10.5

  const ShiftTestResult far =
      mann_whitney_u(x, std::vector<double>{1233, 4356, 987, 39999, 1111, 200000});
  EXPECT_EQ(far.u_statistic, 0.0);
  EXPECT_NEAR(far.p_value, 0.001364, 5e-7);
  EXPECT_STREQ(far.method, mann_whitney_normal_method);
}

TEST(MannWhitney, MatchesRExactOnDepressionData) {  // [Rw]: W = 35, two-sided 764/3003
  const ShiftTestResult r = mann_whitney_u(kDepressionX, kDepressionY);
  EXPECT_EQ(r.u_statistic, 35.0);
  EXPECT_NEAR(r.p_value, 764.0 / 3003.0, kExactTol);
  EXPECT_NEAR(r.p_value, 0.2544, 5e-5);
  EXPECT_STREQ(r.method, mann_whitney_exact_method);
}

// Second method: the exact p-value by enumerating all C(m + n, m) rank sets, with U counted
// directly as #{(i, j): x_i > y_j}.
double brute_force_p(const std::vector<double>& x, const std::vector<double>& y) {
  std::size_t u_obs = 0;
  for (const double xi : x) {
    for (const double yj : y) u_obs += xi > yj ? 1 : 0;
  }
  const std::size_t m = x.size();
  const std::size_t total = m + y.size();
  double below = 0, above = 0, count = 0;
  for (std::uint32_t mask = 0; mask < (1u << total); ++mask) {
    if (static_cast<std::size_t>(std::popcount(mask)) != m) continue;
    std::size_t rank_sum = 0;  // 1-based ranks of the x positions
    for (std::size_t bit = 0; bit < total; ++bit) rank_sum += (mask >> bit) & 1u ? bit + 1 : 0;
    const std::size_t u = rank_sum - m * (m + 1) / 2;
    count += 1;
    below += u <= u_obs ? 1 : 0;
    above += u >= u_obs ? 1 : 0;
  }
  return std::min(1.0, 2.0 * std::min(below, above) / count);
}

TEST(MannWhitney, ExactDistributionMatchesEnumeration) {  // second method, 1e-12 relative
  RandomStream rng(2024);
  const std::pair<std::size_t, std::size_t> sizes[] = {{1, 6}, {3, 4},   {5, 5}, {7, 3},
                                                       {8, 9}, {10, 10}, {4, 12}};
  for (const auto& [m, n] : sizes) {
    for (int rep = 0; rep < 3; ++rep) {
      const std::vector<double> x = normal_sample(rng, m, 0.4 * rep);
      const std::vector<double> y = normal_sample(rng, n, 0.0);
      const ShiftTestResult r = mann_whitney_u(x, y);
      ASSERT_STREQ(r.method, mann_whitney_exact_method);
      const double expected = brute_force_p(x, y);
      EXPECT_NEAR(r.p_value, expected, 1e-12 * expected) << m << "x" << n << " rep " << rep;
    }
  }
}

TEST(MannWhitney, SwappingSamplesMirrorsU) {  // U(y, x) = m n - U(x, y), same two-sided p
  RandomStream rng(5);
  for (const std::size_t n : {8u, 120u}) {
    const std::vector<double> x = normal_sample(rng, n, 0.3);
    const std::vector<double> y = normal_sample(rng, n + 3, 0.0);
    const ShiftTestResult xy = mann_whitney_u(x, y);
    const ShiftTestResult yx = mann_whitney_u(y, x);
    EXPECT_EQ(xy.u_statistic + yx.u_statistic, static_cast<double>(n * (n + 3)));
    EXPECT_NEAR(xy.p_value, yx.p_value, 1e-14);
    EXPECT_EQ(xy.median_shift, -yx.median_shift);
  }
}

TEST(MannWhitney, InvariantUnderMonotoneTransform) {  // rank test: dB or linear, same answer
  RandomStream rng(9);
  std::vector<double> x = normal_sample(rng, 200, 0.2);
  std::vector<double> y = normal_sample(rng, 200, 0.0);
  const ShiftTestResult db = mann_whitney_u(x, y);
  for (double& v : x) v = std::pow(10.0, v / 10.0);
  for (double& v : y) v = std::pow(10.0, v / 10.0);
  const ShiftTestResult linear = mann_whitney_u(x, y);
  EXPECT_EQ(db.u_statistic, linear.u_statistic);
  EXPECT_EQ(db.p_value, linear.p_value);
}

TEST(MannWhitney, DetectsShiftOfHalfSigmaWith200Samples) {
  // Expected z ~ 0.5 sqrt(3 n / (2 pi)) ~ 4.9 for a 0.5-sigma normal shift (Pitman efficiency
  // 3/pi): p ~ 1e-6; bound 1e-3 leaves room for sampling. Shift estimate within 3.5 SE.
  RandomStream rng(77);
  const ShiftTestResult r =
      mann_whitney_u(normal_sample(rng, 200, 0.5), normal_sample(rng, 200, 0.0));
  EXPECT_STREQ(r.method, mann_whitney_normal_method);
  EXPECT_LT(r.p_value, 1e-3);
  EXPECT_NEAR(r.median_shift, 0.5, 3.5 * std::sqrt(std::numbers::pi / 200.0));
}

// Under H0 the p-value is (nearly) uniform: rejection rates at 0.05 and 0.5 within 4 sigma.
// The exact 12 x 12 test is conservative by discreteness (its size at 0.05 is 0.0449 from the
// permutation distribution), still inside the band.
void expect_uniform_p_under_null(std::size_t n, const char* method, std::uint64_t seed) {
  constexpr int trials = 2000;
  int below_05 = 0, below_50 = 0;
  for (int t = 0; t < trials; ++t) {
    RandomStream rng(seed, static_cast<std::uint64_t>(t));
    const ShiftTestResult r =
        mann_whitney_u(normal_sample(rng, n, 0.0), normal_sample(rng, n, 0.0));
    ASSERT_STREQ(r.method, method);
    below_05 += r.p_value <= 0.05 ? 1 : 0;
    below_50 += r.p_value <= 0.5 ? 1 : 0;
  }
  EXPECT_NEAR(below_05 / double(trials), 0.05, four_sigma(0.05, trials));
  EXPECT_NEAR(below_50 / double(trials), 0.5, four_sigma(0.5, trials));
}

TEST(MannWhitney, UniformPValuesUnderNullNormalApproximation) {
  expect_uniform_p_under_null(200, mann_whitney_normal_method, 31);
}

TEST(MannWhitney, UniformPValuesUnderNullExact) {
  expect_uniform_p_under_null(12, mann_whitney_exact_method, 32);
}

TEST(MannWhitney, ExactOnlyBelowFiftyAndWithoutTies) {  // R's wilcox.test rule (exact = NULL)
  RandomStream rng(3);
  const std::vector<double> x49 = normal_sample(rng, 49, 0.0);
  const std::vector<double> y49 = normal_sample(rng, 49, 0.0);
  const std::vector<double> y50 = normal_sample(rng, 50, 0.0);
  EXPECT_STREQ(mann_whitney_u(x49, y49).method, mann_whitney_exact_method);
  EXPECT_STREQ(mann_whitney_u(x49, y50).method, mann_whitney_normal_method);
  EXPECT_STREQ(mann_whitney_u(y50, x49).method, mann_whitney_normal_method);
  std::vector<double> tied = {1.0, 2.0, 3.0};
  EXPECT_STREQ(mann_whitney_u(tied, std::vector<double>{3.0, 4.0}).method,
               mann_whitney_normal_method);
}

TEST(MannWhitney, AllTiedGivesPOne) {  // sigma = 0: U = m n / 2, no evidence of a shift
  const ShiftTestResult r = mann_whitney_u(std::vector<double>{3, 3}, std::vector<double>{3, 3, 3});
  EXPECT_EQ(r.u_statistic, 3.0);
  EXPECT_EQ(r.p_value, 1.0);
  EXPECT_EQ(r.median_shift, 0.0);
}

// --- Welch t ------------------------------------------------------------------------------------

TEST(Welch, MatchesRSleep) {  // [Rt]; half a unit in R's last printed digit
  const std::vector<double> g1 = {0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
  const std::vector<double> g2 = {1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};
  const WelchResult r = welch_t_test(g1, g2);
  EXPECT_NEAR(r.t_statistic, -1.8608, 5e-5);
  EXPECT_NEAR(r.degrees_of_freedom, 17.776, 5e-4);
  EXPECT_NEAR(r.p_value, 0.07939, 5e-6);
  EXPECT_NEAR(r.mean_shift, 0.75 - 2.33, kExactTol);
}

TEST(Welch, ConstantSamplesGiveNaN) {
  const WelchResult r = welch_t_test(std::vector<double>{1, 1, 1}, std::vector<double>{2, 2});
  EXPECT_TRUE(std::isnan(r.t_statistic));
  EXPECT_TRUE(std::isnan(r.p_value));
  EXPECT_EQ(r.mean_shift, -1.0);
}

// --- Median intervals ---------------------------------------------------------------------------

// 1 - 2 P(B <= k), B ~ Binomial(n, 1/2), summed directly.
double order_statistic_coverage(int n, int k) {
  double term = std::pow(0.5, n), cdf = 0.0;
  for (int i = 0; i <= k; ++i) {
    cdf += term;
    term *= static_cast<double>(n - i) / (i + 1);
  }
  return 1.0 - 2.0 * cdf;
}

TEST(MedianInterval, HandComputedOrderStatistics) {  // [Bin]
  std::vector<double> ten(10), twenty(20);
  std::iota(ten.begin(), ten.end(), 1.0);
  std::iota(twenty.begin(), twenty.end(), 1.0);
  // n = 10: P(B <= 1) = 11/1024 <= 0.025 < P(B <= 2) = 56/1024 -> (x_(2), x_(9)).
  Interval i = median_confidence_interval(ten, 0.95);
  EXPECT_EQ(i.low, 2.0);
  EXPECT_EQ(i.high, 9.0);
  // n = 20: P(B <= 5) = 0.0207 <= 0.025 < P(B <= 6) = 0.0577 -> (x_(6), x_(15)).
  i = median_confidence_interval(twenty, 0.95);
  EXPECT_EQ(i.low, 6.0);
  EXPECT_EQ(i.high, 15.0);
  // n = 5: P(B <= 0) = 1/32 > 0.025, nothing reaches 95 %; at 90 % (x_(1), x_(5)).
  const std::vector<double> five = {1, 2, 3, 4, 5};
  i = median_confidence_interval(five, 0.95);
  EXPECT_EQ(i.low, -inf);
  EXPECT_EQ(i.high, inf);
  i = median_confidence_interval(five, 0.90);
  EXPECT_EQ(i.low, 1.0);
  EXPECT_EQ(i.high, 5.0);
}

TEST(MedianInterval, CoverageBySimulation) {
  // Exponential(1) (skewed, median ln 2), n = 25: the interval is (x_(8), x_(18)) with exact
  // coverage 1 - 2 P(B <= 7) = 0.95671 for any continuous law; 4000 trials, 4 sigma.
  constexpr int trials = 4000;
  constexpr int n = 25;
  const double expected = order_statistic_coverage(n, 7);
  int covered = 0;
  for (int t = 0; t < trials; ++t) {
    RandomStream rng(41, static_cast<std::uint64_t>(t));
    std::vector<double> x(n);
    for (double& v : x) v = rng.exponential();
    std::sort(x.begin(), x.end());
    const Interval i = median_confidence_interval(x, 0.95);
    ASSERT_EQ(i.low, x[7]);
    covered += (i.low <= std::log(2.0) && std::log(2.0) <= i.high) ? 1 : 0;
  }
  EXPECT_NEAR(covered / double(trials), expected, four_sigma(expected, trials));
}

TEST(MedianStandardError, HandComputed) {
  // 1..10: 95 % interval (2, 9) with coverage 1 - 22/1024 = 0.978515625, z = Phi^-1(0.98926) =
  // 2.2993623 (Python statistics.NormalDist), SE = 7 / (2 z) = 1.5221612.
  std::vector<double> x(10);
  std::iota(x.begin(), x.end(), 1.0);
  std::reverse(x.begin(), x.end());  // any order
  EXPECT_NEAR(median_standard_error(x), 1.5221611678823752, 1e-9);
  // 1..30: P(B <= 9) = 0.0213870 <= 0.025 < P(B <= 10) = 0.0493686 -> (x_(10), x_(21)) = (10, 21),
  // coverage 0.9572261, z = 2.0259106, SE = 11 / (2 z) = 2.7148286.
  std::vector<double> thirty(30);
  std::iota(thirty.begin(), thirty.end(), 1.0);
  EXPECT_NEAR(median_standard_error(thirty), 2.714828561065118, 1e-9);
  EXPECT_TRUE(std::isnan(median_standard_error(std::vector<double>{1.0})));
}

TEST(MedianStandardError, AgreesWithSimulatedSpreadOfTheMedian) {
  // Second method: the standard deviation of 2000 simulated medians of n = 101 normal values
  // (about sqrt(pi / (2 n)) = 0.1247). Tolerance 10 %: the estimator's own bias (McKean &
  // Schrader report a few %) plus 1.6 % sampling error of the simulated SD.
  constexpr int trials = 2000;
  std::vector<double> medians;
  double se_sum = 0.0;
  for (int t = 0; t < trials; ++t) {
    RandomStream rng(43, static_cast<std::uint64_t>(t));
    const std::vector<double> x = normal_sample(rng, 101, 0.0);
    medians.push_back(median(x));
    se_sum += median_standard_error(x);
  }
  const BoxPlot spread = box_plot(medians);
  EXPECT_NEAR(se_sum / trials / spread.std_dev, 1.0, 0.10);
  EXPECT_NEAR(spread.std_dev, std::sqrt(std::numbers::pi / 202.0), 0.1 * spread.std_dev);
}

TEST(ShiftInterval, MatchesEnumerationOnDepressionData) {
  // Second method: all 3003 rank sets enumerated (C = 9 at 95 %, 12 at 90 %), the 50 sorted
  // differences x_i - y_j: 95 % (d_(9), d_(42)) = (-0.15, 0.76), 90 % (d_(12), d_(39)) =
  // (-0.08, 0.72); Hodges-Lehmann (d_(25) + d_(26)) / 2 = 0.305.
  Interval i = median_shift_interval(kDepressionX, kDepressionY, 0.95);
  EXPECT_NEAR(i.low, -0.15, kExactTol);
  EXPECT_NEAR(i.high, 0.76, kExactTol);
  i = median_shift_interval(kDepressionX, kDepressionY, 0.90);
  EXPECT_NEAR(i.low, -0.08, kExactTol);
  EXPECT_NEAR(i.high, 0.72, kExactTol);
  EXPECT_NEAR(hodges_lehmann_shift(kDepressionX, kDepressionY), 0.305, kExactTol);
}

TEST(ShiftInterval, TooSmallForTheConfidenceIsUnbounded) {
  // m = n = 2: P(U <= 0) = 1/6 > 0.025, so no pair of differences reaches 95 %.
  const Interval i =
      median_shift_interval(std::vector<double>{1, 2}, std::vector<double>{0, 5}, 0.95);
  EXPECT_EQ(i.low, -inf);
  EXPECT_EQ(i.high, inf);
}

TEST(ShiftInterval, NormalApproximationUsesHollanderWolfeOrderStatistics) {
  // m = n = 50 (normal approximation): Hollander, Wolfe & Chicken's C = mn/2 - z sigma rounded
  // to the nearest integer, sigma = sqrt(mn (N + 1) / 12) = 145.057, z = 1.959964:
  // 1250 - 284.306 = 965.69 -> C = 966; the interval is (d_(966), d_(1535)) of the 2500 sorted
  // differences, formed here independently. Exact equality.
  RandomStream rng(61);
  const std::vector<double> x = normal_sample(rng, 50, 0.7);
  const std::vector<double> y = normal_sample(rng, 50, 0.0);
  std::vector<double> d;
  for (const double xi : x) {
    for (const double yj : y) d.push_back(xi - yj);
  }
  std::sort(d.begin(), d.end());
  const double sigma = std::sqrt(2500.0 * 101.0 / 12.0);
  const auto c = static_cast<std::size_t>(std::lround(1250.0 - 1.959963984540054 * sigma));
  ASSERT_EQ(c, 966u);
  const Interval i = median_shift_interval(x, y, 0.95);
  EXPECT_EQ(i.low, d[c - 1]);
  EXPECT_EQ(i.high, d[2500 - c]);
  EXPECT_LT(d[c - 2], i.low);  // neighbouring order statistics differ: the check is sharp
  EXPECT_LT(i.high, d[2500 - c + 1]);
}

// Coverage of the true shift for x ~ y + 1.3, exponential (skewed) samples.
double shift_coverage(std::size_t n, int trials, std::uint64_t seed) {
  int covered = 0;
  for (int t = 0; t < trials; ++t) {
    RandomStream rng(seed, static_cast<std::uint64_t>(t));
    std::vector<double> x(n), y(n);
    for (double& v : x) v = 1.3 + rng.exponential();
    for (double& v : y) v = rng.exponential();
    const Interval i = median_shift_interval(x, y, 0.95);
    covered += (i.low <= 1.3 && 1.3 <= i.high) ? 1 : 0;
  }
  return covered / double(trials);
}

TEST(ShiftInterval, ExactCoverageBySimulation) {
  // m = n = 10, exact: C = 24, coverage 1 - 2 P(U <= 23) = 0.95674 (permutation distribution),
  // exact for a pure shift of any continuous law; 2000 trials, 4 sigma.
  EXPECT_NEAR(shift_coverage(10, 2000, 51), 0.95674, four_sigma(0.95674, 2000));
}

TEST(ShiftInterval, NormalApproximationCoverageBySimulation) {
  // m = n = 60, normal approximation: nominal 0.95; 1000 trials, 4 sigma.
  EXPECT_NEAR(shift_coverage(60, 1000, 52), 0.95, four_sigma(0.95, 1000));
}

// --- Number formatting --------------------------------------------------------------------------

// The Hodges-Lehmann shift and the shift interval select order statistics of the m n pairwise
// differences without forming them; a second method, the brute-force sort of all differences, must
// give exactly the same elements, also with heavy ties (values on a 0.5 dB grid) and unequal sizes.
TEST(ShiftInterval, SelectionEqualsFullSortOfDifferences) {
  RandomStream rng(2024);
  for (const double grid : {0.0, 0.5}) {
    std::vector<double> x(37), y(53);
    const auto draw = [&](double centre) {
      const double v = centre + 3.0 * rng.normal();
      return grid > 0.0 ? grid * std::round(v / grid) : v;
    };
    for (double& v : x) v = draw(0.4);
    for (double& v : y) v = draw(0.0);
    std::vector<double> differences;
    for (const double xi : x) {
      for (const double yj : y) differences.push_back(xi - yj);
    }
    std::sort(differences.begin(), differences.end());
    const double h = 0.5 * static_cast<double>(differences.size() - 1);
    const auto j = static_cast<std::size_t>(h);
    const double brute_median = differences[j] + (h - static_cast<double>(j)) * (differences[j + 1] - differences[j]);
    EXPECT_EQ(hodges_lehmann_shift(x, y), brute_median) << "grid " << grid;
    const Interval ci = median_shift_interval(x, y, 0.95);
    EXPECT_TRUE(std::binary_search(differences.begin(), differences.end(), ci.low));
    EXPECT_TRUE(std::binary_search(differences.begin(), differences.end(), ci.high));
    // Both ends sit at mirrored ranks: some C has d_(C) = low and d_(mn+1-C) = high (1-based; with
    // ties each end matches a range of ranks, and the two ranges must allow a common C).
    const auto first = [&](double v) {
      return static_cast<std::size_t>(std::lower_bound(differences.begin(), differences.end(), v) - differences.begin());
    };
    const auto past = [&](double v) {
      return static_cast<std::size_t>(std::upper_bound(differences.begin(), differences.end(), v) - differences.begin());
    };
    const std::size_t mn = differences.size();
    EXPECT_LE(std::max(first(ci.low) + 1, mn - past(ci.high) + 1), std::min(past(ci.low), mn - first(ci.high)))
        << "grid " << grid;
  }
}

TEST(Format, MatchesPrintfGeneralAndRoundTrips) {  // Python "%.10g" % v as reference
  EXPECT_EQ(format_number(14.97), "14.97");
  EXPECT_EQ(format_number(1e-6), "1e-06");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.3");
  EXPECT_EQ(format_number(123456789012.0), "1.23456789e+11");
  EXPECT_EQ(format_number(1.0 / 3.0), "0.3333333333");
  EXPECT_EQ(format_number(123456.0), "123456");
  EXPECT_EQ(format_number(0.1 + 0.2, 0), "0.30000000000000004");
  EXPECT_EQ(format_number(0.1 + 0.2, 17), "0.30000000000000004");
  EXPECT_EQ(std::stod(format_number(2.0 / 7.0, 0)), 2.0 / 7.0);
}

TEST(Format, NonFiniteAndNegativeZero) {
  EXPECT_EQ(format_number(nan), "");
  EXPECT_EQ(format_number(inf), "inf");
  EXPECT_EQ(format_number(-inf), "-inf");
  EXPECT_EQ(format_number(-0.0), "0");
  EXPECT_EQ(format_fixed(-0.001, 2), "0.00");
  EXPECT_EQ(format_fixed(nan, 2), "");
}

TEST(Format, FixedMatchesPrintf) {  // Python "%.2f" etc. as reference
  EXPECT_EQ(format_fixed(14.456, 2), "14.46");
  EXPECT_EQ(format_fixed(2.5, 0), "2");
  EXPECT_EQ(format_fixed(1e-4, 3), "0.000");
  EXPECT_EQ(format_fixed(-37.25, 1), "-37.2");
  EXPECT_EQ(format_fixed(720.0, 2), "720.00");
}

// --- Rejected inputs -------------------------------------------------------------

TEST(StatsConfig, EveryInvalidInputNamesItsField) {
  const std::vector<double> ok = {1, 2, 3};
  const std::vector<double> with_nan = {1, nan, 3};
  const std::vector<double> with_inf = {1, 2, inf};
  const std::vector<double> empty;
  const std::vector<double> unsorted = {1, 3, 2};

  EXPECT_NE(expect_invalid([&] { box_plot(with_nan); }, "values").find("values[1] = nan"),
            std::string::npos);
  expect_invalid([&] { box_plot(with_inf); }, "values");
  expect_invalid([&] { median(empty); }, "values");
  expect_invalid([&] { quantile_type7(empty, 0.5); }, "sorted");
  expect_invalid([&] { quantile_type7(unsorted, 0.5); }, "sorted");
  expect_invalid([&] { quantile_type7(with_nan, 0.5); }, "sorted");
  expect_invalid([&] { quantile_type7(ok, 1.5); }, "p");
  expect_invalid([&] { quantile_type7(ok, nan); }, "p");

  expect_invalid([&] { mann_whitney_u(empty, ok); }, "x");
  expect_invalid([&] { mann_whitney_u(ok, empty); }, "y");
  expect_invalid([&] { mann_whitney_u(with_nan, ok); }, "x");
  expect_invalid([&] { mann_whitney_u(ok, with_inf); }, "y");
  expect_invalid([&] { welch_t_test(std::vector<double>{1.0}, ok); }, "x");
  expect_invalid([&] { welch_t_test(ok, with_nan); }, "y");

  for (const double c : {0.0, 1.0, -0.5, 1.5, nan}) {
    expect_invalid([&] { median_confidence_interval(ok, c); }, "confidence");
    expect_invalid([&] { median_shift_interval(ok, ok, c); }, "confidence");
  }
  expect_invalid([&] { median_confidence_interval(empty, 0.95); }, "sorted");
  expect_invalid([&] { median_confidence_interval(unsorted, 0.95); }, "sorted");
  expect_invalid([&] { median_standard_error(with_nan); }, "values");
  expect_invalid([&] { median_shift_interval(empty, ok, 0.95); }, "x");
  expect_invalid([&] { median_shift_interval(ok, with_nan, 0.95); }, "y");
  expect_invalid([&] { hodges_lehmann_shift(ok, empty); }, "y");

  expect_invalid([&] { format_number(1.0, 18); }, "significant_digits");
  expect_invalid([&] { format_number(1.0, -1); }, "significant_digits");
  expect_invalid([&] { format_fixed(1.0, 18); }, "decimals");
}

}  // namespace
}  // namespace fogradar::stats
