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
#include "validation.hpp"

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

using fogradar::testing::Tolerance;

// A comparison of a statistic with its reference from this file's header, checked and recorded
// (validation.hpp): `value` against `reference` within `tolerance` of `kind`.
void check(const std::string& id, const std::string& quantity, const std::string& conditions,
           double value, double reference, const std::string& source, double tolerance,
           Tolerance kind = Tolerance::absolute) {
  fogradar::testing::validate({.id = "stats." + id,
                               .group = "experiment: statistics",
                               .quantity = quantity,
                               .unit = "1",
                               .conditions = conditions,
                               .reference = reference,
                               .source = source,
                               .value = value,
                               .tolerance = tolerance,
                               .kind = kind});
}

// A Monte Carlo proportion over `trials` against its probability `p`, within the 4-sigma
// binomial band (four_sigma), checked and recorded.
void check_proportion(const std::string& id, const std::string& quantity,
                      const std::string& conditions, double value, double p,
                      const std::string& source, int trials) {
  const double band = four_sigma(p, trials);
  fogradar::testing::validate({.id = "stats." + id,
                               .group = "experiment: statistics",
                               .quantity = quantity,
                               .unit = "1",
                               .conditions = conditions,
                               .reference = p,
                               .source = source,
                               .value = value,
                               .tolerance = band,
                               .kind = Tolerance::statistical,
                               .samples = static_cast<std::size_t>(trials),
                               .interval_low = p - band,
                               .interval_high = p + band,
                               .confidence = "4-sigma binomial band (normal approximation)"});
}

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
  const char* source = "R quantile(1:10, c(.25, .5, .75)) [Rq]";
  check("quantile.r_1_to_10.p0.25", "type-7 quantile", "x = 1..10, p = 0.25",
        quantile_type7(x, 0.25), 3.25, source, kExactTol);
  check("quantile.r_1_to_10.p0.50", "type-7 quantile", "x = 1..10, p = 0.50",
        quantile_type7(x, 0.50), 5.5, source, kExactTol);
  check("quantile.r_1_to_10.p0.75", "type-7 quantile", "x = 1..10, p = 0.75",
        quantile_type7(x, 0.75), 7.75, source, kExactTol);
}

TEST(Quantile, MatchesROneToNineDeciles) {  // [Rq], exact decimals
  const std::vector<double> x = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  const double expected[] = {1.0, 1.8, 2.6, 3.4, 4.2, 5.0, 5.8, 6.6, 7.4, 8.2, 9.0};
  for (int i = 0; i <= 10; ++i) {
    check("quantile.r_1_to_9.decile" + std::to_string(i), "type-7 quantile",
          "x = 1..9, p = " + std::to_string(i) + "/10", quantile_type7(x, i / 10.0), expected[i],
          "R quantile(1:9, seq(0, 1, .1)) [Rq]", kExactTol);
  }
}

TEST(Quantile, MatchesRMtcarsWeight) {  // [Rq], printed digits are exact
  const std::vector<double> wt = sorted(kMtcarsWt);
  const double p[] = {0.0, 0.25, 0.5, 0.75, 1.0};
  const double expected[] = {1.513, 2.58125, 3.325, 3.61, 5.424};
  for (int i = 0; i < 5; ++i) {
    check("quantile.r_mtcars_wt.p" + std::to_string(p[i]).substr(0, 4), "type-7 quantile",
          "mtcars$wt (32 values), p = " + std::to_string(p[i]).substr(0, 4),
          quantile_type7(wt, p[i]), expected[i], "R quantile(mtcars$wt) [Rq]", kExactTol);
  }
}

TEST(Quantile, PlottingPositionsHitOrderStatistics) {
  // [HF96]: p_k = (k-1)/(n-1) -> x_(k). p_k is rounded to binary, so (n-1) p_k may miss k by an
  // ulp and interpolate a hair towards the neighbour (R's type 7 has no fuzz either):
  // tolerance 1e-14 on N(0, 1) data.
  RandomStream rng(7);
  const std::vector<double> x = sorted(normal_sample(rng, 23, 0.0));
  for (std::size_t k = 0; k < x.size(); ++k) {
    check("quantile.plotting_position.k" + std::to_string(k), "type-7 quantile at p_k",
          "23 N(0, 1) values (seed 7), p_k = " + std::to_string(k) + "/22",
          quantile_type7(x, static_cast<double>(k) / 22.0), x[k],
          "Hyndman & Fan 1996 definition 7: p_k = (k - 1)/(n - 1) hits x_(k) [HF96]", 1e-14);
  }
}

