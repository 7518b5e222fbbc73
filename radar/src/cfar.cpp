#include "fogradar/radar/cfar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "cfar_kernels.hpp"
#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/radar/cfar_design.hpp"

namespace fogradar::radar {

using cfar_kernels::append_cells_above;
using cfar_kernels::half_sums_rule;
using cfar_kernels::interleave_norms;
using cfar_kernels::reference_cells;
using cfar_kernels::ReferenceCells;
using cfar_kernels::two_sided_detect;
using cfar_kernels::two_sided_detect_four;
using cfar_kernels::window_sums;
using cfar_kernels::window_sums_four;

CfarDetector::CfarDetector(const CfarConfig& config) : CfarDetector(config, NoiseCorrelation{}) {}

CfarDetector::CfarDetector(const CfarConfig& config, const NoiseCorrelation& noise,
                           const StopToken& stop)
    : CfarDetector(config, noise, NoiseCorrelation{}, stop) {}

CfarDetector::CfarDetector(const CfarConfig& config, const NoiseCorrelation& range_noise,
                           const NoiseCorrelation& doppler_noise, const StopToken& stop)
    : config_(config) {
  CfarThresholdFactors factors =
      config.shape == CfarShape::range
          ? design_cfar_threshold_factors(config, range_noise, stop)
          : design_cfar_ring_threshold_factors(config, range_noise, doppler_noise, stop);
  alpha_ = factors.interior;
  edge_alpha_ = std::move(factors.edge);
  // The scale of the sums' thresholds: CA divides by N, GO/SO by n (the sums are of n cells).
  const double divisor = static_cast<double>(config.kind == CfarKind::ca ? config.reference_cells()
                                                                         : config.training_cells);
  edge_scale_.resize(edge_alpha_.size());
  for (std::size_t i = 0; i < edge_alpha_.size(); ++i) edge_scale_[i] = edge_alpha_[i] / divisor;
}

void CfarDetector::detect(std::span<const double> power, CfarWorkspace& workspace) const {
  FOGRADAR_CHECK(config_.shape == CfarShape::range);  // range_doppler: detect_map
  config_.validate_profile_length(power.size());
  const std::size_t length = power.size();
  const std::size_t guard = config_.guard_cells;
  const std::size_t n = config_.training_cells;
  const std::size_t big_n = 2 * n;
  const double alpha = alpha_;
  const std::size_t reach = guard + n;  // cells i < reach and i >= length - reach are edge cells

  workspace.threshold.resize(length);
  workspace.detections.clear();
  workspace.detections.reserve(length);

  if (config_.kind == CfarKind::os) {
    // OS: the N reference cells are kept sorted while the cell under test slides; each step
    // replaces the cells that left the reference set by those that entered (two in the
    // interior, one at the edges), O(N) instead of a selection per cell.
    // Threshold = alpha * k-th smallest.
    const std::size_t k = config_.effective_os_rank();
    std::vector<double>& sorted = workspace.order_scratch;
    sorted.resize(big_n);
    ReferenceCells r = reference_cells(0, length, guard, n);
    const auto first_right = std::copy(power.begin() + r.lb, power.begin() + r.le, sorted.begin());
    std::copy(power.begin() + r.rb, power.begin() + r.re, first_right);
    std::sort(sorted.begin(), sorted.end());
    // Replace one value of the sorted buffer by another: locate both by a branch-free binary
    // search (conditional moves, no mispredictions on noise data) and shift only the values
    // between the two positions.
    double* const data = sorted.data();
    const auto count_below = [data, big_n](double value) {
      const double* base = data;
      std::size_t count = big_n;
      while (count > 1) {
        const std::size_t half = count / 2;
        base = base[half] < value ? base + half : base;
        count -= half;
      }
      return static_cast<std::size_t>(base - data) + (*base < value ? 1 : 0);
    };
    const auto replace = [data, big_n, &count_below](double leaving, double entering) {
      const std::size_t out = count_below(leaving);
      std::size_t in = count_below(entering);
      FOGRADAR_CHECK(out < big_n && data[out] == leaving);  // power must not be NaN
      if (in <= out) {
        for (std::size_t j = out; j > in; --j) data[j] = data[j - 1];
        data[in] = entering;
      } else {
        --in;  // `leaving` sat below the insertion point
        for (std::size_t j = out; j < in; ++j) data[j] = data[j + 1];
        data[in] = entering;
      }
    };
    // Cells that left / entered the reference set between two consecutive cells under test: set
    // differences of the left ranges and of the right ranges (a cell never moves between the
    // two). At most one per range end, and as many leave as enter (the set keeps N cells).
    std::array<std::size_t, 4> leaving{};
    std::array<std::size_t, 4> entering{};
    std::size_t leaving_count = 0;
    std::size_t entering_count = 0;
    const auto collect = [](std::array<std::size_t, 4>& into, std::size_t& count, std::size_t begin,
                            std::size_t end) {
      for (std::size_t j = begin; j < end; ++j) {
        FOGRADAR_CHECK(count < into.size());
        into[count++] = j;
      }
    };
    const auto alpha_at = [&](std::size_t i) {
      if (i < reach) return edge_alpha_[i];
      return i >= length - reach ? edge_alpha_[length - 1 - i] : alpha;
    };
    workspace.threshold[0] = alpha_at(0) * sorted[k - 1];
    for (std::size_t i = 1; i < length; ++i) {
      const ReferenceCells next = reference_cells(i, length, guard, n);
      leaving_count = 0;
      entering_count = 0;
      collect(leaving, leaving_count, r.lb, std::min(r.le, next.lb));
      collect(leaving, leaving_count, std::max(r.lb, next.le), r.le);
      collect(leaving, leaving_count, r.rb, std::min(r.re, next.rb));
      collect(leaving, leaving_count, std::max(r.rb, next.re), r.re);
      collect(entering, entering_count, next.lb, std::min(next.le, r.lb));
      collect(entering, entering_count, std::max(next.lb, r.le), next.le);
      collect(entering, entering_count, next.rb, std::min(next.re, r.rb));
      collect(entering, entering_count, std::max(next.rb, r.re), next.re);
      FOGRADAR_CHECK(leaving_count == entering_count);
      for (std::size_t m = 0; m < leaving_count; ++m) {
        replace(power[leaving[m]], power[entering[m]]);
      }
      workspace.threshold[i] = alpha_at(i) * sorted[k - 1];
      r = next;
    }
    append_cells_above(power.data(), workspace.threshold.data(), length, workspace.detections);
  } else {
    const std::span<const double> sums =
        window_sums(power, n, workspace.window_sums, workspace.sum_scratch);
    // CA divides by N, GO/SO by n (the sums are of n cells).
    const double scale = alpha / static_cast<double>(config_.kind == CfarKind::ca ? big_n : n);
    two_sided_detect(power, guard, n, scale, edge_scale_, sums, half_sums_rule(config_.kind),
                     workspace.threshold, workspace.detections);
  }
}

void CfarDetector::detect_four(std::span<const std::complex<double>> rows,
                               CfarFourWorkspace& workspace) const {
  constexpr std::size_t profiles = CfarFourWorkspace::profiles;
  FOGRADAR_CHECK(rows.size() % profiles == 0);
  const std::size_t length = rows.size() / profiles;
  FOGRADAR_CHECK(config_.shape == CfarShape::range);  // range_doppler: detect_map
  config_.validate_profile_length(length);
  workspace.power.resize(profiles * length);
  workspace.pairs.resize(profiles * (length - 1));  // length >= 3 (validated)
  interleave_norms(rows.data(), length, workspace.power.data(), workspace.pairs.data());
  workspace.threshold.resize(profiles * length);
  for (std::vector<std::size_t>& cells : workspace.detections) {
    cells.clear();
    cells.reserve(length);
  }
  if (config_.kind == CfarKind::os) {
    // The sorted window moves differently in every profile: one at a time.
    std::vector<double>& profile = workspace.window_sums;
    profile.resize(length);
    for (std::size_t r = 0; r < profiles; ++r) {
      for (std::size_t j = 0; j < length; ++j) profile[j] = workspace.power[profiles * j + r];
      detect(profile, workspace.one);
      for (std::size_t j = 0; j < length; ++j)
        workspace.threshold[profiles * j + r] = workspace.one.threshold[j];
      workspace.detections[r] = workspace.one.detections;
    }
    return;
  }
  const std::size_t n = config_.training_cells;
  const std::span<const double> sums =
      window_sums_four(workspace.power, n, workspace.pairs, workspace.window_sums);
  const double scale = alpha_ / static_cast<double>(config_.kind == CfarKind::ca ? 2 * n : n);
  two_sided_detect_four(workspace.power.data(), length, config_.guard_cells, n, scale,
                        edge_scale_.data(), sums.data(), half_sums_rule(config_.kind),
                        workspace.threshold.data(), workspace.detections);
}

std::vector<std::size_t> cfar_detect(std::span<const double> power, const CfarConfig& config,
                                     std::vector<double>* threshold_out) {
  const CfarDetector detector(config);
  CfarWorkspace workspace;
  detector.detect(power, workspace);
  if (threshold_out != nullptr) *threshold_out = std::move(workspace.threshold);
  return std::move(workspace.detections);
}

}  // namespace fogradar::radar
