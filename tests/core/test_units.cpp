// Unit conversions against their definitions (exact decimal values; tolerance 1e-15 relative).
#include <gtest/gtest.h>

#include <cmath>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/units.hpp"
#include "validation.hpp"

namespace fogradar {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

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
  validate({.id = "core.units.watt_to_dbm.2W",
            .group = "experiment: statistics",
            .quantity = "power level of 2 W",
            .unit = "dBm",
            .conditions = "2 W",
            .reference = 30.0 + 10.0 * std::log10(2.0),
            .source = "definition: 10 log10(P / 1 mW)",
            .value = watt_to_dbm(2.0),
            .tolerance = 1e-12,
            .kind = Tolerance::absolute});
}

// 10 log10(e): the dB per neper-of-power factor of paper eq. 5.
TEST(Units, NeperToDecibelFactor) {
  validate({.id = "core.units.db_per_neper_power",
            .group = "experiment: statistics",
            .quantity = "dB per neper of power",
            .unit = "dB/Np",
            .conditions = "power ratio",
            .reference = 10.0 / std::log(10.0),
            .source = "closed form: 10 log10(e) = 10 / ln 10 (paper eq. 5)",
            .value = db_per_neper_power,
            .tolerance = 1e-15,
            .kind = Tolerance::absolute});
}

TEST(Units, WavelengthOf77GHz) {
  // c / 77 GHz = 3.893 408 545 mm (c exact, SI 2019).
  validate({.id = "core.units.wavelength.77GHz",
            .group = "experiment: statistics",
            .quantity = "wavelength",
            .unit = "m",
            .conditions = "77 GHz",
            .reference = 3.893408545e-3,
            .source = "c / f with c = 299 792 458 m/s exact (SI 2019)",
            .value = wavelength_from_frequency_m(77e9),
            .tolerance = 1e-12,
            .kind = Tolerance::absolute});
  EXPECT_NEAR(frequency_from_wavelength_hz(wavelength_from_frequency_m(77e9)), 77e9, 1e-3);
  EXPECT_DOUBLE_EQ(celsius_to_kelvin(20.0), 293.15);
}

}  // namespace
}  // namespace fogradar
