// Deterministic, locale-independent number formatting for CSV, JSON and SVG writers
// (std::to_chars: never affected by the C or C++ locale).
#pragma once

#include <string>

namespace fogradar::stats {

// Like printf("%.*g", significant_digits, v) in the "C" locale ("14.97", "1e-06"); with
// significant_digits = 0 the shortest string that reads back to exactly v.
// Non-finite values: NaN -> "" (an empty CSV field; JSON writers should write null),
// +inf -> "inf", -inf -> "-inf". Negative zero prints as "0".
// Throws InvalidParameter naming "significant_digits" unless it is in [0, 17].
std::string format_number(double v, int significant_digits = 10);

// Fixed-point with `decimals` digits after the point ("14.50"), same non-finite rules;
// a value that rounds to zero prints without a sign.
// Throws InvalidParameter naming "decimals" unless it is in [0, 17].
std::string format_fixed(double v, int decimals);

}  // namespace fogradar::stats
