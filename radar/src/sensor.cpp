#include "fogradar/radar/sensor.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/propagation/water_film.hpp"
#include "fogradar/radar/cfar_design.hpp"
#include "fogradar/radar/outputs.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/radar/window.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::radar {
namespace {

constexpr std::size_t complex_bytes = sizeof(std::complex<double>);
constexpr std::size_t double_bytes = sizeof(double);
// Doppler transforms run on blocks of at most this many columns (fft.cpp, ColumnBlockFft).
constexpr std::size_t doppler_block_columns = 32;
// Objects whose rows the estimator interpolates in one pass (estimation.cpp).
constexpr std::size_t interpolation_batch = 4;

// The CPU time of a frame, measured by bench/estimate_calibration (docs/scenario.md, "Time limit"):
// synthesis, the two transforms and the CFAR cost about cells x log2(cells) together (the FFTs'
// n log n, and a map that outgrows the caches); each object's peak search (the scene's few plus
// about P_fa x cells false alarms) sums over the whole map, so a frame grows as cells squared once
// P_fa x cells passes a few.
constexpr double frame_seconds_per_cell_log2_cell = 2.16e-10;
constexpr double frame_seconds_per_cell_and_object = 3.22e-10;
// Each static tone (a scene path, a fog clutter scatterer) is synthesised once per frame over one
// chirp's samples (synthesis.cpp), so the fog's clutter adds per tone and sample.
constexpr double frame_seconds_per_tone_sample = 3.38e-10;

// Wide CFAR windows (bench/estimate_calibration does not reach them; measured with profiles of
// 4096-65536 cells and n = 1000-32767, GO and OS, Blackman-Harris): CA, GO and SO add the N
// reference cells of each of a row's 2 (guard + n) edge cells one by one (cfar_kernels.cpp,
// edge_halves), 21 s for 10 rows of 4.3e9 additions; OS moves up to N sorted values per cell as its
// window slides (a memmove per cell), ~0.05 s per row of 65536 cells with N = 65534.
constexpr double frame_seconds_per_edge_reference = 4.9e-10;
constexpr double frame_seconds_per_sorted_reference = 1.3e-11;

// The fog clutter's tones of a frame, averaged over the steps: clutter_scatterers_per_bin in every
// range bin of every active layer that holds water (scene.cpp, add_fog_clutter).
double mean_clutter_tones(const SensorParams& p, const sensor::Context& context) {
  const double bin_m = derive(p.radar).range_bin_m;
  const auto wet = [](const propagation::FogSpec& fog) {
    if (const auto* lwc = std::get_if<propagation::LiquidWaterContent>(&fog.density))
      return lwc->g_per_m3 > 0.0;
    if (const auto* beta = std::get_if<propagation::OpticalExtinction>(&fog.density))
      return beta->per_km > 0.0;
    return true;
  };
  double tones = 0.0;
  for (std::size_t k = 0; k < context.steps; ++k) {
    const propagation::ActiveLayers active = context.active(k);
    for (std::size_t i = 0; i < context.chamber.layers.size(); ++i) {
      const propagation::FogLayerSpec& layer = context.chamber.layers[i];
      if (!active[i] || !wet(layer.fog)) continue;
      tones += std::ceil(layer.length_m / bin_m) * p.clutter_scatterers_per_bin;
    }
  }
  return tones / static_cast<double>(std::max<std::size_t>(context.steps, 1));
}
constexpr double scene_objects_per_frame = 3.0;
// The rest of a run (setup_cost), CPU seconds measured by bench/estimate_calibration: a chain's
// fixed part (its FFTW wisdom read, the scene) and its part per cell of the frame (windows, plans);
// a summary's part per measurement and per Hodges-Lehmann pair (n_k x n_0 per step); the result
// files' part per measurement (their CSV rows; the box plot and the JSON cost less than the rows).
constexpr double chain_seconds = 1.31e-3;
constexpr double chain_seconds_per_cell = 1.61e-9;
constexpr double summary_seconds_per_measurement = 4.5e-7;
constexpr double summary_seconds_per_pair = 6.4e-10;
constexpr double files_seconds_per_measurement = 7.8e-7;

double mib(std::size_t bytes) {
  return static_cast<double>(bytes) / static_cast<double>(std::size_t{1} << 20);
}

// "1 active layer", "3 layers".
std::string counted(std::size_t count, std::string_view noun) {
  return std::to_string(count) + " " + std::string(noun) + (count == 1 ? "" : "s");
}

const char* const file_names[] = {"radar_samples.csv", "radar_detections.csv", "radar_summary.csv",
                                  "radar_summary.json", "radar_rcs_boxplot.svg"};
// The radar's files as fogradar 0.1 named them: an earlier result set is still replaced whole.
const char* const earlier_file_names[] = {"samples.csv", "summary.csv", "rcs_boxplot.svg"};

class Report : public RadarReport {
 public:
  Report(const SensorParams& params, const sensor::Context& context,
         std::shared_ptr<const std::vector<StepResult>> steps, RadarSummary summary)
      : params_(params),
        context_(context),
        steps_(std::move(steps)),
        summary_(std::move(summary)) {}

