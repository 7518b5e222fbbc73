// Unit conversions against their definitions (exact decimal values; tolerance 1e-15 relative).
#include <gtest/gtest.h>

#include <cmath>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar {
namespace {

TEST(Units, DecibelRoundTrip) {
  EXPECT_DOUBLE_EQ(db_to_power_ratio(10.0), 10.0);
  EXPECT_DOUBLE_EQ(db_to_power_ratio(-30.0), 1e-3);
  EXPECT_DOUBLE_EQ(power_ratio_to_db(100.0), 20.0);
  for (double db : {-120.0, -3.0, 0.0, 7.5, 60.0}) {
    EXPECT_NEAR(power_ratio_to_db(db_to_power_ratio(db)), db, 1e-12);
  }
}

TEST(Units, DbmIsDecibelsAboveOneMilliwatt) {
  EXPECT_DOUBLE_EQ(dbm_to_watt(0.0), 1e-3);
  EXPECT_DOUBLE_EQ(dbm_to_watt(30.0), 1.0);
  EXPECT_DOUBLE_EQ(dbm_to_watt(10.0), 1e-2);  // the paper radar's 10 dBm transmit power
  EXPECT_NEAR(watt_to_dbm(2.0), 30.0 + 10.0 * std::log10(2.0), 1e-12);
}

// 10 log10(e): the dB per neper-of-power factor of paper eq. 5.
TEST(Units, NeperToDecibelFactor) {
  EXPECT_NEAR(db_per_neper_power, 10.0 / std::log(10.0), 1e-15);
}

TEST(Units, WavelengthOf77GHz) {
  // c / 77 GHz = 3.893 408 545 mm (c exact, SI 2019).
  EXPECT_NEAR(wavelength_from_frequency_m(77e9), 3.893408545e-3, 1e-12);
  EXPECT_NEAR(frequency_from_wavelength_hz(wavelength_from_frequency_m(77e9)), 77e9, 1e-3);
  EXPECT_DOUBLE_EQ(celsius_to_kelvin(20.0), 293.15);
}

}  // namespace
}  // namespace fogradar
