// CFAR tests. References (each test names its own and its tolerance):
//   [GK88] P. P. Gandhi, S. A. Kassam, "Analysis of CFAR processors in nonhomogeneous
//          background", IEEE TAES 24(4), 427-445, 1988: Pfa of CA, GO, SO, OS in exponential
//          noise.
//   [R83]  H. Rohling, "Radar CFAR thresholding in clutter and multiple target situations",
//          IEEE TAES 19(4), 608-621, 1983: OS-CFAR Pfa.
//   [Ri14] M. A. Richards, Fundamentals of Radar Signal Processing, 2nd ed., §6.5 (CA Pd for a
//          Swerling 1 target; OS example N = 20, k = 15, alpha = 6.857 for Pfa = 1e-3).
// Monte Carlo tests use fixed-seed std::mt19937_64 streams and statistically sized bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/gamma.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/binomial.hpp>
#include <boost/math/tools/roots.hpp>
#include <cctype>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/radar/cfar.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;

// A number as check ids and conditions show it ("1e-06", "0.5", "16").
std::string id_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// "CA-CFAR", "OS-CFAR", ... for check conditions.
std::string kind_label(CfarKind kind) {
  std::string label(to_string(kind));
  for (char& c : label) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return label + "-CFAR";
}

const CfarKind kAllKinds[] = {CfarKind::ca, CfarKind::go, CfarKind::so, CfarKind::os};

std::string kind_name(const ::testing::TestParamInfo<CfarKind>& info) {
  return std::string(to_string(info.param));
}

// --- Published Pfa expressions, written out independently of the library ----------------------

// [GK88] CA: Pfa = (1 + alpha/N)^-N (threshold alpha times the mean of N cells).
double published_pfa_ca(unsigned big_n, double alpha) {
  return std::pow(1.0 + alpha / big_n, -static_cast<double>(big_n));
}

// [GK88] SO with n cells per side, threshold T times the smaller side sum (T = alpha / n):
//   Pfa = 2 sum_{k=0}^{n-1} C(n-1+k, k) (2+T)^-(n+k)
double published_pfa_so(unsigned n, double alpha) {
  const double t = alpha / n;
  double sum = 0.0;
  for (unsigned k = 0; k < n; ++k) {
    sum += boost::math::binomial_coefficient<double>(n - 1 + k, k) *
           std::pow(2.0 + t, -static_cast<double>(n + k));
  }
  return 2.0 * sum;
}

// [GK88] GO: Pfa = 2 (1+T)^-n - 2 sum_{k=0}^{n-1} C(n-1+k, k) (2+T)^-(n+k)
double published_pfa_go(unsigned n, double alpha) {
  const double t = alpha / n;
  return 2.0 * std::pow(1.0 + t, -static_cast<double>(n)) - published_pfa_so(n, alpha);
}

// [R83] OS: Pfa = prod_{i=0}^{k-1} (N-i) / (N-i+alpha)
double published_pfa_os(unsigned big_n, unsigned k, double alpha) {
  double pfa = 1.0;
  for (unsigned i = 0; i < k; ++i) pfa *= (big_n - i) / (big_n - i + alpha);
  return pfa;
}

