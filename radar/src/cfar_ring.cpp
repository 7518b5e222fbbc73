// The range_doppler CFAR (cfar.hpp): its ring of reference cells, its threshold design for noise
// correlated along range and Doppler, and its detection over a range-Doppler map.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "cfar_correlated.hpp"
#include "cfar_kernels.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/cfar_design.hpp"

namespace fogradar::radar {

namespace {

// The ring's columns of the cell at range `cell` of a profile of `length` cells: the range shape's
// reference ranges [lb, le) and [rb, re), every row of the window, and between them the guard
// columns [le, rb) (the cell's own among them), the Doppler training rows only.
cfar_kernels::ReferenceCells ring_columns(std::size_t cell, std::size_t length,
                                          const CfarConfig& config) {
  return cfar_kernels::reference_cells(cell, length, config.guard_cells, config.training_cells);
}

// Calls visit(column, row offset) for the ring's cells in their order (by column, then by row).
template <class Visit>
void for_each_ring_cell(const cfar_kernels::ReferenceCells& r, const CfarConfig& config,
                        Visit&& visit) {
  const auto outer = static_cast<std::ptrdiff_t>(config.doppler_guard_cells) +
                     static_cast<std::ptrdiff_t>(config.doppler_training_cells);
  const auto inner = static_cast<std::ptrdiff_t>(config.doppler_guard_cells);
  const auto full_column = [&](std::size_t column) {
    for (std::ptrdiff_t row = -outer; row <= outer; ++row) visit(column, row);
  };
  for (std::size_t column = r.lb; column < r.le; ++column) full_column(column);
  for (std::size_t column = r.le; column < r.rb; ++column) {
    for (std::ptrdiff_t row = -outer; row < -inner; ++row) visit(column, row);
    for (std::ptrdiff_t row = inner + 1; row <= outer; ++row) visit(column, row);
  }
  for (std::size_t column = r.rb; column < r.re; ++column) full_column(column);
}

bool designs_for_correlation(const CfarConfig& config, const NoiseCorrelation& range_noise,
                             const NoiseCorrelation& doppler_noise) {
  return config.threshold_design == CfarThresholdDesign::correlated &&
         !(white_within(range_noise,
                        2 * (std::size_t{config.guard_cells} + config.training_cells)) &&
           white_within(doppler_noise, cfar_doppler_correlation_lags(config)));
}

// The range position whose geometry the cell `i` cells from the end shares (header of
// design_cfar_ring_threshold_factors): cells with their guard clipped and the interior are their
// own; the others, with L = i - g reference columns on the left, share with L' = n / 2 (or the
// smallest L') whose geometry has every structure point as far from the rest.
std::size_t representative(std::size_t i, const CfarConfig& config, std::size_t k) {
  const std::size_t g = config.guard_cells, n = config.training_cells;
  if (i <= g || i >= g + n) return std::min(i, g + n);
  const std::size_t height =
      2 * (std::size_t{config.doppler_guard_cells} + config.doppler_training_cells) + 1;
  const std::size_t guard_cells = 2 * std::size_t{config.doppler_training_cells} * (2 * g + 1);
  const auto shares = [&](std::size_t left) {
    if (left < k || left + k >= n) return false;
    if (config.kind != CfarKind::go && config.kind != CfarKind::so) return true;
    // The halves split in the right block, `split` full columns in; its columns beyond: 2n - L.
    const std::size_t before = left * height + guard_cells;
    const std::size_t half = n * height + guard_cells / 2;
    if (before > half) return false;
    const std::size_t split = (half - before) / height;
    return split >= k && split + k <= 2 * n - left;
  };
  if (!shares(i - g)) return i;
  if (shares(n / 2)) return g + n / 2;  // the range shape's choice (cfar_design.cpp)
  for (std::size_t left = 1; left < n; ++left) {
    if (shares(left)) return g + left;
  }
  return i;
}

}  // namespace

std::size_t cfar_doppler_correlation_lags(const CfarConfig& config) {
  return 2 * (std::size_t{config.doppler_guard_cells} + config.doppler_training_cells);
}

std::vector<CfarCellOffset> cfar_ring_offsets(const CfarConfig& config,
                                              std::size_t cells_from_end) {
  config.validate();
  const std::size_t g = config.guard_cells, n = config.training_cells;
  const std::size_t i = std::min(cells_from_end, g + n);
  const cfar_kernels::ReferenceCells r = ring_columns(i, i + g + 2 * n + 1, config);
  std::vector<CfarCellOffset> offsets;
  for_each_ring_cell(r, config, [&](std::size_t column, std::ptrdiff_t row) {
    offsets.push_back({static_cast<std::ptrdiff_t>(column) - static_cast<std::ptrdiff_t>(i), row});
  });
  return offsets;
}

CfarConfig cfar_ring_equivalent(const CfarConfig& config, std::size_t reference_cells) {
  FOGRADAR_CHECK(reference_cells >= 2 && reference_cells % 2 == 0);
  CfarConfig result = config;
  result.shape = CfarShape::range;
  result.guard_cells = 0;
  result.training_cells = static_cast<unsigned>(reference_cells / 2);
  if (config.kind == CfarKind::os && config.os_rank != 0) {
    const double place =
        static_cast<double>(config.os_rank) / static_cast<double>(config.shape_reference_cells());
    result.os_rank = static_cast<unsigned>(
        std::clamp<double>(std::round(place * static_cast<double>(reference_cells)), 1.0,
                           static_cast<double>(reference_cells)));
  }
  return result;
}

CfarThresholdFactors design_cfar_ring_threshold_factors(const CfarConfig& config,
                                                        const NoiseCorrelation& range_noise,
                                                        const NoiseCorrelation& doppler_noise,
                                                        const StopToken& stop) {
  config.validate();
  range_noise.validate();
  doppler_noise.validate();
  FOGRADAR_CHECK(config.shape == CfarShape::range_doppler);
  const std::size_t reach = std::size_t{config.guard_cells} + config.training_cells;
  const bool correlated = designs_for_correlation(config, range_noise, doppler_noise);
  const std::size_t k = structure_cells(range_noise);
  const CellNoise noise{range_noise, doppler_noise};
  std::map<std::size_t, std::vector<std::complex<double>>> draws;  // by the geometry's N
  std::map<std::size_t, double> solved;                            // by representative position
  const auto factor_at = [&](std::size_t i) {
    const std::size_t position = correlated ? representative(i, config, k) : i;
    if (const auto known = solved.find(position); known != solved.end()) return known->second;
    const std::vector<CfarCellOffset> offsets = cfar_ring_offsets(config, position);
    const CfarConfig equivalent = cfar_ring_equivalent(config, offsets.size());
    double factor = cfar_threshold_factor(equivalent);
    if (correlated) {
      auto found = draws.find(offsets.size());
      if (found == draws.end() && config.kind != CfarKind::ca) {
        found =
            draws.emplace(offsets.size(), standard_draws(offsets.size(), kCfarDesignSeed)).first;
      }
      factor = correlated_factor(equivalent, noise, offsets, factor,
                                 found == draws.end()
                                     ? std::span<const std::complex<double>>{}
                                     : std::span<const std::complex<double>>(found->second),
                                 stop);
    }
    solved.emplace(position, factor);
    return factor;
  };
  CfarThresholdFactors factors;
  factors.interior = factor_at(reach);
  factors.edge.resize(reach);
  for (std::size_t i = 0; i < reach; ++i) factors.edge[i] = factor_at(i);
  return factors;
}

double cfar_ring_design_seconds(const CfarConfig& config, const NoiseCorrelation& range_noise,
                                const NoiseCorrelation& doppler_noise) {
  if (!designs_for_correlation(config, range_noise, doppler_noise)) return 0.0;
  const std::size_t k = structure_cells(range_noise);
  std::vector<std::size_t> positions;
  for (std::size_t i = 0; i <= std::size_t{config.guard_cells} + config.training_cells; ++i)
    positions.push_back(representative(i, config, k));
  std::sort(positions.begin(), positions.end());
  const auto geometries =
      static_cast<double>(std::unique(positions.begin(), positions.end()) - positions.begin());
  const auto cells = static_cast<double>(config.shape_reference_cells());
  // Per geometry: CA's eigenvalue solves, ~12 x (N + 1)^3, as for the range shape; the sampled
  // kinds' reference vectors, dense products of N^2 per sample (the ring's Cholesky factor is not
  // banded). Measured (Release, the shared 2-core machine, Hann in both dimensions, N = 132-468):
  // 0.5-1.2 x this for the sampled kinds, 0.3-0.6 x for CA.
  const double exact =
      geometries * (2.2e-5 + 12.0 * 3.8e-10 * (cells + 1.0) * (cells + 1.0) * (cells + 1.0));
  if (config.kind == CfarKind::ca) return exact;
  return exact + geometries * static_cast<double>(kSamples) * 0.3e-9 * cells * cells;
}

void CfarDetector::detect_map(std::span<const double> power, std::size_t rows,
                              CfarMapWorkspace& workspace) const {
  FOGRADAR_CHECK(config_.shape == CfarShape::range_doppler);
  FOGRADAR_CHECK(rows > 0 && power.size() % rows == 0);
  const std::size_t columns = power.size() / rows;
  // Fewer columns than the profile's (the ring reaches every row of them; a tapered window's zero
  // end sample makes the noise of all of them linearly dependent).
  config_.validate_profile_length(columns > 0 ? columns - 1 : 0);
  config_.validate_map_rows(rows);
  const std::size_t reach = std::size_t{config_.guard_cells} + config_.training_cells;
  workspace.threshold.resize(power.size());
  workspace.detections.clear();
  for (std::size_t k = 0; k < columns; ++k) {
    const std::size_t from_end = std::min(k, columns - 1 - k);
    const double alpha = from_end < reach ? edge_alpha_[from_end] : alpha_;
    const cfar_kernels::ReferenceCells r = ring_columns(k, columns, config_);
    std::size_t big_n = 0;
    for_each_ring_cell(r, config_, [&](std::size_t, std::ptrdiff_t) { ++big_n; });
    const std::size_t half = big_n / 2;
    const unsigned rank =
        config_.kind == CfarKind::os ? cfar_ring_equivalent(config_, big_n).effective_os_rank() : 0;
    for (std::size_t d = 0; d < rows; ++d) {
      workspace.cells.clear();
      for_each_ring_cell(r, config_, [&](std::size_t column, std::ptrdiff_t row) {
        const auto at =
            static_cast<std::size_t>(static_cast<std::ptrdiff_t>(d + rows) + row) % rows;
        workspace.cells.push_back(power[at * columns + column]);
      });
      double estimate = 0.0;
      if (config_.kind == CfarKind::os) {
        const auto kth = workspace.cells.begin() + (rank - 1);
        std::nth_element(workspace.cells.begin(), kth, workspace.cells.end());
        estimate = *kth;
      } else {
        double first = 0.0, second = 0.0;
        for (std::size_t j = 0; j < half; ++j) first += workspace.cells[j];
        for (std::size_t j = half; j < big_n; ++j) second += workspace.cells[j];
        estimate = config_.kind == CfarKind::ca ? (first + second) / static_cast<double>(big_n)
                   : config_.kind == CfarKind::go
                       ? std::max(first, second) / static_cast<double>(half)
                       : std::min(first, second) / static_cast<double>(half);
      }
      workspace.threshold[d * columns + k] = alpha * estimate;
    }
  }
  for (std::size_t cell = 0; cell < power.size(); ++cell) {
    if (power[cell] > workspace.threshold[cell]) workspace.detections.push_back(cell);
  }
}

}  // namespace fogradar::radar
