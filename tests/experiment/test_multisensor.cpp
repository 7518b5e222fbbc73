// The experiment with several sensors on one chamber (docs/architecture.md): the result files are
// the same bytes for any thread count; adding or removing a sensor never changes another sensor's
// files (each draws from its own streams, sensor_stream); summary.json carries every sensor's limit
// and summary in the documented layout; the embedded paper scenario holds the sensors' own
// defaults; every invalid [lidar] and [camera] key is refused naming the key and its line.
#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/radar/sensor.hpp"
#include "sensors.hpp"

namespace fogradar::experiment {
namespace {

using Files = std::map<std::string, std::string>;

// Every sensor, each small (fast enough for the Debug sanitizer build): 16-chirp radar frames, 4
// measurements, 3 scans of a 12 degree field of view (the target and the fog in it), 2 frames of a
// 64 x 48 ROI per step.
Scenario small_three_sensors() {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"radar", "lidar", "camera"};
  radar_of(s).radar.chirps_per_frame = 16;
  s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 4;
  lidar_of(s).scans_per_step = 3;
  lidar_of(s).field_of_view_deg = 12.0;
  camera_of(s).frames_per_step = 2;
  camera_of(s).roi.width_px = 64;
  camera_of(s).roi.height_px = 48;
  return s;
}

Files files_of(const Scenario& s, unsigned threads) {
  Files files;
  const ExperimentSummary summary =
      summarize(run_experiment(s, {.threads = threads, .progress = {}}));
  for (sensor::ResultFile& file : result_files(s, summary)) files[file.name] = file.content;
  return files;
}

// The files of the three sensors (docs/scenario.md, Results).
const char* const radar_files[] = {"radar_samples.csv",     "radar_detections.csv",
                                   "radar_summary.csv",     "radar_summary.json",
                                   "radar_rcs_boxplot.svg", "radar_origins.svg"};
const char* const lidar_files[] = {"lidar_echoes.csv", "lidar_summary.csv", "lidar_summary.json",
                                   "lidar_intensity_boxplot.svg", "lidar_scans.svg"};
const char* const camera_files[] = {"camera_histograms.csv", "camera_summary.csv",
                                    "camera_summary.json", "camera_histograms.svg"};

TEST(MultiSensor, EveryFileIsTheSameBytesForAnyThreadCount) {
  const Scenario s = small_three_sensors();
  const Files one = files_of(s, 1), three = files_of(s, 3);
  // Every sensor's files and summary.json, scenario.toml, benchmark.svg (no ROI images asked for).
  EXPECT_EQ(one.size(), 6u + 5u + 4u + 3u);
  for (const auto& [name, content] : one) {
    ASSERT_TRUE(three.contains(name)) << name;
    EXPECT_EQ(content, three.at(name)) << name;
    EXPECT_TRUE(is_result_file_name(name)) << name;
  }
}

// The radar's files of a radar-only run equal those of runs that add the lidar or the camera; the
// lidar's equal between a run with and without the radar and camera; the camera's likewise. The
// scenario (and so scenario.toml and summary.json) differ only in experiment.sensors.
TEST(MultiSensor, AddingASensorLeavesTheOthersFilesUnchanged) {
  Scenario radar_only = small_three_sensors();
  radar_only.experiment.sensors = {"radar"};
  Scenario radar_lidar = radar_only;
  radar_lidar.experiment.sensors = {"radar", "lidar"};
  Scenario lidar_only = radar_only;
  lidar_only.experiment.sensors = {"lidar"};
  Scenario camera_first = radar_only;
  camera_first.experiment.sensors = {"camera", "radar"};
  const Files all = files_of(small_three_sensors(), 2), r = files_of(radar_only, 2),
              rl = files_of(radar_lidar, 2), l = files_of(lidar_only, 2),
              cr = files_of(camera_first, 2);
  EXPECT_EQ(r.size(), 9u);  // its 6 files, summary.json, scenario.toml, benchmark.svg
  EXPECT_FALSE(l.contains("radar_samples.csv"));
  for (const char* radar_file : radar_files) {
    EXPECT_EQ(r.at(radar_file), rl.at(radar_file)) << radar_file;
    EXPECT_EQ(r.at(radar_file), all.at(radar_file)) << radar_file;
    EXPECT_EQ(r.at(radar_file), cr.at(radar_file)) << radar_file;
  }
  for (const char* lidar_file : lidar_files) {
    EXPECT_EQ(l.at(lidar_file), rl.at(lidar_file)) << lidar_file;
    EXPECT_EQ(l.at(lidar_file), all.at(lidar_file)) << lidar_file;
  }
  for (const char* camera_file : camera_files) {
    EXPECT_EQ(cr.at(camera_file), all.at(camera_file)) << camera_file;
  }
  // The radar's entry in summary.json is the same whichever sensors ran beside it.
  EXPECT_EQ(nlohmann::json::parse(r.at("summary.json")).at("sensors").at("radar"),
            nlohmann::json::parse(all.at("summary.json")).at("sensors").at("radar"));
}

// summary.json (docs/scenario.md, Results): the resolved scenario, the chamber, and one entry per
// sensor that ran with its limit, criterion, margin and summary, each summary as the sensor's own
// <name>_summary.json holds it.
TEST(MultiSensor, SummaryJsonCarriesEverySensorsLimitAndSummary) {
  const Scenario s = small_three_sensors();
  const ExperimentSummary summary = summarize(run_experiment(s));
  const Files files = files_of(s, 2);
  const nlohmann::json json = nlohmann::json::parse(files.at("summary.json"));
  EXPECT_EQ(json.size(), 3u);
  EXPECT_TRUE(json.contains("scenario"));
  EXPECT_TRUE(json.contains("chamber"));  // each layer's fog: test_layers.cpp
  ASSERT_TRUE(json.contains("sensors"));
  const nlohmann::json& sensors = json.at("sensors");
  EXPECT_EQ(sensors.size(), 3u);
  for (const char* name : {"radar", "lidar", "camera"}) {
    ASSERT_TRUE(sensors.contains(name)) << name;
    EXPECT_TRUE(sensors.at(name).contains("sensor_limit_layers")) << name;
    EXPECT_FALSE(sensors.at(name).at("criterion").get<std::string>().empty()) << name;
    // A margin exactly when the limit is not reached.
    EXPECT_EQ(sensors.at(name).at("sensor_limit_layers").is_null(),
              !sensors.at(name).at("margin").get<std::string>().empty())
        << name;
  }
  for (const char* name : {"radar", "lidar", "camera"}) {
    EXPECT_EQ(sensors.at(name).at("summary"),
              nlohmann::json::parse(files.at(std::string(name) + "_summary.json")))
        << name;
  }
  EXPECT_EQ(sensors.at("radar").at("sensor_limit_layers"),
            sensors.at("radar").at("summary").at("sensor_limit_layers"));
  EXPECT_EQ(sensors.at("lidar").at("sensor_limit_layers").is_null(),
            !lidar_report(summary).summary().sensor_limit_layers);
  // One benchmark line per sensor, in experiment.sensors' order.
  const std::string table = benchmark_table(summary);
  EXPECT_LT(table.find("radar "), table.find("lidar "));
  EXPECT_LT(table.find("lidar "), table.find("camera "));
}

// A run without the radar writes no radar file and no radar entry in summary.json.
TEST(MultiSensor, WithoutTheRadarNoRadarFiles) {
  Scenario s = small_three_sensors();
  s.experiment.sensors = {"camera"};
  const Files files = files_of(s, 1);
  for (const char* radar_file : radar_files) EXPECT_FALSE(files.contains(radar_file));
  const nlohmann::json json = nlohmann::json::parse(files.at("summary.json"));
  EXPECT_EQ(json.at("sensors").size(), 1u);
  EXPECT_TRUE(json.at("sensors").contains("camera"));
}

// The paper scenario file lists the [lidar] and [camera] keys with the modules' own defaults
// (lidar/params.hpp, camera/params.hpp), so the two cannot drift apart unnoticed.
TEST(MultiSensor, PaperScenarioHoldsTheSensorsDefaults) {
  const Scenario paper = paper_scenario();
  EXPECT_EQ(paper.experiment.sensors, (std::vector<std::string>{"radar", "lidar", "camera"}));
  Scenario defaults = paper;
  lidar_of(defaults) = lidar::LidarParams{};
  camera_of(defaults) = camera::CameraParams{};
  EXPECT_EQ(to_toml(paper), to_toml(defaults));
}

// The sensors' sections written by to_toml read back to the same scenario: the paper's background
// segments (an array of tables), none at all (background = []), and changed enumerations and nested
// keys.
TEST(MultiSensor, SensorSectionsRoundTrip) {
  Scenario s = paper_scenario();
  const std::string paper = to_toml(s);
  EXPECT_EQ(to_toml(parse_scenario(paper, "paper.toml")), paper);
  EXPECT_EQ(lidar_of(parse_scenario(paper, "paper.toml")).background.size(),
            lidar_of(s).background.size());
  lidar_of(s).background.clear();
  lidar_of(s).fog_fluctuation.log_std = 0.0;
  camera_of(s).band = camera::Band::rgb;
  camera_of(s).exposure.mode = camera::ExposureMode::automatic;
  camera_of(s).transfer = camera::TransferCurve::gamma;
  camera_of(s).roi.background.log_sigma = 1.25;
  const std::string changed = to_toml(s);
  const Scenario read = parse_scenario(changed, "changed.toml");
  EXPECT_TRUE(lidar_of(read).background.empty());
  EXPECT_EQ(camera_of(read).band, camera::Band::rgb);
  EXPECT_EQ(to_toml(read), changed);
}

// Items counted over every sensor: progress reaches the total of radar measurements, lidar scans
// and camera frames.
TEST(MultiSensor, ProgressCountsEverySensorsItems) {
  const Scenario s = small_three_sensors();
  std::atomic<std::size_t> last_total{0}, calls{0};
  run_experiment(s, {.threads = 2, .progress = [&](std::size_t, std::size_t total) {
                       last_total = total;
                       ++calls;
                     }});
  const std::size_t expected = 5 * (4 + 3 + 2);
  EXPECT_EQ(last_total.load(), expected);
  EXPECT_EQ(calls.load(), expected);
}

// Every key of [lidar...] and [camera...] as to_toml writes it, given a value its section refuses
// (nan for a number, -1 for an integer, an unknown name for a string, 1 for a boolean): refused
// naming the key as written and its line. The keys come from the resolved scenario, so a key added
// to a sensor later is covered as soon as to_toml writes it.
TEST(MultiSensor, EveryInvalidSensorKeyIsRefusedNamingIt) {
  std::istringstream text(to_toml(paper_scenario()));
  std::string line, section;
  std::size_t tested = 0;
  while (std::getline(text, line)) {
    if (line.rfind("[", 0) == 0) {
      section =
          line.substr(line.find_first_not_of('['), line.find(']') - line.find_first_not_of('['));
      continue;
    }
    const bool sensor_section = section.rfind("lidar", 0) == 0 || section.rfind("camera", 0) == 0;
    const std::size_t equals = line.find(" = ");
    if (!sensor_section || equals == std::string::npos || section == "lidar.background") continue;
    const std::string key = line.substr(0, equals), value = line.substr(equals + 3);
    if (key == "background") continue;  // the array of segments: its own cases below
    std::string bad;
    if (value.front() == '"')
      bad = "\"bogus\"";
    else if (value == "true" || value == "false")
      bad = "1";
    else if (value.find_first_of(".e") == std::string::npos)
      bad = "-1";
    else
      bad = "nan";
    const std::string file = "[" + section + "]\n" + key + " = " + bad + "\n";
    const std::string full = section + "." + key;
    try {
      parse_scenario(file, "bad.toml");
      ADD_FAILURE() << "accepted: " << file;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.field(), full) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("bad.toml:2: " + full, 0), 0u) << e.what();
    }
    ++tested;
  }
  EXPECT_GE(tested,
            21u + 2u + 7u + 3u + 3u + 4u + 2u + 2u);  // every [lidar...] and [camera...] key
}

}  // namespace
}  // namespace fogradar::experiment
