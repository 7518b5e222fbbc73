// Layers of their own ([[chamber.layers]]) and the switching order (experiment.switching_order):
// every sensor's path to the target is Beer–Lambert layer by layer over the layers switched on, in
// the order they come on. References, neither computed by fogradar:
//  - the radar: ITU-R P.840-8's K_l (support/itu_p840.hpp) times each layer's LWC, length and
//    temperature; the droplets (20 µm) are Rayleigh-small at 77 GHz (x = 0.016), where the Mie sum
//    and P.840 agree within 3 % (test_fog.cpp);
//  - the lidar (905 nm) and the camera (visible band): the large-drop limit of the extinction
//    efficiency, Q_ext -> 2 (van de Hulst, Light Scattering by Small Particles, 1957, sec. 8.22),
//    so alpha = 1.5 Q LWC <D^2> / (rho_w <D^3>) for each layer. At x = pi D / lambda of 70 to 110
//    the edge term raises Q by 1.99 x^(-2/3) (Nussenzveig & Wiscombe, Phys. Rev. Lett. 45, 1490
//    (1980)), 4 % to 6 %: the optical depths are checked within 8 %.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "itu_p840.hpp"
#include "sensors.hpp"
#include "validation.hpp"

namespace fogradar::experiment {
namespace {

using fogradar::testing::p840_k_l;
using fogradar::testing::Tolerance;
using fogradar::testing::validate;

// Three layers unlike each other and unlike the study's, switched on middle, far, near. The
// droplets are given once, in [fog.droplets], after the layers: every layer takes them.
constexpr const char* layers_toml = R"(
[chamber]
sensor_gap_m = 2.0
target_gap_m = 4.0

[[chamber.layers]]
length_m = 1.0
fog = { lwc_g_per_m3 = 1.0 }

[[chamber.layers]]
length_m = 0.5
fog = { lwc_g_per_m3 = 4.0, temperature_c = 0.0 }

[[chamber.layers]]
length_m = 2.0
fog = { lwc_g_per_m3 = 2.0 }

[fog.droplets]
distribution = "lognormal"
median_diameter_m = 2e-5
geometric_std = 1.2

[experiment]
sensors = ["radar", "lidar", "camera"]
max_active_layers = 3
switching_order = [1, 2, 0]

[radar]
chirps_per_frame = 16
measurements_per_step = 4

[lidar]
scans_per_step = 3
field_of_view_deg = 12.0

[camera]
frames_per_step = 2
roi = { width_px = 64, height_px = 48 }
)";

struct LayerTruth {
  double length_m;
  double lwc_g_per_m3;
  double temperature_c;
};
constexpr LayerTruth truth[] = {{1.0, 1.0, 20.0}, {0.5, 4.0, 0.0}, {2.0, 2.0, 20.0}};
constexpr std::size_t order[] = {1, 2, 0};

// Extinction (1/m) of a lognormal fog of large drops, Q_ext = 2: the lognormal's moments give
// <D^2> / <D^3> = exp(-2.5 ln^2 sigma_g) / D_median.
double large_drop_extinction_per_m(double lwc_g_per_m3) {
  const double log_sigma = std::log(1.2);
  const double d2_over_d3 = std::exp(-2.5 * log_sigma * log_sigma) / 2e-5;
  return 1.5 * 2.0 * (lwc_g_per_m3 * 1e-3) * d2_over_d3 / 1000.0;
}

// The step's switched layers' sum of f(layer).
template <class PerLayer>
double sum_switched(std::size_t step, PerLayer per_layer) {
  double sum = 0.0;
  for (std::size_t k = 0; k < step; ++k) sum += per_layer(truth[order[k]]);
  return sum;
}

TEST(Layers, EachLayerStartsFromFogAndTakesItsOwnKeys) {
  const Scenario s = parse_scenario(layers_toml, "layers.toml");
  const propagation::ChamberSpec chamber = s.chamber_spec();
  ASSERT_EQ(chamber.layers.size(), 3u);
  EXPECT_DOUBLE_EQ(chamber.target_range_m(), 2.0 + 3.5 + 4.0);
  for (std::size_t i = 0; i < 3; ++i) {
    const propagation::FogSpec& fog = chamber.layers[i].fog;
    EXPECT_EQ(chamber.layers[i].length_m, truth[i].length_m) << i;
    EXPECT_EQ(std::get<propagation::LiquidWaterContent>(fog.density).g_per_m3,
              truth[i].lwc_g_per_m3)
        << i;
    EXPECT_EQ(fog.temperature_c, truth[i].temperature_c) << i;
    EXPECT_EQ(fog.droplets, propagation::DropSizeDistribution(propagation::Lognormal{2e-5, 1.2}))
        << i;
  }
  EXPECT_EQ(s.context().switching_order, (std::vector<std::size_t>{1, 2, 0}));
  EXPECT_EQ(s.context().active(2), (propagation::ActiveLayers{false, true, true}));
  // The resolved scenario reads back to the same chamber and order.
  const Scenario again = parse_scenario(to_toml(s), "scenario.toml");
  EXPECT_EQ(again.chamber_spec().layers, chamber.layers);
  EXPECT_EQ(again.context().switching_order, s.context().switching_order);
  EXPECT_EQ(to_toml(again), to_toml(s));
  // The two named orders.
  const Scenario from_target =
      parse_scenario_over(s, "[experiment]\nswitching_order = \"target_first\"\n", "t.toml");
  EXPECT_EQ(from_target.context().switching_order, (std::vector<std::size_t>{2, 1, 0}));
  const Scenario paper = paper_scenario();
  EXPECT_EQ(paper.context().switching_order, (std::vector<std::size_t>{0, 1, 2, 3}));
}

TEST(Layers, EachSensorsPathIsBeerLambertOverTheLayersSwitchedOnInOrder) {
  const Scenario s = parse_scenario(layers_toml, "layers.toml");
  const sensor::Context context = s.context();
  const ExperimentSummary summary = summarize(run_experiment(s, {.threads = 2, .progress = {}}));
  const auto& radar_steps = radar_report(summary).summary().steps;
  const auto& camera_steps = camera_report(summary).summary().steps;
  const lidar::Lidar& lidar = lidar_report(summary).lidar();
  ASSERT_EQ(radar_steps.size(), 4u);
  ASSERT_EQ(camera_steps.size(), 4u);
  const std::vector<double> no_fluctuation(3, 1.0);
  const auto target_peak = [&](std::size_t step) {
    const std::vector<double> target =
        lidar.waveform(lidar.target_beam(), context.active(step), no_fluctuation).target;
    return *std::max_element(target.begin(), target.end());
  };
  const double clear_peak = target_peak(0);
  const std::string conditions =
      "layers of 1 m at 1 g/m³, 0.5 m at 4 g/m³ and 0 °C, 2 m at 2 "
      "g/m³; lognormal 20 µm drops; switched on 1, 2, 0";
  for (std::size_t step = 1; step <= 3; ++step) {
    const std::string k = std::to_string(step);
    const double radar_db = sum_switched(step, [](const LayerTruth& l) {
      return 2.0 * l.length_m * 1e-3 * p840_k_l(77.0, l.temperature_c) * l.lwc_g_per_m3;
    });
    validate({.id = "experiment.layers.radar_two_way_loss.step" + k,
              .group = "experiment: layers",
              .quantity = "radar two-way fog loss to the target after " + k + " layers",
              .unit = "dB",
              .conditions = conditions,
              .reference = radar_db,
              .source = "ITU-R P.840-8 K_l per layer, summed (Beer–Lambert)",
              .value = radar_steps[step].two_way_attenuation_db,
              .tolerance = 0.03,
              .kind = Tolerance::relative});
    const double depth = sum_switched(step, [](const LayerTruth& l) {
      return large_drop_extinction_per_m(l.lwc_g_per_m3) * l.length_m;
    });
    validate({.id = "experiment.layers.camera_optical_depth.step" + k,
              .group = "experiment: layers",
              .quantity = "camera optical depth -ln t to the target after " + k + " layers",
              .unit = "1",
              .conditions = conditions,
              .reference = depth,
              .source = "Q_ext = 2 (van de Hulst sec. 8.22) per layer, summed (Beer–Lambert)",
              .value = -std::log(camera_steps[step].transmittance),
              .tolerance = 0.08,
              .kind = Tolerance::relative});
    validate({.id = "experiment.layers.lidar_optical_depth.step" + k,
              .group = "experiment: layers",
              .quantity = "lidar two-way optical depth of the target echo after " + k + " layers",
              .unit = "1",
              .conditions = conditions + "; noise-free target beam, no fog fluctuation",
              .reference = 2.0 * depth,
              .source = "Q_ext = 2 (van de Hulst sec. 8.22) per layer, summed (Beer–Lambert)",
              .value = -std::log(target_peak(step) / clear_peak),
              .tolerance = 0.08,
              .kind = Tolerance::relative});
  }
  // summary.json states each layer's place and fog, as the run resolved it.
  const nlohmann::json chamber = nlohmann::json::parse(summary_json(s, summary)).at("chamber");
  EXPECT_EQ(chamber.at("switching_order"), nlohmann::json({1, 2, 0}));
  const nlohmann::json& layers = chamber.at("layers");
  ASSERT_EQ(layers.size(), 3u);
  double start_m = 2.0;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(layers[i].at("start_m").get<double>(), start_m) << i;
    start_m += truth[i].length_m;
    EXPECT_DOUBLE_EQ(layers[i].at("end_m").get<double>(), start_m) << i;
    EXPECT_DOUBLE_EQ(layers[i].at("lwc_g_per_m3").get<double>(), truth[i].lwc_g_per_m3) << i;
    for (const char* name : {"radar", "lidar", "camera"}) {
      EXPECT_TRUE(layers[i].at("sensors").contains(name)) << i << name;
    }
    EXPECT_NEAR(layers[i].at("sensors").at("radar").at("specific_attenuation_db_per_km"),
                p840_k_l(77.0, truth[i].temperature_c) * truth[i].lwc_g_per_m3,
                0.03 * p840_k_l(77.0, truth[i].temperature_c) * truth[i].lwc_g_per_m3)
        << i;
  }
}

