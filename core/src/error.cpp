#include "fogradar/core/error.hpp"

#include <cctype>
#include <cmath>
#include <sstream>
#include <string>

namespace fogradar {

namespace {

std::string located(const std::string& message, const InputLocation& location) {
  if (location.empty()) return message;
  std::string text = location.source;
  if (location.line != 0) {
    text.push_back(':');
    text.append(std::to_string(location.line));
  }
  text.append(": ");
  text.append(message);
  return text;
}

}  // namespace

InvalidParameter::InvalidParameter(std::string field, const std::string& message,
                                   InputLocation location)
    : std::invalid_argument(located(message, location)),
      field_(std::move(field)),
      message_(message),
      location_(std::move(location)) {}

std::string with_section_renamed(std::string_view text, std::string_view from,
                                 std::string_view to) {
  const auto name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.';
  };
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const bool starts_name = i == 0 || !name_char(text[i - 1]);
    // A name follows the section's dot: "radar. " ends a sentence, "radar.x" names a key.
    if (starts_name && text.substr(i).starts_with(from) && i + from.size() < text.size() &&
        std::isalpha(static_cast<unsigned char>(text[i + from.size()])) != 0) {
      out += to;
      i += from.size();
    } else {
      out += text[i++];
    }
  }
  return out;
}

InvalidParameter with_section_renamed(const InvalidParameter& e, std::string_view from,
                                      std::string_view to) {
  return InvalidParameter(with_section_renamed(e.field(), from, to),
                          with_section_renamed(e.message(), from, to), e.location());
}

std::string message_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  std::ostringstream text;
  text.precision(10);
  text << value;
  return text.str();
}

void throw_invalid(std::string_view field, double value, std::string_view constraint) {
  std::ostringstream message;
  message << field << " = " << message_number(value) << ": must be " << constraint;
  throw InvalidParameter(std::string(field), message.str());
}

void throw_invalid(std::string_view field, std::string_view value, std::string_view constraint) {
  std::ostringstream message;
  message << field << " = '" << value << "': must be " << constraint;
  throw InvalidParameter(std::string(field), message.str());
}

void require_finite(std::string_view field, double value) {
  if (!std::isfinite(value)) throw_invalid(field, value, "a finite number");
}

void require_positive(std::string_view field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) throw_invalid(field, value, "finite and > 0");
}

void require_non_negative(std::string_view field, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) throw_invalid(field, value, "finite and >= 0");
}

void require_in_range(std::string_view field, double value, double low, double high) {
  if (!(value >= low && value <= high)) {
    std::ostringstream range;
    range.precision(10);
    range << "in [" << low << ", " << high << "]";
    throw_invalid(field, value, range.str());
  }
}

void check_failed(const char* condition, const char* file, int line) {
  std::ostringstream message;
  message << "internal error: check '" << condition << "' failed at " << file << ':' << line;
  throw InternalError(message.str());
}

}  // namespace fogradar
