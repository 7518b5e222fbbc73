// The CFAR's names and configuration: its keys, the checks of a configuration against a profile,
// and the reference cells a cell under test reads.
#include <algorithm>
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

unsigned CfarConfig::effective_os_rank() const noexcept {
  if (os_rank != 0) return os_rank;
  // round(3N/4), N = 2 n: (3N + 2) / 4 in integers, at least 1.
  const std::uint64_t big_n = 2ULL * training_cells;
  return static_cast<unsigned>(std::max<std::uint64_t>(1, (3 * big_n + 2) / 4));
}

KeyTable<CfarConfig> cfar_keys(std::string prefix) {
  KeyTable<CfarConfig> keys(prefix);
  keys.choice("kind", FOGRADAR_KEY_FIELD(kind), cfar_kind_names, "CFAR detector");
  keys.integer("guard_cells", FOGRADAR_KEY_FIELD(guard_cells), 0, 32766, "per side");
  keys.integer("training_cells", FOGRADAR_KEY_FIELD(training_cells), 1, 32767, "per side");
  keys.number("false_alarm_probability", FOGRADAR_KEY_FIELD(false_alarm_probability),
              open(0.0, 1.0), "design P_fa");
  const std::string rank_key = prefix + "os_rank", training_key = prefix + "training_cells";
  keys.integer("os_rank", FOGRADAR_KEY_FIELD(os_rank), 0, 65534,
               "OS rank k; 0 = round(3/4 · 2·training)")
      .also([training_key](const CfarConfig& c) {
        return "and 0 or at most 2 x " + training_key + " = " + std::to_string(c.reference_cells());
      })
      .with_check([rank_key, training_key](const CfarConfig& c) {
        const std::size_t big_n = c.reference_cells();
        if (c.os_rank > big_n) {
          throw_invalid(rank_key, c.os_rank,
                        "0 (default round(3N/4)) or in [1, " + std::to_string(big_n) +
                            "] (N = 2 x " + training_key + ")");
        }
      })
      .documented_as("integer 0 or [1, 2·training]")
      .when([](const CfarConfig& c) { return c.kind == CfarKind::os; },
            "with " + prefix + "kind = \"os\" (the other kinds average their cells)");
  keys.choice("threshold_design", FOGRADAR_KEY_FIELD(threshold_design), cfar_threshold_design_names,
              "threshold factors solved for the noise cells as the range window correlates them, "
              "so the realised P_fa is the design value (one factor for the interior cells and "
              "one per edge position; docs/radar.md §7); `independent` = the textbook iid factor, "
              "whose realised P_fa with a tapered window is higher (Hann: 2.2× at 1e-3, 10× at "
              "1e-6 for CA)");
  return keys;
}

void CfarConfig::validate() const { cfar_keys("cfar.").check(*this); }

void CfarConfig::validate_profile_length(std::size_t profile_length,
                                         std::string_view prefix) const {
  if (profile_length >= window_length()) return;
  const std::string guard_key = std::string(prefix) + "guard_cells",
                    training_key = std::string(prefix) + "training_cells";
  // Largest guard + n with 2 (guard + n) + 1 <= profile_length.
  const std::size_t usable = profile_length >= 1 ? (profile_length - 1) / 2 : 0;
  const std::string rule = " (2 (guard + training) + 1 <= profile length)";
  const std::string profile =
      "a profile of radar.samples_per_chirp = " + std::to_string(profile_length) + " cells";
  if (usable > guard_cells) {
    throw_invalid(training_key, training_cells,
                  "in [1, " + std::to_string(usable - guard_cells) + "] with " + guard_key + " = " +
                      std::to_string(guard_cells) + " and " + profile + rule);
  }
  // The guard cells alone fill the profile: they are what must shrink.
  const std::string constraint =
      usable > training_cells
          ? "in [0, " + std::to_string(usable - training_cells) + "] with " + training_key + " = " +
                std::to_string(training_cells) + " and " + profile + rule
          : "smaller: with " + training_key + " = " + std::to_string(training_cells) +
                " not even 0 guard cells fit in " + profile + rule;
  throw_invalid(guard_key, guard_cells, constraint);
}

}  // namespace fogradar::radar
