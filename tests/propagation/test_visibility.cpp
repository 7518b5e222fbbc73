// Visibility and optical attenuation relations (paper eq. 1, 2, 5, 6, 9; Kunkel 1984; Kim et al.
// 2001). References are the published closed forms evaluated by hand; tolerances 1e-12 unless said.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/propagation/visibility.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::propagation {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

// EXPECT_DOUBLE_EQ's 4 units in the last place, as a relative tolerance.
constexpr double kDoubleEqRelTol = 4.0 * std::numeric_limits<double>::epsilon();

// A number as written in a check's id and conditions: "0.0001", "681.5".
std::string num(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Records one check of a visibility relation against its hand-evaluated closed form.
void check(const std::string& id, const std::string& quantity, const std::string& unit,
           const std::string& conditions, double value, double reference, const std::string& source,
           double tolerance, Tolerance kind = Tolerance::absolute) {
  validate({.id = "propagation.visibility." + id,
            .group = "physics: fog",
            .quantity = quantity,
            .unit = unit,
            .conditions = conditions,
            .reference = reference,
            .source = source,
            .value = value,
            .tolerance = tolerance,
            .kind = kind});
}

TEST(Visibility, Eq6IsKoschmiederAtTwoPercent) {
  // V beta = -ln 0.02 = 3.912023005428146.
  for (double beta : {1e-4, 0.9, 681.5e-3, 12.0}) {
    check("koschmieder.v_beta.beta" + num(beta), "V beta", "1", "beta = " + num(beta) + " 1/m",
          visibility_m_from_extinction(beta) * beta, 3.912023005428146,
          "Koschmieder, 2 % contrast (paper eq. 6): V beta = -ln 0.02", 1e-12);
    EXPECT_NEAR(extinction_per_m_from_visibility(visibility_m_from_extinction(beta)), beta,
                1e-12 * beta);
  }
  // The study's fog: beta = 900 1/km gives V = 4.347 m (the paper reports 5.74 m measured, which
  // eq. 6 maps to beta = 681.5 1/km: the two numbers in sec. III-B are not the same fog state).
  check("koschmieder.v.beta900per_km", "visibility V", "m", "beta = 900 1/km",
        visibility_m_from_extinction(0.9), 4.346692228,
        "Koschmieder (paper eq. 6): V = -ln 0.02 / beta, evaluated by hand", 1e-8);
}

TEST(Visibility, Eq9CieUsesFivePercent) {
  check("cie.v.beta1", "meteorological visibility", "m", "beta = 1 1/m",
        meteorological_visibility_m(1.0), -std::log(0.05),
        "CIE 5 % contrast (paper eq. 9): V = -ln 0.05 / beta", 1e-15);
  // Ratio of CIE to 2 % visual range = ln 0.05 / ln 0.02 = 0.7657757...
  check("cie_over_koschmieder.beta0.3", "CIE visibility / 2 % visual range", "1", "beta = 0.3 1/m",
        meteorological_visibility_m(0.3) / visibility_m_from_extinction(0.3), 0.7657757302,
        "closed form: ln 0.05 / ln 0.02", 1e-9);
}

TEST(Visibility, Eq5DecibelsPerKm) {
  check("attenuation_db.beta1per_km", "attenuation", "dB/km", "beta = 1 1/km",
        attenuation_db_per_km(1.0), 4.342944819032518, "paper eq. 5: 10 log10(e) beta", 1e-15);
  // the study's 900 1/km fog
  check("attenuation_db.beta900per_km", "attenuation", "dB/km", "beta = 900 1/km",
        attenuation_db_per_km(900.0), 3908.650337, "paper eq. 5: 10 log10(e) beta", 1e-6);
}

TEST(Visibility, Kunkel) {
  check("kunkel.beta.lwc1", "optical extinction beta", "1/km", "LWC = 1 g/m^3",
        kunkel_extinction_per_km(1.0), 144.7, "Kunkel 1984: beta = 144.7 LWC^0.88", kDoubleEqRelTol,
        Tolerance::relative);
  check("kunkel.beta.lwc0.1", "optical extinction beta", "1/km", "LWC = 0.1 g/m^3",
        kunkel_extinction_per_km(0.1), 144.7 * std::pow(0.1, 0.88),
        "Kunkel 1984: beta = 144.7 LWC^0.88", 1e-12);
  for (double lwc : {0.01, 0.2, 3.0}) {
    EXPECT_NEAR(kunkel_lwc_g_per_m3(kunkel_extinction_per_km(lwc)), lwc, 1e-12 * lwc);
  }
  // The inverse written out: LWC = (beta / 144.7)^(1 / 0.88); the study's 900 1/km needs
  // 7.98024 g/m^3 by Kunkel (docs/physics.md sec. 5; `fogradar fog --lwc-from kunkel`).
  check("kunkel.lwc.beta900per_km", "liquid water content", "g/m^3", "beta = 900 1/km",
        kunkel_lwc_g_per_m3(900.0), std::pow(900.0 / 144.7, 1.0 / 0.88),
        "Kunkel 1984 inverted: LWC = (beta / 144.7)^(1/0.88)", 1e-12, Tolerance::relative);
  check("kunkel.lwc.beta900per_km.by_hand", "liquid water content", "g/m^3", "beta = 900 1/km",
        kunkel_lwc_g_per_m3(900.0), 7.980238747,
        "Kunkel 1984 inverted: LWC = (beta / 144.7)^(1/0.88), evaluated by hand", 1e-9);
}

TEST(Visibility, KruseBranchesAtTheirBoundaries) {
  // q = 0.585 V^(1/3) up to 6 km (paper eq. 2): 0.585 * 6^(1/3) = 1.0630155...; 1.3 above 6 km;
  // 1.6 above 50 km. Kruse is discontinuous at 6 km by construction.
  const std::string kruse = "Kruse (paper eq. 2)";
  check("kruse_q.v6km", "Kruse exponent q", "1", "V = 6 km", kruse_q(6.0), 1.0630155468,
        kruse + ": q = 0.585 V^(1/3), evaluated by hand", 1e-9);
  check("kruse_q.v6km_above", "Kruse exponent q", "1", "V just above 6 km",
        kruse_q(std::nextafter(6.0, 7.0)), 1.3, kruse + ": q = 1.3 for 6 < V <= 50 km",
        kDoubleEqRelTol, Tolerance::relative);
  check("kruse_q.v50km", "Kruse exponent q", "1", "V = 50 km", kruse_q(50.0), 1.3,
        kruse + ": q = 1.3 for 6 < V <= 50 km", kDoubleEqRelTol, Tolerance::relative);
  check("kruse_q.v50km_above", "Kruse exponent q", "1", "V just above 50 km",
        kruse_q(std::nextafter(50.0, 51.0)), 1.6, kruse + ": q = 1.6 above 50 km", kDoubleEqRelTol,
        Tolerance::relative);
  check("kruse_q.v1km", "Kruse exponent q", "1", "V = 1 km", kruse_q(1.0), 0.585,
        kruse + ": q = 0.585 V^(1/3)", 1e-15);
}

TEST(Visibility, KimBranchesAreContinuousWhereKimMadeThemSo) {
  // Kim et al. 2001: 0.16 V + 0.34 meets 1.3 at 6 km and V - 0.5 at 1 km; V - 0.5 meets 0 at 0.5
  // km.
  for (double v : {0.5, 1.0, 6.0}) {
    EXPECT_NEAR(kim_q(v), kim_q(std::nextafter(v, 100.0)), 1e-12) << v;
  }
  const std::string kim = "Kim et al. 2001";
  check("kim_q.v0.3km", "Kim exponent q", "1", "V = 0.3 km", kim_q(0.3), 0.0,
        kim + ": q = 0 below 0.5 km", kDoubleEqRelTol, Tolerance::relative);
  check("kim_q.v0.5km", "Kim exponent q", "1", "V = 0.5 km", kim_q(0.5), 0.0,
        kim + ": q = V - 0.5 = 0 at 0.5 km", kDoubleEqRelTol, Tolerance::relative);
  check("kim_q.v0.75km", "Kim exponent q", "1", "V = 0.75 km", kim_q(0.75), 0.25,
        kim + ": q = V - 0.5", 1e-15);
  check("kim_q.v3km", "Kim exponent q", "1", "V = 3 km", kim_q(3.0), 0.82,
        kim + ": q = 0.16 V + 0.34", 1e-15);
  check("kim_q.v51km", "Kim exponent q", "1", "V = 51 km", kim_q(51.0), 1.6,
        kim + ": q = 1.6 above 50 km", kDoubleEqRelTol, Tolerance::relative);
}

TEST(Visibility, Eq1IsAnExtinctionCoefficient) {
  // At 550 nm the wavelength factor is 1: beta = 3.912 / V for any q.
  const std::string eq1 = "paper eq. 1: beta = 3.912 / V (lambda / 550 nm)^-q";
  check("kruse_beta.550nm.v2km", "optical extinction beta (Kruse)", "1/km", "550 nm, V = 2 km",
        kruse_extinction_per_km(2.0, 550.0), 3.912023005428146 / 2.0, eq1 + " at 550 nm", 1e-12);
  // 905 nm (lidar), V = 1 km: Kruse q = 0.585, beta = 3.912 (905/550)^-0.585 = 2.9233 1/km.
  check("kruse_beta.905nm.v1km", "optical extinction beta (Kruse)", "1/km", "905 nm, V = 1 km",
        kruse_extinction_per_km(1.0, 905.0), 3.912023005428146 * std::pow(905.0 / 550.0, -0.585),
        eq1 + ", q = 0.585", 1e-12);
  check("kruse_beta.905nm.v1km.by_hand", "optical extinction beta (Kruse)", "1/km",
        "905 nm, V = 1 km", kruse_extinction_per_km(1.0, 905.0), 2.9233052,
        eq1 + ", q = 0.585, evaluated by hand", 1e-6);
  // Kim below 500 m: wavelength independent.
  check("kim_beta.905nm.v0.2km", "optical extinction beta (Kim)", "1/km", "905 nm, V = 0.2 km",
        kim_extinction_per_km(0.2, 905.0), 3.912023005428146 / 0.2, eq1 + ", Kim q = 0", 1e-12);
}

TEST(Visibility, Eq1AwayFrom550nmInEachVisibilityBand) {
  // One visibility per band of q, at the lidar's 905 nm and at 1550 nm (Kim et al. compared 785
  // and 1550 nm): beta = 3.912 / V (lambda / 550)^-q with q written out per band, not taken from
  // kruse_q or kim_q.
  const std::string eq1 = "paper eq. 1 with q written out: beta = 3.912 / V (lambda / 550 nm)^-q";
  const double koschmieder = 3.912023005428146;
  struct Case {
    double visibility_km;
    double wavelength_nm;
    double kruse_q;
    double kim_q;
  };
  for (const Case& c : {Case{0.3, 905.0, 0.585 * std::cbrt(0.3), 0.0},
                        Case{0.8, 1550.0, 0.585 * std::cbrt(0.8), 0.8 - 0.5},
                        Case{3.0, 905.0, 0.585 * std::cbrt(3.0), 0.16 * 3.0 + 0.34},
                        Case{10.0, 1550.0, 1.3, 1.3}, Case{60.0, 905.0, 1.6, 1.6}}) {
    const std::string conditions =
        num(c.wavelength_nm) + " nm, V = " + num(c.visibility_km) + " km";
    const std::string id = num(c.wavelength_nm) + "nm.v" + num(c.visibility_km) + "km";
    const double ratio = c.wavelength_nm / 550.0;
    check("kruse_beta." + id, "optical extinction beta (Kruse)", "1/km", conditions,
          kruse_extinction_per_km(c.visibility_km, c.wavelength_nm),
          koschmieder / c.visibility_km * std::pow(ratio, -c.kruse_q), eq1 + ", Kruse's q", 1e-12,
          Tolerance::relative);
    check("kim_beta." + id, "optical extinction beta (Kim)", "1/km", conditions,
          kim_extinction_per_km(c.visibility_km, c.wavelength_nm),
          koschmieder / c.visibility_km * std::pow(ratio, -c.kim_q), eq1 + ", Kim's q", 1e-12,
          Tolerance::relative);
  }
  // Two by hand: Kim at V = 3 km, 905 nm (q = 0.82) and Kruse at V = 10 km, 1550 nm (q = 1.3).
  check("kim_beta.905nm.v3km.by_hand", "optical extinction beta (Kim)", "1/km", "905 nm, V = 3 km",
        kim_extinction_per_km(3.0, 905.0), 0.8668135983, eq1 + ", q = 0.82, evaluated by hand",
        1e-9);
  check("kruse_beta.1550nm.v10km.by_hand", "optical extinction beta (Kruse)", "1/km",
        "1550 nm, V = 10 km", kruse_extinction_per_km(10.0, 1550.0), 0.1017282770,
        eq1 + ", q = 1.3, evaluated by hand", 1e-9);
}

TEST(OpticalModelTable, MieFirstThenKruseAndKimAsEq1WithTheirQ) {
  // V = 3 km at 905 nm: Kruse's q = 0.585 V^(1/3) (eq. 2), Kim's q = 0.16 V + 0.34 = 0.82; eq. 1
  // written out; Kim's by hand as in Eq1AwayFrom550nmInEachVisibilityBand. Mie is the value given.
  const std::array<OpticalModel, 3> all = {OpticalModel::kim, OpticalModel::mie,
                                           OpticalModel::kruse};
  const std::vector<OpticalModelExtinction> rows = optical_model_table(all, 1.25, 3000.0, 905.0);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].model, OpticalModel::mie);
  EXPECT_EQ(rows[1].model, OpticalModel::kruse);
  EXPECT_EQ(rows[2].model, OpticalModel::kim);
  EXPECT_EQ(rows[0].extinction_per_km, 1.25);
  EXPECT_FALSE(rows[0].q.has_value());
  const std::string eq1 = "paper eq. 1 written out: beta = 3.912 / V (lambda / 550 nm)^-q";
  const double ratio = 905.0 / 550.0;
  check("table.kruse_q.v3km", "Kruse q (table)", "1", "V = 3 km", rows[1].q.value(),
        0.585 * std::cbrt(3.0), "paper eq. 2: q = 0.585 V^(1/3)", 1e-12, Tolerance::relative);
  check("table.kruse_beta.905nm.v3km", "optical extinction beta (Kruse, table)", "1/km",
        "905 nm, V = 3 km", rows[1].extinction_per_km,
        3.912023005428146 / 3.0 * std::pow(ratio, -0.585 * std::cbrt(3.0)), eq1, 1e-12,
        Tolerance::relative);
  check("table.kim_q.v3km", "Kim q (table)", "1", "V = 3 km", rows[2].q.value(), 0.82,
        "Kim et al. 2001: q = 0.16 V + 0.34", 1e-12, Tolerance::relative);
  check("table.kim_beta.905nm.v3km.by_hand", "optical extinction beta (Kim, table)", "1/km",
        "905 nm, V = 3 km", rows[2].extinction_per_km, 0.8668135983,
        eq1 + ", q = 0.82, evaluated by hand", 1e-9);
}

