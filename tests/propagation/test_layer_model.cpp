// Virtual layer model (paper eq. 3, 4). References: OEIS A000108 (Catalan numbers) and A001263
// (Narayana triangle, read by rows, n >= 1); a brute-force enumeration of every reflection path
// (independent of the dynamic programming under test); eq. 4 for a stack without reflections.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <boost/math/special_functions/lambert_w.hpp>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/propagation/layer_model.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::propagation {
namespace {

constexpr double kRelTol = 1e-12;      // brute force and closed forms, kappa <= 15
constexpr double kDeepRelTol = 1e-10;  // eq. 3 against the DP over hundreds of bins
constexpr unsigned kMaxKappa = 15;
// EXPECT_DOUBLE_EQ's 4 units in the last place, as a relative tolerance.
constexpr double kDoubleEqRelTol = 4.0 * std::numeric_limits<double>::epsilon();

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

// A number as written in a check's id and conditions: "0.9", "0.35".
std::string num(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Records one check of the virtual layer model against its reference.
void check(const std::string& id, const std::string& quantity, const std::string& conditions,
           double value, double reference, const std::string& source, double tolerance,
           Tolerance kind) {
  validate({.id = "propagation.layer_model." + id,
            .group = "physics: chamber",
            .quantity = quantity,
            .unit = "1",
            .conditions = conditions,
            .reference = reference,
            .source = source,
            .value = value,
            .tolerance = tolerance,
            .kind = kind});
}

// An integer sequence term against a published one: exact (a double holds every term below 2^53;
// larger terms are also compared as integers next to this record).
void check_term(const std::string& id, const std::string& quantity, const std::string& conditions,
                std::uint64_t value, std::uint64_t reference, const std::string& source) {
  check(id, quantity, conditions, static_cast<double>(value), static_cast<double>(reference),
        source, 0.0, Tolerance::absolute);
}

// Expects `call` to throw InvalidParameter naming `field`.
void expect_invalid(const std::function<void()>& call, const std::string& field) {
  EXPECT_EQ(test_support::rejected_field(call), field);
}

// ---- Catalan and Narayana numbers ----------------------------------------------------------

TEST(Catalan, MatchesOeisA000108) {
  // OEIS A000108, n = 0..15, plus n = 30, 35 and 36 (the largest that fits in uint64).
  const std::array<std::uint64_t, 16> oeis = {
      1, 1, 2, 5, 14, 42, 132, 429, 1430, 4862, 16796, 58786, 208012, 742900, 2674440, 9694845};
  const std::string a000108 = "OEIS A000108 (Catalan numbers)";
  for (unsigned n = 0; n < oeis.size(); ++n) {
    check_term("catalan.n" + std::to_string(n), "Catalan number C_n", "n = " + std::to_string(n),
               catalan(n), oeis[n], a000108);
  }
  check_term("catalan.n30", "Catalan number C_n", "n = 30", catalan(30), 3814986502092304ULL,
             a000108);
  // C_35 and C_36 exceed 2^53: recorded as doubles, compared exactly as integers.
  check_term("catalan.n35", "Catalan number C_n", "n = 35", catalan(35), 3116285494907301262ULL,
             a000108);
  EXPECT_EQ(catalan(35), 3116285494907301262ULL);
  check_term("catalan.n36", "Catalan number C_n", "n = 36", catalan(36), 11959798385860453492ULL,
             a000108);
  EXPECT_EQ(catalan(36), 11959798385860453492ULL);
}

TEST(Catalan, OverflowThrowsNamingN) {
  expect_invalid([] { catalan(37); }, "n");  // C_37 = 45950804324621742364 > 2^64 - 1
}

TEST(Narayana, MatchesOeisA001263) {
  // OEIS A001263, rows n = 1..8.
  const std::vector<std::vector<std::uint64_t>> rows = {{1},
                                                        {1, 1},
                                                        {1, 3, 1},
                                                        {1, 6, 6, 1},
                                                        {1, 10, 20, 10, 1},
                                                        {1, 15, 50, 50, 15, 1},
                                                        {1, 21, 105, 175, 105, 21, 1},
                                                        {1, 28, 196, 490, 490, 196, 28, 1}};
  const std::string a001263 = "OEIS A001263 (Narayana triangle)";
  const std::string zero = "Narayana number definition: N(n, k) = 0 outside 1 <= k <= n";
  for (unsigned n = 1; n <= rows.size(); ++n) {
    const std::string row = "narayana.n" + std::to_string(n);
    for (unsigned k = 1; k <= n; ++k) {
      check_term(row + ".k" + std::to_string(k), "Narayana number N(n, k)",
                 "n = " + std::to_string(n) + ", k = " + std::to_string(k), narayana(n, k),
                 rows[n - 1][k - 1], a001263);
    }
    check_term(row + ".k0", "Narayana number N(n, k)", "n = " + std::to_string(n) + ", k = 0",
               narayana(n, 0), 0U, zero);
    check_term(row + ".k" + std::to_string(n + 1), "Narayana number N(n, k)",
               "n = " + std::to_string(n) + ", k = " + std::to_string(n + 1), narayana(n, n + 1),
               0U, zero);
  }
  // Python math.comb: N(37, 18), N(37, 19) (largest row that fits), N(100, 2).
  // The first two exceed 2^53: recorded as doubles, compared exactly as integers.
  const std::string comb = "N(n, k) = C(n, k) C(n, k - 1) / n by Python math.comb";
  check_term("narayana.n37.k18", "Narayana number N(n, k)", "n = 37, k = 18", narayana(37, 18),
             7597019633665077000ULL, comb);
  EXPECT_EQ(narayana(37, 18), 7597019633665077000ULL);
  check_term("narayana.n37.k19", "Narayana number N(n, k)", "n = 37, k = 19", narayana(37, 19),
             8441132926294530000ULL, comb);
  EXPECT_EQ(narayana(37, 19), 8441132926294530000ULL);
  check_term("narayana.n100.k2", "Narayana number N(n, k)", "n = 100, k = 2", narayana(100, 2),
             4950U, comb);
  check_term("narayana.n100.k100", "Narayana number N(n, k)", "n = 100, k = 100",
             narayana(100, 100), 1U, comb);
}

TEST(Narayana, RowSumsAreCatalanNumbers) {
  for (unsigned n = 0; n <= 36; ++n) {
    std::uint64_t sum = 0;
    for (unsigned k = 0; k <= n; ++k) sum += narayana(n, k);
    EXPECT_EQ(sum, catalan(n)) << "n = " << n;
  }
}

TEST(Narayana, OverflowThrowsNamingN) {
  expect_invalid([] { narayana(38, 18); }, "n");  // 25431927630793091100 > 2^64 - 1
  expect_invalid([] { narayana(100, 50); }, "n");
}

// ---- Brute-force reference: every path, scored one by one ------------------------------------

// Heights of a path given as steps (+1 up, -1 down), starting at the sensor (0).
std::vector<int> heights_of(const std::vector<int>& steps) {
  std::vector<int> heights = {0};
  for (int step : steps) heights.push_back(heights.back() + step);
  return heights;
}

// All step sequences of length 2n from 0 back to 0 that stay >= 1 in between and below `ceiling`.
void walk(int height, unsigned steps_left, int ceiling, std::vector<int>& steps,
          std::vector<std::vector<int>>& paths) {
  if (steps_left == 0) {
    if (height == 0) paths.push_back(steps);
    return;
  }
  for (int step : {+1, -1}) {
    const int next = height + step;
    const bool returns_now = next == 0 && steps_left == 1;
    if ((next >= 1 || returns_now) && next <= ceiling && next <= static_cast<int>(steps_left) - 1) {
      steps.push_back(step);
      walk(next, steps_left - 1, ceiling, steps, paths);
      steps.pop_back();
    }
  }
}

std::vector<std::vector<int>> all_paths(unsigned n, int ceiling) {
  std::vector<std::vector<int>> paths;
  std::vector<int> steps;
  walk(0, 2 * n, ceiling, steps, paths);
  return paths;
}

// Number of turns (peaks and valleys) of a path: its reflections.
unsigned reflections_of(const std::vector<int>& steps) {
  unsigned turns = 0;
  for (std::size_t s = 1; s < steps.size(); ++s) turns += steps[s] != steps[s - 1] ? 1U : 0U;
  return turns;
}

// Weight of one path in a stack (object at height L+1): at each interior vertex of height h, tau_h
// if the path goes on, rho_h if it turns (rho_object at L+1).
double path_weight(const std::vector<int>& steps, const std::vector<VirtualLayer>& layers,
                   double rho_object) {
  const std::vector<int> heights = heights_of(steps);
  double weight = 1.0;
  for (std::size_t s = 1; s < steps.size(); ++s) {
    const auto h = static_cast<std::size_t>(heights[s]);
    const bool turns = steps[s] != steps[s - 1];
    if (h > layers.size()) {
      weight *= rho_object;
    } else {
      weight *= turns ? layers[h - 1].reflectance : layers[h - 1].transmittance;
    }
  }
  return weight;
}

double brute_force_bin(unsigned n, const std::vector<VirtualLayer>& layers, double rho_object) {
  double sum = 0.0;
  for (const auto& steps : all_paths(n, static_cast<int>(layers.size()) + 1)) {
    sum += path_weight(steps, layers, rho_object);
  }
  return sum;
}

std::vector<VirtualLayer> identical_stack(std::size_t count, double tau, double rho) {
  return std::vector<VirtualLayer>(count, VirtualLayer{tau, rho});
}

TEST(LayerPathCount, EqualsBruteForceCountPerReflectionNumber) {
  for (unsigned kappa = 1; kappa <= kMaxKappa; kappa += 2) {
    const unsigned n = (kappa + 1) / 2;
    std::vector<std::uint64_t> count_by_peaks(n + 1, 0);
    for (const auto& steps : all_paths(n, static_cast<int>(n) + 1)) {
      ++count_by_peaks[(reflections_of(steps) + 1) / 2];  // 2i - 1 reflections -> i peaks
    }
    std::uint64_t total = 0;
    const std::string brute_force = "brute-force enumeration of every reflection path (test)";
    for (unsigned i = 1; i <= std::max(1U, n - 1); ++i) {
      check_term("path_count.kappa" + std::to_string(kappa) + ".i" + std::to_string(i),
                 "paths p_i with 2i - 1 reflections",
                 "kappa = " + std::to_string(kappa) + ", i = " + std::to_string(i),
                 layer_path_count(kappa, i), count_by_peaks[i], brute_force);
      total += count_by_peaks[i];
    }
    check_term("path_count.total.kappa" + std::to_string(kappa), "all paths to bin kappa",
               "kappa = " + std::to_string(kappa), n == 1 ? 1U : catalan(n - 1), total,
               brute_force);
  }
}

TEST(LayerModelIntensity, EqualsBruteForceSumForUnboundedIdenticalStack) {
  for (const auto& [tau, rho] : {std::pair{0.9, 0.05}, std::pair{0.5, 0.5}, std::pair{0.3, 0.6}}) {
    for (unsigned kappa = 1; kappa <= kMaxKappa; kappa += 2) {
      const unsigned n = (kappa + 1) / 2;
      const double expected = 2.5 * brute_force_bin(n, identical_stack(n, tau, rho), 0.0);
      check("intensity.unbounded.tau" + num(tau) + ".rho" + num(rho) + ".kappa" +
                std::to_string(kappa),
            "bin intensity I_kappa / I_0 (eq. 3)",
            "identical layers tau = " + num(tau) + ", rho = " + num(rho) +
                ", I_0 = 2.5, kappa = " + std::to_string(kappa),
            layer_model_intensity(kappa, tau, rho, 2.5), expected,
            "brute-force sum over every reflection path (test)", kRelTol, Tolerance::relative);
    }
  }
}

TEST(LayerStackResponse, EqualsBruteForceForFiniteMixedStacksWithObject) {
  const std::vector<VirtualLayer> mixed = {{0.9, 0.05}, {0.6, 0.3},  {0.8, 0.15}, {0.95, 0.01},
                                           {0.7, 0.2},  {0.85, 0.1}, {0.5, 0.4},  {0.99, 0.005}};
  const unsigned max_bin = (kMaxKappa + 1) / 2;
  for (std::size_t depth = 0; depth <= mixed.size(); ++depth) {
    const std::vector<VirtualLayer> stack(mixed.begin(),
                                          mixed.begin() + static_cast<std::ptrdiff_t>(depth));
    for (double rho_object : {0.0, 0.35, 1.0}) {
      const std::vector<double> response = layer_stack_response(stack, rho_object, max_bin, 0.7);
      ASSERT_EQ(response.size(), max_bin);
      for (unsigned n = 1; n <= max_bin; ++n) {
        const double expected = 0.7 * brute_force_bin(n, stack, rho_object);
        check("stack_response.mixed.depth" + std::to_string(depth) + ".rho_object" +
                  num(rho_object) + ".bin" + std::to_string(n),
              "bin intensity I_n / I_0",
              "mixed stack of " + std::to_string(depth) + " layers, rho_object = " +
                  num(rho_object) + ", I_0 = 0.7, bin " + std::to_string(n),
              response[n - 1], expected, "brute-force sum over every reflection path (test)",
              kRelTol, Tolerance::relative);
      }
    }
  }
}

TEST(LayerStackResponse, DeepIdenticalStackEqualsEq3) {
  // Up to kappa = 15 against eq. 3 directly, then hundreds of bins (p_i far beyond uint64).
  for (unsigned max_bin : {(kMaxKappa + 1) / 2, 300U}) {
    for (const auto& [tau, rho] :
         {std::pair{0.9, 0.05}, std::pair{0.5, 0.5}, std::pair{0.98, 0.02}}) {
      const auto stack = identical_stack(max_bin, tau, rho);
      const std::vector<double> response = layer_stack_response(stack, 0.8, max_bin);
      const double tol = max_bin <= 8 ? kRelTol : kDeepRelTol;
      for (unsigned n = 1; n <= max_bin; ++n) {
        const double expected = layer_model_intensity(2 * n - 1, tau, rho);
        EXPECT_NEAR(response[n - 1], expected, tol * expected) << "bin " << n << " tau " << tau;
      }
    }
  }
}

TEST(LayerStackResponse, LosslessHalfSplitStackIsTheRecurrentRandomWalk) {
  // tau = rho = 1/2 weighs each path of 2n steps 2^(1-2n): the first-return law of the simple
  // symmetric random walk, so sum_{n<=N} I_n = 1 - binom(2N, N) / 4^N (Feller, An Introduction to
  // Probability Theory, vol. 1, 3rd ed., sec. III.3, lemma 1).
  for (unsigned max_bin : {10U, 300U}) {
    const std::vector<double> response =
        layer_stack_response(identical_stack(max_bin, 0.5, 0.5), 0.0, max_bin);
    double total = 0.0;
    for (double intensity : response) total += intensity;
    double no_return_yet = 1.0;  // binom(2N, N) / 4^N = prod_{k<=N} (2k-1)/(2k)
    for (unsigned k = 1; k <= max_bin; ++k) no_return_yet *= (2.0 * k - 1.0) / (2.0 * k);
    check("stack_response.lossless_half_split.sum" + std::to_string(max_bin) + "bins",
          "sum of bin intensities", "tau = rho = 1/2, " + std::to_string(max_bin) + " bins", total,
          1.0 - no_return_yet,
          "closed form: first return of the symmetric random walk, 1 - binom(2N, N) / 4^N "
          "(Feller vol. 1, sec. III.3, lemma 1)",
          kRelTol, Tolerance::absolute);
  }
}

TEST(LayerModelIntensity, FirstBinIsTheFirstLayerEcho) {
  check("intensity.first_bin", "bin intensity I_1", "tau = 0.7, rho = 0.2, I_0 = 3",
        layer_model_intensity(1, 0.7, 0.2, 3.0), 0.6, "closed form: I_1 = I_0 rho (eq. 3)",
        kDoubleEqRelTol, Tolerance::relative);
  // no crossing, no deeper echo
  check("intensity.kappa7.tau0", "bin intensity I_7 / I_0", "tau = 0, rho = 0.9",
        layer_model_intensity(7, 0.0, 0.9), 0.0, "limiting case: tau = 0, no deeper echo", 0.0,
        Tolerance::absolute);
  check("intensity.kappa7.rho0", "bin intensity I_7 / I_0", "tau = 0.9, rho = 0",
        layer_model_intensity(7, 0.9, 0.0), 0.0, "limiting case: rho = 0, no reflection", 0.0,
        Tolerance::absolute);
}

TEST(LayerModelIntensity, SmallKappaEqualsTheSumWrittenOut) {
  // Eq. 3 with the Narayana numbers of rows 1..3 written out (OEIS A001263: 1; 1 1; 1 3 1):
  // I_3 = rho tau^2, I_5 = rho tau^4 + rho^3 tau^2, I_7 = rho tau^6 + 3 rho^3 tau^4 + rho^5 tau^2.
  for (const auto& [tau, rho] : {std::pair{0.414, 0.0896}, std::pair{0.6, 0.35}}) {
    const std::string conditions = "tau = " + num(tau) + ", rho = " + num(rho);
    const double t2 = tau * tau;
    const double r2 = rho * rho;
    const std::pair<unsigned, double> written_out[] = {
        {3, rho * t2},
        {5, rho * t2 * t2 + rho * r2 * t2},
        {7, rho * t2 * t2 * t2 + 3.0 * rho * r2 * t2 * t2 + rho * r2 * r2 * t2}};
    for (const auto& [kappa, expected] : written_out) {
      check("intensity.written_out.tau" + num(tau) + ".rho" + num(rho) + ".kappa" +
                std::to_string(kappa),
            "bin intensity I_kappa / I_0 (eq. 3)",
            conditions + ", kappa = " + std::to_string(kappa),
            layer_model_intensity(kappa, tau, rho), expected,
            "eq. 3 written out with Narayana numbers N(m, i) (OEIS A001263)", kRelTol,
            Tolerance::relative);
    }
  }
}

// ---- rho = 0: only the object's direct echo, eq. 4 ------------------------------------------

TEST(LayerStackResponse, WithoutReflectionsReducesToEq4) {
  for (unsigned depth = 0; depth <= 10; ++depth) {
    const std::vector<double> response =
        layer_stack_response(identical_stack(depth, 0.83, 0.0), 0.4, 12, 2.0);
    for (unsigned n = 1; n <= 12; ++n) {
      const double expected = n == depth + 1 ? object_intensity(depth, 0.83, 0.4, 2.0) : 0.0;
      EXPECT_NEAR(response[n - 1], expected, kRelTol * expected)
          << "depth " << depth << " bin " << n;
    }
  }
  // Non-identical transmittances: I_obj = I_0 rho_obj prod tau_j^2.
  const std::vector<VirtualLayer> stack = {{0.9, 0.0}, {0.5, 0.0}, {0.7, 0.0}};
  const double expected = 0.4 * std::pow(0.9 * 0.5 * 0.7, 2);
  check("stack_response.no_reflection.object_bin", "object bin intensity I_4 / I_0",
        "tau = 0.9, 0.5, 0.7, rho = 0, rho_object = 0.4", layer_stack_response(stack, 0.4, 6)[3],
        expected, "closed form: I_obj = I_0 rho_obj prod tau_j^2 (eq. 4)", kRelTol,
        Tolerance::relative);
  check("object_intensity.kappa4", "object intensity I_obj",
        "4 layers, tau = 0.9, rho_object = 0.5, I_0 = 2", object_intensity(4, 0.9, 0.5, 2.0),
        2.0 * 0.5 * std::pow(0.9, 8), "closed form: I_obj = I_0 rho_obj tau^(2 kappa) (eq. 4)",
        kDoubleEqRelTol, Tolerance::relative);
}

TEST(LayerStackResponse, ZeroBinsGiveEmptyResponse) {
  EXPECT_TRUE(layer_stack_response(identical_stack(3, 0.9, 0.05), 0.5, 0).empty());
}

// ---- Fog to virtual layer ---------------------------------------------------------------------

TEST(VirtualLayerFromFog, BeerLambertTransmittanceAndAreaReflectivity) {
  // 0.15 m range resolution, alpha = 2e-3 /m, eta = 1e-5 m^2/m^3.
  const VirtualLayer layer = virtual_layer_from_fog(2e-3, 1e-5, 0.15);
  const std::string conditions = "alpha = 2e-3 1/m, eta = 1e-5 m^2/m^3, thickness 0.15 m";
  check("virtual_layer.transmittance", "virtual layer transmittance tau", conditions,
        layer.transmittance, std::exp(-3e-4), "closed form: Beer-Lambert tau = exp(-alpha d)",
        kDoubleEqRelTol, Tolerance::relative);
  check("virtual_layer.reflectance", "virtual layer reflectance rho", conditions, layer.reflectance,
        1.5e-6, "closed form: area reflectivity rho = eta d", kDoubleEqRelTol, Tolerance::relative);
}

TEST(LongestLayer, IsTheNonTrivialRootOfTauPlusRhoEqualsOne) {
  // exp(-alpha d) + eta d = 1 with t = 1 - eta d: t exp(-(alpha/eta) t) = exp(-alpha/eta), whose
  // roots are t = -(eta/alpha) W(-(alpha/eta) exp(-alpha/eta)); W_-1 gives the trivial d = 0, the
  // principal branch W_0 the longest layer (Corless et al. 1996; Boost.Math lambert_w0).
  for (const auto& [alpha, eta] :
       {std::pair{2.0, 1.0}, std::pair{0.9, 0.09}, std::pair{1e-2, 1e-3}, std::pair{0.05, 4e-2}}) {
    const double ratio = alpha / eta;
    const double t = -boost::math::lambert_w0(-ratio * std::exp(-ratio)) / ratio;
    const double reference_m = (1.0 - t) / eta;
    const std::string conditions = "alpha = " + num(alpha) + " 1/m, eta = " + num(eta) + " m^2/m^3";
    const double longest_m = longest_layer_m(alpha, eta);
    check("longest_layer.a" + num(alpha) + "_eta" + num(eta), "longest virtual layer", conditions,
          longest_m, reference_m, "closed form by the Lambert W function (principal branch)", 1e-12,
          Tolerance::relative);
    // Its defining property: the layer fits, one double longer does not.
    EXPECT_LE(std::exp(-alpha * longest_m) + eta * longest_m, 1.0);
    const double longer_m = std::nextafter(longest_m, 2.0 * longest_m);
    EXPECT_GT(std::exp(-alpha * longer_m) + eta * longer_m, 1.0);
  }
  expect_invalid([] { longest_layer_m(1.0, 1.0); }, "eta_m2_per_m3");
  expect_invalid([] { longest_layer_m(1.0, 0.0); }, "eta_m2_per_m3");
}

TEST(LayerModelTable, RowsAreEq3AndEq4WrittenOut) {
  // tau = 0.8, rho = 0.05, rho_obj = 0.6: eq. 3 for kappa = 1, 3, 5, 7 written out with the
  // Narayana numbers (1; 1; 1, 1; 1, 3, 1) and eq. 4 I_obj = rho_obj tau^(2k).
  const double tau = 0.8, rho = 0.05, rho_obj = 0.6;
  const std::vector<LayerModelRow> rows = layer_model_table({tau, rho}, 3, rho_obj);
  ASSERT_EQ(rows.size(), 4u);
  const double eq3[] = {rho, rho * tau * tau, rho * std::pow(tau, 4) + std::pow(rho, 3) * tau * tau,
                        rho * std::pow(tau, 6) + 3 * std::pow(rho, 3) * std::pow(tau, 4) +
                            std::pow(rho, 5) * tau * tau};
  for (unsigned k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].layers, k);
    EXPECT_EQ(rows[k].kappa, 2 * k + 1);
    const std::string conditions = "tau = 0.8, rho = 0.05, k = " + num(k);
    check("table.fog.k" + num(k), "fog echo I_kappa / I_0 (table)", conditions,
          rows[k].fog_intensity_per_i0, eq3[k], "paper eq. 3 written out", 1e-12,
          Tolerance::relative);
    check("table.object.k" + num(k), "object echo I_obj / I_0 (table)", conditions,
          rows[k].object_intensity_per_i0, rho_obj * std::pow(tau, 2.0 * k),
          "paper eq. 4: rho_obj tau^(2k)", 1e-12, Tolerance::relative);
  }
}

