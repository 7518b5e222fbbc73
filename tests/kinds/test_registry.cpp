// A kind is its folder and one word in a list: the test tree's range finder
// (tests/kinds/rangefinder/) is registered beside the study's three by the list of kinds in
// tests/CMakeLists.txt, from which the build generates kinds_registry(), as it generates
// standard_registry() from the top CMakeLists.txt's. It runs through run_experiment on the same
// chamber with them; it gets its keys read, refused and written back, its table, files, benchmark
// curve and limit, its result set written and replaced, and the three others' files do not change
// by a byte. Nothing in experiment/ or cli/ knows it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <typeinfo>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/registry.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/rangefinder/sensor.hpp"
#include "sensors.hpp"

namespace fogradar::experiment {

// Generated from tests/CMakeLists.txt's list of kinds (cmake/SensorRegistry.cmake).
SensorRegistry kinds_registry();

namespace {

using rangefinder::RangeFinderParams;

// A kind as another: the range finder under another name, stream key or keys.
class Relabelled : public sensor::SensorKind {
 public:
  Relabelled(sensor::KindInfo info, bool keep_keys)
      : kind_(rangefinder::sensor_kind()), info_(std::move(info)), keep_keys_(keep_keys) {}
  const sensor::KindInfo& info() const override { return info_; }
  const KeyTable<sensor::Params>& keys() const override {
    return keep_keys_ ? kind_->keys() : no_keys_;
  }
  std::unique_ptr<sensor::Params> defaults() const override { return kind_->defaults(); }
  std::shared_ptr<const sensor::ConfiguredSensor> configure(
      const sensor::Params& params, const sensor::Context& context) const override {
    return kind_->configure(params, context);
  }

 private:
  std::shared_ptr<const sensor::SensorKind> kind_;
  sensor::KindInfo info_;
  bool keep_keys_;
  KeyTable<sensor::Params> no_keys_;
};

SensorRegistry four_sensors() { return kinds_registry(); }

// The study's three sensors, small, and the range finder with 9 shots a step needing a two-way
// transmittance of 0.1.
constexpr const char* four_toml = R"(
[radar]
chirps_per_frame = 16
measurements_per_step = 3
[experiment]
sensors = ["radar", "lidar", "camera", "rangefinder"]
[lidar]
scans_per_step = 2
field_of_view_deg = 12.0
[camera]
frames_per_step = 2
[rangefinder]
shots_per_step = 9
min_transmittance = 0.1
)";

std::map<std::string, std::string> files_of(const Scenario& s, const ExperimentSummary& summary) {
  std::map<std::string, std::string> files;
  for (sensor::ResultFile& file : result_files(s, summary)) files[file.name] = file.content;
  return files;
}

TEST(Registry, AKindOfTheTestTreesListRunsBesideTheStudysThree) {
  const SensorRegistry registry = four_sensors();
  const Scenario s = parse_scenario(four_toml, "four.toml", registry);
  const ExperimentSummary summary = summarize(run_experiment(s, {.threads = 2, .progress = {}}));
  ASSERT_EQ(summary.sensors.size(), 4u);

  // Its limit: the paper fog's 900 /km at 550 nm in 1 m layers leaves a two-way transmittance of
  // exp(-1.8 k) after k layers (Beer-Lambert): 0.165 at 1 layer, above 0.1; 0.0273 at 2, below.
  EXPECT_GT(std::exp(-1.8), 0.1);
  EXPECT_LT(std::exp(-3.6), 0.1);
  const sensor::Verdict verdict = summary.sensors.back().summary->verdict();
  ASSERT_TRUE(verdict.layers_to_failure.has_value());
  EXPECT_EQ(*verdict.layers_to_failure, 2u);

  // Its table and its benchmark line where `fogradar run` prints them.
  const std::string tables = sensor_tables(summary);
  EXPECT_NE(tables.find("rangefinder\nlayers   rate  transmittance\n     0      1              1\n"
                        "     1      1       0.165299\n"),
            std::string::npos)
      << tables;
  const std::string benchmark = benchmark_table(summary);
  EXPECT_NE(benchmark.find("rangefinder layers to failure: 2\n"), std::string::npos) << benchmark;

  // Its files, its entry in summary.json and its curve in benchmark.svg.
  const std::map<std::string, std::string> files = files_of(s, summary);
  ASSERT_TRUE(files.contains("rangefinder_shots.csv"));
  EXPECT_EQ(std::count(files.at("rangefinder_shots.csv").begin(),
                       files.at("rangefinder_shots.csv").end(), '\n'),
            1 + 5 * 9);
  const nlohmann::json json = nlohmann::json::parse(files.at("summary.json"));
  EXPECT_EQ(json.at("sensors").at("rangefinder").at("sensor_limit_layers"), 2);
  EXPECT_EQ(json.at("sensors").at("rangefinder").at("summary"),
            nlohmann::json::parse(files.at("rangefinder_summary.json")));
  EXPECT_NE(files.at("benchmark.svg").find("rangefinder echo rate"), std::string::npos);
  EXPECT_NE(files.at("benchmark.svg").find("rangefinder limit 2"), std::string::npos);
  for (const auto& [name, content] : files) EXPECT_TRUE(is_result_file_name(name)) << name;

  // Its keys: written into scenario.toml in its own section, read back, refused when bad.
  const std::string toml = files.at("scenario.toml");
  EXPECT_NE(toml.find("\n[rangefinder]\nshots_per_step = 9\nrange_noise_m = 0.02\n"),
            std::string::npos)
      << toml;
  EXPECT_EQ(to_toml(parse_scenario(toml, "scenario.toml", registry)), toml);
  try {
    parse_scenario("[rangefinder]\n\nmin_transmittance = 0\n", "bad.toml", registry);
    FAIL() << "accepted min_transmittance = 0";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "rangefinder.min_transmittance");
    EXPECT_EQ(std::string(e.what()).rfind("bad.toml:3: rangefinder.min_transmittance = 0: must be "
                                          "in (0, 1]",
                                          0),
              0u)
        << e.what();
  }
  // The standard registry does not know it.
  EXPECT_THROW(parse_scenario(four_toml, "four.toml"), InvalidParameter);
}

