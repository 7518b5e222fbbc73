// The sensor interface's proof: a fourth sensor declared in this file alone,
// an ideal optical range finder, is registered beside the study's three and runs through
// run_experiment on the same chamber with them; it gets its keys read, refused and written back,
// its table, files, benchmark curve and limit, and the three others' files do not change by a byte.
// Nothing in experiment/ or cli/ knows it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/registry.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/stats/format.hpp"
#include "sensors.hpp"

namespace fogradar::experiment {
namespace {

// An ideal range finder: a pulse at the fog's 550 nm extinction, its echo from the target detected
// when the two-way Beer-Lambert transmittance through the active layers, exp(-2 sum beta_i f_i), is
// at least min_transmittance; each detection reads the target range with Gaussian noise.
struct RangeFinderParams {
  std::size_t shots_per_step = 5;
  double range_noise_m = 0.02;
  double min_transmittance = 0.1;
};

KeyTable<RangeFinderParams> range_finder_keys() {
  KeyTable<RangeFinderParams> keys("rangefinder.");
  keys.integer("shots_per_step", FOGRADAR_KEY_FIELD(shots_per_step), 1, 1000, "shots per step");
  keys.number("range_noise_m", FOGRADAR_KEY_FIELD(range_noise_m), closed(0.0, 1.0),
              "standard deviation of a range reading");
  keys.number("min_transmittance", FOGRADAR_KEY_FIELD(min_transmittance), open_closed(0.0, 1.0),
              "the weakest two-way transmittance that still returns an echo");
  return keys;
}

struct Shot {
  bool detected = false;
  double range_m = 0.0;
};

struct StepShots {
  double transmittance = 1.0;
  std::vector<Shot> shots;
};

class RangeFinderSummary : public sensor::SensorSummary {
 public:
  explicit RangeFinderSummary(std::vector<StepShots> steps)
      : steps_(std::move(steps)), table_(steps_.size()) {
    for (std::size_t k = 0; k < steps_.size(); ++k) {
      if (rate(k) < 0.5) {
        limit_ = k;
        break;
      }
    }
    // Its per-step columns, declared once: the CSV, the JSON's steps and the printed table.
    std::vector<std::int64_t> layers;
    std::vector<double> rates, transmittances;
    for (std::size_t k = 0; k < steps_.size(); ++k) {
      layers.push_back(static_cast<std::int64_t>(k));
      rates.push_back(rate(k));
      transmittances.push_back(steps_[k].transmittance);
    }
    table_.integer("active_layers", "", layers);
    table_.number("echo_rate", "", rates).csv_digits(17);
    table_.number("transmittance", "", transmittances).in_csv(false);
    table_.print("active_layers", {.heads = {"layers"}, .width = 6});
    table_.print("echo_rate", {.heads = {"rate"}, .width = 6, .general = true});
    table_.print("transmittance", {.heads = {"transmittance"},
                                   .width = 14,
                                   .general = true,
                                   .precision = 6,
                                   .signless_zero = true});
  }
  double rate(std::size_t k) const {
    std::size_t hits = 0;
    for (const Shot& s : steps_[k].shots) hits += s.detected ? 1 : 0;
    return static_cast<double>(hits) / static_cast<double>(steps_[k].shots.size());
  }
  sensor::Verdict verdict() const override {
    return {.layers_to_failure = limit_,
            .criterion = "fewer than 50 % of the shots return an echo",
            .margin = limit_ ? "" : "echoes in every step"};
  }
  const sensor::StepTable& step_table() const override { return table_; }
  std::string table() const override { return table_.printed(); }
  nlohmann::json json() const override { return {{"steps", table_.json()}}; }
  std::vector<sensor::ResultFile> files() const override {
    std::string csv = "active_layers,shot,detected,range_m\n";
    for (std::size_t k = 0; k < steps_.size(); ++k) {
      for (std::size_t i = 0; i < steps_[k].shots.size(); ++i) {
        const Shot& s = steps_[k].shots[i];
        csv += std::to_string(k) + "," + std::to_string(i) + "," + (s.detected ? "1," : "0,") +
               (s.detected ? stats::format_number(s.range_m, 0) : "") + "\n";
      }
    }
    return {{"rangefinder_shots.csv", csv},
            {"rangefinder_summary.csv", table_.csv()},
            {"rangefinder_summary.json", json().dump(2) + "\n"}};
  }
  sensor::Curve curve() const override {
    sensor::Curve c{
        .metric = "echo rate", .active_layers = {}, .relative_value = {}, .limit = limit_};
    for (std::size_t k = 0; k < steps_.size(); ++k) {
      c.active_layers.push_back(static_cast<double>(k));
      c.relative_value.push_back(rate(k));
    }
    return c;
  }

