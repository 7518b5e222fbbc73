#include "fogradar/radar/cfar_design.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "cfar_correlated.hpp"

namespace fogradar::radar {

namespace {

// A lag's correlation counts towards a geometry's structure from this magnitude on (its square, the
// correlation of the cells' powers, is then 1e-4; for CA exact, geometries that differ beyond it
// differ in their factors by < 1e-4: test_cfar_correlated.cpp).
constexpr double kReachCorrelation = 1e-2;

// The lags a geometry's structure may reach. Every window of the chain reaches at most 4 (Hann and
// Hamming 2, Blackman-Harris and the 80 dB Chebyshev 4 and 3: docs/radar.md §7).
constexpr std::size_t kStructureLags = 16;

// A reference geometry by its number of reference cells on the left of the cell under test, L in
// [0, n] (n: the interior). Geometries whose L and n - L both reach K = structure_cells are the
// same cells near every structure point and differ only in where the far cells lie: one of them, L
// = n / 2, is solved for all (for CA exact they agree to 1e-5 at n = 24: test_cfar_correlated.cpp).
std::size_t solved_left(std::size_t left, std::size_t n, std::size_t k) {
  if (left < k || left + k >= n) return left;
  return n / 2;
}

// The edge cell i of a profile (i < guard + n) has L = max(0, i - guard) cells on its left.
std::size_t left_cells(std::size_t cell, const CfarConfig& config) {
  return cell > config.guard_cells ? cell - config.guard_cells : 0;
}

// The config at training cells m: an explicit OS rank scaled to keep its place k / N.
CfarConfig with_training(const CfarConfig& config, std::size_t m) {
  CfarConfig result = config;
  result.training_cells = static_cast<unsigned>(m);
  if (config.kind == CfarKind::os && config.os_rank != 0) {
    const double place =
        static_cast<double>(config.os_rank) / static_cast<double>(config.reference_cells());
    result.os_rank = static_cast<unsigned>(std::clamp<double>(
        std::round(place * static_cast<double>(2 * m)), 1.0, static_cast<double>(2 * m)));
  }
  return result;
}

// Modelled CPU seconds of solving every distinct geometry of `config` (no anchor).
double solve_seconds(const CfarConfig& config, const NoiseCorrelation& noise, std::size_t k) {
  const std::size_t n = config.training_cells;
  const std::size_t big_n = config.reference_cells();
  const double geometries = static_cast<double>(n <= 2 * k + 1 ? n + 1 : 2 * k + 2);
  const double cells = static_cast<double>(big_n) + 1.0;
  // Per geometry ~12 symmetric eigenvalue solves of (N + 1)^2 (CA's factor, and for GO/SO/OS the
  // tilt factor and the quadratic tilts) and a fixed overhead.
  const double exact = geometries * (2.2e-5 + 12.0 * 3.8e-10 * cells * cells * cells);
  if (config.kind == CfarKind::ca) return exact;
  // Per sample: the reference vector and ~15 evaluations of the conditional tail: Marcum
  // evaluations where the cell under test is correlated with a reference cell (a lag in
  // [guard + 1, guard + N]), else the closed form e^-y.
  bool correlated_cut = false;
  for (std::size_t m = std::size_t{config.guard_cells} + 1;
       m <= config.guard_cells + big_n && m < noise.coefficients.size(); ++m)
    correlated_cut = correlated_cut || noise.coefficients[m] != 0.0;
  // The reference vector's products, averaged over the mixture's components (SampledPfa): the
  // noise itself one banded product (N x the band, at most N^2 / 2), each tilt a dense back
  // substitution (N^2 / 2) and the banded product, each quadratic tilt a dense product (N^2 / 2).
  const double n_cells = static_cast<double>(big_n);
  const double lags = static_cast<double>(noise.coefficients.size());
  const double banded = n_cells * std::min(lags, 0.5 * (n_cells + 1.0));
  const double dense = 0.5 * n_cells * n_cells;
  const double tilts = config.kind == CfarKind::so ? 2.0 : config.kind == CfarKind::os ? 3.0 : 1.0;
  const double quadratic = correlated_cut ? tilts : 0.0;
  const double products =
      (banded + tilts * (dense + banded) + quadratic * dense) / (1.0 + tilts + quadratic);
  const double per_sample = 0.75e-9 * products + (correlated_cut ? 0.7e-6 : 1.7e-7);
  return exact + geometries * static_cast<double>(kSamples) * per_sample;
}

// The training cells the design solves at (cfar_design.hpp): n itself when that fits the budget,
// else the largest m in [2 K + 1, n) that does (at least 2 K + 1, so that every kind of geometry
// exists at the anchor).
std::size_t anchor_training(const CfarConfig& config, const NoiseCorrelation& noise,
                            std::size_t k) {
  const std::size_t n = config.training_cells;
  const std::size_t least = std::min(n, 2 * k + 1);
  if (solve_seconds(config, noise, k) <= kCfarDesignBudgetSeconds) return n;
  // The modelled cost rises with m: bisection for the last m within the budget.
  std::size_t low = least, high = n;  // solve_seconds(high) > budget
  while (high - low > 1) {
    const std::size_t middle = low + (high - low) / 2;
    if (solve_seconds(with_training(config, middle), noise, k) <= kCfarDesignBudgetSeconds) {
      low = middle;
    } else {
      high = middle;
    }
  }
  return low;
}

// GO and SO take the larger or smaller of two half sums, each S/n = 1 + sigma xi with sigma^2 =
// c2/n, c2 = sum_m rho(m)^2 the variance per cell of a sum of correlated cells' powers (1 for
// independent cells): their mean shifts by +-sigma E[max(xi_1, xi_2)] = +-sigma / sqrt(pi) for
// independent standard normal xi. The factor that keeps the design P_fa scales inversely, so its
// ratio to the independent-cell factor carries -+(sqrt(c2) - 1) / sqrt(pi n) to first order, a
// 1/sqrt(n) term beside the 1/n ones the variance of the noise estimate brings (CA and OS: none).
double half_sum_bias_term(CfarKind kind, const NoiseCorrelation& noise) {
  if (kind != CfarKind::go && kind != CfarKind::so) return 0.0;
  // Over the lags of the structure (the first half of a circular correlation at most): the rest
  // is a floor below 2e-4 or the same lags again around the window.
  const std::size_t lags = std::min(kStructureLags, (noise.coefficients.size() - 1) / 2);
  double c2 = 1.0;
  for (std::size_t m = 1; m <= lags; ++m) c2 += 2.0 * noise.coefficients[m] * noise.coefficients[m];
  const double term = (std::sqrt(c2) - 1.0) / std::sqrt(std::numbers::pi);
  return kind == CfarKind::go ? -term : term;
}

bool designs_for_correlation(const CfarConfig& config, const NoiseCorrelation& noise) {
  return config.threshold_design == CfarThresholdDesign::correlated &&
         !white_within(noise, config.guard_cells + config.reference_cells());
}

}  // namespace

// Cells on each side of a structure point (the cell under test's window, the end of a block, the
// boundary of the GO/SO halves) within which two geometries must agree to share a factor: the
// largest lag with |rho| >= kReachCorrelation, plus one. A correlation that has not decayed beyond
// kStructureLags (the last kStructureLags lags aside: the DFT's correlation is circular, rho(m) =
// rho(L - m) for a window of L samples) shares nothing: every geometry is its own, at n.
std::size_t structure_cells(const NoiseCorrelation& noise) {
  const std::size_t size = noise.coefficients.size();
  std::size_t reach = 0;
  for (std::size_t m = 1; m < size; ++m) {
    if (std::abs(noise.coefficients[m]) < kReachCorrelation) continue;
    if (m > kStructureLags && m + kStructureLags < size) {
      return std::numeric_limits<std::size_t>::max() / 4;
    }
    if (m <= kStructureLags) reach = m;
  }
  return reach + 1;
}

std::size_t cfar_correlation_lags(const CfarConfig& config) {
  // The ring's columns span 2 (g + n) on either side of a clipped guard.
  const std::size_t span = config.shape == CfarShape::range
                               ? std::size_t{config.guard_cells} + config.reference_cells()
                               : 2 * (std::size_t{config.guard_cells} + config.training_cells);
  return std::min<std::size_t>(span, kCfarCorrelationLags);
}

std::size_t cfar_design_training_cells(const CfarConfig& config, const NoiseCorrelation& noise) {
  config.validate();
  noise.validate();
  if (!designs_for_correlation(config, noise)) return config.training_cells;
  return anchor_training(config, noise, structure_cells(noise));
}

CfarThresholdFactors design_cfar_threshold_factors(const CfarConfig& config,
                                                   const NoiseCorrelation& noise,
                                                   const StopToken& stop) {
  config.validate();
  noise.validate();
  const double independent = cfar_threshold_factor(config);
  const std::size_t n = config.training_cells;
  const std::size_t reach = std::size_t{config.guard_cells} + n;
  CfarThresholdFactors factors{independent, std::vector<double>(reach, independent)};
  if (!designs_for_correlation(config, noise)) return factors;
  const std::size_t k = structure_cells(noise);
  const std::size_t anchor = anchor_training(config, noise, k);
  const CfarConfig solved_config = with_training(config, anchor);
  const double solved_independent = cfar_threshold_factor(solved_config);
  const std::vector<std::complex<double>> draws =
      config.kind == CfarKind::ca
          ? std::vector<std::complex<double>>{}
          : standard_draws(solved_config.reference_cells(), kCfarDesignSeed);
  // The factor of the geometry with `left` cells on the left at the anchor, solved once.
  std::vector<std::pair<std::size_t, double>> solved;
  const auto solved_factor = [&](std::size_t left) {
    const std::size_t representative = solved_left(left, anchor, k);
    for (const auto& [known, factor] : solved) {
      if (known == representative) return factor;
    }
    const std::size_t cell =
        representative == 0 ? 0 : std::size_t{solved_config.guard_cells} + representative;
    const double factor =
        correlated_factor(solved_config, noise, cfar_reference_offsets(solved_config, cell),
                          solved_independent, draws, stop);
    solved.emplace_back(representative, factor);
    return factor;
  };
  // A geometry of n training cells takes its anchor twin's factor (the same cells near every
  // structure point) with its ratio r to the independent factor brought towards 1: r - 1 =
  // a / sqrt(n) + b / n, a the halves' term of GO/SO (0 for CA and OS), b from the anchor.
  const double half_sum_term = half_sum_bias_term(config.kind, noise);
  const auto factor_at = [&](std::size_t left) {
    if (anchor == n) return solved_factor(left);
    std::size_t twin = anchor / 2;
    if (left == n) {
      twin = anchor;
    } else if (left < k) {
      twin = left;
    } else if (left + k >= n) {
      twin = anchor - (n - left);
    }
    const double ratio = solved_factor(twin) / solved_independent;
    return independent * (1.0 + half_sum_term * (1.0 / std::sqrt(static_cast<double>(n))) +
                          (ratio - 1.0 - half_sum_term / std::sqrt(static_cast<double>(anchor))) *
                              static_cast<double>(anchor) / static_cast<double>(n));
  };
  factors.interior = factor_at(n);
  for (std::size_t i = 0; i < reach; ++i) factors.edge[i] = factor_at(left_cells(i, config));
  return factors;
}

double cfar_design_seconds(const CfarConfig& config, const NoiseCorrelation& noise) {
  if (!designs_for_correlation(config, noise)) return 0.0;
  const std::size_t k = structure_cells(noise);
  return solve_seconds(with_training(config, anchor_training(config, noise, k)), noise, k);
}

}  // namespace fogradar::radar
