#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/core/units.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/propagation/water_film.hpp"
#include "fogradar/radar/outputs.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/stats/format.hpp"
#include "radar_sensor.hpp"

namespace fogradar::radar {
namespace {

// "1 active layer", "3 layers".
std::string counted(std::size_t count, std::string_view noun) {
  return std::to_string(count) + " " + std::string(noun) + (count == 1 ? "" : "s");
}

class Report : public RadarReport {
 public:
  Report(std::shared_ptr<const RadarSensor> sensor,
         std::shared_ptr<const std::vector<StepResult>> steps, RadarSummary summary)
      : sensor_(std::move(sensor)),
        steps_(std::move(steps)),
        summary_(std::move(summary)),
        table_(radar::step_table(summary_)) {}

  const RadarSummary& summary() const override { return summary_; }
  const std::vector<StepResult>& steps() const override { return *steps_; }
  const RadarChain& chain() const override { return sensor_->chain(); }
  const Scene& scene() const override { return sensor_->scene(); }
  const propagation::Chamber& chamber() const override { return sensor_->chamber(); }
  double radome_two_way_loss_db() const override { return sensor_->radome_two_way_loss_db(); }
  double target_film_loss_db() const override { return sensor_->target_film_loss_db(); }

  sensor::Verdict verdict() const override {
    sensor::Verdict v{.layers_to_failure = summary_.sensor_limit_layers,
                      .criterion = sensor_limit_criterion_short,
                      .margin = {}};
    if (v.layers_to_failure) return v;
    if (summary_.attenuation_margin_db) {
      v.margin = "median target SNR " + stats::format_fixed(*summary_.attenuation_margin_db, 1) +
                 " dB above the CFAR threshold at " +
                 counted(summary_.steps.empty() ? 0 : summary_.steps.back().active_layers, "layer");
    } else if (!summary_.steps.empty() && summary_.steps.back().adc_clipped_fraction > 0.0) {
      v.margin = "unknown: the ADC clipped " +
                 percent_of_samples(summary_.steps.back().adc_clipped_fraction) +
                 " % of the samples at the last step";
    } else {
      v.margin = "no target detection at the last step";
    }
    return v;
  }

  const sensor::StepTable& step_table() const override { return table_; }
  std::string table() const override { return summary_table(summary_); }
  nlohmann::json json() const override { return summary_json(summary_); }

  std::vector<sensor::ResultFile> files() const override {
    return {
        {"radar_samples.csv", samples_csv(*steps_)},
        {"radar_detections.csv", detections_csv(*steps_)},
        {"radar_summary.csv", table_.csv()},
        {"radar_summary.json", json().dump(2) + '\n'},
        {"radar_rcs_boxplot.svg", rcs_boxplot_svg(sensor_->params(), sensor_->context(), summary_)},
        {"radar_origins.svg", origins_svg(sensor_->params(), sensor_->context(), summary_)}};
  }

  // The median target RCS as a linear power ratio to clear weather: 10^((m_k - m_0) / 10); 0 at a
  // step without target detections.
  sensor::Curve curve() const override {
    sensor::Curve c{.metric = "RCS",
                    .active_layers = {},
                    .relative_value = {},
                    .limit = summary_.sensor_limit_layers};
    const double clear = summary_.steps.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                : summary_.steps.front().rcs.median;
    for (const StepSummary& s : summary_.steps) {
      c.active_layers.push_back(static_cast<double>(s.active_layers));
      const bool known = s.rcs.n > 0 && std::isfinite(clear);
      c.relative_value.push_back(known ? std::pow(10.0, (s.rcs.median - clear) / 10.0) : 0.0);
    }
    return c;
  }