 private:
  std::vector<StepShots> steps_;
  std::optional<std::size_t> limit_;
  sensor::StepTable table_;
};

// What every run of the range finder shares: its parameters and each layer's extinction.
class RangeFinder : public sensor::Sensor, public std::enable_shared_from_this<RangeFinder> {
 public:
  RangeFinder(const RangeFinderParams& p, const sensor::Context& c,
              const propagation::SegelsteinTable& water)
      : params(p), context(c) {
    for (const propagation::FogLayerSpec& layer : context.chamber.layers) {
      extinction_per_m.push_back(propagation::Fog(layer.fog, water).optical_extinction_per_km() *
                                 1e-3);
    }
  }
  std::unique_ptr<sensor::SensorRun> begin_run() const override;

  RangeFinderParams params;
  sensor::Context context;
  std::vector<double> extinction_per_m;
};

class RangeFinderRun : public sensor::SensorRun {
 public:
  explicit RangeFinderRun(std::shared_ptr<const RangeFinder> sensor)
      : sensor_(std::move(sensor)),
        steps_(std::make_shared<std::vector<StepShots>>(sensor_->context.steps)) {}
  void prepare_step(std::size_t step) override {
    const sensor::Context& context = sensor_->context;
    const propagation::ActiveLayers active = context.active(step);
    double optical_depth = 0.0;
    for (std::size_t i = 0; i < active.size(); ++i) {
      if (active[i])
        optical_depth += sensor_->extinction_per_m[i] * context.chamber.layers[i].length_m;
    }
    (*steps_)[step].transmittance = std::exp(-2.0 * optical_depth);
    (*steps_)[step].shots.resize(sensor_->params.shots_per_step);
  }
  std::unique_ptr<sensor::Worker> make_worker() const override {
    return std::make_unique<ShotWorker>(*this);
  }
  std::unique_ptr<const sensor::SensorSummary> summarize() const override {
    return std::make_unique<RangeFinderSummary>(*steps_);
  }

 private:
  class ShotWorker : public sensor::Worker {
   public:
    explicit ShotWorker(const RangeFinderRun& run) : run_(run) {}
    void measure(std::size_t step, std::size_t index, RandomStream& stream, sensor::RawSink*,
                 const StopToken&) override {
      const RangeFinder& sensor = *run_.sensor_;
      StepShots& s = (*run_.steps_)[step];
      s.shots[index] = {.detected = s.transmittance >= sensor.params.min_transmittance,
                        .range_m = sensor.context.chamber.target_range_m() +
                                   sensor.params.range_noise_m * stream.normal()};
    }

   private:
    const RangeFinderRun& run_;
  };

