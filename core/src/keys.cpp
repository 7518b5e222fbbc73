#include "fogradar/core/keys.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

namespace fogradar {

bool CrossBound::empty() const {
  if (!integer) {
    return range.low > range.high ||
           (range.low == range.high && (range.low_open || range.high_open));
  }
  // The least and greatest integers inside.
  double least = std::ceil(range.low);
  if (range.low_open && least == range.low) least += 1.0;
  double greatest = std::floor(range.high);
  if (range.high_open && greatest == range.high) greatest -= 1.0;
  return least > greatest;
}

std::string CrossBound::constraint() const {
  if (!empty()) {
    return std::string(integer ? "an integer in " : "in ") + (range.low_open ? "(" : "[") +
           low_text + ", " + high_text + (range.high_open ? ")" : "]") + note;
  }
  const std::string kind = integer ? "integer" : "number";
  std::string text = integer ? "an " : "a ";
  text += kind;
  text += range.low_open ? " > " : " >= ";
  text += low_text;
  text += range.high_open ? " and < " : " and <= ";
  text += high_text;
  text += note;
  text += "; no " + kind + " is both: the keys named leave it no value";
  return text;
}

bool Interval::contains(double value) const {
  if (!std::isfinite(value)) return false;
  const bool above = low_open ? value > low : value >= low;
  const bool below = high_open ? value < high : value <= high;
  return above && below;
}

std::string Interval::constraint() const {
  if (std::isinf(high)) {
    return "finite and " + std::string(low_open ? "> " : ">= ") + message_number(low);
  }
  return "in " + std::string(low_open ? "(" : "[") + message_number(low) + ", " +
         message_number(high) + (high_open ? ")" : "]");
}

std::string Interval::doc() const {
  if (std::isinf(high)) return std::string(low_open ? "> " : "≥ ") + doc_number(low);
  return std::string(low_open ? "(" : "[") + doc_number(low) + ", " + doc_number(high) +
         (high_open ? ")" : "]");
}

Interval closed(double low, double high) { return {.low = low, .high = high}; }
Interval open_closed(double low, double high) {
  return {.low = low, .high = high, .low_open = true};
}
Interval open(double low, double high) {
  return {.low = low, .high = high, .low_open = true, .high_open = true};
}
Interval positive() {
  return {.low = 0.0, .high = std::numeric_limits<double>::infinity(), .low_open = true};
}

std::string doc_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent.front() == '-';
  if (exponent.front() == '+' || negative) exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

}  // namespace fogradar
