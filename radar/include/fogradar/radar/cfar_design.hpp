// Threshold factors of a CFAR detector for the noise cells a detector really sees: circular complex
// Gaussian cells correlated by the range window (noise_correlation.hpp), not the independent cells
// of the textbook formulas in cfar.hpp. With the default Hann window the independent-cell factor
// gives 2.2 x the design P_fa at 1e-3 and 10 x at 1e-6 for CA (docs/radar.md §7).
//
// The cell under test x0 = |Y0|^2 and its N reference cells x_j = |Y_j|^2 (Y ~ CN(0, R), R_ij =
// rho(p_i - p_j) for the cells' positions p) give, per kind:
//   CA  exact. Detection is q = |Y0|^2 - (alpha/N) sum_j |Y_j|^2 > 0, a Hermitian quadratic form
//       Y^H Q Y, Q = diag(1, -a, ..., -a), a = alpha/N. With lambda_i the eigenvalues of
//       L^T Q L (R = L L^T; the eigenvalues of R Q), q has the law of sum_i lambda_i E_i with E_i
//       iid Exp(1) (characteristic function prod_i 1/(1 - i w lambda_i): Turin 1960, Biometrika 47,
//       199-201). Q has one positive eigenvalue, so (Sylvester's law of inertia) has L^T Q L:
//       lambda_1 > 0 >= the rest, and
//         P_fa = P(lambda_1 E_1 > sum_{i>1} |lambda_i| E_i) = E[exp(-sum_{i>1} |lambda_i| E_i /
//         lambda_1)]
//              = prod_{i>1} 1 / (1 + |lambda_i| / lambda_1),
//       repeated eigenvalues included. For a cell under test uncorrelated with its reference cells
//       this is 1 / det(I + a C), C the reference cells' correlation matrix.
//   GO, SO, OS  no closed form for sums' maxima/minima or order statistics of correlated cells:
//       the reference vector is sampled and the cell under test's conditional tail integrated
//       exactly. Given the reference cells r, Y0 ~ CN(mu, s^2) with mu = l^T u, s the last diagonal
//       entry of the Cholesky factor of R ordered (reference cells, cell under test), so
//         P(x0 > alpha Z | r) = Q_1(sqrt(2 lambda), sqrt(2 y)),  lambda = |mu|^2/s^2, y = alpha
//         Z/s^2,
//       (Marcum Q: for lambda < 10 the Poisson mixture of gamma tails
//       sum_j e^-lambda lambda^j/j! e^-y sum_{i<=j} y^i/i!, all terms positive; from 10 on the
//       second-order saddlepoint approximation, log_marcum_q1_tail). The mean over r uses
//       importance sampling from a defensive mixture (Hesterberg 1995, Technometrics 37(2),
//       185-194; balance-heuristic weights, Veach & Guibas 1995): the noise itself and
//       exponentially tilted versions of it that make the cells of the noise estimate small
//       (all cells for GO and OS, each half for SO) and, where the cell under test is correlated
//       with its reference cells, for each of those the tilt of |Y0|^2 - a sum |Y_j|^2 at its
//       Chernoff exponent, 2^14 samples of a fixed seed (the same samples for every alpha, so the
//       estimate is smooth and decreasing in alpha). Its relative standard error, measured over
//       independent seeds, is stated in docs/radar.md §7.
// Every cell's factor is solved for its own reference geometry: the interior cells share one; the
// edge cells (edge policy in cfar.hpp) have one-sided or shifted reference windows; the cells i and
// L-1-i from the two ends are mirror images (rho even) and share a factor. A geometry is fixed by
// the number L of its reference cells on the left of the cell under test; geometries whose L and
// n - L both reach K cells (K = the correlation's reach + 1) hold the same cells near the cell
// under test, the ends of their blocks and the halves' boundary, and share one solved factor. The
// design's cost is bounded: where solving at n training cells would take more than
// kCfarDesignBudgetSeconds (cfar_design_seconds' model), the geometries are solved at the anchor m
// < n, the largest within the budget (and at least 2 K + 1), and each geometry at n takes its
// anchor twin's factor (same L near the ends, the shared middle one, the interior) with its ratio r
// to the independent-cell factor brought towards 1: r_n - 1 = a / sqrt(n) + b / n, with b such that
// r_m is the anchor's. The correlation changes the noise estimate's variance (and its covariance
// with the cell under test) by O(1/N) of its mean, hence the 1/n term; GO and SO take the larger or
// smaller of two half sums whose mean the correlation shifts by O(1/sqrt(n)), a = -+(sqrt(c2) - 1)
// / sqrt(pi), c2 = sum_m rho(m)^2 (0 for CA and OS). docs/radar.md §7 gives the measured error of
// the scaling against full designs.
// All arithmetic is scalar or Eigen at the x86-64 baseline with fixed sample counts and seed: the
// same factors in every process, for every thread count and instruction-set clone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fogradar/core/stop.hpp"
#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/noise_correlation.hpp"

