// The bad-input channel: every validator names the field and the allowed range, and NaN never
// passes.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "fogradar/core/error.hpp"

namespace fogradar {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

template <class F>
std::string message_of(F&& f, const std::string& expected_field) {
  try {
    f();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), expected_field);
    return e.what();
  }
  ADD_FAILURE() << "no InvalidParameter thrown";
  return {};
}

TEST(Error, MessageNamesFieldValueAndRange) {
  const std::string m = message_of(
      [] { require_in_range("radar.noise_figure_db", 99.0, 0.0, 30.0); }, "radar.noise_figure_db");
  EXPECT_NE(m.find("radar.noise_figure_db = 99"), std::string::npos) << m;
  EXPECT_NE(m.find("in [0, 30]"), std::string::npos) << m;
}

TEST(Error, NonFiniteNeverPasses) {
  for (double bad : {nan, inf, -inf}) {
    EXPECT_THROW(require_finite("x", bad), InvalidParameter);
    EXPECT_THROW(require_positive("x", bad), InvalidParameter);
    EXPECT_THROW(require_non_negative("x", bad), InvalidParameter);
    EXPECT_THROW(require_in_range("x", bad, -1e300, 1e300), InvalidParameter);
  }
}

// Non-finite values as TOML and the command line spell them, never the stream's "-nan" or a NaN's
// sign.
TEST(Error, NonFiniteValuesAreWrittenAsTyped) {
  EXPECT_EQ(message_of([] { require_in_range("x", nan, 0.0, 1.0); }, "x"),
            "x = nan: must be in [0, 1]");
  EXPECT_EQ(message_of([] { require_in_range("x", -nan, 0.0, 1.0); }, "x"),
            "x = nan: must be in [0, 1]");
  EXPECT_EQ(message_of([] { require_positive("x", inf); }, "x"), "x = inf: must be finite and > 0");
  EXPECT_EQ(message_of([] { require_finite("x", -inf); }, "x"),
            "x = -inf: must be a finite number");
}

TEST(Error, Boundaries) {
  EXPECT_THROW(require_positive("x", 0.0), InvalidParameter);
  EXPECT_NO_THROW(require_non_negative("x", 0.0));
  EXPECT_THROW(require_non_negative("x", -1e-300), InvalidParameter);
  EXPECT_NO_THROW(require_in_range("x", 1.0, 1.0, 2.0));
  EXPECT_NO_THROW(require_in_range("x", 2.0, 1.0, 2.0));
  EXPECT_THROW(require_in_range("x", 2.0000001, 1.0, 2.0), InvalidParameter);
}

TEST(Error, StringValuesAreQuoted) {
  const std::string m = message_of(
      [] { throw_invalid("water_model", "mie", "one of: segelstein, liebe"); }, "water_model");
  EXPECT_EQ(m, "water_model = 'mie': must be one of: segelstein, liebe");
}

// Where a value was given is data of the error, not text to be parsed back: the full message
// puts it in front ("<source>:<line>: "), the bare message and the location stay apart.
TEST(Error, LocationIsKeptApartFromTheMessage) {
  const InvalidParameter at_line("radar.tx_power_dbm",
                                 "radar.tx_power_dbm = 90: must be in [-30, 50]", {"my.toml", 7});
  EXPECT_STREQ(at_line.what(), "my.toml:7: radar.tx_power_dbm = 90: must be in [-30, 50]");
  EXPECT_EQ(at_line.message(), "radar.tx_power_dbm = 90: must be in [-30, 50]");
  EXPECT_EQ(at_line.field(), "radar.tx_power_dbm");
  EXPECT_EQ(at_line.location().source, "my.toml");
  EXPECT_EQ(at_line.location().line, 7U);
  const InvalidParameter no_line("toml", "malformed", {"<scenario>", 0});
  EXPECT_STREQ(no_line.what(), "<scenario>: malformed");
  const InvalidParameter nowhere("--seed", "--seed = '-1': must be an integer");
  EXPECT_STREQ(nowhere.what(), "--seed = '-1': must be an integer");
  EXPECT_TRUE(nowhere.location().empty());
}

// A second sensor of a kind states the kind's keys under its own section: every key name that
// starts with the kind's section moves, and nothing else (a sentence's "radar." or another
// section's "lidar.radar_x").
TEST(Error, KeysMoveToAnInstancesSectionAndNothingElseDoes) {
  EXPECT_EQ(with_section_renamed("radar.samples_per_chirp = 600: must be in [16, "
                                 "radar.chirp_duration_s x radar.sample_rate_hz = 512]",
                                 "radar.", "radar_24."),
            "radar_24.samples_per_chirp = 600: must be in [16, radar_24.chirp_duration_s x "
            "radar_24.sample_rate_hz = 512]");
  EXPECT_EQ(with_section_renamed("seen by the radar. radar.", "radar.", "radar_24."),
            "seen by the radar. radar.");
  EXPECT_EQ(with_section_renamed("lidar.radar.x, xradar.y, (radar.z)", "radar.", "r2."),
            "lidar.radar.x, xradar.y, (r2.z)");
  const InvalidParameter moved = with_section_renamed(
      InvalidParameter("radar.adc_bits", "radar.adc_bits = 30: must be in [0, 24]", {"f.toml", 3}),
      "radar.", "radar_24.");
  EXPECT_EQ(moved.field(), "radar_24.adc_bits");
  EXPECT_STREQ(moved.what(), "f.toml:3: radar_24.adc_bits = 30: must be in [0, 24]");
}

TEST(Error, CheckIsAnInternalError) {
  EXPECT_THROW(FOGRADAR_CHECK(1 + 1 == 3), InternalError);
  EXPECT_NO_THROW(FOGRADAR_CHECK(1 + 1 == 2));
}

}  // namespace
}  // namespace fogradar