double published_pfa(const CfarConfig& config, double alpha) {
  const unsigned n = config.training_cells;
  switch (config.kind) {
    case CfarKind::ca:
      return published_pfa_ca(2 * n, alpha);
    case CfarKind::go:
      return published_pfa_go(n, alpha);
    case CfarKind::so:
      return published_pfa_so(n, alpha);
    case CfarKind::os:
      return published_pfa_os(2 * n, config.effective_os_rank(), alpha);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// --- Configuration ----------------------------------------------------------------------------

void expect_invalid_field(const CfarConfig& config, const std::string& field) {
  EXPECT_EQ(test_support::rejected_field([&] { config.validate(); }), field);
}

// Every invalid field is rejected with InvalidParameter naming it.
// Negative cell counts cannot be represented (unsigned fields); the scenario parser rejects
// them before a CfarConfig exists.
TEST(CfarConfig, RejectsEveryInvalidField) {
  EXPECT_NO_THROW(CfarConfig{}.validate());

  expect_invalid_field({.training_cells = 0}, "cfar.training_cells");
  for (const double pfa : {0.0, 1.0, -1e-3, 1.5, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    expect_invalid_field({.false_alarm_probability = pfa}, "cfar.false_alarm_probability");
  }
  expect_invalid_field({.kind = CfarKind::os, .training_cells = 8, .os_rank = 17}, "cfar.os_rank");
  EXPECT_NO_THROW(
      (CfarConfig{.kind = CfarKind::os, .training_cells = 8, .os_rank = 16}.validate()));
  EXPECT_NO_THROW((CfarConfig{.kind = CfarKind::os, .training_cells = 8, .os_rank = 1}.validate()));

  // Threshold factor and detector construction validate too.
  EXPECT_THROW(cfar_threshold_factor({.training_cells = 0}), InvalidParameter);
  EXPECT_THROW(CfarDetector({.false_alarm_probability = 2.0}), InvalidParameter);
  EXPECT_THROW(cfar_false_alarm_probability({}, -1.0), InvalidParameter);
}

// A window wider than the profile: "cfar.training_cells" with the allowed range in the message.
TEST(CfarConfig, RejectsWindowWiderThanProfile) {
  const CfarConfig config{.guard_cells = 2, .training_cells = 8};  // window 21 cells
  const std::vector<double> power(20, 1.0);
  try {
    cfar_detect(power, config);
    ADD_FAILURE() << "a 20-cell profile was accepted for a 21-cell window";
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.field(), "cfar.training_cells");
    // (20 - 1) / 2 - 2 = 7 training cells fit.
    EXPECT_NE(std::string(error.what()).find("[1, 7]"), std::string::npos) << error.what();
  }
  EXPECT_NO_THROW(cfar_detect(std::vector<double>(21, 1.0), config));

  // Guard cells alone fill the profile: they are named, with the range left by the training cells,
  // (5 - 1) / 2 - 1 = 1, and the other key of the check.
  try {
    cfar_detect(std::vector<double>(5, 1.0), CfarConfig{.guard_cells = 2, .training_cells = 1});
    ADD_FAILURE() << "a 5-cell profile was accepted for a 7-cell window";
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.field(), "cfar.guard_cells") << error.what();
    EXPECT_NE(std::string(error.what()).find("[0, 1]"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("cfar.training_cells = 1"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(cfar_detect(std::vector<double>{}, CfarConfig{}), InvalidParameter);
}

TEST(CfarConfig, KindNamesRoundTrip) {
  for (const CfarKind kind : kAllKinds)
    EXPECT_EQ(cfar_kind_names.parse(to_string(kind), "cfar.kind"), kind);
  try {
    cfar_kind_names.parse("CA-CFAR", "processing.cfar");
    ADD_FAILURE() << "accepted an unknown CFAR kind";
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.field(), "processing.cfar");
  }
}

// Default OS rank: round(3N/4) [R83, Ri14 "typically k ~ 0.75 N"].
TEST(CfarConfig, DefaultOsRankIsThreeQuartersOfReferenceCells) {
  EXPECT_EQ((CfarConfig{.training_cells = 8}.effective_os_rank()), 12u);
  EXPECT_EQ((CfarConfig{.training_cells = 10}.effective_os_rank()), 15u);
  EXPECT_EQ((CfarConfig{.training_cells = 1}.effective_os_rank()), 2u);  // round(1.5)
  EXPECT_EQ((CfarConfig{.training_cells = 8, .os_rank = 5}.effective_os_rank()), 5u);
}

// --- Threshold factors ------------------------------------------------------------------------

// CA closed form alpha = N (Pfa^(-1/N) - 1) against solving (1 + alpha/N)^-N = Pfa numerically
// (TOMS 748 in this test). Tolerance 1e-12 relative (both double precision).
TEST(CfarThreshold, CaClosedFormMatchesNumericalSolution) {
  for (const unsigned n : {1u, 4u, 8u, 16u, 32u}) {
    for (const double pfa : {1e-2, 1e-3, 1e-6, 1e-9}) {
      const CfarConfig config{
          .kind = CfarKind::ca, .training_cells = n, .false_alarm_probability = pfa};
      const double alpha = cfar_threshold_factor(config);
      const auto f = [&](double a) { return std::log(published_pfa_ca(2 * n, a)) - std::log(pfa); };
      std::uintmax_t iterations = 200;
      const auto [lo, hi] = boost::math::tools::toms748_solve(
          f, 0.0, 1e6, boost::math::tools::eps_tolerance<double>(52), iterations);
      const double solved = 0.5 * (lo + hi);
      fogradar::testing::validate(
          {.id = "radar.cfar.ca.alpha.N" + std::to_string(2 * n) + ".pfa" + id_number(pfa),
           .group = "radar: CFAR",
           .quantity = "CA-CFAR threshold factor alpha",
           .unit = "1",
           .conditions = "CA-CFAR, " + std::to_string(2 * n) + " training cells, design P_fa " +
                         id_number(pfa),
           .reference = solved,
           .source = "(1 + alpha/N)^-N = P_fa [GK88] solved numerically (TOMS 748, this test)",
           .value = alpha,
           .tolerance = 1e-12,
           .kind = Tolerance::relative});
    }
  }
}

// GO, SO, OS (and CA): the published Pfa expression [GK88, R83], evaluated at the solved
// threshold factor, equals the design Pfa within 1e-9 relative.
class CfarThresholdKind : public ::testing::TestWithParam<CfarKind> {};

TEST_P(CfarThresholdKind, PublishedPfaAtSolvedFactorEqualsDesign) {
  for (const unsigned n : {1u, 2u, 4u, 8u, 16u, 24u}) {
    for (const double pfa : {0.1, 1e-3, 1e-6, 1e-9}) {
      const CfarConfig config{
          .kind = GetParam(), .training_cells = n, .false_alarm_probability = pfa};
      const double alpha = cfar_threshold_factor(config);
      ASSERT_TRUE(std::isfinite(alpha) && alpha > 0.0);
      const std::string kind(to_string(GetParam()));
      const std::string conditions = kind_label(GetParam()) + ", " + std::to_string(n) +
                                     " training cells per side, design P_fa " + id_number(pfa);
      const std::string id =
          "radar.cfar." + kind + ".n" + std::to_string(n) + ".pfa" + id_number(pfa);
      fogradar::testing::validate(
          {.id = id + ".published_pfa_at_factor",
           .group = "radar: CFAR",
           .quantity = "published P_fa at the solved threshold factor",
           .unit = "1",
           .conditions = conditions,
           .reference = pfa,
           .source = "design P_fa; closed forms of Gandhi & Kassam 1988 (CA, GO, SO) and "
                     "Rohling 1983 (OS)",
           .value = published_pfa(config, alpha),
           .tolerance = 1e-9,
           .kind = Tolerance::relative});
      // The library's own Pfa function agrees with the published form at nearby factors too.
      for (const double scale : {0.5, 1.0, 2.0}) {
        const double expected = published_pfa(config, scale * alpha);
        fogradar::testing::validate(
            {.id = id + ".pfa_function.scale" + id_number(scale),
             .group = "radar: CFAR",
             .quantity = "P_fa at " + id_number(scale) + " x the threshold factor",
             .unit = "1",
             .conditions = conditions,
             .reference = expected,
             .source = "closed forms Gandhi & Kassam 1988 (CA, GO, SO), Rohling 1983 (OS)",
             .value = cfar_false_alarm_probability(config, scale * alpha),
             .tolerance = 1e-9,
             .kind = Tolerance::relative});
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, CfarThresholdKind, ::testing::ValuesIn(kAllKinds), kind_name);

// Limiting case n = 1 (one cell per side), exact inverses of [GK88] by hand:
//   SO: Pfa = 2 / (2 + alpha)                    =>  alpha = 2 / Pfa - 2
//   GO: Pfa = 2 / (1 + alpha) - 2 / (2 + alpha)  =>  Pfa alpha^2 + 3 Pfa alpha + 2 Pfa - 2 = 0
//   OS with N = 2, k = 1 (minimum): Pfa = 2 / (2 + alpha), same as SO.
// Tolerance 1e-12 relative.
TEST(CfarThreshold, SingleCellPerSideClosedForms) {
  for (const double pfa : {0.5, 1e-3, 1e-6}) {
    const double so = cfar_threshold_factor(
        {.kind = CfarKind::so, .training_cells = 1, .false_alarm_probability = pfa});
    const double go = cfar_threshold_factor(
        {.kind = CfarKind::go, .training_cells = 1, .false_alarm_probability = pfa});
    const double go_exact = (-3.0 * pfa + std::sqrt(pfa * pfa + 8.0 * pfa)) / (2.0 * pfa);
    const double os = cfar_threshold_factor(
        {.kind = CfarKind::os, .training_cells = 1, .false_alarm_probability = pfa, .os_rank = 1});
    const struct {
      CfarKind kind;
      double value, reference, tolerance;
      const char* source;
    } checks[] = {{CfarKind::so, so, 2.0 / pfa - 2.0, 1e-12 * so,
                   "inverse of [GK88] SO, n = 1: alpha = 2/P_fa - 2"},
                  {CfarKind::go, go, go_exact, 1e-12 * go_exact,
                   "inverse of [GK88] GO, n = 1: root of P alpha^2 + 3 P alpha + 2 P - 2 = 0"},
                  {CfarKind::os, os, 2.0 / pfa - 2.0, 1e-12 * os,
                   "inverse of [R83] OS, N = 2, k = 1: alpha = 2/P_fa - 2"}};
    for (const auto& check : checks) {
      // The tolerance is 1e-12 of the factor (absolute, as the expectation it replaces).
      fogradar::testing::validate(
          {.id = "radar.cfar." + std::string(to_string(check.kind)) + ".alpha.n1.pfa" +
                 id_number(pfa),
           .group = "radar: CFAR",
           .quantity = "threshold factor alpha, one cell per side",
           .unit = "1",
           .conditions =
               kind_label(check.kind) + ", 1 training cell per side, design P_fa " + id_number(pfa),
           .reference = check.reference,
           .source = check.source,
           .value = check.value,
           .tolerance = check.tolerance,
           .kind = Tolerance::absolute});
    }
  }
}

// The design P_fa down to the smallest positive double (the key's range is (0, 1)).
// log P_fa at the solved factor by the published closed forms, written out in long double log
// space here: CA N = 16 and OS N = 16, k = 12 [R83] (default n = 8), SO n = 8 [GK88]
// 2 sum_{k<n} C(n-1+k, k) (2+t)^-(n+k), and GO at n = 1, where 2 (1+t)^-1 - 2 (2+t)^-1 [GK88]
// is 2 / ((1+t)(2+t)) without cancellation. Tolerance 1e-12 relative on log P_fa (|log P_fa| ~
// 700 has an ulp of 1.1e-13; the solve ends within a few ulps of alpha).
long double tiny_log_pfa(CfarKind kind, unsigned n, long double alpha) {
  const long double big_n = 2.0L * n;
  const long double t = alpha / n;
  long double result = 0.0L;
  switch (kind) {
    case CfarKind::ca:  // N log(N / (N + alpha))
      return -big_n * std::log1p(alpha / big_n);
    case CfarKind::go:  // n = 1: log 2 - log(1+t) - log(2+t)
      return std::log(2.0L) - std::log1p(t) - std::log(2.0L + t);
    case CfarKind::so: {  // log 2 + log sum_k C(n-1+k, k) (2+t)^-(n+k), largest term factored out
      std::vector<long double> terms;
      for (unsigned k = 0; k < n; ++k) {
        terms.push_back(std::lgamma(static_cast<long double>(n + k)) -
                        std::lgamma(static_cast<long double>(k + 1)) -
                        std::lgamma(static_cast<long double>(n)) -
                        static_cast<long double>(n + k) * std::log(2.0L + t));
      }
      const long double top = *std::max_element(terms.begin(), terms.end());
      for (const long double term : terms) result += std::exp(term - top);
      return std::log(2.0L) + top + std::log(result);
    }
    case CfarKind::os:  // sum_{i<k} log((N-i) / (N-i+alpha)), k = 12
      for (unsigned i = 0; i < 12; ++i) result -= std::log1p(alpha / (big_n - i));
      return result;
  }
  return std::numeric_limits<long double>::quiet_NaN();
}

TEST(CfarThreshold, TinyDesignPfaSolvesTheClosedForms) {
  const double smallest = std::numeric_limits<double>::denorm_min();
  for (const CfarKind kind : kAllKinds) {
    const unsigned n = kind == CfarKind::go ? 1 : 8;
    for (const double pfa : {1e-300, 1e-310, smallest}) {
      const CfarConfig config{.kind = kind, .training_cells = n, .false_alarm_probability = pfa};
      double alpha = 0.0;
      ASSERT_NO_THROW(alpha = cfar_threshold_factor(config)) << kind_label(kind) << ' ' << pfa;
      ASSERT_TRUE(std::isfinite(alpha) && alpha > 0.0) << alpha;
      const std::string label = pfa == smallest ? "denorm_min" : id_number(pfa);
      fogradar::testing::validate(
          {.id = "radar.cfar." + std::string(to_string(kind)) + ".tiny_pfa.log_pfa." + label,
           .group = "radar: CFAR",
           .quantity = "log P_fa at the solved threshold factor",
           .unit = "1",
           .conditions = kind_label(kind) + ", n = " + std::to_string(n) +
                         " per side, design P_fa " + id_number(pfa),
           .reference = std::log(pfa),
           .source = kind == CfarKind::os ? "Rohling 1983 closed form, long double logs (this test)"
                                          : "Gandhi & Kassam 1988 closed form, long double logs "
                                            "(this test)",
           .value = static_cast<double>(tiny_log_pfa(kind, n, alpha)),
           .tolerance = 1e-12,
           .kind = Tolerance::relative});
    }
  }
}

// Below the range: 0 and the negative smallest double are refused naming the key.
TEST(CfarConfig, RejectsPfaBelowTheSmallestPositiveDouble) {
  for (const CfarKind kind : kAllKinds) {
    const double smallest = std::numeric_limits<double>::denorm_min();
    EXPECT_NO_THROW((CfarConfig{.kind = kind, .false_alarm_probability = smallest}.validate()));
    for (const double pfa : {0.0, -smallest}) {
      expect_invalid_field({.kind = kind, .false_alarm_probability = pfa},
                           "cfar.false_alarm_probability");
    }
  }
}

// Published value [Ri14 §6.5.6]: OS-CFAR with N = 20, k = 15 needs alpha = 6.857 for
// Pfa = 1e-3. Richards quotes four significant figures (6.857 gives Pfa = 0.99872e-3 by [R83]),
// so the tolerance is 5e-4 relative; we solve 6.8554.
TEST(CfarThreshold, RichardsOsExample) {
  const double alpha = cfar_threshold_factor(
      {.kind = CfarKind::os, .training_cells = 10, .false_alarm_probability = 1e-3, .os_rank = 15});
  fogradar::testing::validate({.id = "radar.cfar.os.alpha.richards_example",
                               .group = "radar: CFAR",
                               .quantity = "OS-CFAR threshold factor alpha",
                               .unit = "1",
                               .conditions = "OS-CFAR, N = 20, k = 15, design P_fa 1e-3",
                               .reference = 6.857,
                               .source = "Richards 2014 §6.5.6 (four significant figures)",
                               .value = alpha,
                               .tolerance = 5e-4,
                               .kind = Tolerance::relative});
}

// Ordering (a property of the estimators): SO's noise estimate is the smallest, GO's the
// largest, so for the same N and Pfa alpha_SO > alpha_CA > alpha_GO [GK88 Fig. 3-4].
TEST(CfarThreshold, SmallestOfNeedsLargestFactor) {
  for (const unsigned n : {2u, 8u, 16u}) {
    const auto alpha = [n](CfarKind kind) {
      return cfar_threshold_factor(
          {.kind = kind, .training_cells = n, .false_alarm_probability = 1e-6});
    };
    EXPECT_GT(alpha(CfarKind::so), alpha(CfarKind::ca));
    EXPECT_GT(alpha(CfarKind::ca), alpha(CfarKind::go));
  }
}

// --- Detector mechanics -----------------------------------------------------------------------

// Brute-force reference of the documented edge policy: guard cells centred on the cell under
// test, up to n nearest cells beyond the guard on each side, a short side's deficit taken from
// the other side; GO/SO halves = first and last n reference cells in range order.
std::vector<double> brute_force_threshold(const std::vector<double>& power,
                                          const CfarConfig& config, double alpha) {
  const long long length = static_cast<long long>(power.size());
  const long long guard = config.guard_cells;
  const std::size_t n = config.training_cells;
  std::vector<double> threshold(power.size());
  for (long long i = 0; i < length; ++i) {
    std::vector<long long> left;
    std::vector<long long> right;
    for (long long j = i - guard - 1; j >= 0; --j) left.push_back(j);
    for (long long j = i + guard + 1; j < length; ++j) right.push_back(j);
    std::size_t a = std::min(n, left.size());
    std::size_t b = std::min(n, right.size());
    if (a < n) b = 2 * n - a;
    if (b < n) a = 2 * n - b;
    std::vector<long long> cells(left.begin(), left.begin() + static_cast<long>(a));
    cells.insert(cells.end(), right.begin(), right.begin() + static_cast<long>(b));
    std::sort(cells.begin(), cells.end());
    std::vector<double> values;
    for (const long long j : cells) values.push_back(power[static_cast<std::size_t>(j)]);
    const double first =
        std::accumulate(values.begin(), values.begin() + static_cast<long>(n), 0.0);
    const double second = std::accumulate(values.begin() + static_cast<long>(n), values.end(), 0.0);
    double estimate = 0.0;
    switch (config.kind) {
      case CfarKind::ca:
        estimate = (first + second) / (2.0 * static_cast<double>(n));
        break;
      case CfarKind::go:
        estimate = std::max(first, second) / static_cast<double>(n);
        break;
      case CfarKind::so:
        estimate = std::min(first, second) / static_cast<double>(n);
        break;
      case CfarKind::os:
        std::sort(values.begin(), values.end());
        estimate = values[config.effective_os_rank() - 1];
        break;
    }
    threshold[static_cast<std::size_t>(i)] = alpha * estimate;
  }
  return threshold;
}

class CfarDetectorKind : public ::testing::TestWithParam<CfarKind> {};

// The window-sum / sorted-buffer implementation equals the brute-force reference of the edge
// policy in every cell (edge and interior), profile lengths from the minimum upward, with a
// 90 dB target in the profile. Tolerance: 1e-12 relative (summation order only: the sums add
// non-negative cells, so no cancellation next to the target).
TEST_P(CfarDetectorKind, ThresholdMatchesBruteForceEdgePolicy) {
  std::mt19937_64 rng(7);
  std::exponential_distribution<double> noise(1.0);
  for (const unsigned guard : {0u, 1u, 3u}) {
    for (const unsigned n : {1u, 4u, 7u}) {
      const CfarConfig config{.kind = GetParam(),
                              .guard_cells = guard,
                              .training_cells = n,
                              .false_alarm_probability = 1e-4};
      const CfarDetector detector(config);
      for (const std::size_t extra : {0u, 1u, 5u, 40u}) {
        std::vector<double> power(config.window_length() + extra);
        for (double& value : power) value = noise(rng);
        power[power.size() / 3] = 1e9;  // a strong target stresses the running sums
        CfarWorkspace workspace;
        detector.detect(power, workspace);
        const std::vector<double> expected =
            brute_force_threshold(power, config, detector.threshold_factor());
        ASSERT_EQ(workspace.threshold.size(), power.size());
        for (std::size_t i = 0; i < power.size(); ++i) {
          EXPECT_NEAR(workspace.threshold[i], expected[i], 1e-12 * expected[i])
              << "cell " << i << " of " << power.size() << " guard " << guard << " n " << n;
          EXPECT_EQ(power[i] > expected[i], std::binary_search(workspace.detections.begin(),
                                                               workspace.detections.end(), i));
        }
      }
    }
  }
}

// Constant background 1 with one strong point target: the threshold away from the target is
// alpha (every estimator returns 1), and only the target cell is detected; its neighbours
// inside the guard cells do not see it.
TEST_P(CfarDetectorKind, DetectsLoneTargetInConstantBackground) {
  const CfarConfig config{
      .kind = GetParam(), .guard_cells = 2, .training_cells = 8, .false_alarm_probability = 1e-6};
  std::vector<double> power(100, 1.0);
  power[50] = 1e4;
  std::vector<double> threshold;
  const std::vector<std::size_t> detections = cfar_detect(power, config, &threshold);
  ASSERT_EQ(detections, std::vector<std::size_t>{50});
  const double alpha = cfar_threshold_factor(config);
  for (std::size_t i = 48; i <= 52; ++i) EXPECT_DOUBLE_EQ(threshold[i], alpha) << i;
  EXPECT_DOUBLE_EQ(threshold[0], alpha);
  EXPECT_DOUBLE_EQ(threshold[99], alpha);
}

// A workspace reused for profiles of different lengths gives the same result as a fresh one.
TEST_P(CfarDetectorKind, WorkspaceReuseIsStateless) {
  const CfarConfig config{
      .kind = GetParam(), .guard_cells = 1, .training_cells = 4, .false_alarm_probability = 1e-2};
  const CfarDetector detector(config);
  std::mt19937_64 rng(3);
  std::exponential_distribution<double> noise(1.0);
  CfarWorkspace reused;
  for (const std::size_t length : {200u, 11u, 64u}) {
    std::vector<double> power(length);
    for (double& value : power) value = noise(rng);
    CfarWorkspace fresh;
    detector.detect(power, fresh);
    detector.detect(power, reused);
    EXPECT_EQ(fresh.threshold, reused.threshold);
    EXPECT_EQ(fresh.detections, reused.detections);
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, CfarDetectorKind, ::testing::ValuesIn(kAllKinds), kind_name);

// The edge cells of CA/GO/SO bit for bit: each half of the reference cells (the first and the last
// n in range order) summed run by run, every contiguous run cell by cell in range order from 0.0
// and the runs' sums added in order, the way the detector documents it; the threshold is
// (edge factor / N or n) times the combined halves. One workspace serves every length, guard and n
// in turn. Exact: the same additions in the same order (a half summed as one chain instead fails).
TEST(CfarDetectorEdges, EdgeThresholdsAreTheRunByRunSumsBitForBit) {
  std::mt19937_64 rng(11);
  std::exponential_distribution<double> noise(1.0);
  CfarWorkspace workspace;
  for (const CfarKind kind : {CfarKind::ca, CfarKind::go, CfarKind::so}) {
    for (const unsigned guard : {0u, 2u, 3u}) {
      for (const unsigned n : {1u, 5u, 8u}) {
        const CfarConfig config{.kind = kind,
                                .guard_cells = guard,
                                .training_cells = n,
                                .false_alarm_probability = 1e-4};
        const CfarDetector detector(config);
        for (const std::size_t extra : {1u, 2u, 7u, 300u, 2u}) {
          std::vector<double> power(config.window_length() + extra);
          for (double& value : power) value = noise(rng);
          power[1] = 1e9;  // a strong cell inside the edge references
          detector.detect(power, workspace);
          const std::size_t length = power.size();
          const std::size_t reach = guard + n;
          for (std::size_t i = 0; i < length; ++i) {
            if (i >= reach && i < length - reach) continue;
            // The reference cells: the nearest n beyond the guard on each side, a short side's
            // deficit taken from the other (docs/radar.md, the edge policy).
            std::vector<std::size_t> left, right;
            for (std::size_t j = i; j-- > 0;) {
              if (i - j > guard) left.push_back(j);
            }
            for (std::size_t j = i + guard + 1; j < length; ++j) right.push_back(j);
            std::size_t a = std::min<std::size_t>(n, left.size());
            std::size_t b = std::min<std::size_t>(n, right.size());
            if (a < n) b = 2 * n - a;
            if (b < n) a = 2 * n - b;
            std::vector<std::size_t> cells(left.begin(), left.begin() + static_cast<long>(a));
            std::reverse(cells.begin(), cells.end());
            cells.insert(cells.end(), right.begin(), right.begin() + static_cast<long>(b));
            const auto half_sum = [&](std::size_t begin, std::size_t end) {
              std::vector<double> runs{0.0};
              for (std::size_t k = begin; k < end; ++k) {
                if (k > begin && cells[k] != cells[k - 1] + 1) runs.push_back(0.0);  // a new run
                runs.back() += power[cells[k]];
              }
              double total = runs[0];
              for (std::size_t r = 1; r < runs.size(); ++r) total += runs[r];
              return total;
            };
            const double first = half_sum(0, n);
            const double second = half_sum(n, 2 * n);
            const double divisor = static_cast<double>(kind == CfarKind::ca ? 2 * n : n);
            const double combined = kind == CfarKind::ca   ? first + second
                                    : kind == CfarKind::go ? std::max(first, second)
                                                           : std::min(first, second);
            const double expected =
                detector.edge_threshold_factor(std::min(i, length - 1 - i)) / divisor * combined;
            ASSERT_EQ(workspace.threshold[i], expected)
                << to_string(kind) << " cell " << i << " of " << length << " guard " << guard
                << " n " << n;
            EXPECT_EQ(power[i] > expected, std::binary_search(workspace.detections.begin(),
                                                              workspace.detections.end(), i));
          }
        }
      }
    }
  }
}

// Four rows at once (detect_four, which the chain's estimation runs) against the one-profile
// detector on each row's |X|^2 (std::norm), bit for bit: every power value, threshold and detection
// list, for CA, GO, SO and OS, guards 0/2/3, n 1/5/8/9/16 (5 and 9: n's binary digits collected in
// sums; 8, 9 and 16: two doubling passes in one), odd
// and even lengths, one workspace across them all. Strong cells at both profile ends, in a
// different row each, put detections and strong reference cells into the edge cells of some lanes
// only. The one-profile detector is pinned by EdgeThresholdsAreTheRunByRunSumsBitForBit and the Pfa
// tests. Exact: each lane must make the same operations in the same order.
TEST(CfarDetectorFour, SameBitsAsOneProfileAtATime) {
  std::mt19937_64 rng(12);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  CfarFourWorkspace four;
  CfarWorkspace one;
  for (const CfarKind kind : {CfarKind::ca, CfarKind::go, CfarKind::so, CfarKind::os}) {
    for (const unsigned guard : {0u, 2u, 3u}) {
      for (const unsigned n : {1u, 5u, 8u}) {
        const CfarConfig config{.kind = kind,
                                .guard_cells = guard,
                                .training_cells = n,
                                .false_alarm_probability = 1e-3};
        const CfarDetector detector(config);
        for (const std::size_t extra : {0u, 1u, 2u, 7u, 300u, 2u}) {
          const std::size_t length = config.window_length() + extra;
          std::vector<std::complex<double>> rows(4 * length);
          for (std::complex<double>& value : rows) value = {gaussian(rng), gaussian(rng)};
          rows[0 * length + 0] = {300.0, 0.0};  // row 0: a detection at the first cell
          rows[1 * length + 1] = {0.0, 3e4};    // row 1: inside its first cells' references
          rows[2 * length + length - 1] = {-300.0, 1.0};  // row 2: a detection at the last cell
          rows[3 * length + length - 2] = {2e3, -2e3};    // row 3: near the end
          detector.detect_four(rows, four);
          ASSERT_EQ(four.power.size(), 4 * length);
          ASSERT_EQ(four.threshold.size(), 4 * length);
          for (std::size_t r = 0; r < 4; ++r) {
            std::vector<double> power(length);
            for (std::size_t j = 0; j < length; ++j) power[j] = std::norm(rows[r * length + j]);
            detector.detect(power, one);
            for (std::size_t j = 0; j < length; ++j) {
              ASSERT_EQ(four.power[4 * j + r], power[j]) << "row " << r << " cell " << j;
              ASSERT_EQ(four.threshold[4 * j + r], one.threshold[j])
                  << to_string(kind) << " row " << r << " cell " << j << " of " << length
                  << " guard " << guard << " n " << n;
            }
            ASSERT_EQ(four.detections[r], one.detections) << to_string(kind) << " row " << r;
          }
          // The strong end cells are found (detections at both profile ends, in one lane each).
          EXPECT_EQ(four.detections[0].front(), 0u);
          EXPECT_EQ(four.detections[2].back(), length - 1);
        }
      }
    }
  }
}

TEST(CfarDetectorFour, RejectsRowsShorterThanTheWindow) {
  const CfarConfig config{.guard_cells = 2, .training_cells = 8};
  const CfarDetector detector(config);
  CfarFourWorkspace four;
  const std::vector<std::complex<double>> rows(4 * (config.window_length() - 1));
  EXPECT_THROW(detector.detect_four(rows, four), InvalidParameter);
}

// --- False-alarm rate on noise ----------------------------------------------------------------

// Two-sided 99.9 % binomial acceptance interval for `cells` independent trials at p: the
// 0.05 % and 99.95 % quantiles (Boost rounds discrete quantiles outwards).
std::pair<double, double> binomial_interval(double cells, double p) {
  const boost::math::binomial_distribution<double> count(cells, p);
  return {boost::math::quantile(count, 0.0005),
          boost::math::quantile(boost::math::complement(count, 0.0005))};
}

class CfarFalseAlarmRate : public ::testing::TestWithParam<CfarKind> {};

// Square-law detected noise (exponential, mean 1), design Pfa = 1e-3, guard 2, n = 8 (N = 16),
// 25'000 profiles of 64 cells = 1.6e6 cells: 1.1e6 interior cells (nominal window inside the
// profile) and 5e5 edge cells (first and last guard + n = 10 cells of each profile). Each
// group's false-alarm count must lie in the 99.9 % binomial interval of the design Pfa.
// Note: decisions of neighbouring cells share reference cells and are weakly correlated; for
// this configuration that widens the count's standard deviation by roughly 5 % over the
// binomial one, so the interval is effectively about 3.1 sigma rather than 3.3 sigma.
TEST_P(CfarFalseAlarmRate, MatchesDesignInInteriorAndEdgeCells) {
  constexpr double kDesignPfa = 1e-3;
  constexpr std::size_t kProfiles = 25'000;
  constexpr std::size_t kLength = 64;
  const CfarConfig config{.kind = GetParam(),
                          .guard_cells = 2,
                          .training_cells = 8,
                          .false_alarm_probability = kDesignPfa};
  const CfarDetector detector(config);
  const std::size_t edge = config.guard_cells + config.training_cells;

  std::mt19937_64 rng(20240601);
  std::exponential_distribution<double> noise(1.0);
  std::vector<double> power(kLength);
  CfarWorkspace workspace;
  std::size_t alarms_interior = 0;
  std::size_t alarms_left = 0;
  std::size_t alarms_right = 0;
  for (std::size_t profile = 0; profile < kProfiles; ++profile) {
    for (double& value : power) value = noise(rng);
    detector.detect(power, workspace);
    for (const std::size_t i : workspace.detections) {
      if (i < edge) {
        ++alarms_left;
      } else if (i >= kLength - edge) {
        ++alarms_right;
      } else {
        ++alarms_interior;
      }
    }
  }
  const double interior_cells = static_cast<double>(kProfiles * (kLength - 2 * edge));
  const double edge_cells = static_cast<double>(kProfiles * 2 * edge);
  const double alarms_edge = static_cast<double>(alarms_left + alarms_right);

  const auto [interior_low, interior_high] = binomial_interval(interior_cells, kDesignPfa);
  const auto [edge_low, edge_high] = binomial_interval(edge_cells, kDesignPfa);
  std::printf(
      "[ measured ] %s-CFAR Pfa interior %.4e (%zu / %.0f, accept [%.0f, %.0f]), "
      "edge %.4e (left %zu + right %zu / %.0f, accept [%.0f, %.0f])\n",
      std::string(to_string(GetParam())).c_str(),
      static_cast<double>(alarms_interior) / interior_cells, alarms_interior, interior_cells,
      interior_low, interior_high, alarms_edge / edge_cells, alarms_left, alarms_right, edge_cells,
      edge_low, edge_high);
  const std::string kind(to_string(GetParam()));
  const struct {
    const char* cells;
    double alarms, count, low, high;
  } groups[] = {{"interior", static_cast<double>(alarms_interior), interior_cells, interior_low,
                 interior_high},
                {"edge", alarms_edge, edge_cells, edge_low, edge_high}};
  for (const auto& group : groups) {
    // The counts' interval as rates: dividing by the cell count keeps the order.
    fogradar::testing::validate(
        {.id = "radar.cfar." + kind + ".realised_pfa." + group.cells + ".pfa1e-3",
         .group = "radar: CFAR",
         .quantity = std::string("realised P_fa, ") + group.cells + " cells",
         .unit = "1",
         .conditions = kind_label(GetParam()) +
                       ", 16 training cells, guard 2, exponential noise, design P_fa 1e-3",
         .reference = kDesignPfa,
         .source = "design P_fa (binomial acceptance interval, Boost.Math quantiles)",
         .value = group.alarms / group.count,
         .tolerance = 0.0,
         .kind = Tolerance::statistical,
         .samples = static_cast<std::size_t>(group.count),
         .interval_low = group.low / group.count,
         .interval_high = group.high / group.count,
         .confidence = "99.9 % two-sided binomial interval of the design P_fa",
         .plot = "cfar_pfa",
         .x = kDesignPfa,
         .x_label = "design P_fa"});
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, CfarFalseAlarmRate, ::testing::ValuesIn(kAllKinds), kind_name);

// --- Detection probability (CA) ---------------------------------------------------------------

constexpr unsigned kPdGuard = 2;
constexpr unsigned kPdTraining = 16;  // N = 32
constexpr double kPdDesignPfa = 1e-6;
constexpr std::size_t kPdTrials = 20'000;
constexpr double kPdTolerance = 0.03;  // absolute; binomial sigma <= 0.0035 at 20'000 trials

// Monte Carlo Pd of CA-CFAR: profiles of 16 disjoint full windows, the cell under test at each
// window centre drawn by `draw_target`, reference cells exponential noise of mean 1.
template <class DrawTarget>
double monte_carlo_pd(std::mt19937_64& rng, DrawTarget draw_target) {
  const CfarConfig config{.kind = CfarKind::ca,
                          .guard_cells = kPdGuard,
                          .training_cells = kPdTraining,
                          .false_alarm_probability = kPdDesignPfa};
  const CfarDetector detector(config);
  const std::size_t window = config.window_length();
  constexpr std::size_t kTargetsPerProfile = 16;
  std::exponential_distribution<double> noise(1.0);
  std::vector<double> power(window * kTargetsPerProfile);
  CfarWorkspace workspace;
  std::size_t hits = 0;
  for (std::size_t trial = 0; trial < kPdTrials; trial += kTargetsPerProfile) {
    for (double& value : power) value = noise(rng);
    for (std::size_t t = 0; t < kTargetsPerProfile; ++t) {
      power[t * window + window / 2] = draw_target(rng);
    }
    detector.detect(power, workspace);
    for (const std::size_t i : workspace.detections) hits += (i % window == window / 2) ? 1 : 0;
  }
  return static_cast<double>(hits) / static_cast<double>(kPdTrials);
}

// Swerling 1: the cell under test is exponential with mean 1 + SNR; closed form
// Pd = (1 + alpha / (N (1 + SNR)))^-N [Ri14 §6.5.3]. Tolerance +-0.03 absolute.
TEST(CfarDetection, CaSwerling1MatchesClosedForm) {
  const double alpha = cfar_threshold_factor({.kind = CfarKind::ca,
                                              .guard_cells = kPdGuard,
                                              .training_cells = kPdTraining,
                                              .false_alarm_probability = kPdDesignPfa});
  const double big_n = 2.0 * kPdTraining;
  std::mt19937_64 rng(11);
  for (const double snr_db : {5.0, 10.0, 15.0, 20.0, 25.0}) {
    const double snr = std::pow(10.0, snr_db / 10.0);
    const double expected = std::pow(1.0 + alpha / (big_n * (1.0 + snr)), -big_n);
    std::exponential_distribution<double> target(1.0 / (1.0 + snr));
    const double measured = monte_carlo_pd(rng, [&](std::mt19937_64& g) { return target(g); });
    std::printf("[ measured ] CA Swerling 1 SNR %4.1f dB: Pd %.4f, closed form %.4f, error %+.4f\n",
                snr_db, measured, expected, measured - expected);
    fogradar::testing::validate(
        {.id = "radar.cfar.ca.swerling1_pd.snr" + id_number(snr_db) + "dB",
         .group = "radar: detection",
         .quantity = "detection probability, Swerling 1 (Monte Carlo)",
         .unit = "1",
         .conditions = "CA-CFAR, 32 training cells, guard 2, design P_fa 1e-6, SNR " +
                       id_number(snr_db) + " dB, 20000 trials",
         .reference = expected,
         .source = "closed form Pd = (1 + alpha / (N (1 + SNR)))^-N [Ri14 §6.5.3]",
         .value = measured,
         .tolerance = kPdTolerance,
         .kind = Tolerance::absolute,
         .plot = "swerling1_pd",
         .x = snr_db,
         .x_label = "SNR (dB)"});
  }
}

// Swerling 0 reference, computed independently: the cell under test |A + w|^2 with |A|^2 = SNR
// and w ~ CN(0, 1) exceeds tau with probability Q1(sqrt(2 SNR), sqrt(2 tau)), the complement
// cdf of a non-central chi-squared with 2 degrees of freedom and lambda = 2 SNR at 2 tau.
// The CA threshold is tau = alpha Z / N with Z ~ Gamma(N, 1), so
//   Pd = integral_0^inf Q1(sqrt(2 SNR), sqrt(2 alpha z / N)) f_Gamma(N,1)(z) dz
// (Gauss-Kronrod 61-point adaptive quadrature, Boost.Math).
double swerling0_ca_pd(double snr, double alpha, double big_n) {
  const boost::math::non_central_chi_squared_distribution<double> cut(2.0, 2.0 * snr);
  const boost::math::gamma_distribution<double> z_dist(big_n, 1.0);
  const auto integrand = [&](double z) {
    return boost::math::cdf(boost::math::complement(cut, 2.0 * alpha * z / big_n)) *
           boost::math::pdf(z_dist, z);
  };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      integrand, 0.0, std::numeric_limits<double>::infinity(), 15, 1e-12);
}

// The quadrature itself: at SNR -> 0 it must reproduce the CA Pfa (1 + alpha/N)^-N
// (tolerance 1e-6 relative).
TEST(CfarDetection, Swerling0IntegralReducesToPfaWithoutTarget) {
  const double alpha = cfar_threshold_factor({.kind = CfarKind::ca,
                                              .guard_cells = kPdGuard,
                                              .training_cells = kPdTraining,
                                              .false_alarm_probability = kPdDesignPfa});
  fogradar::testing::validate(
      {.id = "radar.cfar.ca.swerling0_integral.no_target",
       .group = "radar: detection",
       .quantity = "Swerling 0 detection integral at SNR -> 0 (1e-12)",
       .unit = "1",
       .conditions = "CA-CFAR, 32 training cells, guard 2, design P_fa 1e-6",
       .reference = kPdDesignPfa,
       .source = "closed form CA P_fa (1 + alpha/N)^-N = design P_fa [GK88]",
       .value = swerling0_ca_pd(1e-12, alpha, 2.0 * kPdTraining),
       .tolerance = 1e-6,
       .kind = Tolerance::relative});
}

// Swerling 0 (constant amplitude, random phase, complex Gaussian noise) Monte Carlo against the
// numerical integral above. Tolerance +-0.03 absolute.
TEST(CfarDetection, CaSwerling0MatchesNumericalIntegral) {
  const double alpha = cfar_threshold_factor({.kind = CfarKind::ca,
                                              .guard_cells = kPdGuard,
                                              .training_cells = kPdTraining,
                                              .false_alarm_probability = kPdDesignPfa});
  std::mt19937_64 rng(13);
  std::normal_distribution<double> component(0.0, std::sqrt(0.5));  // E|w|^2 = 1
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
  for (const double snr_db : {5.0, 10.0, 15.0, 20.0, 25.0}) {
    const double snr = std::pow(10.0, snr_db / 10.0);
    const double expected = swerling0_ca_pd(snr, alpha, 2.0 * kPdTraining);
    const double measured = monte_carlo_pd(rng, [&](std::mt19937_64& g) {
      const std::complex<double> sample =
          std::polar(std::sqrt(snr), phase(g)) + std::complex<double>(component(g), component(g));
      return std::norm(sample);
    });
    std::printf("[ measured ] CA Swerling 0 SNR %4.1f dB: Pd %.4f, integral %.4f, error %+.4f\n",
                snr_db, measured, expected, measured - expected);
    fogradar::testing::validate(
        {.id = "radar.cfar.ca.swerling0_pd.snr" + id_number(snr_db) + "dB",
         .group = "radar: detection",
         .quantity = "detection probability, Swerling 0 (Monte Carlo)",
         .unit = "1",
         .conditions = "CA-CFAR, 32 training cells, guard 2, design P_fa 1e-6, SNR " +
                       id_number(snr_db) + " dB, 20000 trials",
         .reference = expected,
         .source = "numerical integral of Marcum Q1 over the Gamma(N, 1) noise estimate "
                   "(Gauss-Kronrod, Boost.Math, this test)",
         .value = measured,
         .tolerance = kPdTolerance,
         .kind = Tolerance::absolute,
         .plot = "swerling0_pd",
         .x = snr_db,
         .x_label = "SNR (dB)"});
  }
}

}  // namespace
}  // namespace fogradar::radar
