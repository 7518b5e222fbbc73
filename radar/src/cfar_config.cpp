// The CFAR's names and configuration: its keys, the checks of a configuration against a profile,
// and the reference cells a cell under test reads.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "cfar_kernels.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/radar/cfar.hpp"

namespace fogradar::radar {

std::vector<std::ptrdiff_t> cfar_reference_offsets(const CfarConfig& config,
                                                   std::size_t cells_from_end) {
  config.validate();
  const std::size_t guard = config.guard_cells;
  const std::size_t n = config.training_cells;
  const std::size_t i = std::min(cells_from_end, guard + n);
  // A profile long enough that cell i has its full window on the right.
  const cfar_kernels::ReferenceCells r =
      cfar_kernels::reference_cells(i, i + guard + 2 * n + 1, guard, n);
  std::vector<std::ptrdiff_t> offsets;
  const auto cell = static_cast<std::ptrdiff_t>(i);
  for (std::size_t j = r.lb; j < r.le; ++j)
    offsets.push_back(static_cast<std::ptrdiff_t>(j) - cell);
  for (std::size_t j = r.rb; j < r.re; ++j)
    offsets.push_back(static_cast<std::ptrdiff_t>(j) - cell);
  return offsets;
}

std::size_t CfarConfig::shape_reference_cells() const noexcept {
  if (shape == CfarShape::range) return reference_cells();
  const std::size_t g = guard_cells, n = training_cells;
  const std::size_t gd = doppler_guard_cells, nd = doppler_training_cells;
  return 2 * n * (2 * (gd + nd) + 1) + 2 * nd * (2 * g + 1);
}

unsigned CfarConfig::effective_os_rank() const noexcept {
  if (os_rank != 0) return os_rank;
  // round(3N/4): (3N + 2) / 4 in integers, at least 1.
  const std::uint64_t big_n = shape_reference_cells();
  return static_cast<unsigned>(std::max<std::uint64_t>(1, (3 * big_n + 2) / 4));
}

KeyTable<CfarConfig> cfar_keys(std::string prefix) {
  KeyTable<CfarConfig> keys(prefix);
  keys.choice("kind", FOGRADAR_KEY_FIELD(kind), cfar_kind_names, "CFAR detector");
  keys.integer("guard_cells", FOGRADAR_KEY_FIELD(guard_cells), 0, 32766, "per side");
  keys.integer("training_cells", FOGRADAR_KEY_FIELD(training_cells), 1, 32767, "per side");
  keys.number("false_alarm_probability", FOGRADAR_KEY_FIELD(false_alarm_probability),
              open(0.0, 1.0), "design P_fa");
  keys.integer("os_rank", FOGRADAR_KEY_FIELD(os_rank), 0, 65534, "OS rank k; 0 = round(3/4 · N)")
      .within([prefix](const CfarConfig& c) { return c.os_rank_bound(prefix); })
      .documented_as("integer 0 or [1, N] (N = 2·training, or the ring's cells)")
      .when([](const CfarConfig& c) { return c.kind == CfarKind::os; },
            "with " + prefix + "kind = \"os\" (the other kinds average their cells)");
  keys.choice("threshold_design", FOGRADAR_KEY_FIELD(threshold_design), cfar_threshold_design_names,
              "threshold factors solved for the noise cells as the range window (and for "
              "range_doppler the Doppler window) correlates them, "
              "so the realised P_fa is the design value (one factor for the interior cells and "
              "one per edge position; docs/radar.md §7); `independent` = the textbook iid factor, "
              "whose realised P_fa with a tapered window is higher (Hann: 2.2× at 1e-3, 10× at "
              "1e-6 for CA)");
  keys.choice("shape", FOGRADAR_KEY_FIELD(shape), cfar_shape_names,
              "reference cells along range in each Doppler row, or `range_doppler`: a ring over "
              "the range-Doppler map, guard and training cells in both dimensions (docs/radar.md "
              "§7.1)");
  const auto ring = [](const CfarConfig& c) { return c.shape == CfarShape::range_doppler; };
  const std::string ring_text = "with " + prefix + "shape = \"range_doppler\"";
  keys.integer("doppler_guard_cells", FOGRADAR_KEY_FIELD(doppler_guard_cells), 0, 32766,
               "Doppler rows per side inside the ring's guard (default 1)")
      .when(ring, ring_text);
  keys.integer("doppler_training_cells", FOGRADAR_KEY_FIELD(doppler_training_cells), 0, 32766,
               "Doppler rows per side of the ring's training cells (default 2; 0 with 0 guard "
               "rows: the range CFAR)")
      .within([prefix](const CfarConfig& c) { return c.ring_size_bound(prefix); })
      .documented_as("integer ≥ 0, with the ring at most 512 cells")
      .when(ring, ring_text);
  return keys;
}

void CfarConfig::validate() const { cfar_keys("cfar.").check(*this); }

namespace {

// 2 (guard + training) + 1 <= L: the guard and training cells per side that fit in L cells.
std::size_t cells_per_side(std::size_t profile_length) {
  return profile_length >= 1 ? (profile_length - 1) / 2 : 0;
}

const char* const window_rule = " (2 (guard + training) + 1 <= profile length)";
const char* const doppler_rule =
    " (2 (doppler guard + doppler training) + 1 <= Doppler rows - 1: distinct rows around the "
    "circular Doppler axis, fewer than all, whose noise a tapered window's zero end sample makes "
    "linearly dependent)";

}  // namespace

CrossBound CfarConfig::training_bound(std::size_t profile_length, std::string_view prefix,
                                      std::string_view profile) const {
  const double most =
      static_cast<double>(cells_per_side(profile_length)) - static_cast<double>(guard_cells);
  return CrossBound{.range = closed(1.0, most),
                    .low_text = "1",
                    .high_text = message_number(most),
                    .integer = true,
                    .note = " with " + std::string(prefix) +
                            "guard_cells = " + std::to_string(guard_cells) + " and " +
                            std::string(profile) + window_rule};
}

CrossBound CfarConfig::guard_bound(std::size_t profile_length, std::string_view prefix,
                                   std::string_view profile) const {
  const std::size_t usable = cells_per_side(profile_length);
  // Guard cells that leave room for one training cell are in range here; training_bound() then
  // names the training cells that do not fit beside them.
  const double most = guard_cells < usable
                          ? static_cast<double>(usable - 1)
                          : static_cast<double>(usable) - static_cast<double>(training_cells);
  return CrossBound{.range = closed(0.0, most),
                    .low_text = "0",
                    .high_text = message_number(most),
                    .integer = true,
                    .note = " with " + std::string(prefix) +
                            "training_cells = " + std::to_string(training_cells) + " and " +
                            std::string(profile) + window_rule};
}

CrossBound CfarConfig::os_rank_bound(std::string_view prefix) const {
  const auto big_n = static_cast<double>(shape_reference_cells());
  return CrossBound{
      .range = closed(0.0, big_n),
      .low_text = "0",
      .high_text = shape == CfarShape::range
                       ? "2 x " + std::string(prefix) + "training_cells = " + message_number(big_n)
                       : "the ring's reference cells N = " + message_number(big_n),
      .integer = true,
      .note = " (0: the default rank round(3N/4))"};
}

void CfarConfig::validate_profile_length(std::size_t profile_length,
                                         std::string_view prefix) const {
  // The detector checks every profile: the messages are made only for a window that does not fit.
  if (profile_length >= window_length()) return;
  const std::string profile = "a profile of " + std::to_string(profile_length) + " cells";
  const CrossBound guard = guard_bound(profile_length, prefix, profile);
  if (!guard.admits(guard_cells)) {
    throw_invalid(std::string(prefix) + "guard_cells", guard_cells, guard.constraint());
  }
  const CrossBound training = training_bound(profile_length, prefix, profile);
  if (!training.admits(training_cells)) {
    throw_invalid(std::string(prefix) + "training_cells", training_cells, training.constraint());
  }
}

CrossBound CfarConfig::doppler_training_bound(std::size_t rows, std::string_view prefix,
                                              std::string_view map) const {
  const double most = static_cast<double>(cells_per_side(rows > 0 ? rows - 1 : 0)) -
                      static_cast<double>(doppler_guard_cells);
  return CrossBound{.range = closed(0.0, most),
                    .low_text = "0",
                    .high_text = message_number(most),
                    .integer = true,
                    .note = " with " + std::string(prefix) +
                            "doppler_guard_cells = " + std::to_string(doppler_guard_cells) +
                            " and " + std::string(map) + doppler_rule};
}

CrossBound CfarConfig::doppler_guard_bound(std::size_t rows, std::string_view prefix,
                                           std::string_view map) const {
  const std::size_t usable = cells_per_side(rows > 0 ? rows - 1 : 0);
  const double most =
      doppler_guard_cells <= usable
          ? static_cast<double>(usable)
          : static_cast<double>(usable) - static_cast<double>(doppler_training_cells);
  return CrossBound{.range = closed(0.0, most),
                    .low_text = "0",
                    .high_text = message_number(most),
                    .integer = true,
                    .note = " with " + std::string(prefix) +
                            "doppler_training_cells = " + std::to_string(doppler_training_cells) +
                            " and " + std::string(map) + doppler_rule};
}

CrossBound CfarConfig::ring_size_bound(std::string_view prefix) const {
  // N = 2 n (2 g_d + 1) + n_d (4 n + 4 g + 2) <= kCfarRingMaxCells.
  const double fixed = 2.0 * training_cells * (2.0 * doppler_guard_cells + 1.0);
  const double per_row = 4.0 * training_cells + 4.0 * guard_cells + 2.0;
  const double most = std::floor((static_cast<double>(kCfarRingMaxCells) - fixed) / per_row);
  return CrossBound{
      .range = closed(0.0, most),
      .low_text = "0",
      .high_text = message_number(most),
      .integer = true,
      .note = " with " + std::string(prefix) + "guard_cells = " + std::to_string(guard_cells) +
              ", " + std::string(prefix) + "training_cells = " + std::to_string(training_cells) +
              " and " + std::string(prefix) + "doppler_guard_cells = " +
              std::to_string(doppler_guard_cells) + " (the ring's N = 2 n (2 (g_d + " +
              "n_d) + 1) + 2 n_d (2 g + 1) at most " + std::to_string(kCfarRingMaxCells) + ")"};
}

void CfarConfig::validate_map_rows(std::size_t rows, std::string_view prefix) const {
  if (shape != CfarShape::range_doppler ||
      rows >= 2 * (std::size_t{doppler_guard_cells} + doppler_training_cells) + 2)
    return;
  const std::string map = "a map of " + std::to_string(rows) + " Doppler rows";
  const CrossBound guard = doppler_guard_bound(rows, prefix, map);
  if (!guard.admits(doppler_guard_cells)) {
    throw_invalid(std::string(prefix) + "doppler_guard_cells", doppler_guard_cells,
                  guard.constraint());
  }
  const CrossBound training = doppler_training_bound(rows, prefix, map);
  throw_invalid(std::string(prefix) + "doppler_training_cells", doppler_training_cells,
                training.constraint());
}

}  // namespace fogradar::radar
