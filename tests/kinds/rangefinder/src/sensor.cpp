#include "fogradar/rangefinder/sensor.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fogradar/core/keys.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::rangefinder {
namespace {

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
  RangeFinderKind() : sensor::Kind<RangeFinderParams>(range_finder_info(), range_finder_keys()) {}

 protected:
  std::shared_ptr<const sensor::ConfiguredSensor> configured(
      const RangeFinderParams& params, const sensor::Context& context) const override {
    return std::make_shared<ConfiguredRangeFinder>(params, context);
  }
};

}  // namespace

std::shared_ptr<const sensor::SensorKind> sensor_kind() {
  return std::make_shared<RangeFinderKind>();
}

}  // namespace fogradar::rangefinder
