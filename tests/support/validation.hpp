// One comparison of fogradar with an independent reference, checked and recorded for the validation
// report (scripts/validate.sh, docs/validation.md): the check is a GoogleTest expectation, and its
// record a test property ("validation:<id>", a JSON object) that GoogleTest's JSON output carries.
//
// Only comparisons with a reference fogradar did not compute are recorded: a published value, a
// table, a closed form, a limiting case or an independent method written out in the test.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace fogradar::testing {

// How a check's tolerance is measured.
enum class Tolerance {
  relative,     // |value - reference| <= tolerance * |reference|
  absolute,     // |value - reference| <= tolerance
  at_most,      // value <= reference + tolerance (a bound: the reference is the limit)
  at_least,     // value >= reference - tolerance
  above,        // value > reference + tolerance (strictly: "above 0")
  statistical,  // value in [interval_low, interval_high]: the reference's confidence interval
  // A known disagreement with a published value, explained in the docs: the reference lies outside
  // fogradar's band [interval_low, interval_high]. The report shows it as a disagreement, never as
  // a pass; the check fails when the reference comes inside the band, where the explanation no
  // longer holds.
  disagreement,
};

struct Check {
  std::string id = {};          // unique across the suites: "water.p840.k_l.77GHz.20C"
  std::string group = {};       // the report's section: "physics: water", "radar: CFAR", ...
  std::string quantity = {};    // "specific attenuation coefficient K_l"
  std::string unit = {};        // "(dB/km)/(g/m^3)", "dB", "1"
  std::string conditions = {};  // "77 GHz, 20 °C"
  double reference = std::numeric_limits<double>::quiet_NaN();
  // "ITU-R P.840-8 eq. (2)-(9)", "closed form: ...", "Wiscombe MIEV0 case 3"
  std::string source = {};
  double value = std::numeric_limits<double>::quiet_NaN();
  double tolerance = 0.0;
  Tolerance kind = Tolerance::relative;
  // Statistical checks: the sample size and the accepted interval, with its confidence;
  // disagreements: fogradar's band and what it is.
  std::size_t samples = 0;
  double interval_low = std::numeric_limits<double>::quiet_NaN();
  double interval_high = std::numeric_limits<double>::quiet_NaN();
  std::string confidence = {};  // "99 % binomial (Wilson) interval"
  // A curve in the report: checks of one plot share its name, x is their abscissa.
  std::string plot = {};
  double x = std::numeric_limits<double>::quiet_NaN();
  std::string x_label = {};
};

inline const char* tolerance_name(Tolerance kind) {
  switch (kind) {
    case Tolerance::relative:
      return "relative";
    case Tolerance::absolute:
      return "absolute";
    case Tolerance::at_most:
      return "at_most";
    case Tolerance::at_least:
      return "at_least";
    case Tolerance::above:
      return "above";
    case Tolerance::statistical:
      return "statistical";
    case Tolerance::disagreement:
      return "disagreement";
  }
  return "";
}

inline bool passes(const Check& c) {
  const double error = std::abs(c.value - c.reference);
  switch (c.kind) {
    case Tolerance::relative:
      return error <= c.tolerance * std::abs(c.reference);
    case Tolerance::absolute:
      return error <= c.tolerance;
    case Tolerance::at_most:
      return c.value <= c.reference + c.tolerance;
    case Tolerance::at_least:
      return c.value >= c.reference - c.tolerance;
    case Tolerance::above:
      return c.value > c.reference + c.tolerance;
    case Tolerance::statistical:
      return c.value >= c.interval_low && c.value <= c.interval_high;
    case Tolerance::disagreement:
      return c.reference < c.interval_low || c.reference > c.interval_high;
  }
  return false;
}

// Expects the check to pass and records it (NaN numbers are recorded as null).
inline void validate(const Check& c) {
  const auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nullptr; };
  // What scripts/validation_report.py refuses in a record, checked where it is made, so that the
  // suite run alone (scripts/test.sh, CI) holds it too.
  EXPECT_FALSE(c.source.empty() || c.quantity.empty() || c.group.empty())
      << c.id << ": a check states its source, quantity and group";
  EXPECT_FALSE(std::fpclassify(c.reference) == FP_SUBNORMAL ||
               std::fpclassify(c.tolerance) == FP_SUBNORMAL)
      << c.id << ": a subnormal reference or tolerance stands in for a kind (`above`)";
  const bool pass = passes(c);
  EXPECT_TRUE(pass) << c.id << ": " << c.quantity << " (" << c.conditions << ") = " << c.value
                    << " " << c.unit << " against " << c.reference << " from " << c.source
                    << ", tolerance " << tolerance_name(c.kind) << " " << c.tolerance
                    << (c.kind == Tolerance::statistical || c.kind == Tolerance::disagreement
                            ? " interval [" + std::to_string(c.interval_low) + ", " +
                                  std::to_string(c.interval_high) + "]"
                            : std::string());
  nlohmann::json record = {{"id", c.id},
                           {"group", c.group},
                           {"quantity", c.quantity},
                           {"unit", c.unit},
                           {"conditions", c.conditions},
                           {"reference", number(c.reference)},
                           {"source", c.source},
                           {"value", number(c.value)},
                           {"tolerance", c.tolerance},
                           {"tolerance_kind", tolerance_name(c.kind)},
                           {"pass", pass}};
  if (c.kind == Tolerance::statistical || c.kind == Tolerance::disagreement) {
    record["samples"] = c.samples;
    record["interval"] = {number(c.interval_low), number(c.interval_high)};
    record["confidence"] = c.confidence;
  }
  if (!c.plot.empty()) {
    record["plot"] = c.plot;
    record["x"] = number(c.x);
    record["x_label"] = c.x_label;
  }
  // ASCII only (\u escapes): GoogleTest's JSON output escapes each byte of UTF-8 on its own.
  ::testing::Test::RecordProperty("validation:" + c.id, record.dump(-1, ' ', true));
}

}  // namespace fogradar::testing