  const RadarSummary& summary() const override { return summary_; }
  const std::vector<StepResult>& steps() const override { return *steps_; }

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

  std::string table() const override { return summary_table(summary_); }
  nlohmann::json json() const override { return summary_json(summary_); }
  std::string summary_csv() const override { return radar::summary_csv(summary_); }

  std::vector<sensor::ResultFile> files() const override {
    return {{"radar_samples.csv", samples_csv(*steps_)},
            {"radar_detections.csv", detections_csv(*steps_)},
            {"radar_summary.csv", summary_csv()},
            {"radar_summary.json", json().dump(2) + '\n'},
            {"radar_rcs_boxplot.svg", rcs_boxplot_svg(params_, context_, summary_)}};
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
      w += stats::format_number(params_.radar.adc_full_scale_dbm, 0);
      w += "): its RCS reads low";
      found.push_back(std::move(w));
    }
    if (summary_.velocity_fold) found.push_back(velocity_fold_text(*summary_.velocity_fold));
    return found;
  }

 private:
  SensorParams params_;
  sensor::Context context_;
  std::shared_ptr<const std::vector<StepResult>> steps_;
  RadarSummary summary_;
};

class Type : public sensor::SensorType {
 public:
  std::string_view name() const override { return "radar"; }
  std::uint64_t stream_key() const override { return radar::stream_key; }
  std::string_view item_noun() const override { return "radar measurements"; }
  std::string_view curve_caption() const override { return "median target RCS as a power ratio"; }
  std::any default_params() const override { return SensorParams{}; }
  const KeyTable<std::any>& keys() const override { return keys_; }

  void validate(const std::any& params, const sensor::Context& context) const override {
    keys_.check(params);
    const SensorParams& p = sensor::params_of<SensorParams>(params);
    // CFAR slides along range, one Doppler bin at a time.
    p.radar.cfar.validate_profile_length(p.radar.samples_per_chirp, "processing.cfar.");
    const Scene scene = make_scene(p.target, p.clutter_scatterers_per_bin);
    scene.validate();
    // Every echo's beat must lie inside [0, fs) with the 1 m margin RadarChain keeps
    // (docs/radar.md).
    const double target_range_m = context.chamber.target_range_m();
    double farthest_m = target_range_m;
    for (const ScatteringCentre& centre : scene.centres) {
      farthest_m = std::max(farthest_m, target_range_m + centre.range_offset_m);
    }
    const double limit_m = derive(p.radar).max_range_m - 1.0;
    if (farthest_m > limit_m) {
      std::ostringstream constraint;
      constraint.precision(10);
      constraint
          << "such that the target's farthest echo, chamber.sensor_gap_m + chamber.layer_count x "
             "chamber.layer_length_m + chamber.target_gap_m (+ the EVT's depth) = "
          << farthest_m
          << " m, lies within the unambiguous range minus 1 m, c x radar.sample_rate_hz x "
             "radar.chirp_duration_s / (2 x radar.sweep_bandwidth_hz) - 1 = "
          << limit_m << " m";
      throw_invalid("chamber.target_gap_m", context.chamber.target_gap_m, constraint.str());
    }
  }

