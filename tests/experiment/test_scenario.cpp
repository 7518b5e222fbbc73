// Scenario files: the embedded paper scenario has the documented paper values (docs/scenario.md), round-trips through to_toml, and every
// bad input is rejected with the key (and its line) named.
#include <gtest/gtest.h>

#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/scenario.hpp"

namespace fogradar::experiment {
namespace {

// The paper-scenario values docs/scenario.md documents, checked against the compiled-in file.
TEST(Scenario, PaperScenarioIsDesignSection4) {
  const Scenario s = paper_scenario();
  EXPECT_EQ(s.radar.centre_frequency_hz, 77e9);  // "sweep centred on 77 GHz"
  EXPECT_EQ(s.radar.sweep_direction, radar::SweepDirection::up);
  EXPECT_EQ(s.radar.sweep_bandwidth_hz, 1e9);
  EXPECT_EQ(s.radar.chirp_duration_s, 51.2e-6);
  EXPECT_EQ(s.radar.samples_per_chirp, 512u);
  EXPECT_EQ(s.radar.sample_rate_hz, 10e6);
  EXPECT_EQ(s.radar.chirps_per_frame, 64u);
  EXPECT_EQ(s.radar.tx_power_dbm, 10.0);
  EXPECT_EQ(s.radar.tx_gain_dbi, 25.0);
  EXPECT_EQ(s.radar.rx_gain_dbi, 25.0);
  EXPECT_EQ(s.radar.azimuth_beamwidth_deg, 10.0);
  EXPECT_EQ(s.radar.elevation_beamwidth_deg, 10.0);
  EXPECT_EQ(s.radar.noise_figure_db, 12.0);
  EXPECT_EQ(s.radar.window, radar::WindowType::hann);
  EXPECT_EQ(s.radar.cfar.kind, radar::CfarKind::ca);
  EXPECT_EQ(s.radar.cfar.false_alarm_probability, 1e-6);
  EXPECT_EQ(s.chamber.sensor_gap_m, 2.0);
  EXPECT_EQ(s.chamber.layer_count, 4u);
  EXPECT_EQ(s.chamber.layer_length_m, 1.0);
  EXPECT_EQ(s.chamber.target_gap_m, 4.0);
  ASSERT_TRUE(std::holds_alternative<propagation::OpticalExtinction>(s.fog.density));
  EXPECT_EQ(std::get<propagation::OpticalExtinction>(s.fog.density).per_km, 900.0);
  EXPECT_EQ(s.fog.temperature_c, 20.0);
  // 20 C reaches the radar-frequency index only through the temperature-dependent model.
  EXPECT_EQ(s.fog.water_model, propagation::WaterModel::liebe);
  EXPECT_EQ(s.target.model, TargetModel::evt);
  EXPECT_EQ(s.target.rcs_dbsm, 10.0);
  EXPECT_EQ(s.experiment.measurements_per_step, 200u);
  EXPECT_EQ(s.experiment.max_active_layers, 4u);
  EXPECT_EQ(s.experiment.seed, 1u);
}

TEST(Scenario, ResolvedTomlRoundTrips) {
  Scenario s = paper_scenario();
  s.fog.droplets = propagation::advection_fog();
  s.fog.density = propagation::Visibility{37.5};
  s.target.model = TargetModel::point;
  s.radar.cfar.kind = radar::CfarKind::os;
  s.radar.sweep_direction = radar::SweepDirection::down;
  s.radar.centre_frequency_hz = 76.5e9;
  s.fog.water_model = propagation::WaterModel::segelstein;
  s.fog.temperature_c = propagation::segelstein_table_temperature_c;
  s.radar.cfar.threshold_design = radar::CfarThresholdDesign::independent;
  const std::string text = to_toml(s);
  EXPECT_EQ(to_toml(parse_scenario(text, "resolved.toml")), text);
}

// The retired key that named the start of a down-chirp "carrier" is refused, and the message names
// the keys that replace it; the Segelstein table (about 25 C) is refused with any other water
// temperature, and the message names the model that takes one.
TEST(Scenario, RetiredCarrierKeyAndUnusedTemperatureAreRefused) {
  try {
    parse_scenario("[radar]\n\ncarrier_frequency_hz = 77e9\n", "old.toml");
    FAIL() << "accepted radar.carrier_frequency_hz";
  } catch (const InvalidParameter& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.field(), "radar.carrier_frequency_hz");
    EXPECT_EQ(message.rfind("old.toml:3:", 0), 0u) << message;
    EXPECT_NE(message.find("radar.centre_frequency_hz"), std::string::npos) << message;
    EXPECT_NE(message.find("radar.sweep_direction"), std::string::npos) << message;
  }
  try {
    parse_scenario("[fog]\nwater_model = \"segelstein\"\ntemperature_c = 0.0\n", "cold.toml");
    FAIL() << "accepted segelstein at 0 C";
  } catch (const InvalidParameter& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.field(), "fog.temperature_c");
    EXPECT_EQ(message.rfind("cold.toml:3:", 0), 0u) << message;
    EXPECT_NE(message.find("liebe"), std::string::npos) << message;
  }
  // The paper's 20 C with the table, temperature not given: refused too (the table cannot use it).
  EXPECT_THROW(parse_scenario("[fog]\nwater_model = \"segelstein\"\n", "table.toml"),
               InvalidParameter);
  // The table at its own temperature, and Liebe at any temperature in its range, are accepted.
  EXPECT_NO_THROW(
      parse_scenario("[fog]\nwater_model = \"segelstein\"\ntemperature_c = 25\n", "ok.toml"));
  EXPECT_EQ(parse_scenario("[fog]\ntemperature_c = 0\n", "liebe.toml").fog.temperature_c, 0.0);
}

