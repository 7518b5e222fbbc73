// The chamber channel. References: the path integral of a piecewise-constant attenuation written
// out by hand for the study's geometry (l_s = 2 m, four 1 m layers, l_t = 4 m); the volume integral
// of eta over a spherical shell sector; eq. 4 of the virtual layer model as a second method.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/propagation/layer_model.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::propagation {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

const SegelsteinTable& table() {
  static const SegelsteinTable instance;
  return instance;
}

ChamberSpec paper_chamber(double lwc_g_per_m3) {
  ChamberSpec spec;
  for (FogLayerSpec& layer : spec.layers) layer.fog.density = LiquidWaterContent{lwc_g_per_m3};
  return spec;
}

TEST(Chamber, PaperGeometry) {
  const ChamberSpec spec = paper_chamber(1.0);
  EXPECT_DOUBLE_EQ(spec.target_range_m(), 10.0);
  const Chamber chamber(spec, 77e9, table());
  ASSERT_EQ(chamber.layer_count(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(chamber.layer(i).start_m, 2.0 + static_cast<double>(i));
    EXPECT_DOUBLE_EQ(chamber.layer(i).end_m, 3.0 + static_cast<double>(i));
  }
}

TEST(Chamber, TwoWayAttenuationIsThePathIntegral) {
  const Chamber chamber(paper_chamber(2.0), 77e9, table());
  const double a_db_per_m = chamber.layer(0).optics.specific_attenuation_db_per_km * 1e-3;
  ASSERT_GT(a_db_per_m, 0.0);
  const std::string path_integral =
      "closed form: path integral of the piecewise-constant attenuation, 2 x layer length x "
      "specific attenuation";
  const auto check = [&](const std::string& id, const std::string& quantity,
                         const std::string& unit, const std::string& conditions, double value,
                         double reference, Tolerance kind, double tolerance) {
    validate({.id = "propagation.chamber.two_way." + id,
              .group = "physics: chamber",
              .quantity = quantity,
              .unit = unit,
              .conditions = "77 GHz, 2 g/m³ per layer, " + conditions,
              .reference = reference,
              .source = path_integral,
              .value = value,
              .tolerance = tolerance,
              .kind = kind});
  };
  for (std::size_t k = 0; k <= 4; ++k) {
    const ActiveLayers active = first_layers_active(k, 4);
    const std::string layers = std::to_string(k) + " layers on";
    // To the target every active layer is crossed twice over its full metre.
    check("attenuation.target10m." + std::to_string(k) + "layers", "two-way attenuation", "dB",
          "target at 10 m, " + layers, chamber.two_way_attenuation_db(10.0, active),
          2.0 * static_cast<double>(k) * a_db_per_m, Tolerance::absolute, 1e-12);
    // In front of the fog nothing is lost.
    check("attenuation.before_fog1.5m." + std::to_string(k) + "layers", "two-way attenuation", "dB",
          "range 1.5 m (before the fog), " + layers, chamber.two_way_attenuation_db(1.5, active),
          0.0, Tolerance::absolute, 0.0);
  }
  // Half way into the third layer with three layers on: 2 * (1 + 1 + 0.5) m.
  check("attenuation.range4.5m.3layers", "two-way attenuation", "dB",
        "range 4.5 m (half way into layer 3), 3 layers on",
        chamber.two_way_attenuation_db(4.5, first_layers_active(3, 4)), 5.0 * a_db_per_m,
        Tolerance::absolute, 1e-12);
  // Only the last layer switched on (not the study's order, but a valid chamber state).
  check("attenuation.target10m.last_layer_only", "two-way attenuation", "dB",
        "target at 10 m, only layer 4 on",
        chamber.two_way_attenuation_db(10.0, {false, false, false, true}), 2.0 * a_db_per_m,
        Tolerance::absolute, 1e-12);
  check("transmittance.target10m.4layers", "two-way transmittance", "1",
        "target at 10 m, 4 layers on",
        chamber.two_way_transmittance(10.0, first_layers_active(4, 4)),
        std::pow(10.0, -0.8 * a_db_per_m), Tolerance::absolute, 1e-12);
}

// Second method: a layer of thickness d is kappa virtual layers of d/kappa with tau = exp(-alpha
// d/kappa); eq. 4 with rho_obj = 1 gives tau^(2 kappa) = the chamber's two-way transmittance.
TEST(Chamber, AgreesWithVirtualLayerEq4) {
  const Chamber chamber(paper_chamber(20.0), 77e9, table());
  const double alpha_per_m = chamber.layer(0).optics.extinction_per_m;
  const unsigned kappa = 4 * 20;  // 4 m of fog in 5 cm virtual layers
  const VirtualLayer virtual_layer = virtual_layer_from_fog(alpha_per_m, 0.0, 0.05);
  EXPECT_NEAR(object_intensity(kappa, virtual_layer.transmittance, 1.0) /
                  chamber.two_way_transmittance(10.0, first_layers_active(4, 4)),
              1.0, 1e-12);
}

// sigma = eta omega (b^3 - a^3)/3: checked against a midpoint sum of eta omega r^2 dr.
TEST(Chamber, BackscatterIsTheVolumeIntegral) {
  const Chamber chamber(paper_chamber(0.5), 77e9, table());
  const double eta = chamber.layer(0).optics.volume_backscatter_m2_per_m3;
  const double omega = 0.03;
  const ActiveLayers active = first_layers_active(2, 4);
  const double r0 = 2.5, r1 = 7.0;  // half of layer 1, all of layer 2, layers 3-4 off
  // Only [2.5, 4] holds fog (layer 1 is [2, 3], layer 2 is [3, 4]).
  double midpoint = 0.0;
  const int steps = 100000;
  const double fog_end = 4.0, width = (fog_end - r0) / steps;
  for (int i = 0; i < steps; ++i) {
    const double r = r0 + width * (i + 0.5);
    midpoint += eta * omega * r * r * width;
  }
  const auto check = [](const std::string& id, const std::string& conditions, double value,
                        double reference, const std::string& source, Tolerance kind,
                        double tolerance) {
    validate({.id = "propagation.chamber.backscatter_cross_section." + id,
              .group = "physics: chamber",
              .quantity = "fog backscatter cross section",
              .unit = "m^2",
              .conditions = "77 GHz, 0.5 g/m³ per layer, omega = 0.03 sr, " + conditions,
              .reference = reference,
              .source = source,
              .value = value,
              .tolerance = tolerance,
              .kind = kind});
  };
  check("shell2.5_7m.2layers", "shell 2.5-7 m, layers 1-2 on",
        chamber.backscatter_cross_section_m2(r0, r1, omega, active), midpoint,
        "volume integral of eta omega r^2 dr, midpoint sum (1e5 steps) in the test",
        Tolerance::relative, 1e-8);
  check("shell0_2m.2layers", "shell 0-2 m (before the fog), layers 1-2 on",
        chamber.backscatter_cross_section_m2(0.0, 2.0, omega, active), 0.0,
        "limiting case: no fog in the shell, no backscatter", Tolerance::absolute, 0.0);
  check("shell0_10m.no_layers", "shell 0-10 m, no layer on",
        chamber.backscatter_cross_section_m2(0.0, 10.0, omega, first_layers_active(0, 4)), 0.0,
        "limiting case: no fog in the shell, no backscatter", Tolerance::absolute, 0.0);
}

// Layers of the same fog share one resolution of it (chamber.cpp); each layer must still carry what
// its own fog gives alone, so a fog differing from an earlier one in any field is resolved anew.
// Reference: Fog constructed from each layer's spec on its own; the same arithmetic, so equal bits.
TEST(Chamber, EachLayerHasItsOwnFogsOptics) {
  FogSpec thin;
  thin.density = OpticalExtinction{300.0};
  FogSpec wider_droplets = thin;
  wider_droplets.droplets = Lognormal{.median_diameter_m = 1e-6, .geometric_std = 1.6};
  FogSpec table_index = thin;  // the other water model, at the only temperature it takes
  table_index.water_model = WaterModel::segelstein;
  table_index.temperature_c = segelstein_table_temperature_c;
  FogSpec warmer = thin;  // Liebe's index at 77 GHz depends on the temperature
  warmer.temperature_c = 30.0;
  FogSpec by_lwc;
  by_lwc.density = LiquidWaterContent{0.5};
  const std::vector<FogSpec> fogs{thin,        FogSpec{}, thin,   wider_droplets, by_lwc,
                                  table_index, FogSpec{}, warmer, by_lwc};

  ChamberSpec spec;
  spec.layers.clear();
  for (const FogSpec& fog : fogs) spec.layers.push_back({.length_m = 0.5, .fog = fog});
  const Chamber chamber(spec, 77e9, table());
  ASSERT_EQ(chamber.layer_count(), fogs.size());
  for (std::size_t i = 0; i < fogs.size(); ++i) {
    SCOPED_TRACE(i);
    const Fog alone(fogs[i], table());
    const FogOptics expected = alone.at_frequency(77e9);
    const LayerOptics& layer = chamber.layer(i);
    EXPECT_EQ(layer.lwc_g_per_m3, alone.lwc_g_per_m3());
    EXPECT_EQ(layer.optics.extinction_per_m, expected.extinction_per_m);
    EXPECT_EQ(layer.optics.absorption_per_m, expected.absorption_per_m);
    EXPECT_EQ(layer.optics.scattering_per_m, expected.scattering_per_m);
    EXPECT_EQ(layer.optics.specific_attenuation_db_per_km, expected.specific_attenuation_db_per_km);
    EXPECT_EQ(layer.optics.volume_backscatter_m2_per_m3, expected.volume_backscatter_m2_per_m3);
    EXPECT_EQ(layer.optics.refractive_index, expected.refractive_index);
    EXPECT_DOUBLE_EQ(layer.start_m, spec.sensor_gap_m + 0.5 * static_cast<double>(i));
  }
  // The fogs differ where they should: otherwise the test could not tell a wrong reuse.
  EXPECT_NE(chamber.layer(0).lwc_g_per_m3, chamber.layer(3).lwc_g_per_m3);
  EXPECT_NE(chamber.layer(0).optics.extinction_per_m, chamber.layer(5).optics.extinction_per_m);
  EXPECT_NE(chamber.layer(0).optics.extinction_per_m, chamber.layer(7).optics.extinction_per_m);
  EXPECT_NE(chamber.layer(0).lwc_g_per_m3, chamber.layer(1).lwc_g_per_m3);
}

TEST(Chamber, RejectsInvalidGeometryAndStates) {
  const auto field_of = [](const ChamberSpec& spec) {
    return test_support::rejected_field([&] { Chamber(spec, 77e9, table()); });
  };
  ChamberSpec spec;
  spec.layers[2].length_m = 0.0;
  EXPECT_EQ(field_of(spec), "chamber.layers[2].length_m");
  spec = ChamberSpec{};
  spec.sensor_gap_m = -1.0;
  EXPECT_EQ(field_of(spec), "chamber.sensor_gap_m");
  spec = ChamberSpec{};
  spec.target_gap_m = std::nan("");
  EXPECT_EQ(field_of(spec), "chamber.target_gap_m");
  spec = ChamberSpec{};
  spec.layers.clear();
  EXPECT_EQ(field_of(spec), "chamber.layers");
  spec = ChamberSpec{};
  spec.layers[1].fog.density = LiquidWaterContent{-1.0};
  EXPECT_EQ(field_of(spec), "fog.lwc_g_per_m3");
  spec = ChamberSpec{};
  spec.sensor_gap_m = 0.0;  // fog up to the sensor and the target is a valid chamber
  spec.target_gap_m = 0.0;
  EXPECT_EQ(field_of(spec), "accepted");

  const Chamber chamber(ChamberSpec{}, 77e9, table());
  EXPECT_THROW(first_layers_active(5, 4), InvalidParameter);
  EXPECT_THROW(chamber.two_way_attenuation_db(10.0, ActiveLayers(3, true)), InvalidParameter);
  EXPECT_THROW(chamber.two_way_attenuation_db(-1.0, first_layers_active(1, 4)), InvalidParameter);
  EXPECT_THROW(chamber.backscatter_cross_section_m2(5.0, 4.0, 0.1, first_layers_active(1, 4)),
               InvalidParameter);
}

}  // namespace
}  // namespace fogradar::propagation
