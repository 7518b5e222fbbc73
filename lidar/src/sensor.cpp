#include "fogradar/lidar/sensor.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "fogradar/lidar/outputs.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::lidar {
namespace {

const char* const file_names[] = {"lidar_echoes.csv", "lidar_summary.csv", "lidar_summary.json",
                                  "lidar_intensity_boxplot.svg", "lidar_scans.svg"};

std::string counted_layers(std::size_t count) {
  return std::to_string(count) + (count == 1 ? " layer" : " layers");
}

class Report : public LidarReport {
 public:
  Report(std::shared_ptr<const Lidar> lidar,
         std::shared_ptr<const std::vector<LidarStepResult>> steps)
      : lidar_(std::move(lidar)),
        steps_(std::move(steps)),
        summary_(summarize(lidar_->params(), *steps_)) {}

  const Lidar& lidar() const override { return *lidar_; }
  const std::vector<LidarStepResult>& steps() const override { return *steps_; }
  const LidarSummary& summary() const override { return summary_; }

  sensor::Verdict verdict() const override {
    sensor::Verdict v{.layers_to_failure = summary_.sensor_limit_layers,
                      .criterion = lidar_sensor_limit_criterion,
                      .margin = {}};
    if (!v.layers_to_failure && !summary_.steps.empty()) {
      const LidarStepSummary& last = summary_.steps.back();
      v.margin = "target told from fog in " +
                 stats::format_fixed(100.0 * last.target_told_rate, 1) + " % of the scans at " +
                 counted_layers(last.active_layers) + " (fails below 50 %)";
    }
    return v;
  }

  std::string table() const override { return lidar_summary_table(summary_); }
  nlohmann::json json() const override { return lidar_summary_json(*lidar_, summary_); }

  std::vector<sensor::ResultFile> files() const override {
    return {{"lidar_echoes.csv", lidar_echoes_csv(*lidar_, *steps_)},
            {"lidar_summary.csv", lidar_summary_csv(summary_)},
            {"lidar_summary.json", json().dump(2) + '\n'},
            {"lidar_intensity_boxplot.svg", lidar_intensity_boxplot_svg(*lidar_, summary_)},
            {"lidar_scans.svg", lidar_scans_svg(*lidar_, *steps_)}};
  }

  // The median target intensity (a missing target counted as 0, as Fig. 6) over clear weather.
  sensor::Curve curve() const override {
    sensor::Curve c{.metric = "intensity",
                    .active_layers = {},
                    .relative_value = {},
                    .limit = summary_.sensor_limit_layers};
    const double clear =
        summary_.steps.empty() ? 0.0 : summary_.steps.front().target_intensity.median;
    for (const LidarStepSummary& s : summary_.steps) {
      c.active_layers.push_back(static_cast<double>(s.active_layers));
      c.relative_value.push_back(
          clear > 0.0 && s.target_intensity.n > 0 ? s.target_intensity.median / clear : 0.0);
    }
    return c;
  }

 private:
  std::shared_ptr<const Lidar> lidar_;
  std::shared_ptr<const std::vector<LidarStepResult>> steps_;
  LidarSummary summary_;
};

class Run : public sensor::SensorRun {
 public:
  Run(const LidarParams& params, const sensor::Context& context,
      const propagation::SegelsteinTable& water)
      : context_(context),
        lidar_(std::make_shared<const Lidar>(params, context.chamber, water)),
        steps_(std::make_shared<std::vector<LidarStepResult>>(context.steps)),
        fog_(context.steps) {
    for (std::size_t k = 0; k < context.steps; ++k) {
      active_.push_back(context.active(k));
      (*steps_)[k].active_layers = k;
      (*steps_)[k].scans.resize(params.scans_per_step);
    }
  }

  std::size_t items_per_step() const override { return lidar_->params().scans_per_step; }

  // The step's scan-to-scan fog series, from the stream index the lidar reserves for it.
  void prepare_step(std::size_t step) override {
    fog_[step] = lidar_->fog_fluctuation(
        sensor_stream(context_.seed, stream_key, step, lidar_->fog_series_index()));
  }

  std::unique_ptr<sensor::Worker> make_worker() const override {
    return std::make_unique<ScanWorker>(*this);
  }

  std::unique_ptr<const sensor::SensorSummary> summarize() const override {
    return std::make_unique<Report>(lidar_, steps_);
  }

