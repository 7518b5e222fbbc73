// Visibility and optical attenuation relations (paper eq. 1, 2, 5, 6, 9; Kunkel 1984; Kim et al.
// 2001). References are the published closed forms evaluated by hand; tolerances 1e-12 unless said.
#include <gtest/gtest.h>

#include "rejected_field.hpp"

#include <cmath>

#include "fogradar/core/error.hpp"
#include "fogradar/propagation/visibility.hpp"

namespace fogradar::propagation {
namespace {

TEST(Visibility, Eq6IsKoschmiederAtTwoPercent) {
  // V beta = -ln 0.02 = 3.912023005428146.
  for (double beta : {1e-4, 0.9, 681.5e-3, 12.0}) {
    EXPECT_NEAR(visibility_m_from_extinction(beta) * beta, 3.912023005428146, 1e-12);
    EXPECT_NEAR(extinction_per_m_from_visibility(visibility_m_from_extinction(beta)), beta, 1e-12 * beta);
  }
  // The study's fog: beta = 900 1/km gives V = 4.347 m (the paper reports 5.74 m measured, which
  // eq. 6 maps to beta = 681.5 1/km: the two numbers in sec. III-B are not the same fog state).
  EXPECT_NEAR(visibility_m_from_extinction(0.9), 4.346692228, 1e-8);
}

TEST(Visibility, Eq9CieUsesFivePercent) {
  EXPECT_NEAR(meteorological_visibility_m(1.0), -std::log(0.05), 1e-15);
  // Ratio of CIE to 2 % visual range = ln 0.05 / ln 0.02 = 0.7657757...
  EXPECT_NEAR(meteorological_visibility_m(0.3) / visibility_m_from_extinction(0.3), 0.7657757302, 1e-9);
}

TEST(Visibility, Eq5DecibelsPerKm) {
  EXPECT_NEAR(attenuation_db_per_km(1.0), 4.342944819032518, 1e-15);
  EXPECT_NEAR(attenuation_db_per_km(900.0), 3908.650337, 1e-6);  // the study's 900 1/km fog
}

TEST(Visibility, Kunkel) {
  EXPECT_DOUBLE_EQ(kunkel_extinction_per_km(1.0), 144.7);
  EXPECT_NEAR(kunkel_extinction_per_km(0.1), 144.7 * std::pow(0.1, 0.88), 1e-12);
  for (double lwc : {0.01, 0.2, 3.0}) {
    EXPECT_NEAR(kunkel_lwc_g_per_m3(kunkel_extinction_per_km(lwc)), lwc, 1e-12 * lwc);
  }
}

TEST(Visibility, KruseBranchesAtTheirBoundaries) {
  // q = 0.585 V^(1/3) up to 6 km (paper eq. 2): 0.585 * 6^(1/3) = 1.0630155...; 1.3 above 6 km;
  // 1.6 above 50 km. Kruse is discontinuous at 6 km by construction.
  EXPECT_NEAR(kruse_q(6.0), 1.0630155468, 1e-9);
  EXPECT_DOUBLE_EQ(kruse_q(std::nextafter(6.0, 7.0)), 1.3);
  EXPECT_DOUBLE_EQ(kruse_q(50.0), 1.3);
  EXPECT_DOUBLE_EQ(kruse_q(std::nextafter(50.0, 51.0)), 1.6);
  EXPECT_NEAR(kruse_q(1.0), 0.585, 1e-15);
}

TEST(Visibility, KimBranchesAreContinuousWhereKimMadeThemSo) {
  // Kim et al. 2001: 0.16 V + 0.34 meets 1.3 at 6 km and V - 0.5 at 1 km; V - 0.5 meets 0 at 0.5 km.
  for (double v : {0.5, 1.0, 6.0}) {
    EXPECT_NEAR(kim_q(v), kim_q(std::nextafter(v, 100.0)), 1e-12) << v;
  }
  EXPECT_DOUBLE_EQ(kim_q(0.3), 0.0);
  EXPECT_DOUBLE_EQ(kim_q(0.5), 0.0);
  EXPECT_NEAR(kim_q(0.75), 0.25, 1e-15);
  EXPECT_NEAR(kim_q(3.0), 0.82, 1e-15);
  EXPECT_DOUBLE_EQ(kim_q(51.0), 1.6);
}

TEST(Visibility, Eq1IsAnExtinctionCoefficient) {
  // At 550 nm the wavelength factor is 1: beta = 3.912 / V for any q.
  EXPECT_NEAR(kruse_extinction_per_km(2.0, 550.0), 3.912023005428146 / 2.0, 1e-12);
  // 905 nm (lidar), V = 1 km: Kruse q = 0.585, beta = 3.912 (905/550)^-0.585 = 2.9233 1/km.
  EXPECT_NEAR(kruse_extinction_per_km(1.0, 905.0), 3.912023005428146 * std::pow(905.0 / 550.0, -0.585), 1e-12);
  EXPECT_NEAR(kruse_extinction_per_km(1.0, 905.0), 2.9233052, 1e-6);
  // Kim below 500 m: wavelength independent.
  EXPECT_NEAR(kim_extinction_per_km(0.2, 905.0), 3.912023005428146 / 0.2, 1e-12);
}

TEST(Visibility, RejectsNonPhysicalInput) {
  EXPECT_THROW(visibility_m_from_extinction(0.0), InvalidParameter);
  EXPECT_THROW(extinction_per_m_from_visibility(-1.0), InvalidParameter);
  EXPECT_THROW(kruse_q(std::nan("")), InvalidParameter);
  EXPECT_THROW(kim_q(0.0), InvalidParameter);
  EXPECT_THROW(kunkel_extinction_per_km(-0.1), InvalidParameter);
  EXPECT_THROW(kruse_extinction_per_km(1.0, -905.0), InvalidParameter);
  EXPECT_EQ(test_support::rejected_field([] { attenuation_db_per_km(-1.0); }), "extinction_per_km");
}

}  // namespace
}  // namespace fogradar::propagation