  std::shared_ptr<const RangeFinder> sensor_;
  std::shared_ptr<std::vector<StepShots>> steps_;  // the workers store their shots by index
};

std::unique_ptr<sensor::SensorRun> RangeFinder::begin_run() const {
  return std::make_unique<RangeFinderRun>(shared_from_this());
}

// The range finder for one scenario: its parameters, whose keys hold allowed values, and the
// chamber.
class ConfiguredRangeFinder : public sensor::ConfiguredSensor {
 public:
  ConfiguredRangeFinder(const RangeFinderParams& p, const sensor::Context& c)
      : params_(p), context_(c) {}
  std::size_t items_per_step() const override { return params_.shots_per_step; }
  sensor::Cost cost() const override {
    return {.item = {.item_seconds = 1e-7,
                     .detail = "one shot",
                     .key = "rangefinder.shots_per_step",
                     .items_key = "rangefinder.shots_per_step"},
            .setup = {.make_seconds = 0.0,
                      .run_seconds = 0.0,
                      .report_seconds = 0.0,
                      .detail = "nothing to make",
                      .key = "rangefinder.shots_per_step"}};
  }
  sensor::MemoryPart memory(unsigned) const override {
    return {.bytes = context_.steps * params_.shots_per_step * sizeof(Shot),
            .detail = "rangefinder.shots_per_step",
            .key = "rangefinder.shots_per_step"};
  }
  std::vector<sensor::RawKind> raw_kinds() const override { return {}; }
  sensor::FogReport fog_report(const propagation::FogSpec& fog, double length_m,
                               const propagation::SegelsteinTable& water) const override {
    const double t =
        std::exp(-2.0 * propagation::Fog(fog, water).optical_extinction_per_km() * 1e-3 * length_m);
    return {.json = {{"two_way_transmittance_per_layer", t}}, .line = "  rangefinder"};
  }
  std::shared_ptr<const sensor::Sensor> make(const propagation::SegelsteinTable& water,
                                             const StopToken&) const override {
    return std::make_shared<RangeFinder>(params_, context_, water);
  }

 private:
  RangeFinderParams params_;
  sensor::Context context_;
};

sensor::KindInfo range_finder_info() {
  return {.name = "rangefinder",
          .stream_key = 3,
          .band = sensor::Band::optical,
          .item_noun = "range finder shots",
          .curve_caption = "echo rate"};
}

class RangeFinderKind : public sensor::Kind<RangeFinderParams> {
 public:
  explicit RangeFinderKind(sensor::KindInfo info = range_finder_info(),
                           KeyTable<RangeFinderParams> keys = range_finder_keys())
      : sensor::Kind<RangeFinderParams>(std::move(info), std::move(keys)) {}
  bool owns_file_name(std::string_view name) const override {
    return name == "rangefinder_shots.csv" || name == "rangefinder_summary.csv" ||
           name == "rangefinder_summary.json";
  }

 protected:
  std::shared_ptr<const sensor::ConfiguredSensor> configured(
      const RangeFinderParams& params, const sensor::Context& context) const override {
    return std::make_shared<ConfiguredRangeFinder>(params, context);
  }
};

SensorRegistry four_sensors() {
  SensorRegistry registry = standard_registry();
  registry.add(std::make_shared<RangeFinderKind>());
  return registry;
}

// The study's three sensors, small, and the range finder with 9 shots a step needing a two-way
// transmittance of 0.1.
constexpr const char* four_toml = R"(
[radar]
chirps_per_frame = 16
[experiment]
sensors = ["radar", "lidar", "camera", "rangefinder"]
measurements_per_step = 3
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

TEST(Registry, AFourthSensorRunsBesideTheStudysThreeFromThisFileAlone) {
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
  for (const auto& [name, content] : files) EXPECT_TRUE(result_file_names(s)(name)) << name;

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
  EXPECT_EQ(compared, 5u + 5u + 4u);
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

// A registry holds each name, stream key and scenario key once: a second sensor that would share
// one is refused, whatever it measures.
TEST(Registry, RefusesASensorThatSharesANameAStreamOrAKey) {
  sensor::KindInfo renamed = range_finder_info();
  renamed.name = "twin";
  renamed.stream_key = 4;
  sensor::KindInfo same_stream = range_finder_info();
  same_stream.name = "other";
  SensorRegistry registry = four_sensors();
  EXPECT_THROW(registry.add(std::make_shared<RangeFinderKind>()), InternalError);  // the name
  EXPECT_THROW(registry.add(std::make_shared<RangeFinderKind>(renamed)),
               InternalError);  // rangefinder.* keys
  EXPECT_THROW(
      registry.add(std::make_shared<RangeFinderKind>(same_stream, KeyTable<RangeFinderParams>())),
      InternalError);  // stream key 3
  EXPECT_EQ(registry.names(),
            (std::vector<std::string>{"radar", "lidar", "camera", "rangefinder"}));
}

}  // namespace
}  // namespace fogradar::experiment