// The result set as `fogradar run` writes it: the run's files, the range finder's among them, go
// into the output directory in one step; a second run replaces them, its files being those the
// set's record lists, where a file it does not list, even under the range finder's prefix, is
// refused and left in place.
TEST(Registry, ItsResultFilesAreWrittenAndReplacedInTheOutputDirectory) {
  namespace fs = std::filesystem;
  const SensorRegistry registry = four_sensors();
  Scenario s = parse_scenario(four_toml, "four.toml", registry);
  s.experiment.sensors = {"camera", "rangefinder"};
  const fs::path dir = fs::path(::testing::TempDir()) / "fogradar_kinds_result_set";
  fs::remove_all(dir);
  const auto write = [&] {
    OutputDirectory out(dir);
    return out.replace(
        result_files(s, summarize(run_experiment(s, {.threads = 2, .progress = {}}))));
  };
  ASSERT_TRUE(write());
  ASSERT_TRUE(fs::exists(dir / "rangefinder_shots.csv"));
  ASSERT_TRUE(fs::exists(dir / "rangefinder_summary.json"));
  EXPECT_TRUE(write());  // its own files are replaced
  EXPECT_TRUE(fs::exists(dir / "rangefinder_shots.csv"));
  std::ofstream(dir / "rangefinder_notes.txt") << "the user's\n";
  EXPECT_THROW(write(), InvalidParameter);
  EXPECT_TRUE(fs::exists(dir / "rangefinder_notes.txt"));
  fs::remove_all(dir);
}