  std::size_t items_per_step(const std::any&, const sensor::Context& context) const override {
    return context.measurements_per_step;
  }

  sensor::MemoryPart memory(const std::any& params, const sensor::Context& context,
                            unsigned threads) const override {
    const SensorParams& p = sensor::params_of<SensorParams>(params);
    const MemoryEstimate e = memory_estimate(p, context.steps * context.measurements_per_step);
    std::ostringstream detail;
    detail.precision(6);
    detail << "radar.samples_per_chirp = " << p.radar.samples_per_chirp
           << " x radar.chirps_per_frame = " << p.radar.chirps_per_frame << ": " << threads << " x "
           << mib(e.per_thread_bytes) << " MiB frame workspace; experiment.measurements_per_step = "
           << context.measurements_per_step << ": " << mib(e.records_bytes)
           << " MiB per-measurement records; " << mib(e.shared_bytes) << " MiB windows and plans";
    return {.bytes = threads * e.per_thread_bytes + e.shared_bytes + e.records_bytes,
            .detail = detail.str(),
            .key = "radar.samples_per_chirp"};
  }

  sensor::TimePart item_time(const std::any& params,
                             const sensor::Context& context) const override {
    const RadarParams& p = sensor::params_of<SensorParams>(params).radar;
    const double cells = static_cast<double>(p.samples_per_chirp * p.chirps_per_frame);
    const double tones = mean_clutter_tones(sensor::params_of<SensorParams>(params), context);
    const double objects = scene_objects_per_frame + p.cfar.false_alarm_probability * cells;
    const double reference_cells = static_cast<double>(p.cfar.reference_cells());
    const double edge_references =
        p.cfar.kind == CfarKind::os
            ? 0.0
            : static_cast<double>(p.chirps_per_frame) * 2.0 *
                  static_cast<double>(std::size_t{p.cfar.guard_cells} + p.cfar.training_cells) *
                  reference_cells;
    const double edge_seconds = p.cfar.kind == CfarKind::os
                                    ? cells * reference_cells * frame_seconds_per_sorted_reference
                                    : edge_references * frame_seconds_per_edge_reference;
    std::ostringstream detail;
    detail.precision(6);
    detail << "radar.samples_per_chirp = " << p.samples_per_chirp
           << " x radar.chirps_per_frame = " << p.chirps_per_frame << " cells, about " << objects
           << " objects (" << scene_objects_per_frame
           << " + processing.cfar.false_alarm_probability = " << p.cfar.false_alarm_probability
           << " x cells), about " << tones
           << " fog clutter tones (fog.clutter_scatterers_per_bin = "
           << sensor::params_of<SensorParams>(params).clutter_scatterers_per_bin
           << " per range bin of the active layers), " << edge_references
           << " CFAR edge-cell additions (2 x (processing.cfar.guard_cells + training_cells) x N "
              "per Doppler row)";
    const double rest =
        cells * (std::log2(cells) * frame_seconds_per_cell_log2_cell +
                 objects * frame_seconds_per_cell_and_object) +
        tones * static_cast<double>(p.samples_per_chirp) * frame_seconds_per_tone_sample;
    return {.item_seconds = rest + edge_seconds,
            .detail = detail.str(),
            .key = edge_seconds > rest                         ? "processing.cfar.training_cells"
                   : p.samples_per_chirp >= p.chirps_per_frame ? "radar.samples_per_chirp"
                                                               : "radar.chirps_per_frame",
            .items_key = "experiment.measurements_per_step"};
  }