  // ADC clipping in any frame: the fraction of all the run's samples with a clipped rail (sums of
  // integers over every measurement), since a clipped echo reads low.
  std::vector<std::string> warnings() const override {
    std::size_t samples = 0, clipped = 0;
    for (const StepResult& step : *steps_) {
      for (const MeasurementRecord& r : step.records) {
        samples += r.samples;
        clipped += r.clipped_samples;
      }
    }
    std::vector<std::string> found;
    if (clipped > 0 && samples > 0) {
      std::string w = "the radar's ADC clipped ";
      w += percent_of_samples(static_cast<double>(clipped) / static_cast<double>(samples));
      w += " % of the samples (radar.adc_full_scale_dbm = ";
      w += stats::format_number(sensor_->params().radar.adc_full_scale_dbm, 0);
      w += "): its RCS reads low";
      found.push_back(std::move(w));
    }
    if (summary_.velocity_fold) found.push_back(velocity_fold_text(*summary_.velocity_fold));
    return found;
  }

 private:
  std::shared_ptr<const RadarSensor> sensor_;
  std::shared_ptr<const std::vector<StepResult>> steps_;
  RadarSummary summary_;
  sensor::StepTable table_;
};

}  // namespace

class RadarWorker : public sensor::Worker {
 public:
  explicit RadarWorker(const RadarRun& run) : run_(run) {}

  void measure(std::size_t step, std::size_t index, RandomStream& stream, sensor::RawSink* raw,
               const StopToken& stop) override;