// ---- Rejected inputs --------------------------------------------------------------------------

TEST(LayerModelConfig, RejectsEveryInvalidField) {
  expect_invalid([] { layer_path_count(4, 1); }, "kappa");
  expect_invalid([] { layer_path_count(7, 0); }, "i");
  expect_invalid([] { layer_path_count(7, 4); }, "i");
  expect_invalid([] { layer_path_count(1, 2); }, "i");
  expect_invalid([] { layer_model_intensity(2, 0.5, 0.1); }, "kappa");
  expect_invalid([] { layer_model_intensity(3, 1.1, 0.0); }, "tau");
  expect_invalid([] { layer_model_intensity(3, std::nan(""), 0.0); }, "tau");
  expect_invalid([] { layer_model_intensity(3, 0.5, -0.1); }, "rho");
  expect_invalid([] { layer_model_intensity(3, 0.6, 0.5); }, "rho");
  expect_invalid([] { layer_model_intensity(3, 0.6, 0.1, -1.0); }, "i0");
  expect_invalid([] { object_intensity(2, -0.1, 0.5); }, "tau");
  expect_invalid([] { object_intensity(2, 0.9, 1.5); }, "rho_object");
  expect_invalid([] { object_intensity(2, 0.9, 0.5, std::nan("")); }, "i0");

  expect_invalid([] { VirtualLayer{1.2, 0.0}.validate(); }, "VirtualLayer.transmittance");
  expect_invalid([] { VirtualLayer{0.5, -0.2}.validate(); }, "VirtualLayer.reflectance");
  expect_invalid([] { VirtualLayer{0.7, 0.4}.validate(); }, "VirtualLayer.reflectance");
  const std::vector<VirtualLayer> bad_stack = {{0.9, 0.05}, {0.9, 0.2}};
  expect_invalid([&] { layer_stack_response(bad_stack, 0.5, 4); }, "VirtualLayer.reflectance");
  const std::vector<VirtualLayer> good_stack = {{0.9, 0.05}};
  expect_invalid([&] { layer_stack_response(good_stack, 1.5, 4); }, "rho_object");
  expect_invalid([&] { layer_stack_response(good_stack, 0.5, 4, -2.0); }, "i0");

  expect_invalid([] { virtual_layer_from_fog(-1e-3, 1e-5, 0.15); }, "extinction_per_m");
  expect_invalid([] { virtual_layer_from_fog(1e-3, -1e-5, 0.15); }, "eta_m2_per_m3");
  expect_invalid([] { virtual_layer_from_fog(1e-3, 1e-5, 0.0); }, "thickness_m");
  expect_invalid([] { virtual_layer_from_fog(1e-3, 1e-5, std::nan("")); }, "thickness_m");
  expect_invalid([] { virtual_layer_from_fog(0.0, 2.0, 1.0); }, "eta_m2_per_m3");  // tau + rho = 3
}

}  // namespace
}  // namespace fogradar::propagation
