// Materials and Fresnel coefficients. References: ITU-R P.2040-3 (08/2023) Table 3, its a, b, c, d
// written here independently of the library's table and evaluated by hand (numpy, below); the
// Fresnel closed forms at normal and grazing incidence and Brewster's angle (Born & Wolf, 7th ed.,
// sec. 1.5.2-1.5.3); ITU-R P.840's water index at 77 GHz, 20 C; fused silica's published n_d.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/propagation/materials.hpp"
#include "fogradar/propagation/water.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::propagation {
namespace {

using complex = std::complex<double>;
using fogradar::test_support::rejected_field;
using fogradar::testing::Tolerance;
using fogradar::testing::validate;

// A number as check ids and conditions show it ("77", "0.5").
std::string id_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

constexpr double deg = pi / 180.0;

std::string message_of(void (*call)()) {
  try {
    call();
  } catch (const InvalidParameter& error) {
    return error.what();
  }
  return "accepted";
}

// eps' = a f^b, sigma = c f^d, eps'' = 17.98 sigma / f with P.2040-3 Table 3's a, b, c, d, each
// value from /usr/bin/python3 -c "a,b,c,d,f=...; s=c*f**d; print(a*f**b, s, 17.98*s/f)".
struct TableValue {
  Material material;
  double frequency_ghz;
  double eps_real;
  double sigma_s_per_m;
  double eps_imag;
};
constexpr TableValue table_values[] = {
    {Material::concrete, 77.0, 5.24, 1.381195074, 0.3225180186},  // 5.24, 0, 0.0462, 0.7822
    {Material::concrete, 24.0, 5.24, 0.5549363953, 0.4157398495},
    {Material::brick, 24.0, 3.91, 0.03957407347, 0.02964757671},       // 3.91, 0, 0.0238, 0.16
    {Material::plasterboard, 77.0, 2.73, 0.5032420954, 0.1175102971},  // 2.73, 0, 0.0085, 0.9395
    {Material::wood, 77.0, 1.99, 0.4943546427, 0.1154350192},          // 1.99, 0, 0.0047, 1.0718
    {Material::glass, 77.0, 6.31, 1.210788195, 0.2827269058},          // 6.31, 0, 0.0036, 1.3394
    {Material::floorboard, 77.0, 3.66, 1.559713717, 0.3642032809},     // 3.66, 0, 0.0044, 1.3515
    {Material::metal, 77.0, 1.0, 1e7, 2335064.935},                    // 1, 0, 1e7, 0
    {Material::medium_dry_ground, 5.0, 12.77009884, 0.4823798425, 1.734637914},  // 15, -0.1, ...
};

TEST(Materials, PermittivityFollowsP2040Table3) {
  for (const TableValue& row : table_values) {
    SCOPED_TRACE(std::string(to_string(row.material)));
    const complex eps = radio_permittivity(row.material, row.frequency_ghz * 1e9);
    const std::string name(to_string(row.material));
    const std::string id =
        "propagation.materials.p2040." + name + "." + id_number(row.frequency_ghz) + "GHz";
    const std::string conditions = name + ", " + id_number(row.frequency_ghz) + " GHz";
    const std::string source =
        "ITU-R P.2040-3 Table 3: eps' = a f^b, eps'' = 17.98 c f^d / f (evaluated by hand)";
    validate({.id = id + ".eps_real",
              .group = "physics: materials",
              .quantity = "real relative permittivity eps'",
              .unit = "1",
              .conditions = conditions,
              .reference = row.eps_real,
              .source = source,
              .value = eps.real(),
              .tolerance = 1e-9,
              .kind = Tolerance::relative});
    validate({.id = id + ".eps_imag",
              .group = "physics: materials",
              .quantity = "imaginary relative permittivity eps''",
              .unit = "1",
              .conditions = conditions,
              .reference = row.eps_imag,
              .source = source,
              .value = eps.imag(),
              .tolerance = 1e-9,
              .kind = Tolerance::relative});
    const std::optional<ItuP2040Fit> fit = itu_p2040_fit(row.material);
    ASSERT_TRUE(fit);
    EXPECT_NEAR(itu_p2040_conductivity_s_per_m(*fit, row.frequency_ghz), row.sigma_s_per_m,
                1e-9 * row.sigma_s_per_m);
  }
}

TEST(Materials, ValidRangesAreTable3s) {
  EXPECT_EQ(radio_frequency_range(Material::concrete).min_ghz, 1.0);
  EXPECT_EQ(radio_frequency_range(Material::concrete).max_ghz, 100.0);
  EXPECT_EQ(radio_frequency_range(Material::brick).max_ghz, 40.0);
  EXPECT_EQ(radio_frequency_range(Material::floorboard).min_ghz, 50.0);
  EXPECT_EQ(radio_frequency_range(Material::wood).min_ghz, 0.001);
  EXPECT_EQ(radio_frequency_range(Material::glass).min_ghz, 0.1);
}

TEST(Materials, OutsideTheFitIsRefusedNamingMaterialAndRange) {
  EXPECT_EQ(rejected_field([] { radio_permittivity(Material::brick, 77e9, "--frequency-ghz"); }),
            "--frequency-ghz");
  const std::string brick = message_of([] { radio_permittivity(Material::brick, 77e9); });
  EXPECT_NE(brick.find("frequency_hz = 7.7e+10"), std::string::npos) << brick;
  EXPECT_NE(brick.find("'brick'"), std::string::npos) << brick;
  EXPECT_NE(brick.find("[1000000000, 4e+10] Hz"), std::string::npos) << brick;
  EXPECT_EQ(rejected_field([] { radio_permittivity(Material::floorboard, 24e9); }), "frequency_hz");
  EXPECT_EQ(rejected_field([] { radio_permittivity(Material::concrete, 100e9); }), "accepted");
  EXPECT_EQ(rejected_field([] { radio_permittivity(Material::concrete, 100.1e9); }),
            "frequency_hz");
  EXPECT_EQ(rejected_field([] { radio_permittivity(Material::plastic, 5e9); }), "frequency_hz");
}

TEST(Materials, NamesReadBackAndUnknownNamesAreListed) {
  const std::vector<std::string> names = material_names.names();
  EXPECT_EQ(names.size(), 16u);
  for (const std::string& name : names) {
    EXPECT_EQ(to_string(material_names.parse(name, "material")), name);
  }
  const std::string message = message_of([] { material_names.parse("steel", "--material"); });
  EXPECT_NE(message.find("--material = 'steel'"), std::string::npos) << message;
  EXPECT_NE(message.find("concrete"), std::string::npos) << message;
  EXPECT_NE(message.find("plastic"), std::string::npos) << message;
}

// ITU-R P.840's double-Debye model gives m = 3.67 + 2.16i for water at 77 GHz and 20 C (three
// figures; tests/propagation/test_water_film.cpp).
TEST(Materials, WaterIsLiebeAt20C) {
  const complex m = refractive_index_from_permittivity(radio_permittivity(Material::water, 77e9));
  EXPECT_NEAR(m.real(), 3.67, 0.006);
  EXPECT_NEAR(m.imag(), 2.16, 0.006);
}

TEST(Materials, PlasticIsLowLossPolyethylene) {
  const complex eps = radio_permittivity(Material::plastic, 77e9);
  EXPECT_NEAR(eps.real(), 1.526 * 1.526, 1e-12);
  EXPECT_NEAR(eps.imag() / eps.real(), 3e-4, 1e-15);
}

// Normal incidence: TE = (1 - sqrt(eps)) / (1 + sqrt(eps)), TM = -TE (the sign convention).
TEST(Fresnel, NormalIncidenceClosedForm) {
  for (const complex eps : {complex(4.0, 0.0), complex(5.24, 0.3225), complex(80.0, 30.0)}) {
    const complex root = std::sqrt(eps);
    const complex expected = (1.0 - root) / (1.0 + root);
    const FresnelCoefficients g = fresnel_reflection(eps, 90.0 * deg);
    EXPECT_NEAR(std::abs(g.te - expected), 0.0, 1e-14);
    EXPECT_NEAR(std::abs(g.tm + expected), 0.0, 1e-14);
  }
}

// Grazing incidence: both coefficients tend to -1, as 1 - O(psi).
TEST(Fresnel, GrazingTendsToMinusOne) {
  for (const complex eps : {complex(4.0, 0.0), complex(5.24, 0.3225)}) {
    const FresnelCoefficients g = fresnel_reflection(eps, 1e-6);
    EXPECT_NEAR(std::abs(g.te + 1.0), 0.0, 1e-5);
    EXPECT_NEAR(std::abs(g.tm + 1.0), 0.0, 1e-5);
  }
}

// Brewster: for real eps, TM vanishes at grazing angle psi_B = atan(1 / sqrt(eps)) (B&W 1.5.3),
// and not on either side of it; TE does not vanish there.
TEST(Fresnel, BrewsterAngleForTm) {
  for (const double eps : {2.25, 4.0, 6.31}) {
    const double brewster = std::atan(1.0 / std::sqrt(eps));
    validate({.id = "propagation.materials.fresnel.brewster.eps" + id_number(eps),
              .group = "physics: materials",
              .quantity = "|Gamma_TM| at Brewster's grazing angle",
              .unit = "1",
              .conditions = "real eps = " + id_number(eps) +
                            ", psi_B = atan(1/sqrt(eps)) = " + id_number(brewster / deg) + " deg",
              .reference = 0.0,
              .source = "Brewster's angle, Born & Wolf 7th ed. sec. 1.5.3",
              .value = std::abs(fresnel_reflection(eps, brewster).tm),
              .tolerance = 1e-14,
              .kind = Tolerance::absolute});
    EXPECT_GT(std::abs(fresnel_reflection(eps, brewster - 2.0 * deg).tm), 0.01);
    EXPECT_GT(std::abs(fresnel_reflection(eps, brewster + 2.0 * deg).tm), 0.01);
    EXPECT_GT(std::abs(fresnel_reflection(eps, brewster).te), 0.2);
  }
}

// P.2040's metal (sigma = 1e7 S/m, |eps| ~ 2e6 at 77 GHz) against the surface-impedance
// (Leontovich) limit of a good conductor, Z = 1 / sqrt(eps): TE = (Z sin psi - 1) / (Z sin psi +
// 1), TM = (sin psi - Z) / (sin psi + Z), exact to O(1 / |eps|) (Senior & Volakis, Approximate
// Boundary Conditions in Electromagnetics, 1995, ch. 2). From 10 deg up both are 1 to 1e-2; TM dips
// only near its pseudo-Brewster angle, sin psi ~ |Z| (0.04 deg here).
TEST(Fresnel, MetalReflectsAlmostAll) {
  const complex eps = radio_permittivity(Material::metal, 77e9);
  const complex z = 1.0 / std::sqrt(eps);
  for (const double psi_deg : {0.01, 0.04, 0.3, 1.0, 10.0, 30.0, 60.0, 90.0}) {
    const double s = std::sin(psi_deg * deg);
    const FresnelCoefficients g = fresnel_reflection(eps, psi_deg * deg);
    EXPECT_NEAR(std::abs(g.te - (z * s - 1.0) / (z * s + 1.0)), 0.0, 1e-6) << psi_deg;
    EXPECT_NEAR(std::abs(g.tm - (s - z) / (s + z)), 0.0, 1e-6) << psi_deg;
    if (psi_deg >= 10.0) {
      EXPECT_NEAR(std::abs(g.te), 1.0, 1e-2);
      EXPECT_NEAR(std::abs(g.tm), 1.0, 1e-2);
    }
  }
}

// A lossy case against numpy: concrete at 77 GHz, 30 deg grazing,
// /usr/bin/python3 -c "import numpy as np; eps=5.24+1j*17.98*0.0462*77**0.7822/77;
//   p=np.radians(30); r=np.sqrt(eps-np.cos(p)**2); print((np.sin(p)-r)/(np.sin(p)+r),
//   (eps*np.sin(p)-r)/(eps*np.sin(p)+r))"
TEST(Fresnel, LossyConcreteAgainstNumpy) {
  const FresnelCoefficients g =
      fresnel_reflection(radio_permittivity(Material::concrete, 77e9), 30.0 * deg);
  EXPECT_NEAR(g.te.real(), -0.618689385437426, 1e-12);
  EXPECT_NEAR(g.te.imag(), -0.011067378330502115, 1e-12);
  EXPECT_NEAR(g.tm.real(), 0.10604318396805577, 1e-12);
  EXPECT_NEAR(g.tm.imag(), 0.012665738981663503, 1e-12);
}

// Fused silica: n_d = 1.4585 at 587.56 nm and n = 1.4440 at 1550 nm (Malitson 1965's values, as
// optical glass catalogues list them).
TEST(OpticalIndex, FusedSilicaPublishedValues) {
  const SegelsteinTable table;
  EXPECT_NEAR(optical_refractive_index(Material::glass, 587.56e-9, table).real(), 1.4585, 1e-4);
  EXPECT_NEAR(optical_refractive_index(Material::glass, 1550e-9, table).real(), 1.4440, 1e-4);
}

// Aluminium: Rakic's Lorentz-Drude model evaluated by numpy (w = 1239.841984 / 905 eV, the sum of
// the Drude and four Lorentz terms of Rakic 1998 Table 1, then sqrt), and its normal-incidence
// reflectance at 1550 nm, about 0.97 for aluminium in the near infrared.
TEST(OpticalIndex, AluminiumRakic) {
  const SegelsteinTable table;
  const complex m905 = optical_refractive_index(Material::metal, 905e-9, table);
  EXPECT_NEAR(m905.real(), 1.9714625626421218, 1e-9);
  EXPECT_NEAR(m905.imag(), 8.25472375342162, 1e-9);
  const complex m1550 = optical_refractive_index(Material::metal, 1550e-9, table);
  EXPECT_NEAR(m1550.real(), 1.5355444308646036, 1e-9);
  EXPECT_NEAR(m1550.imag(), 15.3304002742725, 1e-9);
  const double reflectance = std::norm((1.0 - m1550) / (1.0 + m1550));
  EXPECT_GT(reflectance, 0.96);
  EXPECT_LT(reflectance, 0.99);
}

TEST(OpticalIndex, WaterIsSegelsteinAndOthersAreRefused) {
  const SegelsteinTable table;
  EXPECT_EQ(optical_refractive_index(Material::water, 905e-9, table),
            table.refractive_index(905e-9));
  const std::string message = [&table] {
    try {
      optical_refractive_index(Material::concrete, 905e-9, table, "--wavelength-nm");
    } catch (const InvalidParameter& error) {
      EXPECT_EQ(error.field(), "--wavelength-nm");
      return std::string(error.what());
    }
    return std::string("accepted");
  }();
  EXPECT_NE(message.find("'concrete'"), std::string::npos) << message;
  EXPECT_NE(message.find("water, glass, metal"), std::string::npos) << message;
  EXPECT_EQ(rejected_field([&table] { optical_refractive_index(Material::metal, 300e-9, table); }),
            "wavelength_m");
  EXPECT_EQ(rejected_field([&table] { optical_refractive_index(Material::glass, 4e-6, table); }),
            "wavelength_m");
}

}  // namespace
}  // namespace fogradar::propagation
