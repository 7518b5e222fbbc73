// One-dimensional CFAR detection on a square-law (power) profile: CA, GO, SO and OS, with the
// threshold factor set from a design false-alarm probability for exponential (square-law
// detected complex Gaussian) noise. The formulas below hold for independent cells; a detector
// given the noise correlation of its profile (CfarDetector(config, noise)) solves its factors for
// the correlated cells instead (cfar_design.hpp) unless the config asks for `independent`.
//
// Conventions (all four kinds): N = 2 * training_cells reference cells, n = training_cells per
// side, noise level estimate Z, threshold = alpha * Z, detection when power > threshold.
//   CA  Z = (1/N) sum of all N reference cells
//       Pfa = (1 + alpha/N)^(-N)  =>  alpha = N (Pfa^(-1/N) - 1)          (closed form)
//   GO  Z = max(S_lead, S_lag) / n,  S = sum of the n cells on one side
//   SO  Z = min(S_lead, S_lag) / n
//       with t = alpha / n (Gandhi & Kassam 1988, IEEE TAES 24(4) 427-445, eqs. for GO/SO;
//       Richards, Fundamentals of Radar Signal Processing, 2nd ed., §6.5.5):
//       Pfa_SO = 2 sum_{k=0}^{n-1} C(n-1+k, k) (2+t)^-(n+k)
//       Pfa_GO = 2 (1+t)^-n - Pfa_SO
//   OS  Z = x_(k), the k-th smallest of the N reference cells
//       Pfa = prod_{i=0}^{k-1} (N-i) / (N-i+alpha)          (Rohling 1983, IEEE TAES 19(4))
// GO, SO and OS are solved for alpha numerically (Boost.Math TOMS 748 on log Pfa).
//
// EDGE POLICY (cells whose nominal window [i-g-n, i+g+n] leaves the profile): the guard cells
// stay centred on the cell under test (clipped at the profile end) and the training window
// slides inward: the side that runs out of cells contributes what it has, the other side
// contributes the remainder, taken contiguously beyond its own n cells. Every cell therefore
// keeps exactly N = 2n training cells, disjoint from the cell under test and its guard cells.
// For GO and SO the "two halves" are the first n and the last n of those N cells in range
// order (in the interior exactly the leading and lagging windows).
// What holds: in homogeneous iid exponential noise the reference cells of every cell, edge or
// interior, are N iid samples independent of the cell under test, so the design Pfa holds
// exactly for all four kinds in every cell. In correlated noise the edge cells' reference windows
// (one-sided, contiguous) have other correlations than the interior's: the correlated design gives
// each its own factor (cfar_design.hpp). What changes at the edges: the reference cells
// are not centred on the cell under test, so in non-homogeneous backgrounds (clutter edges,
// a strong target near the profile end) edge cells behave like a one-sided CFAR, and GO/SO no
// longer compare "leading vs lagging" side of the cell under test.
// Requirement: profile length >= 2 (guard + training) + 1, the full window; shorter profiles
// are rejected with InvalidParameter naming "cfar.training_cells" and its allowed range.
//
// SHAPE range_doppler (CfarDetector::detect_map, cfar_ring.cpp): the reference cells of cell (d, k)
// of a range-Doppler map are a ring, the window's rectangle of 2 (guard + training) + 1 range cells
// by 2 (doppler_guard + doppler_training) + 1 Doppler rows less the guard rectangle around the
// cell. Along range the window follows the edge policy above; along Doppler it wraps (the Doppler
// axis is circular). With doppler_guard = doppler_training = 0 it is the range CFAR of every row.
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/keys.hpp"
#include "fogradar/core/stop.hpp"
#include "fogradar/radar/noise_correlation.hpp"