  sensor::SetupTime setup_time(const std::any& params,
                               const sensor::Context& context) const override {
    const SensorParams& p = sensor::params_of<SensorParams>(params);
    const SetupCost c = setup_cost(p, context);
    std::ostringstream detail;
    detail.precision(3);
    detail << "fog optics " << c.fog_seconds << " s, chain " << c.chain_seconds
           << " s, CFAR design (processing.cfar.kind = " << to_string(p.radar.cfar.kind)
           << ", processing.cfar.threshold_design = " << to_string(p.radar.cfar.threshold_design)
           << ") " << c.cfar_design_seconds << " s";
    const double largest = std::max({c.fog_seconds, c.chain_seconds, c.cfar_design_seconds});
    return {.make_seconds = c.fog_seconds + c.chain_seconds + c.cfar_design_seconds,
            .run_seconds = c.summary_seconds,
            .report_seconds = c.report_seconds,
            .detail = detail.str(),
            .key = largest == c.cfar_design_seconds ? "processing.cfar.threshold_design"
                   : largest == c.chain_seconds     ? "radar.samples_per_chirp"
                                                    : "fog.droplets"};
  }

  std::vector<sensor::RawKind> raw_kinds(const std::any& params,
                                         const sensor::Context&) const override {
    return radar_raw_kinds(sensor::params_of<SensorParams>(params));
  }

  bool owns_file_name(std::string_view file_name) const override {
    return std::find(std::begin(file_names), std::end(file_names), file_name) !=
               std::end(file_names) ||
           std::find(std::begin(earlier_file_names), std::end(earlier_file_names), file_name) !=
               std::end(earlier_file_names);
  }

  // The fog at the radar's sweep centre: specific attenuation, backscatter, and the two-way loss
  // through one layer, 2 A L.
  sensor::Band band() const override { return sensor::Band::radio; }

  sensor::FogReport fog_report(const std::any& params, const propagation::FogSpec& spec,
                               double layer_length_m,
                               const propagation::SegelsteinTable& water) const override {
    const SensorParams& p = sensor::params_of<SensorParams>(params);
    const propagation::Fog fog(spec, water);
    const propagation::FogOptics o = fog.at_frequency(p.radar.centre_frequency_hz);
    const double loss_db = 2.0 * o.specific_attenuation_db_per_km * layer_length_m * 1e-3;
    std::ostringstream line;
    line << "  radar (" << o.frequency_hz * 1e-9 << " GHz)         2-way loss " << loss_db << " dB";
    return {.json = {{"frequency_hz", o.frequency_hz},
                     {"specific_attenuation_db_per_km", o.specific_attenuation_db_per_km},
                     {"volume_backscatter_m2_per_m3", o.volume_backscatter_m2_per_m3},
                     {"two_way_loss_db_per_layer", loss_db}},
            .line = line.str()};
  }

  std::shared_ptr<const sensor::Sensor> make(
      const std::any& params, const sensor::Context& context,
      const propagation::SegelsteinTable& water) const override {
    return make_or_stop(params, context, water, StopToken());
  }

  std::shared_ptr<const sensor::Sensor> make_or_stop(const std::any& params,
                                                     const sensor::Context& context,
                                                     const propagation::SegelsteinTable& water,
                                                     const StopToken& stop) const override {
    return std::make_shared<RadarSensor>(sensor::params_of<SensorParams>(params), context, water,
                                         stop);
  }

 private:
  KeyTable<std::any> keys_ = sensor::erase_keys(sensor_keys());
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

KeyTable<SensorParams> sensor_keys() {
  KeyTable<SensorParams> keys;
  keys.include(radar_param_keys(), FOGRADAR_KEY_FIELD(radar));
  keys.include(target_keys(), FOGRADAR_KEY_FIELD(target));
  keys.integer("fog.clutter_scatterers_per_bin", FOGRADAR_KEY_FIELD(clutter_scatterers_per_bin), 1,
               64, "random point scatterers per range bin that make up the radar's fog clutter");
  return keys;
}

SetupCost setup_cost(const SensorParams& params, const sensor::Context& context) {
  const RadarParams& r = params.radar;
  const double wavelength_m = derive(r).wavelength_m;
  // Each distinct fog once (propagation::Chamber), in the chamber and in summary.json's report.
  double fog_seconds = 0.0;
  const std::vector<propagation::FogLayerSpec>& layers = context.chamber.layers;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    std::size_t same = 0;
    while (same < i && layers[same].fog != layers[i].fog) ++same;
    if (same < i) continue;
    fog_seconds += propagation::fog_resolution_seconds(layers[i].fog) +
                   propagation::bulk_optics_seconds(layers[i].fog.droplets, wavelength_m);
  }
  const double cells = static_cast<double>(r.samples_per_chirp * r.chirps_per_frame);
  const double per_step = static_cast<double>(context.measurements_per_step);
  const double steps = static_cast<double>(context.steps);
  return {
      .fog_seconds = fog_seconds,
      .chain_seconds = chain_seconds + cells * chain_seconds_per_cell,
      .cfar_design_seconds = cfar_design_seconds(
          r.cfar, window_noise_correlation(make_window(r.window, r.samples_per_chirp),
                                           cfar_correlation_lags(r.cfar))),
      .summary_seconds = steps * per_step *
                         (summary_seconds_per_measurement + per_step * summary_seconds_per_pair),
      .report_seconds = fog_seconds + steps * per_step * files_seconds_per_measurement};
}