namespace fogradar::radar {

struct CfarThresholdFactors {
  double interior = 0.0;
  // edge[i]: the cells i and L-1-i (i < guard + training) of a profile of L cells.
  std::vector<double> edge;
};

// Positions of the reference cells relative to the cell under test of a cell `cells_from_end` cells
// from a profile end (0 = first cell; >= guard + training: an interior cell), in range order.
std::vector<std::ptrdiff_t> cfar_reference_offsets(const CfarConfig& config,
                                                   std::size_t cells_from_end);

// How correlated_false_alarm_probability evaluates: CA exactly and the others by sampling
// (automatic), or every kind by sampling (to test the sampled method against the exact ones).
enum class CorrelatedPfaMethod { automatic, sampled };

// The seed of the design's samples.
inline constexpr std::uint64_t kCfarDesignSeed = 0xCFA2D351C0FFEEULL;

// A cell of a range-Doppler map relative to the cell under test: range cells, Doppler rows.
struct CfarCellOffset {
  std::ptrdiff_t range = 0;
  std::ptrdiff_t doppler = 0;
  bool operator==(const CfarCellOffset&) const = default;
};

// The range_doppler ring's reference cells of a cell `cells_from_end` range cells from a profile
// end (>= guard + training: an interior cell), in the order whose first and second halves are GO's
// and SO's: by range cell, then by Doppler row. Along range the window follows the range shape's
// edge policy (its 2 n reference columns carry every row of the window, its guard columns, clipped,
// the Doppler training rows); the rows wrap. In the interior the halves are the cells before and
// after the cell under test, the cell's own column split between them by Doppler sign.
std::vector<CfarCellOffset> cfar_ring_offsets(const CfarConfig& config, std::size_t cells_from_end);

// The config whose independent-cell formulas are the ring's of `reference_cells` cells (even): the
// range shape with reference_cells / 2 training cells per side and the OS rank kept at its place
// k / N of the interior ring (0 stays the default round(3N/4)).
CfarConfig cfar_ring_equivalent(const CfarConfig& config, std::size_t reference_cells);

// The range_doppler shape's factors (interior; edge[i] for the cells i and L-1-i along range) for
// noise correlated along range by `range_noise` (the range window's) and along Doppler by
// `doppler_noise` (the Doppler window's), the cells' correlation their product: per distinct
// geometry CA's exact factor, the others' from the sampled P_fa, as for range. Geometries share a
// factor as for range where the range correlation's reach K allows it: the ring's cells at L and L'
// range columns left of the guard, both at least K from every block end and from the column where
// the halves split, differ only in far columns. No anchor: the ring is at most kCfarRingMaxCells.
// `independent` or white noise in both dimensions: the independent-cell factor of each geometry's
// N.
CfarThresholdFactors design_cfar_ring_threshold_factors(const CfarConfig& config,
                                                        const NoiseCorrelation& range_noise,
                                                        const NoiseCorrelation& doppler_noise,
                                                        const StopToken& stop = StopToken());

// P_fa of one geometry of cells anywhere on the map (cfar_ring_offsets; `config` the equivalent
// config of their count) at factor alpha, as correlated_false_alarm_probability.
double correlated_cell_false_alarm_probability(
    const CfarConfig& config, const NoiseCorrelation& range_noise,
    const NoiseCorrelation& doppler_noise, std::span<const CfarCellOffset> offsets, double alpha,
    CorrelatedPfaMethod method = CorrelatedPfaMethod::automatic,
    std::uint64_t seed = kCfarDesignSeed);

// The CPU seconds design_cfar_ring_threshold_factors takes (a cost model for the run-time
// estimate, as cfar_design_seconds): 0 where the independent-cell factors serve.
double cfar_ring_design_seconds(const CfarConfig& config, const NoiseCorrelation& range_noise,
                                const NoiseCorrelation& doppler_noise);

// The Doppler correlation lags a ring design reads: 2 (doppler guard + doppler training).
std::size_t cfar_doppler_correlation_lags(const CfarConfig& config);

// P_fa of the config's detector at factor alpha >= 0 for a cell with the reference cells at
// `offsets` (from cfar_reference_offsets) in noise correlated by `noise` (method in the header
// comment; the sampling mixture is tilted for this alpha, its samples drawn from `seed`'s stream).
// Validates the config.
double correlated_false_alarm_probability(
    const CfarConfig& config, const NoiseCorrelation& noise,
    std::span<const std::ptrdiff_t> offsets, double alpha,
    CorrelatedPfaMethod method = CorrelatedPfaMethod::automatic,
    std::uint64_t seed = kCfarDesignSeed);

// log P(|Y0|^2 > y s^2) for Y0 ~ CN(mu, s^2), lambda = |mu|^2 / s^2 >= 0, y >= 0: log Marcum
// Q_1(sqrt(2 lambda), sqrt(2 y)), the cell under test's conditional tail of the sampled method
// (exact series for lambda < 10, second-order saddlepoint approximation from 10 on).
double log_marcum_q1_tail(double lambda, double y);

// The modelled CPU seconds beyond which the design solves at an anchor of fewer training cells
// (header comment).
inline constexpr double kCfarDesignBudgetSeconds = 0.2;

// Correlation lags a design reads: guard + N, at most kCfarCorrelationLags. Beyond it the
// coefficients are taken as 0: they are, exactly, for every window of the chain but Chebyshev,
// whose flat floor (from the spikes at its ends) stays below 2e-4 at 80 dB up to 65536 samples
// (1.9e-4 there; the anchor's geometries need at most guard + 174 lags). So
// window_noise_correlation costs at most kCfarCorrelationLags x the window's length (~0.05 s at
// 65536 samples).
inline constexpr std::size_t kCfarCorrelationLags = 256;
std::size_t cfar_correlation_lags(const CfarConfig& config);

// The training cells per side the design solves its geometries at: config.training_cells, or the
// anchor of fewer cells where that would exceed the budget (header comment).
std::size_t cfar_design_training_cells(const CfarConfig& config, const NoiseCorrelation& noise);

// The factors that give the design P_fa in every cell: the independent-cell factor of
// cfar_threshold_factor everywhere when config.threshold_design is `independent` or the noise is
// white (then exact for all kinds), else solved per reference geometry (header comment). Looks at
// `stop` before every sample it draws and every evaluation of a P_fa, and throws Stopped when it is
// asked for.
CfarThresholdFactors design_cfar_threshold_factors(const CfarConfig& config,
                                                   const NoiseCorrelation& noise,
                                                   const StopToken& stop = StopToken());

// The CPU seconds design_cfar_threshold_factors takes for this config and noise, a cost model for
// the run-time estimate and the anchor (on the project's shared 2-core machine, Release, the
// measured CPU time is 0.52-1.7 x the model for n = 4-64, g = 0 and 2, every window, GO/SO/OS;
// docs/radar.md §7): 0 where the iid factors serve; per solved geometry (at most 2 K + 2) CA's
// eigenvalue solves, ~12 x (N + 1)^3, and for GO/SO/OS 2^14 samples x (the reference vector's
// products, N^2 / 2 per tilted component and N x the correlation's band for the noise itself, + ~15
// conditional tails, Marcum evaluations where the cell under test is correlated with a reference
// cell), at the anchor's N. At most kCfarDesignBudgetSeconds unless the anchor's floor 2 K + 1
// needs more (not for the chain's windows).
double cfar_design_seconds(const CfarConfig& config, const NoiseCorrelation& noise);

}  // namespace fogradar::radar