TEST(Quantile, SmallSamples) {  // closed forms: n = 1 constant, n = 2 linear a + p (b - a)
  const std::vector<double> one = {4.5};
  for (const double p : {0.0, 0.3, 1.0}) {
    check("quantile.n1.p" + std::to_string(p).substr(0, 4), "type-7 quantile",
          "x = {4.5}, p = " + std::to_string(p).substr(0, 4), quantile_type7(one, p), 4.5,
          "closed form: n = 1, the quantile is the value", 0.0);
  }
  const std::vector<double> two = {-1.0, 3.0};
  for (const double p : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    check("quantile.n2.p" + std::to_string(p).substr(0, 4), "type-7 quantile",
          "x = {-1, 3}, p = " + std::to_string(p).substr(0, 4), quantile_type7(two, p),
          -1.0 + 4.0 * p, "closed form: n = 2, a + p (b - a)", kExactTol);
  }
  check("median.n4", "median", "x = {5, -2, 9, 1}",
        median(std::vector<double>{5.0, -2.0, 9.0, 1.0}), 3.0, "by hand: (1 + 5) / 2", kExactTol);
}

// --- Box plot -----------------------------------------------------------------------------------

TEST(BoxPlot, TukeyOnOneToTenAndFifty) {
  // [Rbs] and by hand: type-7 quartiles of 11 values sit at h = 2.5, 5, 7.5 -> 3.5, 6, 8.5 (equal
  // to Tukey's hinges since n = 4k + 3); IQR 5, fences -4 and 16. Mean 105/11, sd by the
  // closed form sqrt((sum x^2 - n mean^2)/(n - 1)) with sum x^2 = 2885.
  std::vector<double> x = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 50};
  const BoxPlot b = box_plot(x);
  EXPECT_EQ(b.n, 11u);
  const char* data = "x = 1..10, 50";
  const char* source = "R boxplot.stats(c(1:10, 50)) [Rbs] and by hand";
  check("box_plot.r_1_to_10_50.min", "minimum", data, b.min, 1.0, source, kExactTol);
  check("box_plot.r_1_to_10_50.q1", "type-7 lower quartile", data, b.q1, 3.5, source, kExactTol);
  check("box_plot.r_1_to_10_50.median", "median", data, b.median, 6.0, source, kExactTol);
  check("box_plot.r_1_to_10_50.q3", "type-7 upper quartile", data, b.q3, 8.5, source, kExactTol);
  check("box_plot.r_1_to_10_50.max", "maximum", data, b.max, 50.0, source, kExactTol);
  check("box_plot.r_1_to_10_50.whisker_low", "lower whisker", data, b.whisker_low, 1.0, source,
        kExactTol);
  check("box_plot.r_1_to_10_50.whisker_high", "upper whisker", data, b.whisker_high, 10.0, source,
        kExactTol);
  EXPECT_EQ(b.outliers, std::vector<double>{50.0});
  check("box_plot.r_1_to_10_50.mean", "mean", data, b.mean, 105.0 / 11.0, "closed form: 105 / 11",
        kExactTol);
  check("box_plot.r_1_to_10_50.std_dev", "sample standard deviation", data, b.std_dev,
        std::sqrt((2885.0 - 105.0 * 105.0 / 11.0) / 10.0),
        "closed form: sqrt((sum x^2 - n mean^2) / (n - 1)), sum x^2 = 2885", kExactTol);
}