MemoryEstimate memory_estimate(const SensorParams& params, std::size_t measurements) {
  const std::size_t samples = params.radar.samples_per_chirp,
                    chirps = params.radar.chirps_per_frame;
  const std::size_t cells = samples * chirps;
  MemoryEstimate e;
  // Per thread (MeasurementWorkspace): the complex frame, the chirps x samples detection mask and
  // the one-chirp buffer of the range FFT chirp by chirp.
  const std::size_t frame =
      cells * complex_bytes + cells * sizeof(std::uint8_t) + samples * complex_bytes;
  // CFAR along one range row: the row's power, threshold, detections, window sums and two profiles
  // of block sums (CfarWorkspace); along four rows at once (CfarFourWorkspace): their power,
  // thresholds, detections, pair sums and window sums, four profiles each, and the one-row
  // workspace OS uses for them.
  const std::size_t one_row_cfar = 6 * samples * double_bytes;
  const std::size_t cfar =
      one_row_cfar + CfarFourWorkspace::profiles * 5 * samples * double_bytes + one_row_cfar;
  // Estimation: range kernels (re, im; two values per sample; a batch of objects), the batch's
  // Doppler columns, the rotated peak-search buffers (4 of the longer axis), and per axis a
  // Dirichlet table and an inverse DFT with 2n cosines and 2n sines each.
  const std::size_t estimation = 2 * interpolation_batch * 2 * samples * double_bytes +
                                 interpolation_batch * chirps * complex_bytes +
                                 4 * std::max(samples, chirps) * double_bytes +
                                 2 * 4 * (samples + chirps) * double_bytes;
  // The Doppler transform's packed block buffer.
  const std::size_t doppler_block = doppler_block_columns * chirps * complex_bytes;
  // Tones: every centre's paths plus the fog clutter, at most clutter_scatterers_per_bin per range
  // bin of the unambiguous range; twice for the vector's growth.
  const std::size_t tones = 2 * sizeof(Tone) * (params.clutter_scatterers_per_bin * samples + 64);
  e.per_thread_bytes = frame + cfar + estimation + doppler_block + tones;
  // Shared: the windows (range, Doppler, range pairs), both window spectra (16 x oversampled
  // complex tables, OriginClassifier) and the FFT plans (about two complex twiddles per point and
  // axis).
  const std::size_t windows = (3 * samples + chirps) * double_bytes;
  const std::size_t spectra = 16 * (samples + chirps + 2) * complex_bytes;
  const std::size_t plans = 2 * (samples + chirps) * complex_bytes;
  e.shared_bytes = windows + spectra + plans;
  // Per measurement: its record and radar_samples.csv's row, and its detections with their
  // radar_detections.csv rows (at most 128 characters a row). Detections per frame: 4 for the
  // target's (the examples measure 1.0-1.1 a frame, at most 3) and twice the design false alarms.
  const std::size_t detections =
      4 + static_cast<std::size_t>(std::ceil(2.0 * params.radar.cfar.false_alarm_probability *
                                             static_cast<double>(cells)));
  constexpr std::size_t csv_row_bytes = 128;
  e.records_bytes = measurements * (sizeof(MeasurementRecord) + csv_row_bytes +
                                    detections * (sizeof(DetectionRecord) + csv_row_bytes));
  return e;
}