// Adding a sensor never changes another's numbers: the three study sensors' files are the same
// bytes with and without the range finder beside them.
TEST(Registry, TheFourthSensorLeavesTheOthersFilesUnchanged) {
  const SensorRegistry registry = four_sensors();
  const Scenario four = parse_scenario(four_toml, "four.toml", registry);
  Scenario three = four;
  three.experiment.sensors = {"radar", "lidar", "camera"};
  const std::map<std::string, std::string> with =
      files_of(four, summarize(run_experiment(four, {.threads = 2, .progress = {}})));
  const std::map<std::string, std::string> without =
      files_of(three, summarize(run_experiment(three, {.threads = 1, .progress = {}})));
  std::size_t compared = 0;
  for (const auto& [name, content] : without) {
    if (name == "summary.json" || name == "scenario.toml" || name == "benchmark.svg") continue;
    ASSERT_TRUE(with.contains(name)) << name;
    EXPECT_EQ(with.at(name), content) << name;
    ++compared;
  }
  EXPECT_EQ(compared, 6u + 5u + 4u);
}

// A scenario holds each kind's parameters as the kind's own struct, opaque to experiment/: a copy
// of the scenario holds a copy of them, and the struct is reached only as what it is.
TEST(Registry, AScenarioCopiesItsSensorsParametersAndKnowsTheirStruct) {
  const Scenario original = parse_scenario(four_toml, "four.toml", four_sensors());
  Scenario copy = original;
  lidar_of(copy).scans_per_step = 7;
  copy.params<RangeFinderParams>("rangefinder").shots_per_step = 11;
  EXPECT_EQ(lidar_of(original).scans_per_step, 2u);
  EXPECT_EQ(original.params<RangeFinderParams>("rangefinder").shots_per_step, 9u);
  EXPECT_EQ(copy.configure("rangefinder")->items_per_step(), 11u);
  EXPECT_EQ(original.configure("rangefinder")->items_per_step(), 9u);
  EXPECT_THROW((void)copy.params<RangeFinderParams>("lidar"), std::bad_cast);
}

// A sensor's files begin with its kind's name and '_', which the result set turns into its
// instance's: a kind that writes another's names is a bug, refused before any file is written.
TEST(Registry, AKindsFilesMustCarryItsName) {
  sensor::KindInfo twin = rangefinder::sensor_kind()->info();
  twin.name = "twin";
  twin.stream_key = 4;
  SensorRegistry registry = four_sensors();
  registry.add(std::make_shared<Relabelled>(twin, false));
  Scenario s = parse_scenario(four_toml, "four.toml", registry);
  s.experiment.sensors = {"twin"};
  const ExperimentSummary summary = summarize(run_experiment(s, {.threads = 1, .progress = {}}));
  try {
    (void)result_files(s, summary);
    ADD_FAILURE() << "accepted a twin's file named rangefinder_*";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor kind 'twin' wrote 'rangefinder_"),
              std::string::npos)
        << e.what();
  }
}

// A registry holds each name, stream key and scenario key once: a second sensor that would share
// one is refused, whatever it measures.
TEST(Registry, RefusesASensorThatSharesANameAStreamOrAKey) {
  const sensor::KindInfo info = rangefinder::sensor_kind()->info();
  sensor::KindInfo renamed = info;
  renamed.name = "twin";
  renamed.stream_key = 4;
  sensor::KindInfo same_stream = info;
  same_stream.name = "other";
  SensorRegistry registry = four_sensors();
  EXPECT_THROW(registry.add(rangefinder::sensor_kind()), InternalError);  // the name
  EXPECT_THROW(registry.add(std::make_shared<Relabelled>(renamed, true)),
               InternalError);  // rangefinder.* keys
  EXPECT_THROW(registry.add(std::make_shared<Relabelled>(same_stream, false)),
               InternalError);  // stream key 3
  EXPECT_EQ(registry.names(),
            (std::vector<std::string>{"radar", "lidar", "camera", "rangefinder"}));
  // What it adds to the standard registry, named by the same list.
  EXPECT_EQ(standard_registry().names(), (std::vector<std::string>{"radar", "lidar", "camera"}));
}

}  // namespace
}  // namespace fogradar::experiment