TEST(BoxPlot, LowerFenceIsInclusive) {
  // By hand, n = 11: sorted (v, 1, ..., 10) has q1 = (2 + 3)/2 = 2.5, median 5, q3 = 7.5,
  // IQR 5, lower fence -5: v = -6 is an outlier (whisker at 1), v = -5 sits on the fence and is
  // the whisker (whisker_low = smallest value >= q1 - 1.5 IQR).
  std::vector<double> x = {-6, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  BoxPlot b = box_plot(x);
  const char* source = "by hand: type-7 quartiles, fences q1 - 1.5 IQR and q3 + 1.5 IQR";
  check("box_plot.fence.q1", "type-7 lower quartile", "x = -6, 1..10", b.q1, 2.5, source,
        kExactTol);
  check("box_plot.fence.median", "median", "x = -6, 1..10", b.median, 5.0, source, kExactTol);
  check("box_plot.fence.q3", "type-7 upper quartile", "x = -6, 1..10", b.q3, 7.5, source,
        kExactTol);
  check("box_plot.fence.whisker_low.v-6", "lower whisker", "x = -6, 1..10", b.whisker_low, 1.0,
        source, 0.0);
  check("box_plot.fence.whisker_high.v-6", "upper whisker", "x = -6, 1..10", b.whisker_high, 10.0,
        source, 0.0);
  EXPECT_EQ(b.outliers, std::vector<double>{-6.0});
  x[0] = -5.0;
  b = box_plot(x);
  check("box_plot.fence.whisker_low.v-5", "lower whisker (a value on the lower fence)",
        "x = -5, 1..10", b.whisker_low, -5.0, source, 0.0);
  EXPECT_TRUE(b.outliers.empty());
}

TEST(BoxPlot, TypeSevenDiffersFromTukeyHingesOnMtcarsWeight) {
  // By hand (n = 32): type-7 q1 = x_(8) + 0.75 (x_(9) - x_(8)) = 2.58125, q3 = x_(24) + 0.25
  // (x_(25) - x_(24)) = 3.61, IQR 1.02875, fences 1.038125 and 5.153125: whisker_high = 4.07 and
  // three outliers 5.25, 5.345, 5.424. R's boxplot.stats uses Tukey's hinges 2.5425 and 3.65
  // instead (fence 5.31125): whisker 5.25 and two outliers. Our box states type 7.
  const BoxPlot b = box_plot(kMtcarsWt);
  const char* data = "mtcars$wt (32 values)";
  const char* source = "by hand: type-7 quartiles of the 32 values [Rq], fences 1.5 IQR";
  check("box_plot.mtcars_wt.q1", "type-7 lower quartile", data, b.q1, 2.58125, source, kExactTol);
  check("box_plot.mtcars_wt.q3", "type-7 upper quartile", data, b.q3, 3.61, source, kExactTol);
  check("box_plot.mtcars_wt.whisker_low", "lower whisker", data, b.whisker_low, 1.513, source,
        kExactTol);
  check("box_plot.mtcars_wt.whisker_high", "upper whisker", data, b.whisker_high, 4.07, source,
        kExactTol);
  EXPECT_EQ(b.outliers, (std::vector<double>{5.25, 5.345, 5.424}));
  check("box_plot.mtcars_wt.mean", "mean", data, b.mean, 3.21725, "by hand: sum 102.952 / 32",
        kExactTol);  // sum 102.952 / 32
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
  const std::pair<const char*, double> statistics[] = {{"mean", one.mean},
                                                       {"min", one.min},
                                                       {"q1", one.q1},
                                                       {"median", one.median},
                                                       {"q3", one.q3},
                                                       {"max", one.max},
                                                       {"whisker_low", one.whisker_low},
                                                       {"whisker_high", one.whisker_high}};
  for (const auto& [name, v] : statistics) {
    check(std::string("box_plot.singleton.") + name, name, "x = {14.97}", v, 14.97,
          "limiting case: n = 1, every statistic is the value", 0.0);
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
  const char* data = "x, y of [Rw] (10 and 12 values, ties)";
  const char* source = "R wilcox.test: W = 51.5, p-value = 0.5966 [Rw]";
  check("mann_whitney.r_ties.u", "U statistic", data, r.u_statistic, 51.5, source, 0.0);
  check("mann_whitney.r_ties.p", "two-sided p-value", data, r.p_value, 0.5966, source, 5e-5);
  EXPECT_STREQ(r.method, mann_whitney_normal_method);
  check("mann_whitney.r_ties.median_shift", "median shift", data, r.median_shift, 8.0 - 10.5,
        "by hand: medians 8 and 10.5", kExactTol);  // medians 8 and 10.5

  const ShiftTestResult far =
      mann_whitney_u(x, std::vector<double>{1233, 4356, 987, 39999, 1111, 200000});
  const char* far_data = "x of [Rw], y = c(1233, 4356, 987, 39999, 1111, 200000)";
  const char* far_source = "R wilcox.test: W = 0, p-value = 0.001364 [Rw]";
  check("mann_whitney.r_far.u", "U statistic", far_data, far.u_statistic, 0.0, far_source, 0.0);
  check("mann_whitney.r_far.p", "two-sided p-value", far_data, far.p_value, 0.001364, far_source,
        5e-7);
  EXPECT_STREQ(far.method, mann_whitney_normal_method);
}

TEST(MannWhitney, MatchesRExactOnDepressionData) {  // [Rw]: W = 35, two-sided 764/3003
  const ShiftTestResult r = mann_whitney_u(kDepressionX, kDepressionY);
  const char* data = "Hollander & Wolfe depression data (10 and 5 values)";
  check("mann_whitney.depression.u", "U statistic", data, r.u_statistic, 35.0,
        "R wilcox.test help example: W = 35 [Rw]", 0.0);
  check("mann_whitney.depression.p_exact", "two-sided exact p-value", data, r.p_value,
        764.0 / 3003.0, "full enumeration: 764 / 3003 [Rw]", kExactTol);
  check("mann_whitney.depression.p_r", "two-sided exact p-value", data, r.p_value, 0.2544,
        "R wilcox.test help example: one-sided 0.1272, two-sided 0.2544 [Rw]", 5e-5);
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
      const std::string where =
          std::to_string(m) + "x" + std::to_string(n) + ".rep" + std::to_string(rep);
      check("mann_whitney.exact_vs_enumeration." + where, "two-sided exact p-value",
            "normal samples " + where, r.p_value, expected,
            "second method: enumeration of all C(m + n, m) rank sets", 1e-12, Tolerance::relative);
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
  const char* data = "two samples of 200 N(0, 1) values 0.5 apart (seed 77)";
  check("mann_whitney.half_sigma_shift.p", "two-sided p-value", data, r.p_value, 1e-3,
        "closed form: z ~ 0.5 sqrt(3 n / (2 pi)) ~ 4.9 (Pitman efficiency 3/pi), p ~ 1e-6", 0.0,
        Tolerance::at_most);
  check("mann_whitney.half_sigma_shift.median_shift", "median shift", data, r.median_shift, 0.5,
        "the samples' true shift; 3.5 standard errors sqrt(pi / n)",
        3.5 * std::sqrt(std::numbers::pi / 200.0));
}

// Under H0 the p-value is (nearly) uniform: rejection rates at 0.05 and 0.5 within 4 sigma.
// The exact 12 x 12 test is conservative by discreteness (its size at 0.05 is 0.0449 from the
// permutation distribution), still inside the band.
void expect_uniform_p_under_null(std::size_t n, const char* method, std::uint64_t seed,
                                 const std::string& id) {
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
  const std::string conditions = std::to_string(trials) + " pairs of " + std::to_string(n) +
                                 " N(0, 1) values under H0, " + method;
  check_proportion("mann_whitney.null." + id + ".rejection_0.05", "rejection rate at 0.05",
                   conditions, below_05 / double(trials), 0.05,
                   "uniform p-value under H0: P(p <= 0.05) = 0.05", trials);
  check_proportion("mann_whitney.null." + id + ".rejection_0.5", "rejection rate at 0.5",
                   conditions, below_50 / double(trials), 0.5,
                   "uniform p-value under H0: P(p <= 0.5) = 0.5", trials);
}

TEST(MannWhitney, UniformPValuesUnderNullNormalApproximation) {
  expect_uniform_p_under_null(200, mann_whitney_normal_method, 31, "normal_200");
}

TEST(MannWhitney, UniformPValuesUnderNullExact) {
  expect_uniform_p_under_null(12, mann_whitney_exact_method, 32, "exact_12");
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
  const char* source = "limiting case: all tied, sigma = 0, U = m n / 2, no evidence of a shift";
  check("mann_whitney.all_tied.u", "U statistic", "x = {3, 3}, y = {3, 3, 3}", r.u_statistic, 3.0,
        source, 0.0);
  check("mann_whitney.all_tied.p", "two-sided p-value", "x = {3, 3}, y = {3, 3, 3}", r.p_value, 1.0,
        source, 0.0);
  check("mann_whitney.all_tied.median_shift", "median shift", "x = {3, 3}, y = {3, 3, 3}",
        r.median_shift, 0.0, source, 0.0);
}

// --- Welch t ------------------------------------------------------------------------------------

TEST(Welch, MatchesRSleep) {  // [Rt]; half a unit in R's last printed digit
  const std::vector<double> g1 = {0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
  const std::vector<double> g2 = {1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};
  const WelchResult r = welch_t_test(g1, g2);
  const char* data = "R's sleep data, extra ~ group";
  const char* source = "R t.test: t = -1.8608, df = 17.776, p-value = 0.07939 [Rt]";
  check("welch.r_sleep.t", "t statistic", data, r.t_statistic, -1.8608, source, 5e-5);
  check("welch.r_sleep.df", "degrees of freedom", data, r.degrees_of_freedom, 17.776, source, 5e-4);
  check("welch.r_sleep.p", "two-sided p-value", data, r.p_value, 0.07939, source, 5e-6);
  check("welch.r_sleep.mean_shift", "mean shift", data, r.mean_shift, 0.75 - 2.33,
        "by hand: means 0.75 and 2.33", kExactTol);
}

TEST(Welch, ConstantSamplesGiveNaN) {
  const WelchResult r = welch_t_test(std::vector<double>{1, 1, 1}, std::vector<double>{2, 2});
  EXPECT_TRUE(std::isnan(r.t_statistic));
  EXPECT_TRUE(std::isnan(r.p_value));
  check("welch.constant.mean_shift", "mean shift", "x = {1, 1, 1}, y = {2, 2}", r.mean_shift, -1.0,
        "by hand: 1 - 2", 0.0);
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
  const char* source = "Binomial(n, 1/2) order statistics by hand (Conover 1999 sec. 3.2) [Bin]";
  check("median_interval.n10.low", "95 % median interval, low end", "x = 1..10", i.low, 2.0, source,
        0.0);
  check("median_interval.n10.high", "95 % median interval, high end", "x = 1..10", i.high, 9.0,
        source, 0.0);
  // n = 20: P(B <= 5) = 0.0207 <= 0.025 < P(B <= 6) = 0.0577 -> (x_(6), x_(15)).
  i = median_confidence_interval(twenty, 0.95);
  check("median_interval.n20.low", "95 % median interval, low end", "x = 1..20", i.low, 6.0, source,
        0.0);
  check("median_interval.n20.high", "95 % median interval, high end", "x = 1..20", i.high, 15.0,
        source, 0.0);
  // n = 5: P(B <= 0) = 1/32 > 0.025, nothing reaches 95 %; at 90 % (x_(1), x_(5)).
  const std::vector<double> five = {1, 2, 3, 4, 5};
  i = median_confidence_interval(five, 0.95);
  EXPECT_EQ(i.low, -inf);
  EXPECT_EQ(i.high, inf);
  i = median_confidence_interval(five, 0.90);
  check("median_interval.n5.90.low", "90 % median interval, low end", "x = 1..5", i.low, 1.0,
        source, 0.0);
  check("median_interval.n5.90.high", "90 % median interval, high end", "x = 1..5", i.high, 5.0,
        source, 0.0);
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
  check_proportion("median_interval.coverage.exponential_n25", "coverage of the median ln 2",
                   "4000 samples of 25 Exp(1) values, 95 % interval (x_(8), x_(18))",
                   covered / double(trials), expected,
                   "closed form: 1 - 2 P(B <= 7), B ~ Binomial(25, 1/2) = 0.95671", trials);
}

TEST(MedianStandardError, HandComputed) {
  // 1..10: 95 % interval (2, 9) with coverage 1 - 22/1024 = 0.978515625, z = Phi^-1(0.98926) =
  // 2.2993623 (Python statistics.NormalDist), SE = 7 / (2 z) = 1.5221612.
  std::vector<double> x(10);
  std::iota(x.begin(), x.end(), 1.0);
  std::reverse(x.begin(), x.end());  // any order
  check("median_standard_error.n10", "standard error of the median", "x = 1..10",
        median_standard_error(x), 1.5221611678823752,
        "by hand: 7 / (2 z), z = Phi^-1(0.98926) (Python statistics.NormalDist)", 1e-9);
  // 1..30: P(B <= 9) = 0.0213870 <= 0.025 < P(B <= 10) = 0.0493686 -> (x_(10), x_(21)) = (10, 21),
  // coverage 0.9572261, z = 2.0259106, SE = 11 / (2 z) = 2.7148286.
  std::vector<double> thirty(30);
  std::iota(thirty.begin(), thirty.end(), 1.0);
  check("median_standard_error.n30", "standard error of the median", "x = 1..30",
        median_standard_error(thirty), 2.714828561065118,
        "by hand: 11 / (2 z), z = 2.0259106 (Python statistics.NormalDist)", 1e-9);
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
  const char* data = "2000 samples of 101 N(0, 1) values (seed 43)";
  check("median_standard_error.vs_simulated_spread", "mean standard error / simulated SD", data,
        se_sum / trials / spread.std_dev, 1.0,
        "second method: SD of 2000 simulated medians; 10 % (estimator bias and sampling)", 0.10,
        Tolerance::relative);
  check("median_standard_error.simulated_spread", "SD of the simulated medians", data,
        spread.std_dev, std::sqrt(std::numbers::pi / 202.0),
        "closed form: asymptotic sqrt(pi / (2 n)); 10 % of the simulated SD", 0.1 * spread.std_dev);
}

TEST(ShiftInterval, MatchesEnumerationOnDepressionData) {
  // Second method: all 3003 rank sets enumerated (C = 9 at 95 %, 12 at 90 %), the 50 sorted
  // differences x_i - y_j: 95 % (d_(9), d_(42)) = (-0.15, 0.76), 90 % (d_(12), d_(39)) =
  // (-0.08, 0.72); Hodges-Lehmann (d_(25) + d_(26)) / 2 = 0.305.
  Interval i = median_shift_interval(kDepressionX, kDepressionY, 0.95);
  const char* data = "Hollander & Wolfe depression data";
  const char* source = "second method: the 3003 rank sets enumerated, 50 sorted differences";
  check("shift_interval.depression.95.low", "95 % shift interval, low end", data, i.low, -0.15,
        source, kExactTol);
  check("shift_interval.depression.95.high", "95 % shift interval, high end", data, i.high, 0.76,
        source, kExactTol);
  i = median_shift_interval(kDepressionX, kDepressionY, 0.90);
  check("shift_interval.depression.90.low", "90 % shift interval, low end", data, i.low, -0.08,
        source, kExactTol);
  check("shift_interval.depression.90.high", "90 % shift interval, high end", data, i.high, 0.72,
        source, kExactTol);
  check("shift_interval.depression.hodges_lehmann", "Hodges-Lehmann shift", data,
        hodges_lehmann_shift(kDepressionX, kDepressionY), 0.305,
        "second method: (d_(25) + d_(26)) / 2 of the sorted differences", kExactTol);
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
  const char* data = "50 N(0.7, 1) and 50 N(0, 1) values (seed 61)";
  const char* source = "Hollander, Wolfe & Chicken C = 966, differences formed independently";
  check("shift_interval.normal_approximation.low", "95 % shift interval, low end", data, i.low,
        d[c - 1], source, 0.0);
  check("shift_interval.normal_approximation.high", "95 % shift interval, high end", data, i.high,
        d[2500 - c], source, 0.0);
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
  check_proportion("shift_interval.coverage.exact_10", "coverage of the true shift 1.3",
                   "2000 pairs of 10 exponential values, exact interval",
                   shift_coverage(10, 2000, 51), 0.95674,
                   "permutation distribution: 1 - 2 P(U <= 23) = 0.95674", 2000);
}

TEST(ShiftInterval, NormalApproximationCoverageBySimulation) {
  // m = n = 60, normal approximation: nominal 0.95; 1000 trials, 4 sigma.
  check_proportion("shift_interval.coverage.normal_60", "coverage of the true shift 1.3",
                   "1000 pairs of 60 exponential values, normal approximation",
                   shift_coverage(60, 1000, 52), 0.95, "nominal confidence 0.95", 1000);
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
    const double brute_median =
        differences[j] + (h - static_cast<double>(j)) * (differences[j + 1] - differences[j]);
    check("shift_interval.hodges_lehmann_vs_sort.grid" + std::to_string(grid).substr(0, 3),
          "Hodges-Lehmann shift", "37 and 53 values, grid " + std::to_string(grid).substr(0, 3),
          hodges_lehmann_shift(x, y), brute_median,
          "second method: median of the fully sorted pairwise differences", 0.0);
    const Interval ci = median_shift_interval(x, y, 0.95);
    EXPECT_TRUE(std::binary_search(differences.begin(), differences.end(), ci.low));
    EXPECT_TRUE(std::binary_search(differences.begin(), differences.end(), ci.high));
    // Both ends sit at mirrored ranks: some C has d_(C) = low and d_(mn+1-C) = high (1-based; with
    // ties each end matches a range of ranks, and the two ranges must allow a common C).
    const auto first = [&](double v) {
      return static_cast<std::size_t>(std::lower_bound(differences.begin(), differences.end(), v) -
                                      differences.begin());
    };
    const auto past = [&](double v) {
      return static_cast<std::size_t>(std::upper_bound(differences.begin(), differences.end(), v) -
                                      differences.begin());
    };
    const std::size_t mn = differences.size();
    EXPECT_LE(std::max(first(ci.low) + 1, mn - past(ci.high) + 1),
              std::min(past(ci.low), mn - first(ci.high)))
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