std::shared_ptr<const sensor::SensorType> sensor_type() { return std::make_shared<Type>(); }

std::vector<sensor::RawKind> radar_raw_kinds(const SensorParams& params) {
  const RadarParams& p = params.radar;
  const RadarDerived d = derive(p);
  const std::size_t chirps = p.chirps_per_frame, samples = p.samples_per_chirp;
  sensor::RawAxis chirp_time{"chirp_time_s", "s", {}}, sample_time{"sample_time_s", "s", {}},
      velocity{"velocity_m_per_s", "m/s", {}}, range{"range_m", "m", {}};
  for (std::size_t c = 0; c < chirps; ++c) {
    chirp_time.values.push_back(static_cast<double>(c) * p.chirp_interval_s);
    // Row c of the map is Doppler bin c, or c - N_c from N_c/2 on (processing.hpp).
    const double bin =
        static_cast<double>(c) - (2 * c >= chirps ? static_cast<double>(chirps) : 0.0);
    velocity.values.push_back(d.sweep_sign * bin * d.velocity_resolution_m_per_s);
  }
  for (std::size_t n = 0; n < samples; ++n) {
    sample_time.values.push_back(static_cast<double>(n) / p.sample_rate_hz);
    range.values.push_back(static_cast<double>(n) * d.range_bin_m);
  }
  const std::size_t detections =
      4 + static_cast<std::size_t>(std::ceil(2.0 * p.cfar.false_alarm_probability *
                                             static_cast<double>(chirps * samples)));
  // The map's scale (processing.hpp): thermal noise of k T0 F fs per sample reaches each cell as
  // that times sum(w_r^2) sum(w_d^2); a tone of amplitude a on a bin centre peaks at
  // |X| = a N CG_r N_c CG_d.
  const std::vector<double> range_window = make_window(p.window, samples);
  const std::vector<double> doppler_window = make_window(p.window, chirps);
  const double noise_level = d.noise_power_w * noise_power_gain(range_window, doppler_window);
  const double gain = coherent_amplitude_gain(range_window, doppler_window);
  std::vector<sensor::RawKind> kinds(7);
  kinds[raw_beat] = {
      .name = "beat",
      .description =
          "the beat signal as synthesised, complex baseband I/Q at the receiver input "
          "before the window: chirps x samples",
      .units = "sqrt(W)",
      .element = sensor::RawElement::complex128,
      .dimensions = {"chirp", "sample"},
      .shape = {chirps, samples},
      .axes = {chirp_time, sample_time},
      .columns = {},
      .rows_per_item = 0,
      .attributes = {}};
  kinds[raw_range_doppler] = {
      .name = "range_doppler",
      .description =
          "|X|^2 of the windowed 2-D DFT of the beat, as the CFAR sees it: Doppler rows "
          "in FFT order (bin d >= N_c/2 is d - N_c) x range columns; range_m is the "
          "range of a static echo in each column, velocity_m_per_s each row's",
      .units = "W (beat units squared, with the window's and the DFT's gains)",
      .element = sensor::RawElement::float64,
      .dimensions = {"doppler", "range"},
      .shape = {chirps, samples},
      .axes = {velocity, range},
      .columns = {},
      .rows_per_item = 0,
      .attributes = {{"thermal_noise_level", noise_level}, {"coherent_amplitude_gain", gain}}};
  kinds[raw_detections] = {
      .name = "detections",
      .description =
          "every detection of the frame with its origin (radar_detections.csv): range "
          "corrected for the range-Doppler coupling, received power at the receiver "
          "input; in_gate: within the association gate; associated: the gate's "
          "strongest, radar_samples.csv's; range_cell, doppler_cell: the peak cell the "
          "attribution looked at (column and row of range_doppler and origins); layer: for "
          "a fog origin, the chamber layer (chamber.layers[layer]) that dominates the fog "
          "there, else -1",
      .units = "",
      .element = sensor::RawElement::table,
      .dimensions = {},
      .shape = {},
      .axes = {},
      .columns = {{"range_m", "m", false, {}},
                  {"velocity_m_per_s", "m/s", false, {}},
                  {"power_dbm", "dBm", false, {}},
                  {"snr_db", "dB", false, {}},
                  {"rcs_dbsm", "dBsm", false, {}},
                  {"origin", "", false, sensor::origin_labels()},
                  {"in_gate", "", true, {}},
                  {"associated", "", true, {}},
                  {"range_cell", "", true, {}},
                  {"doppler_cell", "", true, {}},
                  {"layer", "", true, {}}},
      .rows_per_item = detections,
      .attributes = {}};
  // The beat's parts (synthesis.hpp, FrameParts), on request: beat = signal + noise exactly for
  // static paths, to rounding with moving ones, both before the ADC.
  kinds[raw_signal] = kinds[raw_beat];
  kinds[raw_signal].name = "signal";
  kinds[raw_signal].description =
      "the beat signal without its thermal noise: the paths, the fog clutter and the phase noise "
      "(before the ADC); beat = signal + noise";
  kinds[raw_signal].by_default = false;
  kinds[raw_noise] = kinds[raw_beat];
  kinds[raw_noise].name = "noise";
  kinds[raw_noise].description =
      "the receiver's thermal noise of the beat signal as drawn, CN(0, k T0 F fs) per sample "
      "(before the ADC)";
  kinds[raw_noise].by_default = false;
  // Where a detection of the frame would come from, per cell: what the chain's attribution gives a
  // detection peaking there. A detection names its peak cell (range_cell, doppler_cell); from its
  // range_m and velocity_m_per_s alone the column is near range bin (range_m + range_coupling_s
  // velocity_m_per_s) / range_bin_m (the coupling the estimate removed) and the row near Doppler
  // bin velocity_m_per_s / velocity_bin_m_per_s, within the interpolation's offset from the peak.
  kinds[raw_origins] = kinds[raw_range_doppler];
  kinds[raw_origins].name = "origins";
  kinds[raw_origins].description =
      "the frame's ground truth per cell: the origin the chain's attribution gives a detection "
      "peaking there (target, fog, sidelobe, noise, or clipping in a frame whose ADC clipped), "
      "Doppler rows in FFT order x range columns as range_doppler";
  kinds[raw_origins].units = "";
  kinds[raw_origins].element = sensor::RawElement::uint8;
  kinds[raw_origins].labels = sensor::origin_labels();
  kinds[raw_origins].by_default = false;
  kinds[raw_origins].attributes = {
      {"range_bin_m", d.range_bin_m},
      {"velocity_bin_m_per_s", d.sweep_sign * d.velocity_resolution_m_per_s},
      {"range_coupling_s",
       doppler_shift_hz(1.0, d) * speed_of_light_m_per_s / (2.0 * d.chirp_slope_hz_per_s)}};
  kinds[raw_origin_layers] = kinds[raw_origins];
  kinds[raw_origin_layers].name = "origin_layers";
  kinds[raw_origin_layers].description =
      "the frame's fog layer per cell, beside origins: where the origin is fog, the chamber layer "
      "(the index in chamber.layers, 0-based from the sensor) whose echoes dominate the fog "
      "there; -1 elsewhere";
  kinds[raw_origin_layers].element = sensor::RawElement::int16;
  kinds[raw_origin_layers].labels = {};
  return kinds;
}

RadarSensor::RadarSensor(const SensorParams& params, const sensor::Context& context,
                         const propagation::SegelsteinTable& water, const StopToken& stop)
    : params_(params),
      context_(context),
      scene_(make_scene(params.target, params.clutter_scatterers_per_bin)),
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
      params.target.water_film_m,
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
    step.records.resize(sensor_->items_per_step());
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
      velocity_fold(sensor_->params().target.radial_velocity_m_per_s, sensor_->chain().derived());
  return std::make_unique<Report>(sensor_->params(), sensor_->context(), steps_,
                                  std::move(summary));
}

}  // namespace fogradar::radar