TEST(OpticalModelTable, At550nmEveryModelIsTheFogsOwnExtinction) {
  // Eq. 1 at 550 nm is eq. 6 whatever q: beta = -ln(0.02) / V; Mie given as that same value.
  const std::array<OpticalModel, 2> empirical = {OpticalModel::kruse, OpticalModel::kim};
  for (const double visibility_m : {200.0, 2000.0, 20000.0}) {
    const double beta_per_km = 3.912023005428146 / (visibility_m * 1e-3);
    for (const OpticalModelExtinction& row :
         optical_model_table(empirical, beta_per_km, visibility_m, 550.0)) {
      check("table.550nm." + std::string(optical_model_names.name(row.model)) + ".v" +
                num(visibility_m) + "m",
            "optical extinction beta at 550 nm (table)", "1/km", "V = " + num(visibility_m) + " m",
            row.extinction_per_km, beta_per_km, "paper eq. 6: beta = -ln(0.02) / V", 1e-12,
            Tolerance::relative);
    }
  }
}

TEST(OpticalModelTable, WithoutWaterNoExtinctionAndNoQ) {
  // Limiting case: eq. 1 as V grows without bound.
  const std::array<OpticalModel, 1> kim = {OpticalModel::kim};
  const std::vector<OpticalModelExtinction> rows =
      optical_model_table(kim, 0.0, std::numeric_limits<double>::infinity(), 905.0);
  ASSERT_EQ(rows.size(), 2u);  // Mie is always there; Kruse was not asked for
  EXPECT_EQ(rows[1].model, OpticalModel::kim);
  EXPECT_EQ(rows[1].extinction_per_km, 0.0);
  EXPECT_FALSE(rows[1].q.has_value());
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
