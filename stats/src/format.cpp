#include "fogradar/stats/format.hpp"

#include <array>
#include <charconv>
#include <cmath>

#include "fogradar/core/error.hpp"

namespace fogradar::stats {

namespace {

// Non-finite v: writes "" (NaN), "inf" or "-inf" into out and returns true; finite v: false.
bool format_non_finite(double v, std::string& out) {
  if (std::isnan(v)) {
    out.clear();
    return true;
  }
  if (std::isinf(v)) {
    out = v > 0 ? "inf" : "-inf";
    return true;
  }
  return false;
}

// "-0", "-0.00": a value that printed as zero loses its sign.
std::string drop_negative_zero(std::string text) {
  if (text.starts_with('-') && text.find_first_not_of("0.", 1) == std::string::npos) {
    text.erase(0, 1);
  }
  return text;
}

}  // namespace

std::string format_number(double v, int significant_digits) {
  require_in_range("significant_digits", significant_digits, 0, 17);
  std::string out;
  if (format_non_finite(v, out)) return out;
  // Shortest %g of a double: at most 24 characters ("-2.2250738585072014e-308").
  std::array<char, 32> buffer{};
  const auto result = significant_digits == 0
                          ? std::to_chars(buffer.data(), buffer.data() + buffer.size(), v)
                          : std::to_chars(buffer.data(), buffer.data() + buffer.size(), v,
                                          std::chars_format::general, significant_digits);
  FOGRADAR_CHECK(result.ec == std::errc());
  return drop_negative_zero(std::string(buffer.data(), result.ptr));
}

std::string format_fixed(double v, int decimals) {
  require_in_range("decimals", decimals, 0, 17);
  std::string out;
  if (format_non_finite(v, out)) return out;
  // Largest finite double: 309 integer digits, a sign, a point and 17 decimals.
  std::array<char, 336> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v,
                                    std::chars_format::fixed, decimals);
  FOGRADAR_CHECK(result.ec == std::errc());
  return drop_negative_zero(std::string(buffer.data(), result.ptr));
}

}  // namespace fogradar::stats