TEST(Scenario, FileOnlyNeedsTheKeysItChanges) {
  const Scenario s = parse_scenario("[radar]\ntx_power_dbm = 12\n[experiment]\nseed = 7\n", "mine.toml");
  EXPECT_EQ(s.radar.tx_power_dbm, 12.0);
  EXPECT_EQ(s.experiment.seed, 7u);
  EXPECT_EQ(s.radar.samples_per_chirp, 512u);  // untouched paper value
}

struct BadInput {
  const char* name;
  const char* toml;
  const char* key;
  int line;  // 0: no line expected
};

class ScenarioRejects : public ::testing::TestWithParam<BadInput> {};

TEST_P(ScenarioRejects, NamesTheKeyAndLine) {
  const BadInput& bad = GetParam();
  try {
    parse_scenario(bad.toml, "bad.toml");
    FAIL() << "accepted: " << bad.toml;
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), bad.key) << e.what();
    const std::string message = e.what();
    EXPECT_NE(message.find(bad.key), std::string::npos) << message;
    if (bad.line > 0) {
      EXPECT_EQ(message.rfind("bad.toml:" + std::to_string(bad.line) + ":", 0), 0u) << message;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    BadInputs, ScenarioRejects,
    ::testing::Values(
        BadInput{"malformed", "[radar\ncentre_frequency_hz = 77e9\n", "toml", 1},
        BadInput{"unknown_section", "[radr]\nx = 1\n", "radr", 1},
        BadInput{"unknown_key", "[radar]\ntx_power_w = 0.01\n", "radar.tx_power_w", 2},
        BadInput{"wrong_type", "[radar]\n\ntx_power_dbm = \"ten\"\n", "radar.tx_power_dbm", 3},
        BadInput{"negative", "[chamber]\nsensor_gap_m = -2\n", "chamber.sensor_gap_m", 2},
        BadInput{"nan", "[fog]\ntemperature_c = nan\n", "fog.temperature_c", 2},
        BadInput{"inf", "[radar]\nnoise_figure_db = inf\n", "radar.noise_figure_db", 2},
        BadInput{"zero_layers", "[chamber]\nlayer_count = 0\n", "chamber.layer_count", 2},
        BadInput{"zero_length_layer", "[chamber]\nlayer_length_m = 0.0\n", "chamber.layer_length_m",
                 2},
        BadInput{"too_many_active", "[experiment]\nmax_active_layers = 5\n",
                 "experiment.max_active_layers", 2},
        BadInput{"cfar_wider_than_profile", "[processing.cfar]\ntraining_cells = 300\n",
                 "processing.cfar.training_cells", 2},
        BadInput{"frequency_outside_water_models", "[radar]\ncentre_frequency_hz = 5e12\n",
                 "radar.centre_frequency_hz", 2},
        BadInput{"retired_carrier_key", "[radar]\ncarrier_frequency_hz = 77e9\n",
                 "radar.carrier_frequency_hz", 2},
        BadInput{"unknown_sweep_direction", "[radar]\nsweep_direction = \"sawtooth\"\n",
                 "radar.sweep_direction", 2},
        BadInput{"segelstein_at_another_temperature",
                 "[fog]\nwater_model = \"segelstein\"\ntemperature_c = 0\n", "fog.temperature_c",
                 3},
        BadInput{"liebe_below_its_range", "[fog]\ntemperature_c = -25\n", "fog.temperature_c", 2},
        BadInput{"unknown_window", "[processing]\nwindow = \"kaiser\"\n", "processing.window", 2},
        BadInput{"unknown_cfar", "[processing.cfar]\nkind = \"xx\"\n", "processing.cfar.kind", 2},
        BadInput{"unknown_threshold_design", "[processing.cfar]\nthreshold_design = \"iid\"\n",
                 "processing.cfar.threshold_design", 2},
        BadInput{"pfa_out_of_range", "[processing.cfar]\nfalse_alarm_probability = 1.5\n",
                 "processing.cfar.false_alarm_probability", 2},
        BadInput{"negative_integer", "[experiment]\nmeasurements_per_step = -3\n",
                 "experiment.measurements_per_step", 2},
        BadInput{"zero_measurements", "[experiment]\nmeasurements_per_step = 0\n",
                 "experiment.measurements_per_step", 2},
        BadInput{"two_fog_densities", "[fog]\nlwc_g_per_m3 = 0.1\nvisibility_m = 20\n", "fog", 0},
        BadInput{"negative_lwc", "[fog]\nlwc_g_per_m3 = -0.1\n", "fog.lwc_g_per_m3", 2},
        BadInput{"unknown_distribution", "[fog.droplets]\ndistribution = \"cloud\"\n",
                 "fog.droplets.distribution", 2},
        BadInput{"bad_water_model", "[fog]\nwater_model = \"mie\"\n", "fog.water_model", 2},
        BadInput{"samples_exceed_chirp", "[radar]\nsamples_per_chirp = 1024\n",
                 "radar.samples_per_chirp", 2},
        BadInput{"bad_reflection", "[target]\nfloor_reflection_coefficient = -1.5\n",
                 "target.floor_reflection_coefficient", 2},
        BadInput{"bad_swerling", "[target]\nswerling = 2\n", "target.swerling", 2},
        BadInput{"bad_target_model", "[target]\nmodel = \"truck\"\n", "target.model", 2},
        BadInput{"bool_as_number", "[target]\nfloor_multipath = 1\n", "target.floor_multipath", 2},
        BadInput{"droplet_too_big",
                 "[fog.droplets]\ndistribution = \"monodisperse\"\ndiameter_m = 0.01\n",
                 "fog.droplets.diameter_m", 3}),
    [](const ::testing::TestParamInfo<BadInput>& param_info) {
      return std::string(param_info.param.name);
    });

}  // namespace
}  // namespace fogradar::experiment