namespace fogradar::radar {

enum class CfarKind { ca, go, so, os };

// The reference cells: along range in each Doppler row, or a ring over the range-Doppler map.
enum class CfarShape { range, range_doppler };

// How the threshold factor is designed: for the correlated noise cells the detector is given
// (cfar_design.hpp), or with the independent-cell formulas below whatever the correlation.
enum class CfarThresholdDesign { correlated, independent };

inline constexpr auto cfar_kind_names = enum_names<CfarKind>(
    {{CfarKind::ca, "ca"}, {CfarKind::go, "go"}, {CfarKind::so, "so"}, {CfarKind::os, "os"}});
inline constexpr auto cfar_threshold_design_names =
    enum_names<CfarThresholdDesign>({{CfarThresholdDesign::correlated, "correlated"},
                                     {CfarThresholdDesign::independent, "independent"}});
inline constexpr auto cfar_shape_names = enum_names<CfarShape>(
    {{CfarShape::range, "range"}, {CfarShape::range_doppler, "range_doppler"}});
constexpr std::string_view to_string(CfarKind kind) noexcept { return cfar_kind_names.name(kind); }
constexpr std::string_view to_string(CfarShape shape) noexcept {
  return cfar_shape_names.name(shape);
}
constexpr std::string_view to_string(CfarThresholdDesign design) noexcept {
  return cfar_threshold_design_names.name(design);
}

struct CfarConfig {
  CfarKind kind = CfarKind::ca;
  unsigned guard_cells = 2;               // per side, excluded from the noise estimate
  unsigned training_cells = 8;            // per side, n >= 1; N = 2 n reference cells in total
  double false_alarm_probability = 1e-6;  // design Pfa in (0, 1)
  unsigned os_rank = 0;  // OS: k in [1, N]; 0 selects the default k = round(3N/4) (Rohling 1983)
  CfarThresholdDesign threshold_design = CfarThresholdDesign::correlated;
  CfarShape shape = CfarShape::range;
  unsigned doppler_guard_cells = 1;     // range_doppler: Doppler rows per side inside the guard
  unsigned doppler_training_cells = 2;  // range_doppler: Doppler rows per side of training, >= 0

  // Throws InvalidParameter naming the key of cfar_keys("cfar.") it breaks: "cfar.training_cells"
  // (in [1, 32767]), "cfar.false_alarm_probability" (in (0, 1)), "cfar.os_rank" (0 or in [1, N]).
  void validate() const;
  // The bounds a profile of `profile_length` cells sets on the window, 2 (guard + training) + 1 <=
  // profile_length, under the keys' `prefix`; `profile` names the profile in messages ("a profile
  // of radar.samples_per_chirp = 512 cells"). The training cells take the blame while the guard
  // cells leave room for one: guard_bound() refuses only guard cells that alone fill the profile.
  CrossBound training_bound(std::size_t profile_length, std::string_view prefix,
                            std::string_view profile) const;
  CrossBound guard_bound(std::size_t profile_length, std::string_view prefix,
                         std::string_view profile) const;
  // The OS rank's bound the training cells set: 0 (the default rank) or at most N (2 n, or the
  // ring's cells for range_doppler).
  CrossBound os_rank_bound(std::string_view prefix) const;
  // range_doppler: the Doppler rows' bound a map of `rows` rows sets, 2 (doppler_guard +
  // doppler_training) + 1 <= rows - 1 (distinct rows around the circular Doppler axis, and fewer
  // than all: a tapered window's zero end sample makes the noise of all rows linearly dependent, so
  // that the design's correlation matrix would be singular), blaming the training rows (guard rows:
  // as guard_bound); the range cells' bounds are training_bound's and guard_bound's for a profile
  // one cell shorter, for the same reason; and the ring's size bound, at most
  // kCfarRingMaxCells reference cells (its threshold design's cost grows as N^2 to N^3).
  CrossBound doppler_training_bound(std::size_t rows, std::string_view prefix,
                                    std::string_view map) const;
  CrossBound doppler_guard_bound(std::size_t rows, std::string_view prefix,
                                 std::string_view map) const;
  CrossBound ring_size_bound(std::string_view prefix) const;
  // Throws InvalidParameter naming "<prefix>guard_cells" or "<prefix>training_cells" with the bound
  // above that a profile of `profile_length` cells breaks.
  void validate_profile_length(std::size_t profile_length, std::string_view prefix = "cfar.") const;
  // range_doppler: throws InvalidParameter naming "<prefix>doppler_guard_cells" or
  // "<prefix>doppler_training_cells" with the bound a map of `rows` Doppler rows breaks.
  void validate_map_rows(std::size_t rows, std::string_view prefix = "cfar.") const;

