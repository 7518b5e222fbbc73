// Checks of option values as typed, run by CLI11 before it converts them: CLI11 turns an empty
// string into 0 or the default and reports a failed conversion without the allowed range, so each
// numeric option is parsed here in full and refused with fogradar::InvalidParameter naming the
// option, the text typed and the allowed range (main() maps it to exit status 2).
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/core/keys.hpp"

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

// A key's range (Key::range, in the key's unit) in the unit of an option that sets the key to
// option x `key_per_option_unit`.
inline Interval option_range(Interval key_range, double key_per_option_unit) {
  const double option_per_key_unit = 1.0 / key_per_option_unit;
  key_range.low *= option_per_key_unit;
  key_range.high *= option_per_key_unit;
  return key_range;
}

// A key's range in an option's unit as a message states it after "must be ": "in [0.001, 1e7]"
// (the numbers as the help and docs/scenario.md write them), "finite and > 0".
inline std::string option_constraint(Interval key_range, double key_per_option_unit = 1.0) {
  const Interval range = option_range(key_range, key_per_option_unit);
  return std::isinf(range.high) ? range.constraint() : "in " + range.doc();
}

// A number option that sets a scenario key to option x `key_per_option_unit`: the key's own range
// decides, in the key's unit, as it does for the scenario; the message states it in the option's
// unit, followed by `rule` (a bound other options set).
inline CLI::Validator key_number(std::string option, Interval key_range,
                                 double key_per_option_unit = 1.0, std::string rule = "") {
  const std::string constraint = option_constraint(key_range, key_per_option_unit) + rule;
  return CLI::Validator(
      [option, key_range, key_per_option_unit, constraint](const std::string& text) {
        const std::optional<double> value = parse_whole<double>(text);
        if (!value || !key_range.contains(*value * key_per_option_unit)) {
          throw_invalid(option, text, constraint);
        }
        return std::string();
      },
      "", "");
}

// A word option that takes one of `names`.
inline CLI::Validator one_of(std::string option, std::vector<std::string> names) {
  return CLI::Validator(
      [option, names](const std::string& text) {
        if (std::find(names.begin(), names.end(), text) == names.end()) {
          std::string allowed;
          for (const std::string& name : names) {
            allowed += allowed.empty() ? "one of '" : ", '";
            allowed += name;
            allowed += "'";
          }
          throw_invalid(option, text, allowed);
        }
        return std::string();
      },
      "", "");
}

// A bound as a message states it, six significant digits rounded inward (down for an upper
// bound), so that the number shown is itself allowed.
inline std::string bound_text(double bound, bool upper) {
  const double unit = std::pow(10.0, std::floor(std::log10(std::abs(bound))) - 5.0);
  std::ostringstream text;
  text << std::setprecision(6)
       << (upper ? std::floor(bound / unit) : std::ceil(bound / unit)) * unit;
  return text.str();
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
