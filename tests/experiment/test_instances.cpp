// Sensor instances (docs/scenario.md, "Sensor instances"): a second radar and a second lidar beside
// the kinds' own, each with its kind's keys under its own section, its own files, rows and
// messages. Adding an instance changes no other instance's bytes; two instances with the same keys
// give the same results apart from their names; the reader refuses bad names and kinds and names
// every moved key's new place.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/radar/sensor.hpp"
#include "sensors.hpp"

namespace fogradar::experiment {
namespace {

using Files = std::map<std::string, std::string>;

// The paper chamber with small sensors (16-chirp frames, 4 measurements; 3 scans of a 12 degree
// field of view), given as a file gives it, and further instances after it.
constexpr const char* small_toml = R"(
[radar]
chirps_per_frame = 16
measurements_per_step = 4

[lidar]
scans_per_step = 3
field_of_view_deg = 12.0
)";

constexpr const char* instances_toml = R"(
[radar_24]
kind = "radar"
centre_frequency_hz = 24.125e9
sweep_bandwidth_hz = 250e6
chirps_per_frame = 16
measurements_per_step = 4

[radar_24.processing.cfar]
kind = "os"

[lidar_1550]
kind = "lidar"
wavelength_m = 1550e-9
scans_per_step = 3
field_of_view_deg = 12.0
)";

Files files_of(const Scenario& s) {
  Files files;
  const ExperimentSummary summary = summarize(run_experiment(s, {.threads = 2, .progress = {}}));
  for (sensor::ResultFile& file : result_files(s, summary)) files[file.name] = file.content;
  return files;
}

Scenario with_sensors(const std::string& text, const std::string& sensors) {
  return parse_scenario(text + "[experiment]\nsensors = " + sensors + "\n", "s.toml");
}

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "bad.toml");
  } catch (const InvalidParameter& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Instances, AddingInstancesChangesNoOtherInstancesBytes) {
  const Files alone = files_of(with_sensors(small_toml, R"(["radar", "lidar"])"));
  const Scenario both = with_sensors(std::string(small_toml) + instances_toml,
                                     R"(["radar", "radar_24", "lidar", "lidar_1550"])");
  const Files all = files_of(both);
  for (const char* name : {"radar_samples.csv", "radar_detections.csv", "radar_summary.csv",
                           "radar_summary.json", "lidar_echoes.csv", "lidar_summary.csv"}) {
    ASSERT_TRUE(all.contains(name)) << name;
    EXPECT_EQ(all.at(name), alone.at(name)) << name;
  }
  // The instances' own files, under their names.
  for (const char* name : {"radar_24_samples.csv", "radar_24_summary.csv", "radar_24_summary.json",
                           "radar_24_rcs_boxplot.svg", "lidar_1550_echoes.csv",
                           "lidar_1550_summary.csv", "lidar_1550_scans.svg"}) {
    EXPECT_TRUE(all.contains(name)) << name;
  }
  // Each instance has its own result: the 24 GHz radar's summary is not the 77 GHz one's.
  EXPECT_NE(all.at("radar_24_summary.csv"), all.at("radar_summary.csv"));
  for (const auto& [name, content] : all) EXPECT_TRUE(is_result_file_name(name)) << name;
}