  std::size_t reference_cells() const noexcept { return 2 * std::size_t{training_cells}; }
  // The reference cells of an interior cell: 2 n for range, the ring's for range_doppler,
  // 2 n (2 (g_d + n_d) + 1) + 2 n_d (2 g + 1).
  std::size_t shape_reference_cells() const noexcept;
  std::size_t window_length() const noexcept {
    return 2 * (std::size_t{guard_cells} + training_cells) + 1;
  }
  // The rank k used by OS: os_rank, or round(3N/4) (at least 1) when os_rank == 0.
  unsigned effective_os_rank() const noexcept;
};

// The most reference cells a range_doppler ring may have.
inline constexpr std::size_t kCfarRingMaxCells = 512;

// The scenario keys of a CFAR under `prefix` ("radar.processing.cfar."): kind, guard and training
// cells per side, design P_fa, OS rank, threshold design, shape and the Doppler guard and training
// rows.
KeyTable<CfarConfig> cfar_keys(std::string prefix);

// Threshold factor alpha for the config's kind, N and design Pfa for independent cells (see the
// header comment for the conventions and formulas). Validates the config.
double cfar_threshold_factor(const CfarConfig& config);

// Pfa of the config's detector at threshold factor alpha >= 0 in homogeneous iid exponential noise
// (the inverse of cfar_threshold_factor; false_alarm_probability is not read). GO is evaluated
// as the positive series 2 sum_{j>=n} C(n-1+j, j) (2+t)^-(n+j) (equal to the published form,
// without its cancellation).
double cfar_false_alarm_probability(const CfarConfig& config, double alpha);

// Reusable per-thread buffers for CfarDetector::detect.
struct CfarWorkspace {
  std::vector<double> threshold;        // threshold per cell (same length as the profile)
  std::vector<std::size_t> detections;  // indices of cells with power > threshold, ascending
  std::vector<double> order_scratch;    // OS: the N reference cells, sorted
  std::vector<double> window_sums;      // CA/GO/SO: sums of every training_cells consecutive cells
  std::vector<double> sum_scratch;  // CA/GO/SO: block sums while forming window_sums (2 profiles)
};

// The |X|^2 profiles of four rows of one length side by side, for CfarDetector::detect_four: cell j
// of profile r at index 4 j + r, so that each lane of a four-lane vector works on one profile (all
// buffers but `one` and `detections` are interleaved so). Reusable per-thread buffers like
// CfarWorkspace.
struct CfarFourWorkspace {
  static constexpr std::size_t profiles = 4;
  std::vector<double> power;      // the four profiles |X|^2, interleaved
  std::vector<double> threshold;  // threshold per cell, interleaved as power
  std::array<std::vector<std::size_t>, profiles> detections;  // per profile, ascending
  std::vector<double> pairs;        // sums of 2, then 4, 8, ... adjacent cells (in place)
  std::vector<double> window_sums;  // CA/GO/SO: sums of training_cells adjacent cells
  CfarWorkspace one;                // OS: one profile at a time
};

// Reusable per-thread buffers for CfarDetector::detect_map.
struct CfarMapWorkspace {
  std::vector<double> threshold;        // threshold per cell of the map (its layout)
  std::vector<std::size_t> detections;  // map indices d * columns + k above it, ascending
  std::vector<double> cells;            // one cell's reference cells
};

// A validated configuration with its threshold factors solved once: the hot-path object.
// Immutable after construction, so one detector may be shared by many threads, each with its
// own CfarWorkspace.
class CfarDetector {
 public:
  // For profiles of independent cells (white noise): the formulas above, exact for every kind.
  explicit CfarDetector(const CfarConfig& config);
  // For profiles whose noise cells are correlated as `noise` says (window_noise_correlation of the
  // range window for a range profile): the factors of design_cfar_threshold_factors, one for the
  // interior cells and one per edge position (range_doppler: the constructor below with white
  // Doppler rows). Validates both. Throws Stopped when `stop` is asked for during the design.
  CfarDetector(const CfarConfig& config, const NoiseCorrelation& noise,
               const StopToken& stop = StopToken());
  // For either shape: range the constructor above (doppler_noise unread); range_doppler the ring's
  // factors for cells correlated along range by `range_noise` (the range window's) and along
  // Doppler by `doppler_noise` (the Doppler window's, window_noise_correlation of it to lag
  // cfar_doppler_correlation_lags) (design_cfar_ring_threshold_factors).
  CfarDetector(const CfarConfig& config, const NoiseCorrelation& range_noise,
               const NoiseCorrelation& doppler_noise, const StopToken& stop = StopToken());