 private:
  const RadarRun& run_;
  MeasurementWorkspace workspace_;
  Measurement measurement_;
  std::vector<double> power_;          // |X|^2 of a map asked for as raw data
  std::vector<double> rows_;           // detection rows asked for as raw data
  std::vector<std::uint8_t> origins_;  // the origin map asked for as raw data
  std::vector<std::int16_t> layers_;   // and its fog layers
};

RadarSensor::RadarSensor(const SensorParams& params, const sensor::Context& context,
                         const propagation::SegelsteinTable& water, const StopToken& stop)
    : params_(params),
      context_(context),
      scene_(make_scene(params.target, context.target, context.room,
                        params.clutter_scatterers_per_bin, params.radar.centre_frequency_hz)),
      chamber_(context.chamber, params.radar.centre_frequency_hz, water),
      chain_(params.radar, FftPlanner::shipped_wisdom, stop) {
  chain_.check_compatible(scene_, chamber_);
  for (std::size_t k = 0; k < context.steps; ++k) active_.push_back(context.active(k));
  // The films take the water index of the fog next to them, at the sweep centre: its model and
  // temperature.
  const double wavelength_m = derive(params.radar).wavelength_m;
  const Radome& radome = params.radar.radome;
  const std::complex<double> radome_index = propagation::refractive_index_from_permittivity(
      {radome.relative_permittivity, radome.relative_permittivity * radome.loss_tangent});
  radome_two_way_loss_db_ = propagation::film_two_way_loss_db(
      radome.water_film_m, chamber_.layer(0).optics.refractive_index, radome_index,
      radome.thickness_m, wavelength_m);
  target_film_loss_db_ = propagation::conductor_film_loss_db(
      context.target.water_film_m,
      chamber_.layer(chamber_.layer_count() - 1).optics.refractive_index, wavelength_m);
  scene_.radome_two_way_transmittance = db_to_power_ratio(-radome_two_way_loss_db_);
  scene_.target_film_reflectance = db_to_power_ratio(-target_film_loss_db_);
}

std::unique_ptr<sensor::SensorRun> RadarSensor::begin_run() const {
  return std::make_unique<RadarRun>(shared_from_this());
}

double RadarSensor::cfar_threshold_db() const {
  return power_ratio_to_db(chain_.cfar().threshold_factor());
}

double RadarSensor::expected_false_alarm_cells_per_frame() const {
  return chain_.cfar().config().false_alarm_probability *
         static_cast<double>(params_.radar.chirps_per_frame * params_.radar.samples_per_chirp);
}

RadarRun::RadarRun(std::shared_ptr<const RadarSensor> sensor)
    : sensor_(std::move(sensor)),
      steps_(std::make_shared<std::vector<StepResult>>(sensor_->context().steps)) {
  const propagation::Chamber& chamber = sensor_->chamber();
  for (std::size_t k = 0; k < steps_->size(); ++k) {
    StepResult& step = (*steps_)[k];
    step.active_layers = k;
    step.two_way_attenuation_db =
        chamber.two_way_attenuation_db(chamber.target_range_m(), sensor_->active(k));
    step.radome_two_way_loss_db = sensor_->radome_two_way_loss_db();
    step.target_film_loss_db = sensor_->target_film_loss_db();
    step.records.resize(sensor_->params().measurements_per_step);
  }
}

std::unique_ptr<sensor::Worker> RadarRun::make_worker() const {
  return std::make_unique<RadarWorker>(*this);
}

void RadarWorker::measure(std::size_t step, std::size_t index, RandomStream& stream,
                          sensor::RawSink* raw, const StopToken& stop) {
  FrameTaps taps;
  if (raw != nullptr && raw->wants(raw_beat)) {
    taps.beat = [raw](std::span<const std::complex<double>> beat) { raw->write(raw_beat, beat); };
  }
  if (raw != nullptr && raw->wants(raw_signal)) {
    taps.signal = [raw](std::span<const std::complex<double>> s) { raw->write(raw_signal, s); };
  }
  if (raw != nullptr && raw->wants(raw_noise)) {
    taps.noise = [raw](std::span<const std::complex<double>> n) { raw->write(raw_noise, n); };
  }
  if (raw != nullptr && raw->wants(raw_range_doppler)) {
    taps.range_doppler = [this, raw](std::span<const std::complex<double>> map) {
      power_.resize(map.size());
      squared_magnitudes(map, power_);
      raw->write(raw_range_doppler, std::span<const double>(power_));
    };
  }
  const RadarSensor& sensor = *run_.sensor_;
  // Made by the first item, which can stop while it is made.
  if (workspace_.frame.empty()) workspace_ = sensor.chain().make_workspace(stop);
  sensor.chain().measure(sensor.scene(), sensor.chamber(), sensor.active(step), stream, workspace_,
                         measurement_, taps, stop);
  MeasurementRecord& record = (*run_.steps_)[step].records[index];
  record = record_of(measurement_, sensor.chamber().target_range_m(),
                     sensor.params().radar.association_gate_m);
  if (raw != nullptr && raw->wants(raw_detections)) {
    rows_.clear();
    for (const DetectionRecord& d : record.detections) {
      rows_.insert(rows_.end(),
                   {d.range_m, d.velocity_m_per_s, watt_to_dbm(d.received_power_w), d.snr_db,
                    d.rcs_dbsm, static_cast<double>(d.origin), d.in_gate ? 1.0 : 0.0,
                    d.associated ? 1.0 : 0.0, static_cast<double>(d.range_cell),
                    static_cast<double>(d.doppler_cell), static_cast<double>(d.layer)});
    }
    raw->append_rows(raw_detections, rows_);
  }
  const bool origins = raw != nullptr && raw->wants(raw_origins);
  const bool layers = raw != nullptr && raw->wants(raw_origin_layers);
  if (origins || layers) {
    origins_.resize(workspace_.frame.size());
    layers_.resize(layers ? workspace_.frame.size() : 0);
    sensor.chain().origin_classifier().origin_map(
        workspace_.tones, measurement_.synthesis.clipped_samples > 0, origins_, layers_);
    if (origins) raw->write(raw_origins, std::span<const std::uint8_t>(origins_));
    if (layers) raw->write(raw_origin_layers, std::span<const std::int16_t>(layers_));
  }
}

std::unique_ptr<const sensor::SensorSummary> RadarRun::summarize() const {
  RadarSummary summary = radar::summarize(*steps_, sensor_->cfar_threshold_db(),
                                          sensor_->expected_false_alarm_cells_per_frame());
  summary.velocity_fold =
      velocity_fold(sensor_->context().target.radial_velocity_m_per_s, sensor_->chain().derived());
  return std::make_unique<Report>(sensor_, steps_, std::move(summary));
}

}  // namespace fogradar::radar