// Two instances of one kind with the same keys give the same results, file for file, apart from
// their names: every instance of a kind draws the kind's random numbers for item (k, i).
TEST(Instances, TwoInstancesWithTheSameKeysGiveTheSameResults) {
  const std::string twins = std::string(small_toml) +
                            "[radar_2]\nkind = \"radar\"\nchirps_per_frame = 16\n"
                            "measurements_per_step = 4\n[lidar_2]\nkind = \"lidar\"\n"
                            "scans_per_step = 3\nfield_of_view_deg = 12.0\n[experiment]\n"
                            "sensors = [\"radar\", \"radar_2\", \"lidar\", \"lidar_2\"]\n";
  const Files files = files_of(parse_scenario(twins, "twins.toml"));
  std::size_t compared = 0;
  for (const auto& [name, content] : files) {
    for (const std::string kind : {"radar", "lidar"}) {
      if (!name.starts_with(kind + "_") || name.starts_with(kind + "_2_")) continue;
      const std::string twin = kind + "_2" + name.substr(kind.size());
      ASSERT_TRUE(files.contains(twin)) << twin;
      EXPECT_EQ(files.at(twin), content) << twin;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 6u + 5u);
  const ExperimentSummary summary = summarize(
      run_experiment(parse_scenario(twins, "twins.toml"), {.threads = 1, .progress = {}}));
  EXPECT_EQ(summary.of<radar::RadarReport>("radar_2").summary().steps[1].rcs.median,
            summary.of<radar::RadarReport>("radar").summary().steps[1].rcs.median);
}

TEST(Instances, AnInstanceHasItsKindsKeysUnderItsSection) {
  const Scenario s = parse_scenario(instances_toml, "s.toml");
  std::set<std::string> radar, radar_24;
  for (const Key<Scenario>& key : s.keys().keys()) {
    if (key.type == KeyType::retired) continue;
    const std::string_view name(key.name);
    if (name.starts_with("radar.")) radar.insert(std::string(name.substr(6)));
    if (name.starts_with("radar_24.")) radar_24.insert(std::string(name.substr(9)));
  }
  radar.insert("kind");  // the instance's own key, fixed where it is made
  EXPECT_EQ(radar_24, radar);
  EXPECT_TRUE(radar_24.contains("processing.cfar.shape"));
  EXPECT_TRUE(radar_24.contains("target.rcs_dbsm"));
  // The resolved file reads back to the same scenario.
  EXPECT_EQ(to_toml(parse_scenario(to_toml(s), "again.toml")), to_toml(s));
}

TEST(Instances, MessagesNameTheInstancesKeys) {
  EXPECT_EQ(error_of("[radar_24]\nkind = \"radar\"\nsamples_per_chirp = 600\n"),
            "bad.toml:3: radar_24.samples_per_chirp = 600: must be an integer in [16, 512]: the "
            "samples fit in the chirp, radar_24.chirp_duration_s x radar_24.sample_rate_hz = 512");
  // A bound the kind's configure() checks, across the instance's key and the chamber's.
  EXPECT_EQ(error_of("[lidar_1550]\nkind = \"lidar\"\noverlap_range_m = 0\n[chamber]\n"
                     "sensor_gap_m = 0\n")
                .rfind("bad.toml:3: lidar_1550.overlap_range_m = 0: must be > 0 with "
                       "chamber.sensor_gap_m = 0",
                       0),
            0u);
  EXPECT_EQ(error_of("[radar_24]\nkind = \"sonar\"\n"),
            "bad.toml:2: radar_24.kind = 'sonar': must be one of 'radar', 'lidar', 'camera'");
  EXPECT_EQ(error_of("[Radar2]\nkind = \"radar\"\n"),
            "bad.toml:2: [Radar2]: a sensor instance's section must be " +
                std::string(instance_name_rule));
  EXPECT_EQ(error_of("[radar_9]\ncentre_frequency_hz = 3e9\n"),
            "bad.toml:1: unknown section or key 'radar_9' (sections: chamber, fog, target, "
            "experiment, radar, lidar, camera; a further sensor instance gives its kind: "
            "[radar_9] kind = \"radar\")");
  // A scenario read over one that has the instance may repeat its kind, not change it.
  const Scenario base = parse_scenario(instances_toml, "base.toml");
  EXPECT_NO_THROW(parse_scenario_over(base, "[radar_24]\nkind = \"radar\"\n", "over.toml"));
  try {
    parse_scenario_over(base, "[radar_24]\nkind = \"lidar\"\n", "over.toml");
    ADD_FAILURE() << "a changed kind was accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(std::string(e.what()),
              "over.toml:2: radar_24.kind = 'lidar': must be 'radar', the kind the instance was "
              "made with");
  }
  EXPECT_EQ(error_of("[experiment]\nsensors = [\"radar\", \"radar_24\"]\n")
                .rfind("bad.toml:2: experiment.sensors = [\"radar\", \"radar_24\"]", 0),
            0u);
}

// The memory and time estimates of an instance, which a limit's refusal quotes, name its keys.
TEST(Instances, EstimatesNameTheInstancesKeys) {
  const Scenario s = parse_scenario(instances_toml, "s.toml");
  const sensor::MemoryPart memory = s.configure("radar_24")->memory(1);
  EXPECT_NE(memory.detail.find("radar_24.measurements_per_step = 4"), std::string::npos)
      << memory.detail;
  EXPECT_EQ(memory.detail.find("radar."), std::string::npos) << memory.detail;
  const sensor::Cost cost = s.configure("radar_24")->cost();
  EXPECT_EQ(cost.item.items_key, "radar_24.measurements_per_step");
  EXPECT_EQ(s.configure("lidar_1550")->cost().item.items_key, "lidar_1550.scans_per_step");
  EXPECT_EQ(s.configure("radar")->cost().item.items_key, "radar.measurements_per_step");
}

// Every key the radar moved under [radar] is refused where it was, naming its new place.
TEST(Instances, MovedKeysNameTheirNewPlace) {
  const std::vector<std::pair<std::string, std::string>> moved = {
      {"[processing]\nwindow = \"hann\"\n", "radar.processing.window"},
      {"[processing.cfar]\nkind = \"os\"\n", "radar.processing.cfar.kind"},
      {"[target]\nrcs_dbsm = 3.0\n", "radar.target.rcs_dbsm"},
      {"[target]\nmodel = \"point\"\n", "radar.target.model"},
      {"[target]\nsensor_height_m = 1.0\n", "radar.height_m"},
      {"[fog]\nclutter_scatterers_per_bin = 2\n", "radar.clutter_scatterers_per_bin"},
      {"[experiment]\nmeasurements_per_step = 3\n", "radar.measurements_per_step"}};
  for (const auto& [text, place] : moved) {
    const std::string message = error_of(text);
    EXPECT_NE(message.find("is no longer read"), std::string::npos) << message;
    EXPECT_NE(message.find(place), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace fogradar::experiment
