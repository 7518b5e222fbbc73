// Two error channels (docs/architecture.md, Conventions): bad user input throws InvalidParameter
// naming the field and the allowed range; broken invariants (programmer errors) go through
// FOGRADAR_CHECK.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fogradar {

// Where a refused value was given: a text the user wrote (a scenario or sweep file, "<scenario>")
// and its line there. Empty for a value set in code or on the command line; line 0 where the
// text has no one line for it.
struct InputLocation {
  std::string source;
  std::size_t line = 0;

  bool empty() const noexcept { return source.empty(); }
};

// Bad input: a parameter outside its allowed range. `field()` names it ("Fog.lwc_g_per_m3",
// "--frequency-ghz", "radar.centre_frequency_hz"), `message()` says what is wrong with it, and
// `location()` where it was given; `what()` is the full one-line message,
// "<source>:<line>: <message>" where there is a location.
class InvalidParameter : public std::invalid_argument {
 public:
  InvalidParameter(std::string field, const std::string& message, InputLocation location = {});
  const std::string& field() const noexcept { return field_; }
  const std::string& message() const noexcept { return message_; }
  const InputLocation& location() const noexcept { return location_; }

 private:
  std::string field_;
  std::string message_;
  InputLocation location_;
};

// `text` with every key name under section `from` ("radar.", at the start of a name: not after a
// letter, digit, '_' or '.') moved under `to` ("radar_24."): a second sensor of a kind states its
// keys, written for the kind's own section, under its own.
std::string with_section_renamed(std::string_view text, std::string_view from, std::string_view to);
// `e` with its field and message so renamed, its location kept.
InvalidParameter with_section_renamed(const InvalidParameter& e, std::string_view from,
                                      std::string_view to);

// A number as bad-input messages write it: ten significant digits, "1e+09"; NaN and the
// infinities as TOML and the command line spell them ("nan", "inf", "-inf"), not as a stream does.
std::string message_number(double value);

// Throws InvalidParameter "<field> = <value>: must be <constraint>" (e.g. "> 0", "in [0, 50]").
[[noreturn]] void throw_invalid(std::string_view field, double value, std::string_view constraint);
[[noreturn]] void throw_invalid(std::string_view field, std::string_view value,
                                std::string_view constraint);

// Validation helpers used by every parameter struct's validate(). NaN fails every check.
void require_finite(std::string_view field, double value);
void require_positive(std::string_view field, double value);
void require_non_negative(std::string_view field, double value);
void require_in_range(std::string_view field, double value, double low, double high);

// Invariant violated inside fogradar itself: a bug, not bad input.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

[[noreturn]] void check_failed(const char* condition, const char* file, int line);

}  // namespace fogradar

#define FOGRADAR_CHECK(condition) \
  ((condition) ? static_cast<void>(0) : ::fogradar::check_failed(#condition, __FILE__, __LINE__))
