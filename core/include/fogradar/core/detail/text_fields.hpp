// Reading the shipped data tables (data/): fields split off a line, numbers parsed exactly as
// written. A malformed table is a broken installation, not bad user input: FOGRADAR_CHECK.
#pragma once

#include <charconv>
#include <string_view>
#include <system_error>

#include "fogradar/core/error.hpp"

namespace fogradar::detail {

// Splits off the text up to `separator`; the remainder follows it (or is empty).
inline std::string_view take_field(std::string_view& text, char separator) {
  const std::size_t end = text.find(separator);
  const std::string_view field = text.substr(0, end);
  text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
  return field;
}

// The whole field as one number (std::from_chars: locale-independent, correctly rounded).
inline double parse_number(std::string_view field) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  FOGRADAR_CHECK(error == std::errc() && end == field.data() + field.size());
  return value;
}

}  // namespace fogradar::detail
