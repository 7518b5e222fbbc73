// The sensor benchmark's physics (docs/sensor-benchmark.md): two instances of one kind whose
// parameters differ only in their band, configured in one scenario through their kind
// (Scenario::configure, sensor::SensorKind::configure), and the fog as each configured sensor sees
// it (sensor::ConfiguredSensor::fog_report, the numbers a run uses). References: ITU-R P.840-8's
// K_l written out in support/itu_p840.hpp; the Mie series of Bohren & Huffman 1983 Appendix A
// written out in support/bhmie.hpp, itself checked here against the book's sample output.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "bhmie.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/propagation/dsd.hpp"
#include "fogradar/propagation/water.hpp"
#include "itu_p840.hpp"
#include "validation.hpp"

namespace fogradar::experiment {
namespace {

using fogradar::testing::bhmie;
using fogradar::testing::p840_k_l;
using fogradar::testing::Tolerance;
using fogradar::testing::validate;

const propagation::SegelsteinTable& water() {
  static const propagation::SegelsteinTable instance;
  return instance;
}

// The fog of the scenario's first layer as the sensor named `name` sees it.
nlohmann::json fog_view(const Scenario& s, const std::string& name) {
  const propagation::ChamberSpec chamber = s.chamber_spec();
  const propagation::FogLayerSpec& layer = chamber.layers.front();
  return s.configure(name)->fog_report(layer.fog, layer.length_m, water()).json;
}

// ---- Radar: 24.125 GHz against the study's 77 GHz ----------------------------------------------

// The study's fog (beta 900 /km at 550 nm, lognormal droplets of median 1 um, Liebe water at 20 C)
// seen by the study's 77 GHz radar and by one at the 24.0-24.25 GHz ISM band's centre, 24.125 GHz.
// Both are Rayleigh (x = pi D / lambda < 0.05 even for the largest droplet of the quadrature, the
// D^6 tail's 46 um; the corrections to Rayleigh absorption are O(x^2)), where the
// attenuation is K_l(f, T) x LWC with the same LWC for both: the ratio of their two-way losses per
// layer is P.840's K_l(24.125 GHz) / K_l(77 GHz) = 0.113 at 20 C. Tolerance 3 %: the benchmark's
// requirement (the Mie sum agrees with P.840's closed form to 0.03 %, test_sensor_bands.cpp);
// measured 0.0007 %.
TEST(SensorBenchmarkRadar, FogLossRatio24To77GHzIsP840s) {
  const Scenario s = parse_scenario(
      "[fog]\ntemperature_c = 20.0\n[radar_24]\nkind = \"radar\"\ncentre_frequency_hz = "
      "24.125e9\n[experiment]\nsensors = [\"radar\", \"radar_24\"]\n",
      "radars.toml");

  const double largest_droplet_m = propagation::quadrature_range(s.fog.droplets).max_m;
  for (const double f_hz : {24.125e9, 77e9}) {
    EXPECT_LT(std::numbers::pi * largest_droplet_m * f_hz / 299792458.0, 0.05) << f_hz;
  }

  const nlohmann::json at_24 = fog_view(s, "radar_24");
  const nlohmann::json at_77 = fog_view(s, "radar");
  EXPECT_EQ(at_24.at("frequency_hz").get<double>(), 24.125e9);
  EXPECT_EQ(at_77.at("frequency_hz").get<double>(), 77e9);
  validate({.id = "benchmark.radar.loss_ratio_24_77.20C",
            .group = "physics: sensor bands",
            .quantity = "two-way fog loss per layer, 24.125 GHz radar / 77 GHz radar",
            .unit = "1",
            .conditions = "the paper scenario's fog (β 900 /km, lognormal 1 µm, σg 1.5), 20 °C, "
                          "Liebe; the radar and an instance radar_24 alike but for "
                          "centre_frequency_hz",
            .reference = p840_k_l(24.125, 20.0) / p840_k_l(77.0, 20.0),
            .source = "ITU-R P.840-8 eqs. (2)-(9), written out in support/itu_p840.hpp",
            .value = at_24.at("two_way_loss_db_per_layer").get<double>() /
                     at_77.at("two_way_loss_db_per_layer").get<double>(),
            .tolerance = 0.03,
            .kind = Tolerance::relative});
}

// ---- Lidar: 1550 nm against the study's 905 nm --------------------------------------------------

// The independent reference's own check: Bohren & Huffman 1983 Appendix A's sample output, radius
// 0.525 um, wavelength 0.6328 um, m = 1.55: Q_ext = 3.10543 (six digits: tolerance 2e-6).
TEST(SensorBenchmarkLidar, ReferenceMieSeriesReproducesBohrenHuffmanSample) {
  const double x = 2.0 * std::numbers::pi * 0.525 / 0.6328;
  EXPECT_NEAR(bhmie(x, {1.55, 0.0}).extinction, 3.10543, 2e-6 * 3.10543);
}

// Water's index at the three wavelengths from Segelstein 1981, typed in from the rows nearest to
// 550, 905 and 1550 nm (549.5, 905.7 and 1549 nm: within 1 nm, where n changes by < 1e-4).
struct Band {
  const char* name;
  double wavelength_m;
  std::complex<double> index;
};
constexpr Band visible{"550nm", 550e-9, {1.335972, 2.442e-9}};
constexpr Band lidar_bands[] = {{"905nm", 905e-9, {1.323520, 5.150e-7}},
                                {"1550nm", 1550e-9, {1.310923, 1.348e-4}}};

// Monodisperse droplets of diameter 1 um (the study's "diameter about 1 µm", sec. III-B; not
// radius) at beta = 900 /km at 550 nm, seen by the study's 905 nm lidar and by one at 1550 nm. With
// one droplet size the number density cancels: beta(lambda) = beta_550 Q_ext(pi D / lambda) /
// Q_ext(pi D / 550 nm), each Q_ext from the Mie series written out in support/bhmie.hpp (x = 3.47
// at 905 nm, 2.03 at 1550 nm, 5.71 at 550 nm). Tolerance 3 %: the benchmark's requirement (the
// index rows above against the table's interpolation at the exact wavelengths move Q_ext by < 0.1
// %).
TEST(SensorBenchmarkLidar, ExtinctionOfOneMicronDropletsMatchesIndependentMie) {
  const std::string fog =
      "[fog]\nextinction_per_km = 900.0\n[fog.droplets]\ndistribution = \"monodisperse\"\n"
      "diameter_m = 1e-6\n";
  const Scenario s = parse_scenario(
      fog + "[lidar_1550]\nkind = \"lidar\"\nwavelength_m = 1550e-9\n", "lidars.toml");
  const double diameter_m = 1e-6, beta_550_per_m = 0.9;
  const double q_550 =
      bhmie(std::numbers::pi * diameter_m / visible.wavelength_m, visible.index).extinction;

  double extinction_per_m[2];
  for (int i = 0; i < 2; ++i) {
    const Band& band = lidar_bands[i];
    const nlohmann::json view = fog_view(s, i == 0 ? "lidar" : "lidar_1550");
    EXPECT_EQ(view.at("wavelength_m").get<double>(), band.wavelength_m);
    extinction_per_m[i] = view.at("extinction_per_m").get<double>();
    const double q =
        bhmie(std::numbers::pi * diameter_m / band.wavelength_m, band.index).extinction;
    validate({.id = std::string("benchmark.lidar.extinction.monodisperse_1um.") + band.name,
              .group = "physics: sensor bands",
              .quantity = "fog extinction seen by the lidar",
              .unit = "1/m",
              .conditions = std::string("monodisperse droplets of diameter 1 µm, β 900 /km at 550 "
                                        "nm; the lidar and an instance lidar_1550 at ") +
                            band.name,
              .reference = beta_550_per_m * q / q_550,
              .source = "β550 Q_ext(λ)/Q_ext(550 nm), BHMIE (Bohren & Huffman 1983 App. A) written "
                        "out in support/bhmie.hpp, Segelstein rows typed in",
              .value = extinction_per_m[i],
              .tolerance = 0.03,
              .kind = Tolerance::relative});
  }
  // The 1550 nm lidar sees less of this fog: the droplets are near the first extinction maximum at
  // 905 nm and below it at 1550 nm.
  EXPECT_LT(extinction_per_m[1], 0.5 * extinction_per_m[0]);
}

}  // namespace
}  // namespace fogradar::experiment
