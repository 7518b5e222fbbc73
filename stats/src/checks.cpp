#include <algorithm>
#include <cmath>
#include <string>

#include "detail.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::stats::detail {

namespace {

std::string element_name(std::string_view field, std::size_t index) {
  return std::string(field) + "[" + std::to_string(index) + "]";
}

std::string value_text(double v) { return std::isnan(v) ? "nan" : format_number(v); }

}  // namespace

void require_finite_values(std::string_view field, std::span<const double> values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InvalidParameter(
          std::string(field),
          element_name(field, i) + " = " + value_text(values[i]) + ": must be a finite number");
    }
  }
}

void require_min_size(std::string_view field, std::span<const double> values,
                      std::size_t min_size) {
  if (values.size() < min_size) {
    throw InvalidParameter(std::string(field),
                           std::string(field) + " has " + std::to_string(values.size()) +
                               " values: must have at least " + std::to_string(min_size));
  }
}

void require_sorted_sample(std::string_view field, std::span<const double> sorted) {
  require_min_size(field, sorted, 1);
  require_finite_values(field, sorted);
  const auto unsorted = std::is_sorted_until(sorted.begin(), sorted.end());
  if (unsorted != sorted.end()) {
    const auto i = static_cast<std::size_t>(unsorted - sorted.begin());
    throw InvalidParameter(std::string(field), element_name(field, i) + " = " +
                                                   value_text(sorted[i]) +
                                                   ": must be sorted ascending (>= previous " +
                                                   value_text(sorted[i - 1]) + ")");
  }
}

void require_confidence(double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw_invalid("confidence", confidence, "in (0, 1)");
  }
}

std::vector<double> sorted_copy(std::span<const double> values) {
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

}  // namespace fogradar::stats::detail