  const CfarConfig& config() const noexcept { return config_; }
  // The interior cells' factor.
  double threshold_factor() const noexcept { return alpha_; }
  // The factor of the cells i and L-1-i of a profile of L cells, i < guard + training.
  double edge_threshold_factor(std::size_t i) const noexcept { return edge_alpha_[i]; }

  // Thresholds and detections for one profile into `workspace` (resized to the profile,
  // so no allocation once it has served a profile at least this long). CA/GO/SO read sums of
  // training_cells consecutive cells, formed by doubling in O(log n) per cell from non-negative
  // terms only (relative error < (2 log2 n + 1) eps, whatever the profile's dynamic range); OS
  // keeps the N reference cells sorted while the window slides (binary search + O(N) moves per
  // cell, about 10x faster than a selection per cell). `power` must be finite and non-negative
  // (square-law detected). Throws InvalidParameter via validate_profile_length.
  void detect(std::span<const double> power, CfarWorkspace& workspace) const;
  // Square-law detection and CFAR of four consecutive rows of `rows` (rows.size() / 4 values each):
  // workspace.power[4 j + r] = |rows[r L + j]|^2 (re^2 + im^2, as std::norm), then detect for each
  // of the four profiles, with the same bits: every threshold and detection of profile r is what
  // detect gives for it alone (each vector lane makes the operations detect makes on one profile,
  // in the same order). The edge cells, summed cell by cell, cost a quarter per profile, and |X|^2
  // forms the window sums' first pass while it is in registers. Throws as detect.
  void detect_four(std::span<const std::complex<double>> rows, CfarFourWorkspace& workspace) const;
  // range_doppler: thresholds and detections of a map of |Y|^2 (`rows` Doppler rows of
  // power.size() / rows range cells, row-major) into `workspace`. Each cell's ring is added cell by
  // cell (O(N) per cell; OS: a selection, std::nth_element), every sum of non-negative values.
  // Throws InvalidParameter via validate_profile_length and validate_map_rows.
  void detect_map(std::span<const double> power, std::size_t rows,
                  CfarMapWorkspace& workspace) const;

 private:
  CfarConfig config_;
  double alpha_;
  std::vector<double> edge_alpha_;  // guard + training factors
  std::vector<double> edge_scale_;  // edge_alpha_ / N (CA) or / n (GO, SO): the sums' scale
};

// Convenience form: indices of detected cells (ascending); optionally the threshold per cell.
std::vector<std::size_t> cfar_detect(std::span<const double> power, const CfarConfig& config,
                                     std::vector<double>* threshold_out = nullptr);

}  // namespace fogradar::radar