// Each refusal: one line naming the key as written, its value and what it allows.
TEST(Layers, BadLayersAndOrdersAreRefusedWithTheTrueRange) {
  const std::string layer = "[[chamber.layers]]\nlength_m = 1.0\n";
  const std::string three = layer + layer + layer;
  const std::pair<std::string, std::string> cases[] = {
      {"[chamber]\nlayer_count = 3\n" + three,
       "bad.toml:2: chamber.layer_count is given: it takes effect only without "
       "[[chamber.layers]], which gives each layer's length"},
      {three + "[experiment]\nmax_active_layers = 5\n",
       "bad.toml:8: experiment.max_active_layers = 5: must be an integer in [0, 3] (the layers "
       "[[chamber.layers]] lists)"},
      {three + "[experiment]\nmax_active_layers = 3\nswitching_order = [0, 2, 0]\n",
       "bad.toml:9: experiment.switching_order = [0, 2, 0]: must be an array naming each of 0 … 2 "
       "once"},
      {"[experiment]\nswitching_order = [0, 1, 2]\n",
       "bad.toml:2: experiment.switching_order = [0, 1, 2]: must be an array naming each of 0 … 3 "
       "once"},
      {"[experiment]\nswitching_order = [0, -1]\n",
       "bad.toml:2: experiment.switching_order = [0, -1]: must be sensor_first, "
       "target_first, or an array naming each layer index 0 … n−1 once (-1 is no index)"},
      // Over several lines the array is written out by fogradar, a 0.0 in it too.
      {"[experiment]\nswitching_order = [\n  0,\n  0.0,\n]\n",
       "bad.toml:2: experiment.switching_order = [0, 0.0]: must be sensor_first, target_first, or "
       "an array naming each layer index 0 … n−1 once (0.0 is no index)"},
      {"[chamber]\nlayers = [\n  0.0,\n]\n",
       "bad.toml:3: chamber.layers: must be an array of tables [[chamber.layers]] with keys "
       "length_m, fog"},
      {"[experiment]\nswitching_order = \"random\"\n",
       "bad.toml:2: experiment.switching_order = 'random': must be one of 'sensor_first', "
       "'target_first', or an array naming each layer index 0 … n−1 once"},
      {"[[chamber.layers]]\nlength_m = 0\n",
       "bad.toml:2: chamber.layers[0].length_m = 0: must be in (0, 10000]"},
      {"[[chamber.layers]]\nlength_m = 1.0\n[[chamber.layers]]\nfog = { lwc_g_per_m3 = 1.0 }\n",
       "bad.toml:3: chamber.layers[1].length_m is missing: every [[chamber.layers]] layer must "
       "give "
       "it, a number in (0, 10000]"},
      {"[[chamber.layers]]\nlength_m = 1.0\nfog = 3\n",
       "bad.toml:3: chamber.layers[0].fog = 3: must be a table [chamber.layers[0].fog] with keys "
       "droplets, extinction_per_km, lwc_g_per_m3, temperature_c, visibility_m, water_model"},
      {"[[chamber.layers]]\nlength_m = 1.0\nfog = { lwc = 1.0 }\n",
       "bad.toml:3: unknown key 'chamber.layers[0].fog.lwc' (known keys of "
       "[chamber.layers[0].fog]: droplets extinction_per_km lwc_g_per_m3 temperature_c "
       "visibility_m water_model)"},
      {"[[chamber.layers]]\nlength_m = 1.0\nfog = { lwc_g_per_m3 = 1.0, visibility_m = 20.0 }\n",
       "bad.toml:3: chamber.layers[0].fog.lwc_g_per_m3 (line 3) and "
       "chamber.layers[0].fog.visibility_m (line 3) are both given: at most one fog density of "
       "chamber.layers[0].fog.lwc_g_per_m3, chamber.layers[0].fog.extinction_per_km, "
       "chamber.layers[0].fog.visibility_m per [chamber.layers[0].fog]"},
      {"[[chamber.layers]]\nlength_m = 1.0\nfog = { water_model = \"segelstein\", temperature_c = "
       "10.0 }\n",
       "bad.toml:3: chamber.layers[0].fog.temperature_c = 10.0: must be"},
  };
  for (const auto& [toml, expected] : cases) {
    try {
      parse_scenario(toml, "bad.toml");
      ADD_FAILURE() << "accepted: " << toml;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(std::string(e.what()).substr(0, expected.size()), expected) << toml;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
  // A layer that names the table's water model without a temperature takes the table's 25 C, as
  // [fog] does; a layer that says nothing inherits [fog]'s choice.
  const Scenario s = parse_scenario(
      "[experiment]\nmax_active_layers = 2\n[[chamber.layers]]\nlength_m = 1.0\nfog = { "
      "water_model = \"segelstein\" }\n[[chamber.layers]]\nlength_m = 2.0\n",
      "ok");
  EXPECT_EQ(s.chamber.layers[0].fog.temperature_c, propagation::segelstein_table_temperature_c);
  EXPECT_EQ(s.chamber.layers[1].fog, s.fog);
}

// The study's eq. 4 for the lidar: behind k layers the target echo is the clear one times
// prod tau_i^2. With no scan-to-scan fog fluctuation the simulated median intensity of the target
// echo must follow it, step by step, from the clear step's own median (so the receiver noise's
// bias on a peak, about +6 % of the clear echo, largely cancels). The layers are the ones above at
// a fifth of their LWC, so the target stays above the threshold through all three. Reference:
// exp(-2 sum alpha_i f_i) with alpha_i from Q_ext = 2, within 5 %: the edge term's 6 % of the
// optical depth is at most 2.5 % of these transmittances (two-way depth <= 0.4), the rest is the
// noise's bias on weaker echoes and the median of 41 scans. The summary's eq4_intensity column is
// checked against the same optical depths within 8 %, as above.
TEST(Layers, LidarTargetEchoFollowsEq4WithoutFogFluctuation) {
  std::string text = layers_toml;
  for (const auto& [from, to] : {std::pair{"lwc_g_per_m3 = 1.0", "lwc_g_per_m3 = 0.2"},
                                 std::pair{"lwc_g_per_m3 = 4.0", "lwc_g_per_m3 = 0.8"},
                                 std::pair{"lwc_g_per_m3 = 2.0", "lwc_g_per_m3 = 0.4"},
                                 std::pair{"scans_per_step = 3", "scans_per_step = 41"}}) {
    text.replace(text.find(from), std::string_view(from).size(), to);
  }
  Scenario s = parse_scenario(text, "thin.toml");
  s.experiment.sensors = {"lidar"};
  lidar_of(s).fog_fluctuation.log_std = 0.0;
  const ExperimentSummary summary = summarize(run_experiment(s, {.threads = 2, .progress = {}}));
  const auto& steps = lidar_report(summary).summary().steps;
  ASSERT_EQ(steps.size(), 4u);
  const double clear = steps[0].target_intensity.median;
  for (std::size_t step = 1; step <= 3; ++step) {
    const std::string k = std::to_string(step);
    const double transmittance = std::exp(-2.0 * sum_switched(step, [](const LayerTruth& l) {
      return large_drop_extinction_per_m(l.lwc_g_per_m3 / 5.0) * l.length_m;
    }));
    ASSERT_EQ(steps[step].target_detections, steps[step].scans) << step;
    validate({.id = "experiment.layers.lidar_eq4_median.step" + k,
              .group = "experiment: layers",
              .quantity = "lidar target echo's median intensity after " + k +
                          " layers, over the clear step's",
              .unit = "1",
              .conditions = "the layers above at a fifth of their LWC, switched on 1, 2, 0; no fog "
                            "fluctuation; 41 scans",
              .reference = transmittance,
              .source = "the study's eq. 4 with Q_ext = 2 per layer (van de Hulst sec. 8.22)",
              .value = steps[step].target_intensity.median / clear,
              .tolerance = 0.05,
              .kind = Tolerance::relative});
    EXPECT_NEAR(-std::log(steps[step].eq4_intensity / steps[0].eq4_intensity),
                -std::log(transmittance), 0.08 * -std::log(transmittance))
        << step;
  }
}

// experiment.max_active_layers not given follows the chamber: every layer it has, whether
// chamber.layer_count gives them or [[chamber.layers]] lists them. Given beyond them, it is refused
// naming itself, the value as typed and the true range.
TEST(Layers, ActiveLayersFollowTheChamber) {
  const char* radar_only =
      "[experiment]\nsensors = [\"radar\"]\n"
      "[radar]\nchirps_per_frame = 16\nmeasurements_per_step = 2\n";
  const Scenario two = parse_scenario("[chamber]\nlayer_count = 2\n", "two.toml");
  EXPECT_EQ(two.steps(), 3u);
  EXPECT_EQ(two.context().steps, 3u);
  const Scenario eight =
      parse_scenario(std::string("[chamber]\nlayer_count = 8\n") + radar_only, "eight.toml");
  EXPECT_EQ(eight.steps(), 9u);
  const ExperimentSummary summary =
      summarize(run_experiment(eight, {.threads = 2, .progress = {}}));
  const auto& steps = radar_report(summary).summary().steps;
  ASSERT_EQ(steps.size(), 9u);
  // Every one of the 8 layers is switched on by the last step: 8 times one layer's loss.
  EXPECT_NEAR(steps[8].two_way_attenuation_db, 8.0 * steps[1].two_way_attenuation_db,
              1e-9 * steps[8].two_way_attenuation_db);
  // The value in force is written, and reads back to the same scenario.
  const std::string written = to_toml(eight);
  EXPECT_NE(written.find("max_active_layers = 8\n"), std::string::npos);
  EXPECT_EQ(to_toml(parse_scenario(written, "written.toml")), written);
  const Scenario listed = parse_scenario(
      "[[chamber.layers]]\nlength_m = 1.0\n[[chamber.layers]]\nlength_m = 2.0\n"
      "[[chamber.layers]]\nlength_m = 0.5\n",
      "listed.toml");
  EXPECT_EQ(listed.steps(), 4u);
  EXPECT_EQ(parse_scenario("[experiment]\nmax_active_layers = 1\n[chamber]\nlayer_count = 8\n",
                           "fewer.toml")
                .steps(),
            2u);
  const std::pair<std::string, std::string> refused[] = {
      {"[chamber]\nlayer_count = 2\n[experiment]\nmax_active_layers = 3\n",
       "beyond.toml:4: experiment.max_active_layers = 3: must be an integer in [0, "
       "chamber.layer_count = 2] (chamber.layer_count at line 2)"},
      {"[experiment]\nmax_active_layers = 4\n[[chamber.layers]]\nlength_m = 1.0\n",
       "beyond.toml:2: experiment.max_active_layers = 4: must be an integer in [0, 1] (the layers "
       "[[chamber.layers]] lists) (chamber.layers at line 3)"},
  };
  for (const auto& [text, message] : refused) {
    try {
      parse_scenario(text, "beyond.toml");
      ADD_FAILURE() << text << " accepted";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(std::string(e.what()), message);
      EXPECT_EQ(e.field(), "experiment.max_active_layers");
    }
  }
}

// Every example scenario of the README reads and validates; the layered one lists its four layers.
TEST(Layers, EveryExampleScenarioReads) {
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FOGRADAR_EXAMPLES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++files;
    EXPECT_NO_THROW(load_scenario_file(entry.path().string())) << entry.path();
  }
  EXPECT_GE(files, 8u);
  const Scenario layered =
      load_scenario_file(std::string(FOGRADAR_EXAMPLES_DIR) + "/layered_chamber.toml");
  ASSERT_EQ(layered.chamber_spec().layers.size(), 4u);
  EXPECT_EQ(layered.context().switching_order, (std::vector<std::size_t>{3, 2, 1, 0}));
  EXPECT_EQ(layered.chamber.layers[1].fog.density,
            propagation::FogDensity(propagation::LiquidWaterContent{0.0}));
}

}  // namespace
}  // namespace fogradar::experiment
