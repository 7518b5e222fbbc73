// Scenario files: the embedded paper scenario has the documented paper values (docs/scenario.md),
// round-trips through to_toml, and every bad input is rejected with the key (and its line) named.
#include <gtest/gtest.h>

#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/radar/sensor.hpp"
#include "sensors.hpp"

namespace fogradar::experiment {
namespace {

// The paper-scenario values docs/scenario.md documents, checked against the compiled-in file.
TEST(Scenario, PaperScenarioIsDesignSection4) {
  const Scenario s = paper_scenario();
  const radar::RadarParams& r = radar_of(s).radar;
  EXPECT_EQ(r.centre_frequency_hz, 77e9);  // "sweep centred on 77 GHz"
  EXPECT_EQ(r.sweep_direction, radar::SweepDirection::up);
  EXPECT_EQ(r.sweep_bandwidth_hz, 1e9);
  EXPECT_EQ(r.chirp_duration_s, 51.2e-6);
  EXPECT_EQ(r.samples_per_chirp, 512u);
  EXPECT_EQ(r.sample_rate_hz, 10e6);
  EXPECT_EQ(r.chirps_per_frame, 64u);
  EXPECT_EQ(r.tx_power_dbm, 10.0);
  EXPECT_EQ(r.tx_gain_dbi, 25.0);
  EXPECT_EQ(r.rx_gain_dbi, 25.0);
  EXPECT_EQ(r.azimuth_beamwidth_deg, 10.0);
  EXPECT_EQ(r.elevation_beamwidth_deg, 10.0);
  EXPECT_EQ(r.noise_figure_db, 12.0);
  EXPECT_EQ(r.window, radar::WindowType::hann);
  EXPECT_EQ(r.cfar.kind, radar::CfarKind::ca);
  EXPECT_EQ(r.cfar.false_alarm_probability, 1e-6);
  EXPECT_EQ(s.chamber.sensor_gap_m, 2.0);
  EXPECT_EQ(s.chamber.layer_count, 4u);
  EXPECT_EQ(s.chamber.layer_length_m, 1.0);
  EXPECT_EQ(s.chamber.target_gap_m, 4.0);
  ASSERT_TRUE(std::holds_alternative<propagation::OpticalExtinction>(s.fog.density));
  EXPECT_EQ(std::get<propagation::OpticalExtinction>(s.fog.density).per_km, 900.0);
  EXPECT_EQ(s.fog.temperature_c, 20.0);
  // 20 C reaches the radar-frequency index only through the temperature-dependent model.
  EXPECT_EQ(s.fog.water_model, propagation::WaterModel::liebe);
  EXPECT_EQ(radar_of(s).target.model, radar::TargetModel::evt);
  EXPECT_EQ(radar_of(s).target.rcs_dbsm, 10.0);
  EXPECT_EQ(s.params<fogradar::radar::SensorParams>("radar").measurements_per_step, 200u);
  EXPECT_FALSE(s.experiment.max_active_layers.has_value());  // every layer
  EXPECT_EQ(s.steps(), 5u);
  EXPECT_EQ(s.experiment.seed, 1u);
}

TEST(Scenario, ResolvedTomlRoundTrips) {
  Scenario s = paper_scenario();
  s.fog.droplets = propagation::advection_fog();
  s.fog.density = propagation::Visibility{37.5};
  radar_of(s).target.model = radar::TargetModel::point;
  radar_of(s).radar.cfar.kind = radar::CfarKind::os;
  radar_of(s).radar.sweep_direction = radar::SweepDirection::down;
  radar_of(s).radar.centre_frequency_hz = 76.5e9;
  s.fog.water_model = propagation::WaterModel::segelstein;
  s.fog.temperature_c = propagation::segelstein_table_temperature_c;
  radar_of(s).radar.cfar.threshold_design = radar::CfarThresholdDesign::independent;
  s.experiment.sensors = {"camera", "radar"};
  const std::string text = to_toml(s);
  EXPECT_EQ(to_toml(parse_scenario(text, "resolved.toml")), text);
  EXPECT_EQ(parse_scenario(text, "resolved.toml").experiment.sensors, s.experiment.sensors);
}

// experiment.sensors selects the sensors in the order given; a run that names only some of them is
// valid, and a Scenario built in code is checked like a file.
TEST(Scenario, SensorsAreChosenByName) {
  const Scenario s = parse_scenario("[experiment]\nsensors = [\"lidar\", \"radar\"]\n", "s.toml");
  EXPECT_EQ(s.experiment.sensors, (std::vector<std::string>{"lidar", "radar"}));
  EXPECT_TRUE(s.runs("radar"));
  EXPECT_FALSE(s.runs("camera"));
  Scenario twice = paper_scenario();
  twice.experiment.sensors = {"radar", "radar"};
  EXPECT_THROW(twice.validate(), InvalidParameter);
  Scenario none = paper_scenario();
  none.experiment.sensors.clear();
  EXPECT_THROW(none.validate(), InvalidParameter);
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
  // The table chosen without a temperature takes its own 25 C, as `fogradar fog` does, not the
  // paper scenario's assumed 20 C (which it cannot use); the resolved scenario states it.
  const Scenario table = parse_scenario("[fog]\nwater_model = \"segelstein\"\n", "table.toml");
  EXPECT_EQ(table.fog.temperature_c, 25.0);
  EXPECT_EQ(to_toml(parse_scenario(to_toml(table), "resolved.toml")), to_toml(table));
  // A temperature the file gives is checked as given, the paper's 20 C too.
  try {
    parse_scenario("[fog]\nwater_model = \"segelstein\"\ntemperature_c = 20\n", "warm.toml");
    FAIL() << "accepted segelstein at 20 C";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(std::string(e.what()),
              "warm.toml:3: fog.temperature_c = 20: must be = 25 with fog.water_model = "
              "\"segelstein\" (a table for about 25 C without temperature dependence); "
              "fog.water_model = \"liebe\" takes [-20, 50] (fog.water_model at line 2)");
  }
  // The table at its own temperature, and Liebe at any temperature in its range, are accepted.
  EXPECT_NO_THROW(
      parse_scenario("[fog]\nwater_model = \"segelstein\"\ntemperature_c = 25\n", "ok.toml"));
  EXPECT_EQ(parse_scenario("[fog]\ntemperature_c = 0\n", "liebe.toml").fog.temperature_c, 0.0);
}

TEST(Scenario, FileOnlyNeedsTheKeysItChanges) {
  const Scenario s =
      parse_scenario("[radar]\ntx_power_dbm = 12\n[experiment]\nseed = 7\n", "mine.toml");
  EXPECT_EQ(radar_of(s).radar.tx_power_dbm, 12.0);
  EXPECT_EQ(s.experiment.seed, 7u);
  EXPECT_EQ(radar_of(s).radar.samples_per_chirp, 512u);  // untouched paper value
}

// A bad scenario input and what its one message must say: the key as written (the exception's
// field, with "bad.toml:<line>:" in front when the key has a line), the allowed range or set as
// docs/scenario.md states it, and for a check that combines keys, the other key with its line.
struct BadInput {
  const char* name;
  const char* toml;
  const char* key;
  int line;                     // 0: no line expected
  const char* allowed;          // text of the allowed range or set
  const char* other = nullptr;  // another key of a combined check, with its line
};

class ScenarioRejects : public ::testing::TestWithParam<BadInput> {};

TEST_P(ScenarioRejects, NamesTheKeyLineAndRange) {
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
    EXPECT_NE(message.find(bad.allowed), std::string::npos) << message;
    if (bad.other != nullptr) {
      EXPECT_NE(message.find(bad.other), std::string::npos) << message;
    }
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    BadInputs, ScenarioRejects,
    ::testing::Values(
        BadInput{"malformed", "[radar\ncentre_frequency_hz = 77e9\n", "toml", 1, "malformed TOML"},
        BadInput{"unknown_section", "[radr]\nx = 1\n", "radr", 1,
                 "sections: chamber, fog, target, experiment, radar, lidar, camera"},
        BadInput{"unknown_key", "[radar]\ntx_power_w = 0.01\n", "radar.tx_power_w", 2,
                 "known keys of [radar]: adc_bits"},
        BadInput{"wrong_type", "[radar]\n\ntx_power_dbm = \"ten\"\n", "radar.tx_power_dbm", 3,
                 "= 'ten': must be a number"},
        BadInput{"negative", "[chamber]\nsensor_gap_m = -2\n", "chamber.sensor_gap_m", 2,
                 "[0, 10000]"},
        BadInput{"nan", "[fog]\ntemperature_c = nan\n", "fog.temperature_c", 2, "[-20, 50]"},
        BadInput{"inf", "[radar]\nnoise_figure_db = inf\n", "radar.noise_figure_db", 2, "[0, 40]"},
        BadInput{"zero_layers", "[chamber]\nlayer_count = 0\n", "chamber.layer_count", 2,
                 "an integer in [1, 1000]"},
        BadInput{"too_many_layers", "[chamber]\nlayer_count = 1001\n", "chamber.layer_count", 2,
                 "an integer in [1, 1000]"},
        BadInput{"zero_length_layer", "[chamber]\nlayer_length_m = 0.0\n", "chamber.layer_length_m",
                 2, "in (0, 10000]"},
        BadInput{"too_many_active", "[experiment]\nmax_active_layers = 5\n",
                 "experiment.max_active_layers", 2, "[0, chamber.layer_count = 4]"},
        // Not the reader's widest bound: the true one, from chamber.layer_count.
        BadInput{"far_too_many_active", "[experiment]\nmax_active_layers = 5000000000\n",
                 "experiment.max_active_layers", 2, "[0, chamber.layer_count = 4]"},
        BadInput{"too_many_active_for_given_layers",
                 "[chamber]\nlayer_count = 2\n[experiment]\nmax_active_layers = 3\n",
                 "experiment.max_active_layers", 4, "[0, chamber.layer_count = 2]",
                 "chamber.layer_count at line 2"},
        BadInput{"cfar_wider_than_profile", "[radar.processing.cfar]\ntraining_cells = 300\n",
                 "radar.processing.cfar.training_cells", 2, "[1, 253]",
                 "radar.samples_per_chirp = 512"},
        BadInput{"cfar_wider_than_given_profile",
                 "[radar]\nsamples_per_chirp = 32\n[radar.processing.cfar]\nguard_cells = "
                 "4\ntraining_cells = 20\n",
                 "radar.processing.cfar.training_cells", 5,
                 "[1, 11] with radar.processing.cfar.guard_cells = 4",
                 "radar.samples_per_chirp at line 2"},
        BadInput{"guard_cells_fill_the_profile", "[radar.processing.cfar]\nguard_cells = 300\n",
                 "radar.processing.cfar.guard_cells", 2,
                 "[0, 247] with radar.processing.cfar.training_cells = 8",
                 "radar.samples_per_chirp = 512"},
        // The key the file gives is named by its line although the other key breaks the rule.
        BadInput{"paper_guard_cells_in_a_given_profile", "[radar]\nsamples_per_chirp = 16\n",
                 "radar.processing.cfar.training_cells", 2, "[1, 5]",
                 "radar.samples_per_chirp at line 2"},
        BadInput{"huge_guard_cells", "[radar.processing.cfar]\nguard_cells = 4294967296\n",
                 "radar.processing.cfar.guard_cells", 2,
                 "in [0, 247] with radar.processing.cfar.training_cells = 8 and a profile of "
                 "radar.samples_per_chirp = 512 cells"},
        BadInput{
            "huge_os_rank",
            "[radar.processing.cfar]\nkind = \"os\"\ntraining_cells = 4\nos_rank = 70000\n",
            "radar.processing.cfar.os_rank", 4,
            "an integer in [0, 2 x radar.processing.cfar.training_cells = 8] (0: the default rank "
            "round(3N/4))",
            "radar.processing.cfar.training_cells at line 3"},
        BadInput{"os_rank_beyond_training",
                 "[radar.processing.cfar]\nkind = \"os\"\ntraining_cells = 4\nos_rank = 9\n",
                 "radar.processing.cfar.os_rank", 4,
                 "[0, 2 x radar.processing.cfar.training_cells = 8]",
                 "radar.processing.cfar.training_cells at line 3"},
        // Keys that would do nothing are refused, naming what makes them work.
        BadInput{"os_rank_without_os", "[radar.processing.cfar]\nos_rank = 4\n",
                 "radar.processing.cfar.os_rank", 2,
                 "takes effect only with radar.processing.cfar.kind = \"os\""},
        BadInput{"full_scale_without_adc", "[radar]\nadc_full_scale_dbm = -30\n",
                 "radar.adc_full_scale_dbm", 2, "takes effect only with radar.adc_bits > 0"},
        BadInput{"retired_floor_multipath", "[target]\nfloor_multipath = false\n",
                 "target.floor_multipath", 2, "chamber.room.floor = false"},
        BadInput{"retired_floor_coefficient", "[target]\nfloor_reflection_coefficient = -0.5\n",
                 "target.floor_reflection_coefficient", 2,
                 "chamber.room.floor.reflection_coefficient"},
        BadInput{"floor_material_and_coefficient",
                 "[chamber.room.floor]\nmaterial = \"concrete\"\nreflection_coefficient = -0.5\n",
                 "chamber.room.floor.reflection_coefficient", 3, "are both given"},
        BadInput{"unknown_material", "[chamber.room.left_wall]\nmaterial = \"cardboard\"\n",
                 "chamber.room.left_wall.material", 2, "concrete"},
        BadInput{"wall_at_zero", "[chamber.room.left_wall]\ndistance_m = 0\n",
                 "chamber.room.left_wall.distance_m", 2, "(0, 1000]"},
        BadInput{"switch_as_number", "[chamber.room]\nceiling = 4\n", "chamber.room.ceiling", 2,
                 "must be false, or a table [chamber.room.ceiling]"},
        // What the lidar cannot see of the room (lidar::scan_plane_room), the lidar running.
        BadInput{"lidar_wall_by_coefficient",
                 "[chamber.room.left_wall]\ndistance_m = 3\nreflection_coefficient = -0.6\n",
                 "chamber.room.left_wall.reflection_coefficient", 3,
                 "replaced by chamber.room.left_wall.material for the lidar"},
        BadInput{"lidar_wall_without_optical_sample",
                 "[chamber.room.right_wall]\nmaterial = \"plasterboard\"\n",
                 "chamber.room.right_wall.material", 2,
                 "a material with a published diffuse reflectance: concrete, brick, wood"},
        BadInput{"lidar_object_without_optical_sample",
                 "[[chamber.objects]]\nshape = \"plate\"\nmaterial = \"glass\"\n",
                 "chamber.objects[0].material", 3,
                 "a material with a published diffuse reflectance: concrete, brick, wood"},
        BadInput{"lidar_wavelength_without_reflectance",
                 "[lidar]\nwavelength_m = 940e-9\n[chamber.room.back_wall]\nmaterial = "
                 "\"concrete\"\n",
                 "lidar.wavelength_m", 2, "within 10 nm of 550, 905 or 1550 nm"},
        BadInput{"lidar_above_ceiling",
                 "[lidar]\nheight_m = 5\n[chamber.room.ceiling]\nheight_m = 4\n", "lidar.height_m",
                 2, "< chamber.room.ceiling.height_m = 4",
                 "chamber.room.ceiling.height_m at line 4"},
        // The radar, beside the lidar at the origin, refuses it first (the lidar's own refusal,
        // radius_m < its distance from the axis, is tested in tests/lidar/).
        BadInput{"sensors_inside_a_barrel",
                 "[[chamber.objects]]\nshape = \"cylinder\"\nx_m = 0.2\ny_m = 0\nradius_m = 0.3\n",
                 "chamber.objects[0].x_m", 3, "with the radar outside the object"},
        BadInput{"target_beyond_unambiguous_range", "[chamber]\ntarget_gap_m = 300\n",
                 "chamber.target_gap_m", 2, "75.74686925 m", "radar.sample_rate_hz"},
        BadInput{"target_beyond_given_range",
                 "[radar]\nsample_rate_hz = 5e6\nsamples_per_chirp = 256\n[chamber]\ntarget_gap_m "
                 "= 40\n",
                 "chamber.target_gap_m", 5, "unambiguous range minus 1 m",
                 "radar.sample_rate_hz at line 2"},
        BadInput{"bandwidth_over_half_the_centre",
                 "[radar]\ncentre_frequency_hz = 10e9\nsweep_bandwidth_hz = 6e9\n",
                 "radar.sweep_bandwidth_hz", 3, "radar.centre_frequency_hz / 2 = 5000000000",
                 "radar.centre_frequency_hz at line 2"},
        BadInput{"interval_shorter_than_chirp", "[radar]\nchirp_interval_s = 1e-6\n",
                 "radar.chirp_interval_s", 2, "[radar.chirp_duration_s = 5.12e-05, 1]"},
        BadInput{"frequency_outside_water_models", "[radar]\ncentre_frequency_hz = 5e12\n",
                 "radar.centre_frequency_hz", 2, "[1000000000, 3e+11]"},
        BadInput{"retired_carrier_key", "[radar]\ncarrier_frequency_hz = 77e9\n",
                 "radar.carrier_frequency_hz", 2, "radar.sweep_direction"},
        BadInput{"unknown_sweep_direction", "[radar]\nsweep_direction = \"sawtooth\"\n",
                 "radar.sweep_direction", 2, "one of up, down"},
        BadInput{"segelstein_at_another_temperature",
                 "[fog]\nwater_model = \"segelstein\"\ntemperature_c = 0\n", "fog.temperature_c", 3,
                 "= 25 with fog.water_model", "fog.water_model at line 2"},
        BadInput{"liebe_below_its_range", "[fog]\ntemperature_c = -25\n", "fog.temperature_c", 2,
                 "[-20, 50]"},
        BadInput{"unknown_window", "[radar.processing]\nwindow = \"kaiser\"\n",
                 "radar.processing.window", 2, "one of rectangular, hann"},
        BadInput{"unknown_cfar", "[radar.processing.cfar]\nkind = \"xx\"\n",
                 "radar.processing.cfar.kind", 2, "one of ca, go, so, os"},
        BadInput{"unknown_threshold_design",
                 "[radar.processing.cfar]\nthreshold_design = \"iid\"\n",
                 "radar.processing.cfar.threshold_design", 2, "one of correlated, independent"},
        // An empty name is a given name, refused like any other unknown one (it kept the default).
        BadInput{"empty_sweep_direction", "[radar]\nsweep_direction = \"\"\n",
                 "radar.sweep_direction", 2, "'': must be one of up, down"},
        BadInput{"empty_window", "[radar.processing]\nwindow = \"\"\n", "radar.processing.window",
                 2, "'': must be one of rectangular"},
        BadInput{"empty_cfar_kind", "[radar.processing.cfar]\nkind = \"\"\n",
                 "radar.processing.cfar.kind", 2, "'': must be one of ca"},
        BadInput{"empty_threshold_design", "[radar.processing.cfar]\nthreshold_design = \"\"\n",
                 "radar.processing.cfar.threshold_design", 2, "'': must be one of correlated"},
        BadInput{"empty_target_model", "[radar.target]\nmodel = \"\"\n", "radar.target.model", 2,
                 "'': must be one of evt, point"},
        BadInput{"empty_water_model", "[fog]\nwater_model = \"\"\n", "fog.water_model", 2,
                 "'': must be one of liebe, segelstein"},
        BadInput{"empty_distribution", "[fog.droplets]\ndistribution = \"\"\n",
                 "fog.droplets.distribution", 2, "'': must be one of 'lognormal'"},
        BadInput{"pfa_out_of_range", "[radar.processing.cfar]\nfalse_alarm_probability = 1.5\n",
                 "radar.processing.cfar.false_alarm_probability", 2, "(0, 1)"},
        BadInput{"negative_integer", "[radar]\nmeasurements_per_step = -3\n",
                 "radar.measurements_per_step", 2, "an integer in [1, 1000000]"},
        BadInput{"zero_measurements", "[radar]\nmeasurements_per_step = 0\n",
                 "radar.measurements_per_step", 2, "an integer in [1, 1000000]"},
        // Integer keys state their documented range, not the C type's.
        BadInput{"samples_beyond_unsigned", "[radar]\nsamples_per_chirp = 5000000000\n",
                 "radar.samples_per_chirp", 2,
                 "= 5000000000: must be an integer in [16, 512]: the samples fit in the chirp, "
                 "radar.chirp_duration_s x radar.sample_rate_hz = 512"},
        BadInput{"fractional_samples", "[radar]\nsamples_per_chirp = 1.5\n",
                 "radar.samples_per_chirp", 2, "= 1.5: must be an integer in [16, 512]"},
        BadInput{"too_many_chirps", "[radar]\nchirps_per_frame = 16385\n", "radar.chirps_per_frame",
                 2, "an integer in [1, 16384]"},
        BadInput{"too_many_adc_bits", "[radar]\nadc_bits = 25\n", "radar.adc_bits", 2,
                 "an integer in [0, 24]"},
        BadInput{"no_clutter_scatterers", "[radar]\nclutter_scatterers_per_bin = 0\n",
                 "radar.clutter_scatterers_per_bin", 2, "an integer in [1, 64]"},
        BadInput{"negative_seed", "[experiment]\nseed = -1\n", "experiment.seed", 2,
                 "an integer in [0, 9223372036854775807]"},
        BadInput{"sensors_not_an_array", "[experiment]\nsensors = \"radar\"\n",
                 "experiment.sensors", 2,
                 "a non-empty array of distinct names from \"radar\", \"lidar\", \"camera\""},
        BadInput{"no_sensors", "[experiment]\nsensors = []\n", "experiment.sensors", 2,
                 "a non-empty array of distinct names"},
        BadInput{"unknown_sensor", "[experiment]\n\nsensors = [\"radar\", \"sonar\"]\n",
                 "experiment.sensors", 3, "(\"sonar\" is no sensor)"},
        BadInput{"sensor_twice", "[experiment]\nsensors = [\"lidar\", \"lidar\"]\n",
                 "experiment.sensors", 2, "(\"lidar\" is named twice)"},
        BadInput{"sensor_not_a_name", "[experiment]\nsensors = [\"radar\", 3]\n",
                 "experiment.sensors", 2, "(3 is not a string)"},
        BadInput{
            "two_fog_densities", "[fog]\nlwc_g_per_m3 = 0.1\nvisibility_m = 20\n",
            "fog.visibility_m", 3,
            "at most one fog density of fog.lwc_g_per_m3, fog.extinction_per_km, fog.visibility_m",
            "fog.lwc_g_per_m3 (line 2)"},
        BadInput{"negative_lwc", "[fog]\nlwc_g_per_m3 = -0.1\n", "fog.lwc_g_per_m3", 2, "[0, 100]"},
        BadInput{"unknown_distribution", "[fog.droplets]\ndistribution = \"cloud\"\n",
                 "fog.droplets.distribution", 2, "one of 'lognormal', 'monodisperse'"},
        BadInput{"bad_water_model", "[fog]\nwater_model = \"mie\"\n", "fog.water_model", 2,
                 "one of liebe, segelstein"},
        BadInput{"samples_exceed_chirp", "[radar]\nsamples_per_chirp = 1024\n",
                 "radar.samples_per_chirp", 2,
                 "an integer in [16, 512]: the samples fit in the chirp, radar.chirp_duration_s x "
                 "radar.sample_rate_hz = 512"},
        BadInput{"bad_reflection", "[chamber.room.floor]\nreflection_coefficient = -1.5\n",
                 "chamber.room.floor.reflection_coefficient", 2, "[-1, 1]"},
        BadInput{"bad_swerling", "[radar.target]\nmodel = \"point\"\nswerling = 2\n",
                 "radar.target.swerling", 3, "one of 0, 1, 3"},
        BadInput{"negative_swerling", "[radar.target]\nmodel = \"point\"\nswerling = -1\n",
                 "radar.target.swerling", 3, "'-1': must be one of 0, 1, 3"},
        BadInput{"bad_target_model", "[radar.target]\nmodel = \"truck\"\n", "radar.target.model", 2,
                 "one of evt, point"},
        BadInput{"bool_as_number", "[camera]\nwrite_roi_images = 1\n", "camera.write_roi_images", 2,
                 "= 1: must be true or false"},
        BadInput{"droplet_too_big",
                 "[fog.droplets]\ndistribution = \"monodisperse\"\ndiameter_m = 0.01\n",
                 "fog.droplets.diameter_m", 3, "[1e-08, 0.001]"},
        // A key of another droplet family than the one chosen takes no effect: refused, saying
        // which.
        BadInput{"droplet_key_of_another_family", "[fog.droplets]\ndiameter_m = 1e-5\n",
                 "fog.droplets.diameter_m", 2,
                 "takes effect only with fog.droplets.distribution = \"monodisperse\""},
        // A sub-table given a plain value is named as that sub-table.
        BadInput{"sub_table_as_value", "[lidar]\nfog_fluctuation = 3\n", "lidar.fog_fluctuation", 2,
                 "lidar.fog_fluctuation = 3: must be a table [lidar.fog_fluctuation]"},
        BadInput{"section_as_value", "radar = 5\n", "radar", 1,
                 "radar = 5: must be a table [radar] with keys adc_bits, adc_full_scale_dbm"},
        // The lists of known keys name the sub-tables too.
        BadInput{"unknown_key_lists_sub_tables", "[camera]\nroix = 1\n", "camera.roix", 2,
                 " noise roi transfer "},
        BadInput{"unknown_lidar_key", "[lidar]\npulse_width_s = 5e-9\n", "lidar.pulse_width_s", 2,
                 "known keys of [lidar]"},
        BadInput{"unknown_camera_key", "[camera.roi]\nsize_px = 3\n", "camera.roi.size_px", 2,
                 "known keys of [camera.roi]"},
        BadInput{"lidar_wavelength", "[lidar]\nwavelength_m = 77e-3\n", "lidar.wavelength_m", 2,
                 "[4e-07, 2e-06]"},
        BadInput{"lidar_echoes", "[lidar]\nmax_echoes = 9\n", "lidar.max_echoes", 2,
                 "an integer in [1, 8]"},
        BadInput{"lidar_fluctuation", "[lidar.fog_fluctuation]\nlog_std = 3\n",
                 "lidar.fog_fluctuation.log_std", 2, "[0, 2]"},
        BadInput{"lidar_background_not_tables", "[lidar]\nbackground = [1, 2]\n",
                 "lidar.background", 2, "an array of tables [[lidar.background]]"},
        BadInput{"lidar_background_key", "[[lidar.background]]\nx0_m = 1\nz_m = 2\n",
                 "lidar.background[0].z_m", 3, "known keys of [lidar.background[0]]"},
        BadInput{
            "lidar_background_reflectivity",
            "[[lidar.background]]\nx0_m = 1\ny0_m = 0\nx1_m = 2\ny1_m = 0\nreflectivity = 1.5\n",
            "lidar.background[0].reflectivity", 6, "[0, 1]"},
        BadInput{"camera_band", "[camera]\nband = \"infrared\"\n", "camera.band", 2,
                 "one of photopic, rgb, monochromatic"},
        BadInput{"camera_exposure_mode", "[camera.exposure]\nmode = \"\"\n", "camera.exposure.mode",
                 2, "one of fixed, auto"},
        // Fog that begins at the lidar returns the divergent integral of dr / r^2 without an
        // overlap function.
        BadInput{"lidar_fog_at_the_aperture",
                 "[chamber]\nsensor_gap_m = 0.0\n[lidar]\noverlap_range_m = 0.0\n",
                 "lidar.overlap_range_m", 4, "> 0 with chamber.sensor_gap_m = 0",
                 "chamber.sensor_gap_m at line 2"},
        BadInput{"camera_cell", "[camera.roi]\ncell_px = 100\n", "camera.roi.cell_px", 2,
                 "[2, 60]"},
        BadInput{"camera_frames", "[camera]\nframes_per_step = 0\n", "camera.frames_per_step", 2,
                 "an integer in [1, 100000]"},
        BadInput{"camera_noise_type", "[camera.noise]\nenabled = \"yes\"\n", "camera.noise.enabled",
                 2, "must be true or false"},
        // The water-covered sensor and target: a permittivity below vacuum's, a negative film, a
        // window film too thin for its incoherent model.
        BadInput{"radome_permittivity",
                 "[radar.radome]\nthickness_m = 0.005\nrelative_permittivity = 0.5\n",
                 "radar.radome.relative_permittivity", 3, "[1, 100]"},
        // A radome's material without a radome (thickness 0, the default) would change nothing.
        BadInput{"radome_permittivity_without_radome",
                 "[radar.radome]\nrelative_permittivity = 4.0\n",
                 "radar.radome.relative_permittivity", 2,
                 "radar.radome.relative_permittivity = 4.0: takes effect only with "
                 "radar.radome.thickness_m > 0"},
        BadInput{"radome_loss_without_radome",
                 "[radar.radome]\nthickness_m = 0.0\nloss_tangent = 0.02\nwater_film_m = 1e-4\n",
                 "radar.radome.loss_tangent", 3,
                 "radar.radome.loss_tangent = 0.02: takes effect only with "
                 "radar.radome.thickness_m > 0"},
        BadInput{"target_water_film", "[target]\nwater_film_m = -1e-4\n", "target.water_film_m", 2,
                 "[0, 0.01]"},
        BadInput{"lidar_window_film", "[lidar]\nwindow_water_film_m = 5e-7\n",
                 "lidar.window_water_film_m", 2, "0 (dry) or in [1e-06, 0.01]"}),
    [](const ::testing::TestParamInfo<BadInput>& param_info) {
      return std::string(param_info.param.name);
    });

// The exact message for each kind of bad value: the key as written, the value as typed
// (not as a double prints it), and the true range or set, for a value of the wrong type too.
TEST(Scenario, EveryMessageQuotesTheValueAsTypedAndTheTrueRange) {
  const std::pair<const char*, const char*> cases[] = {
      // Bounded by chamber.layer_count, not by the field's type (INT64_MAX).
      {"[experiment]\nmax_active_layers = -1\n",
       "bad.toml:2: experiment.max_active_layers = -1: must be an integer in [0, "
       "chamber.layer_count = 4]"},
      {"[chamber]\nlayer_count = 2\n[experiment]\nmax_active_layers = -1\n",
       "bad.toml:4: experiment.max_active_layers = -1: must be an integer in [0, "
       "chamber.layer_count = 2] (chamber.layer_count at line 2)"},
      {"[experiment]\nmax_active_layers = 9223372036854775807\n",
       "bad.toml:2: experiment.max_active_layers = 9223372036854775807: must be an integer in [0, "
       "chamber.layer_count = 4]"},
      {"[experiment]\nmax_active_layers = 1.5\n",
       "bad.toml:2: experiment.max_active_layers = 1.5: must be an integer in [0, "
       "chamber.layer_count = 4]"},
      // A value of the wrong type: the range or set its key allows.
      {"[lidar]\nthreshold_reflectivity = true\n",
       "bad.toml:2: lidar.threshold_reflectivity = true: must be a number in (0, 1]"},
      {"[lidar]\nintensity_scale = \"big\"\n",
       "bad.toml:2: lidar.intensity_scale = 'big': must be a finite number > 0"},
      {"[radar]\nchirp_interval_s = false\n",
       "bad.toml:2: radar.chirp_interval_s = false: must be a number in [radar.chirp_duration_s = "
       "5.12e-05, 1]"},
      {"[radar]\nsweep_direction = 3\n",
       "bad.toml:2: radar.sweep_direction = 3: must be a string, one of up, down"},
      {"[radar.target]\nmodel = \"point\"\nswerling = \"one\"\n",
       "bad.toml:3: radar.target.swerling = 'one': must be an integer, one of 0, 1, 3"},
      // Keys that would do nothing are refused, naming what makes them work.
      {"[radar.target]\nswerling = 1\n",
       "bad.toml:2: radar.target.swerling = 1: takes effect only with radar.target.model = "
       "\"point\" (the "
       "EVT's "
       "five centres have heights of their own and a steady RCS)"},
      {"[radar.target]\nheight_m = 1.1\n",
       "bad.toml:2: radar.target.height_m = 1.1: takes effect only with radar.target.model = "
       "\"point\" (the "
       "EVT's five centres have heights of their own and a steady RCS)"},
      {"[camera]\nframes_per_step = true\n",
       "bad.toml:2: camera.frames_per_step = true: must be an integer in [1, 100000]"},
      // A sub-table given a plain value.
      {"[lidar]\nfog_fluctuation = 3\n",
       "bad.toml:2: lidar.fog_fluctuation = 3: must be a table [lidar.fog_fluctuation] with keys "
       "correlation_time_s, log_std"},
      {"[camera]\nroi = 5\n",
       "bad.toml:2: camera.roi = 5: must be a table [camera.roi] with keys background, cell_px, "
       "height_px, target, target_fraction, width_px"},
      {"fog.droplets = 1.50\n",
       "bad.toml:1: fog.droplets = 1.50: must be a table [fog.droplets] with keys alpha, "
       "b_per_um_gamma, diameter_m, distribution, gamma, geometric_std, median_diameter_m"},
      // Numbers as typed.
      {"[lidar]\nwavelength_m = 3e-7\n",
       "bad.toml:2: lidar.wavelength_m = 3e-7: must be in [4e-07, 2e-06]"},
      {"[chamber]\nsensor_gap_m = 1e5\n",
       "bad.toml:2: chamber.sensor_gap_m = 1e5: must be in [0, 10000]"},
      {"[experiment]\nseed = 1e5\n",
       "bad.toml:2: experiment.seed = 1e5: must be an integer in [0, 9223372036854775807]"},
      {"[radar] # \xc3\xbc\ntx_power_dbm = 1_000.5 # \xc3\xbc\n",
       "bad.toml:2: radar.tx_power_dbm = 1_000.5: must be in [-30, 50]"},
      {"[radar]\nsamples_per_chirp = 0x10_0000\n",
       "bad.toml:2: radar.samples_per_chirp = 0x10_0000: must be an integer in [16, 512]: the "
       "samples fit in the chirp, radar.chirp_duration_s x radar.sample_rate_hz = 512"},
      {"[fog]\nvisibility_m = 1E-4\n",
       "bad.toml:2: fog.visibility_m = 1E-4: must be in [0.001, 10000000]"},
      // A layer's length given as nan is quoted, not taken for a missing one.
      {"[[chamber.layers]]\nlength_m = nan\n",
       "bad.toml:2: chamber.layers[0].length_m = nan: must be in (0, 10000] (chamber.layers at "
       "line "
       "1)"},
      {"[[chamber.layers]]\nlength_m = 1.0\n[[chamber.layers]]\nlength_m = -nan\n",
       "bad.toml:4: chamber.layers[1].length_m = -nan: must be in (0, 10000] (chamber.layers at "
       "line 1)"},
      // A range the other keys leave empty is said to be so, not printed as [16, 5].
      {"[radar]\nsample_rate_hz = 1e5\n",
       "bad.toml:2: radar.samples_per_chirp = 512: must be an integer >= 16 and <= 5: the samples "
       "fit in the chirp, radar.chirp_duration_s x radar.sample_rate_hz = 5.12; no integer is "
       "both: the keys named leave it no value (radar.sample_rate_hz at line 2)"},
      {"[radar]\nsample_rate_hz = 1e6\n",
       "bad.toml:2: radar.samples_per_chirp = 512: must be an integer in [16, 51]: the samples fit "
       "in the chirp, radar.chirp_duration_s x radar.sample_rate_hz = 51.2 (radar.sample_rate_hz "
       "at line 2)"},
      {"[lidar]\nmin_range_m = 100\nmax_range_m = 50\n",
       "bad.toml:3: lidar.max_range_m = 50: must be in (lidar.min_range_m = 100, 1000] "
       "(lidar.min_range_m at line 2)"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      parse_scenario(text, "bad.toml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(std::string(e.what()), expected) << text;
    }
  }
}

// Every number key of the scenario refuses nan and the infinities quoting them as typed, whichever
// check refuses them (its own range, or a bound across keys).
TEST(Scenario, EveryNumberKeyQuotesNanAndInfAsTyped) {
  const Scenario paper = paper_scenario();
  std::size_t checked = 0;
  for (const Key<Scenario>& key : paper.keys().keys()) {
    if (key.type != KeyType::number || !key.takes_effect(paper)) continue;
    for (const char* typed : {"nan", "-nan", "+nan", "inf", "+inf", "-inf"}) {
      std::string text = "[";
      text.append(key.section()).append("]\n").append(key.short_name());
      text.append(" = ").append(typed).append("\n");
      try {
        parse_scenario(text, "bad.toml");
        ADD_FAILURE() << "accepted: " << text;
      } catch (const InvalidParameter& e) {
        const std::string expected = "bad.toml:2: " + key.name + " = " + typed + ": must be ";
        EXPECT_EQ(std::string(e.what()).substr(0, expected.size()), expected) << e.what();
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 6u * 60u);
}

// Documented bounds are accepted exactly (checked in the user's units, before any conversion), and
// the widest integers the documentation allows are read.
TEST(Scenario, DocumentedBoundsAreAccepted) {
  EXPECT_EQ(parse_scenario("[fog]\ntemperature_c = -20\n", "cold.toml").fog.temperature_c, -20.0);
  EXPECT_EQ(parse_scenario("[fog]\ntemperature_c = 50\n", "warm.toml").fog.temperature_c, 50.0);
  EXPECT_EQ(
      parse_scenario("[experiment]\nseed = 9223372036854775807\n", "seed.toml").experiment.seed,
      9223372036854775807u);
  EXPECT_EQ(radar_of(parse_scenario("[radar.processing.cfar]\nguard_cells = 247\n", "guard.toml"))
                .radar.cfar.guard_cells,
            247u);
  // Each number key at both ends of its docs/scenario.md range (the others at their paper values).
  // The paper's hall holds concrete (radio data for 1-100 GHz) and plastic barrels (10-300 GHz)
  // 2.5-5.5 m ahead: the frequencies outside, and a radar so high that the barrels' echoes lie
  // beyond its unambiguous range, run in a hall without them.
  const char* bounds[] = {
      "[chamber]\nobjects = []\n[chamber.room]\nleft_wall = false\n[chamber.room.floor]\n"
      "reflection_coefficient = -0.7\n[radar]\ncentre_frequency_hz = 300e9\n",
      "[chamber]\nobjects = []\n[radar]\ncentre_frequency_hz = 2e9\nsweep_bandwidth_hz = 1e9\n",
      "[radar]\nsweep_bandwidth_hz = 1e6\n",
      "[radar]\nsweep_bandwidth_hz = 38.5e9\nsample_rate_hz = 1e10\n",  // range: c fs Tc / (2 B)
      "[radar]\nchirp_duration_s = 1e-2\nchirp_interval_s = 1\n",
      "[radar]\nchirp_interval_s = 51.2e-6\n",
      "[radar]\nsamples_per_chirp = 16\n[radar.processing.cfar]\nguard_cells = 0\ntraining_cells = "
      "7\n",
      "[radar]\nsample_rate_hz = 1e10\n",
      "[radar]\nchirps_per_frame = 1\n",
      "[radar]\nchirps_per_frame = 16384\n",
      "[radar]\ntx_power_dbm = -30\ntx_gain_dbi = 0\nrx_gain_dbi = 60\n",
      "[radar]\ntx_power_dbm = 50\ntx_gain_dbi = 60\nrx_gain_dbi = 0\n",
      "[radar]\nazimuth_beamwidth_deg = 0.1\nelevation_beamwidth_deg = 180\n",
      "[radar]\nnoise_figure_db = 0\nreference_temperature_k = 1\n",
      "[radar]\nnoise_figure_db = 40\nreference_temperature_k = 1000\n",
      "[radar]\nadc_bits = 24\nadc_full_scale_dbm = -100\nphase_noise_rms_rad = "
      "3.141592653589793\n",
      "[radar]\nadc_bits = 1\nadc_full_scale_dbm = 30\nphase_noise_rms_rad = 0\n",
      "[radar.processing]\nassociation_gate_m = 1000\n",
      "[radar.processing.cfar]\nkind = \"os\"\nos_rank = 16\n",
      "[radar.target]\nrcs_dbsm = -60\n",
      "[radar.target]\nrcs_dbsm = 60\n",
      "[chamber]\nobjects = []\n[radar.target]\nmodel = \"point\"\nheight_m = 100\n[radar]\n"
      "height_m = 100\n",
      "[chamber.room.floor]\nreflection_coefficient = -1\n[target]\nmicro_motion_std_m = 0.1\n",
      "[chamber.room.floor]\nreflection_coefficient = 1\n",
      "[chamber]\nsensor_gap_m = 0\ntarget_gap_m = 0\nlayer_count = 1000\nlayer_length_m = 0.05\n",
      "[fog]\nextinction_per_km = 1e6\n",
      "[fog]\nlwc_g_per_m3 = 100\n",
      "[fog]\nvisibility_m = 1e-3\n",
      "[fog]\nvisibility_m = 1e7\n",
      "[radar]\nclutter_scatterers_per_bin = 64\n",
      "[fog.droplets]\nmedian_diameter_m = 1e-8\ngeometric_std = 1.01\n",
      "[fog.droplets]\nmedian_diameter_m = 1e-3\ngeometric_std = 3\n",
      "[fog.droplets]\ndistribution = \"monodisperse\"\ndiameter_m = 1e-8\n",
      "[fog.droplets]\ndistribution = \"monodisperse\"\ndiameter_m = 1e-3\n",
      "[radar]\nmeasurements_per_step = 1000000\n[experiment]\nmax_active_layers = 0\n",
      "[radar.radome]\nthickness_m = 0.05\nrelative_permittivity = 100\nloss_tangent = 1\n"
      "water_film_m = 0.01\n",
      "[radar.radome]\nthickness_m = 1e-4\nrelative_permittivity = 1\nloss_tangent = 0\n",
      "[radar.radome]\nthickness_m = 0\nwater_film_m = 1e-4\n",
      "[target]\nwater_film_m = 0.01\n",
      "[lidar]\nwindow_water_film_m = 1e-6\n[camera]\nwindow_water_film_m = 0.01\n",
  };
  for (const char* text : bounds) {
    try {
      parse_scenario(text, "bound.toml");
    } catch (const InvalidParameter& e) {
      ADD_FAILURE() << text << " refused: " << e.what();
    }
  }
}

}  // namespace
}  // namespace fogradar::experiment
