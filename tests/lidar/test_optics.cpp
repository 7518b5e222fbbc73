// The lidar's fog optics at 905 nm (alpha = extinction, beta_pi = volume backscatter / 4 pi), each
// against a reference independent of the Mie series:
// - the Rayleigh limit (Bohren & Huffman 1983 eq. 5.7-5.8 with the 180 deg phase function 3/2 of
//   dipole scattering, i.e. sigma_b = pi^5 D^6 / lambda^4 |K|^2) for droplets of x = 0.035;
// - van de Hulst's anomalous-diffraction extinction (Light Scattering by Small Particles, 1957,
//   §11.22) for large droplets;
// - the lidar ratio of liquid-water clouds and fog at 905 nm, S = 18.8 sr (O'Connor, Illingworth &
//   Hogan 2004, J. Atmos. Oceanic Technol. 21, 777-786, who calibrate 905 nm ceilometers on it).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "fogradar/lidar/lidar.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "validation.hpp"

namespace fogradar::lidar {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

constexpr double pi = std::numbers::pi;
constexpr double wavelength_m = 905e-9;
constexpr double water_density_g_per_m3 = 1e6;

const propagation::SegelsteinTable& table() {
  static const propagation::SegelsteinTable instance;
  return instance;
}

propagation::ChamberSpec one_layer(propagation::DropSizeDistribution droplets, double lwc) {
  propagation::ChamberSpec chamber;
  chamber.layers.resize(1);
  chamber.layers[0].fog = {.density = propagation::LiquidWaterContent{lwc}, .droplets = droplets};
  return chamber;
}

// Number of droplets of diameter D per m^3 holding `lwc` g/m^3 of water.
double concentration(double diameter_m, double lwc) {
  return lwc / (water_density_g_per_m3 * pi * std::pow(diameter_m, 3) / 6.0);
}

// Rayleigh limit: x = pi 10 nm / 905 nm = 0.035; Mie's first corrections are O(x^2) ~ 1e-3, so the
// coefficients agree to 1 %.
TEST(LidarOptics, SmallDropletsMatchTheRayleighLimit) {
  const double d = 10e-9;
  const double lwc = 0.1;
  const Lidar lidar(LidarParams{}, one_layer(propagation::Monodisperse{d}, lwc), table());
  const std::complex<double> m = table().refractive_index(wavelength_m);
  const std::complex<double> k = (m * m - 1.0) / (m * m + 2.0);
  const double n = concentration(d, lwc);
  const double scattering =
      2.0 * std::pow(pi, 5) * std::pow(d, 6) / (3.0 * std::pow(wavelength_m, 4)) * std::norm(k);
  const double absorption = pi * pi * std::pow(d, 3) / wavelength_m * k.imag();
  const double backscatter =
      std::pow(pi, 5) * std::pow(d, 6) / std::pow(wavelength_m, 4) * std::norm(k);
  validate({.id = "lidar.optics.rayleigh.extinction.D10nm",
            .group = "lidar",
            .quantity = "fog extinction coefficient alpha",
            .unit = "1/m",
            .conditions = "905 nm, monodisperse D = 10 nm (x = 0.035), 0.1 g/m^3",
            .reference = n * (scattering + absorption),
            .source = "Rayleigh limit: Bohren & Huffman 1983 eq. 5.7-5.8",
            .value = lidar.layer_extinction_per_m(0),
            .tolerance = 0.01,
            .kind = Tolerance::relative});
  validate({.id = "lidar.optics.rayleigh.backscatter.D10nm",
            .group = "lidar",
            .quantity = "fog backscatter coefficient beta_pi",
            .unit = "1/(m sr)",
            .conditions = "905 nm, monodisperse D = 10 nm (x = 0.035), 0.1 g/m^3",
            .reference = n * backscatter / (4.0 * pi),
            .source = "Rayleigh limit: Bohren & Huffman 1983 eq. 5.7-5.8, dipole phase function "
                      "3/2 at 180 deg",
            .value = lidar.layer_backscatter_per_m_sr(0),
            .tolerance = 0.01,
            .kind = Tolerance::relative});
}

// Anomalous diffraction, Q = 2 - 4/rho sin(rho) + 4/rho^2 (1 - cos(rho)), rho = 2 x (n - 1). It
// lacks the edge (grazing-ray) term of the exact extinction, about +2 x^(-2/3) (Nussenzveig &
// Wiscombe 1980, Phys. Rev. Lett. 45, 1490): +4 % at x = 120 (D = 35 um), +3 % at x = 210 (D = 60
// um), so the tolerance is 5 %.
TEST(LidarOptics, LargeDropletExtinctionMatchesAnomalousDiffraction) {
  for (const double d : {35e-6, 60e-6}) {
    const double lwc = 0.2;
    const Lidar lidar(LidarParams{}, one_layer(propagation::Monodisperse{d}, lwc), table());
    const double x = pi * d / wavelength_m;
    const double rho = 2.0 * x * (table().refractive_index(wavelength_m).real() - 1.0);
    const double q = 2.0 - 4.0 / rho * std::sin(rho) + 4.0 / (rho * rho) * (1.0 - std::cos(rho));
    const double expected = concentration(d, lwc) * q * pi * d * d / 4.0;
    const std::string diameter_um = std::to_string(static_cast<int>(std::round(d * 1e6)));
    validate({.id = "lidar.optics.anomalous_diffraction.extinction.D" + diameter_um + "um",
              .group = "lidar",
              .quantity = "fog extinction coefficient alpha",
              .unit = "1/m",
              .conditions = "905 nm, monodisperse D = " + diameter_um + " um, 0.2 g/m^3",
              .reference = expected,
              .source = "anomalous diffraction: van de Hulst 1957 §11.22",
              .value = lidar.layer_extinction_per_m(0),
              .tolerance = 0.05,
              .kind = Tolerance::relative});
  }
}

// Fog or cloud droplets of a broad distribution (lognormal, median 10 um, sigma_g 1.5: effective
// radius ~7 um) have S = alpha / beta_pi = 18.8 sr at 905 nm (O'Connor et al. 2004; they give it as
// nearly constant for effective radii 4-20 um). Tolerance 15 %: the spread of measured and
// computed water-cloud lidar ratios near 1 um in that paper and its references (about 17-21 sr).
TEST(LidarOptics, LidarRatioOfNaturalFogIsAbout19Sr) {
  const Lidar lidar(
      LidarParams{},
      one_layer(propagation::Lognormal{.median_diameter_m = 10e-6, .geometric_std = 1.5}, 0.1),
      table());
  const double ratio = lidar.layer_extinction_per_m(0) / lidar.layer_backscatter_per_m_sr(0);
  validate({.id = "lidar.optics.lidar_ratio.lognormal10um",
            .group = "lidar",
            .quantity = "lidar ratio S = alpha / beta_pi",
            .unit = "sr",
            .conditions = "905 nm, lognormal fog, median 10 um, sigma_g 1.5, 0.1 g/m^3",
            .reference = 18.8,
            .source = "O'Connor, Illingworth & Hogan 2004, J. Atmos. Oceanic Technol. 21, 777-786",
            .value = ratio,
            .tolerance = 0.15,
            .kind = Tolerance::relative});
}

// The same fog in every layer: each layer resolved identically, at its own interval of the chamber.
TEST(LidarOptics, LayersTileTheChamber) {
  const propagation::ChamberSpec chamber;  // the study's: 2 m gap, four 1 m layers
  const Lidar lidar(LidarParams{}, chamber, table());
  ASSERT_EQ(lidar.layer_count(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(lidar.layer_start_m(i), 2.0 + static_cast<double>(i));
    EXPECT_DOUBLE_EQ(lidar.layer_end_m(i), 3.0 + static_cast<double>(i));
    EXPECT_EQ(lidar.layer_extinction_per_m(i), lidar.layer_extinction_per_m(0));
  }
  EXPECT_DOUBLE_EQ(lidar.target_range_m(), 10.0);
}

}  // namespace
}  // namespace fogradar::lidar