 private:
  class ScanWorker : public sensor::Worker {
   public:
    explicit ScanWorker(const Run& run) : run_(run) {}
    void measure(std::size_t step, std::size_t index, RandomStream& stream,
                 sensor::RawSink*) override {
      (*run_.steps_)[step].scans[index] =
          run_.lidar_->measure(run_.active_[step], run_.fog_[step].scan(index), stream);
    }

   private:
    const Run& run_;
  };

  sensor::Context context_;
  std::shared_ptr<const Lidar> lidar_;
  std::vector<propagation::ActiveLayers> active_;
  std::shared_ptr<std::vector<LidarStepResult>> steps_;
  std::vector<FogFluctuationSeries> fog_;
};

class Type : public sensor::SensorType {
 public:
  std::string_view name() const override { return "lidar"; }
  std::uint64_t stream_key() const override { return lidar::stream_key; }
  std::string_view item_noun() const override { return "lidar scans"; }
  std::string_view curve_caption() const override {
    return "median target intensity (a missing target counted as 0)";
  }
  std::any default_params() const override { return LidarParams{}; }
  KeyTable<std::any> keys() const override { return sensor::erase_keys(lidar_keys()); }

  void validate(const std::any& params, const sensor::Context&) const override {
    sensor::params_of<LidarParams>(params).validate();
  }

  std::size_t items_per_step(const std::any& params, const sensor::Context&) const override {
    return sensor::params_of<LidarParams>(params).scans_per_step;
  }

  sensor::MemoryPart memory(const std::any& params, const sensor::Context& context,
                            unsigned threads) const override {
    const LidarParams& p = sensor::params_of<LidarParams>(params);
    std::ostringstream detail;
    detail.precision(6);
    detail << "lidar.scans_per_step = " << p.scans_per_step << " of " << p.beam_count()
           << " beams: lidar.field_of_view_deg = " << p.field_of_view_deg
           << " / lidar.angular_step_deg = " << p.angular_step_deg;
    return {.bytes = lidar_memory_bytes(p, context.steps, threads),
            .detail = detail.str(),
            .key = "lidar.scans_per_step"};
  }

  std::vector<sensor::RawKind> raw_kinds(const std::any&, const sensor::Context&) const override {
    return {};
  }

  bool owns_file_name(std::string_view file_name) const override {
    return std::find(std::begin(file_names), std::end(file_names), file_name) !=
           std::end(file_names);
  }

  // The layer's extinction alpha and backscatter beta_pi at the lidar's wavelength (Mie, resolved
  // by the Lidar itself), their ratio, and the two-way Beer-Lambert loss 10 log10(e) 2 alpha L.
  sensor::FogReport fog_report(const std::any& params, const propagation::FogSpec& spec,
                               double layer_length_m,
                               const propagation::SegelsteinTable& water) const override {
    const LidarParams& p = sensor::params_of<LidarParams>(params);
    propagation::ChamberSpec chamber;
    chamber.layers = {propagation::FogLayerSpec{.length_m = layer_length_m, .fog = spec}};
    const Lidar lidar(p, chamber, water);
    const double alpha = lidar.layer_extinction_per_m(0);
    const double beta = lidar.layer_backscatter_per_m_sr(0);
    const double loss_db = 10.0 * std::log10(std::exp(1.0)) * 2.0 * alpha * layer_length_m;
    const double ratio = alpha / beta;
    std::ostringstream line;
    line << "  lidar (" << p.wavelength_m * 1e9 << " nm)         extinction " << alpha
         << " 1/m, backscatter beta_pi " << beta << " 1/(m sr), 2-way loss " << loss_db << " dB";
    return {.json = {{"wavelength_m", p.wavelength_m},
                     {"extinction_per_m", alpha},
                     {"backscatter_per_m_sr", beta},
                     {"lidar_ratio_sr",
                      std::isfinite(ratio) ? nlohmann::json(ratio) : nlohmann::json(nullptr)},
                     {"two_way_loss_db_per_layer", loss_db}},
            .line = line.str()};
  }

  std::unique_ptr<sensor::SensorRun> start(
      const std::any& params, const sensor::Context& context,
      const propagation::SegelsteinTable& water) const override {
    return std::make_unique<Run>(sensor::params_of<LidarParams>(params), context, water);
  }
};

}  // namespace

std::shared_ptr<const sensor::SensorType> sensor_type() { return std::make_shared<Type>(); }

}  // namespace fogradar::lidar
