// Checks of option values as typed, run by CLI11 before it converts them: CLI11 turns an empty
// string into 0 or the default and reports a failed conversion without the allowed range, so each
// numeric option is parsed here in full and refused with fogradar::InvalidParameter naming the
// option, the text typed and the allowed range (main() maps it to exit status 2).
#pragma once

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>

#include "fogradar/core/error.hpp"

namespace fogradar::cli {

// The whole text as one number (no sign-only, blank or trailing text), or nothing.
template <class Number>
std::optional<Number> parse_whole(const std::string& text) {
  Number value{};
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc{} || ptr != end) return std::nullopt;
  return value;
}

// An integer option in [low, high].
inline CLI::Validator integer_in(std::string option, std::int64_t low, std::int64_t high) {
  return CLI::Validator(
      [option, low, high](const std::string& text) {
        const std::optional<std::int64_t> value = parse_whole<std::int64_t>(text);
        if (!value || *value < low || *value > high) {
          throw_invalid(
              option, text,
              "an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
        }
        return std::string();
      },
      "", "");
}

// A number option in [low, high]; `range` states it as the help text does (units, exceptions).
inline CLI::Validator number_in(std::string option, double low, double high, std::string range) {
  return CLI::Validator(
      [option, low, high, range](const std::string& text) {
        const std::optional<double> value = parse_whole<double>(text);
        if (!value || !(*value >= low && *value <= high)) throw_invalid(option, text, range);
        return std::string();
      },
      "", "");
}

// A path option: any text but the empty one.
inline CLI::Validator non_empty_path(std::string option) {
  return CLI::Validator(
      [option](const std::string& text) {
        if (text.empty()) throw_invalid(option, text, "a path (not empty)");
        return std::string();
      },
      "", "");
}

// Keeps the text an option was typed as in `typed`, for a message that refuses its value after the
// parse (a bound that depends on other options).
inline CLI::Validator keep_text(std::string* typed) {
  return CLI::Validator(
      [typed](const std::string& text) {
        *typed = text;
        return std::string();
      },
      "", "");
}

}  // namespace fogradar::cli
