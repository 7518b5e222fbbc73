#include "fogradar/lidar/sensor.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::lidar {
namespace {

// The CPU time of a scan, fitted to `fogradar run --threads 1` of one-sensor lidar scenarios of
// 36001 beams of 41 and of 401 samples on the project's 2-core VM (release build): per sample the
// noise drawn, the signal added, the maximum taken; per beam its ray traced. bench/
// estimate_calibration measures them again (docs/scenario.md, "Time limit").
constexpr double scan_seconds_per_sample = 1.32e-9;
constexpr double scan_seconds_per_beam = 26e-9;
// The rest of a run (setup_time), CPU seconds measured by bench/estimate_calibration besides the
// Mie sums (a Lidar's scene costs less than they): a summary's part and the result files' part
// (their CSV rows, the scan plots) per beam of every scan.
constexpr double summary_seconds_per_beam = 3.3e-8;
constexpr double files_seconds_per_beam = 2.2e-7;

// Each distinct fog resolved and its bulk optics at the lidar's wavelength, as Lidar makes its
// layers (and fog_report a layer's).
double fog_seconds(const LidarParams& p, const propagation::ChamberSpec& chamber) {
  double seconds = 0.0;
  for (std::size_t i = 0; i < chamber.layers.size(); ++i) {
    std::size_t same = 0;
    while (same < i && chamber.layers[same].fog != chamber.layers[i].fog) ++same;
    if (same < i) continue;
    seconds += propagation::fog_resolution_seconds(chamber.layers[i].fog) +
               propagation::bulk_optics_seconds(chamber.layers[i].fog.droplets, p.wavelength_m);
  }
  return seconds;
}

std::string counted_layers(std::size_t count) {
  return std::to_string(count) + (count == 1 ? " layer" : " layers");
}

class Report : public LidarReport {
 public:
  Report(std::shared_ptr<const Lidar> lidar,
         std::shared_ptr<const std::vector<LidarStepResult>> steps,
         std::span<const propagation::ActiveLayers> active)
      : lidar_(std::move(lidar)),
        steps_(std::move(steps)),
        summary_(summarize(*lidar_, *steps_, active)),
        table_(lidar_step_table(summary_)) {}

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

  const sensor::StepTable& step_table() const override { return table_; }
  std::string table() const override { return lidar_summary_table(summary_); }
  nlohmann::json json() const override { return lidar_summary_json(*lidar_, summary_); }

  std::vector<sensor::ResultFile> files() const override {
    return {{"lidar_echoes.csv", lidar_echoes_csv(*lidar_, *steps_)},
            {"lidar_summary.csv", table_.csv()},
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
  sensor::StepTable table_;
};

// The lidar made for one scenario: its beams, fog and detector on the chamber and its room's
// shapes in the scan plane (Lidar), made once.
class Made : public sensor::Sensor, public std::enable_shared_from_this<Made> {
 public:
  Made(const LidarParams& params, const sensor::Context& context, std::span<const Shape> room,
       const propagation::SegelsteinTable& water)
      : context_(context),
        lidar_(std::make_shared<const Lidar>(params, context.chamber, water, room)) {
    for (std::size_t k = 0; k < context.steps; ++k) active_.push_back(context.active(k));
  }

  std::unique_ptr<sensor::SensorRun> begin_run() const override;

  const sensor::Context& context() const { return context_; }
  const std::shared_ptr<const Lidar>& lidar() const { return lidar_; }
  const propagation::ActiveLayers& active(std::size_t step) const { return active_.at(step); }
  const std::vector<propagation::ActiveLayers>& active() const { return active_; }

 private:
  sensor::Context context_;
  std::shared_ptr<const Lidar> lidar_;
  std::vector<propagation::ActiveLayers> active_;
};

class Run : public sensor::SensorRun {
 public:
  explicit Run(std::shared_ptr<const Made> made)
      : made_(std::move(made)),
        lidar_(made_->lidar()),
        steps_(std::make_shared<std::vector<LidarStepResult>>(made_->context().steps)),
        fog_(made_->context().steps) {
    for (std::size_t k = 0; k < steps_->size(); ++k) {
      (*steps_)[k].active_layers = k;
      (*steps_)[k].scans.resize(lidar_->params().scans_per_step);
    }
  }

  // The step's scan-to-scan fog series, from the stream index the lidar reserves for it.
  void prepare_step(std::size_t step) override {
    fog_[step] = lidar_->fog_fluctuation(
        sensor_stream(made_->context().seed, stream_key, step, lidar_->fog_series_index()));
  }

  std::unique_ptr<sensor::Worker> make_worker() const override {
    return std::make_unique<ScanWorker>(*this);
  }

  std::unique_ptr<const sensor::SensorSummary> summarize() const override {
    return std::make_unique<Report>(lidar_, steps_, made_->active());
  }

 private:
  class ScanWorker : public sensor::Worker {
   public:
    explicit ScanWorker(const Run& run) : run_(run) {}
    void measure(std::size_t step, std::size_t index, RandomStream& stream, sensor::RawSink* raw,
                 const StopToken& stop) override {
      const bool waveforms = raw != nullptr && raw->wants(raw_waveforms);
      if (waveforms) {
        waveforms_.resize(run_.lidar_->beam_count() * run_.lidar_->samples_per_beam());
      }
      LidarScan& scan = (*run_.steps_)[step].scans[index];
      const bool truth = raw != nullptr && raw->wants(raw_origins);
      scan = run_.lidar_->measure(run_.made_->active(step), run_.fog_[step].scan(index), stream,
                                  waveforms ? std::span<double>(waveforms_) : std::span<double>(),
                                  stop, truth ? &origins_ : nullptr);
      if (truth) {
        rows_.clear();
        for (const OriginRun& o : origins_) {
          rows_.insert(rows_.end(), {static_cast<double>(o.beam), o.start_m, o.end_m,
                                     static_cast<double>(o.origin), static_cast<double>(o.layer)});
        }
        raw->append_rows(raw_origins, rows_);
      }
      if (waveforms) raw->write(raw_waveforms, std::span<const double>(waveforms_));
      if (raw != nullptr && raw->wants(raw_echoes)) {
        rows_.clear();
        for (const LidarEcho& e : scan.echoes) {
          rows_.insert(
              rows_.end(),
              {static_cast<double>(e.beam), run_.lidar_->beam_angle_deg(e.beam),
               static_cast<double>(e.index), e.range_m, e.intensity, static_cast<double>(e.origin),
               e.attributed_range_m, static_cast<double>(e.layer)});
        }
        raw->append_rows(raw_echoes, rows_);
      }
    }

   private:
    const Run& run_;
    std::vector<double> waveforms_, rows_;  // asked for as raw data
    std::vector<OriginRun> origins_;
  };

  std::shared_ptr<const Made> made_;
  std::shared_ptr<const Lidar> lidar_;
  std::shared_ptr<std::vector<LidarStepResult>> steps_;
  std::vector<FogFluctuationSeries> fog_;
};

std::unique_ptr<sensor::SensorRun> Made::begin_run() const {
  return std::make_unique<Run>(shared_from_this());
}

class Configured : public sensor::ConfiguredSensor {
 public:
  Configured(const LidarParams& params, const sensor::Context& context)
      : p_(params),
        context_(context),
        room_(context.runs ? room_shapes(scan_plane_room(context.room, params), params.height_m)
                           : std::vector<Shape>{}) {}

  std::size_t items_per_step() const override { return p_.scans_per_step; }

  sensor::MemoryPart memory(unsigned threads) const override {
    const LidarParams& p = p_;
    std::ostringstream detail;
    detail.precision(6);
    detail << "lidar.scans_per_step = " << p.scans_per_step << " of " << p.beam_count()
           << " beams: lidar.field_of_view_deg = " << p.field_of_view_deg
           << " / lidar.angular_step_deg = " << p.angular_step_deg;
    return {.bytes = lidar_memory_bytes(p, context_.steps, threads),
            .detail = detail.str(),
            .key = "lidar.scans_per_step"};
  }

  sensor::Cost cost() const override { return {.item = item_time(), .setup = setup_time()}; }

  std::vector<sensor::RawKind> raw_kinds() const override {
    return lidar_raw_kinds(p_, context_.chamber.layers.size());
  }

  // The layer's extinction alpha and backscatter beta_pi at the lidar's wavelength (Mie, resolved
  // by the Lidar itself), their ratio, and the two-way Beer-Lambert loss 10 log10(e) 2 alpha L.
  sensor::FogReport fog_report(const propagation::FogSpec& spec, double layer_length_m,
                               const propagation::SegelsteinTable& water) const override {
    const LidarParams& p = p_;
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

  std::shared_ptr<const sensor::Sensor> make(const propagation::SegelsteinTable& water,
                                             const StopToken& stop) const override {
    FOGRADAR_CHECK(context_.runs);  // configured with its room
    stop.check();
    return std::make_shared<Made>(p_, context_, room_, water);
  }

 private:
  sensor::TimePart item_time() const {
    const LidarParams& p = p_;
    const std::size_t beams = p.beam_count(), samples = p.samples_per_beam();
    std::ostringstream detail;
    detail.precision(6);
    detail << beams << " beams (lidar.field_of_view_deg = " << p.field_of_view_deg
           << " / lidar.angular_step_deg = " << p.angular_step_deg << ") x " << samples
           << " samples (2 lidar.max_range_m = " << p.max_range_m
           << " m / c / lidar.sample_interval_ns = " << p.sample_interval_ns << ")";
    return {.item_seconds =
                static_cast<double>(beams) *
                (static_cast<double>(samples) * scan_seconds_per_sample + scan_seconds_per_beam),
            .detail = detail.str(),
            .key = samples >= beams ? "lidar.sample_interval_ns" : "lidar.angular_step_deg",
            .items_key = "lidar.scans_per_step"};
  }

  sensor::SetupTime setup_time() const {
    const LidarParams& p = p_;
    const double fogs = fog_seconds(p, context_.chamber);
    const double beams = static_cast<double>(context_.steps * p.scans_per_step * p.beam_count());
    std::ostringstream detail;
    detail.precision(3);
    detail << "fog optics at lidar.wavelength_m = " << p.wavelength_m << ": " << fogs << " s";
    return {.make_seconds = fogs,
            .run_seconds = beams * summary_seconds_per_beam,
            .report_seconds = fogs + beams * files_seconds_per_beam,
            .detail = detail.str(),
            .key = "fog.droplets"};
  }

  LidarParams p_;
  sensor::Context context_;
  std::vector<Shape> room_;
};

class Kind : public sensor::Kind<LidarParams> {
 public:
  Kind()
      : sensor::Kind<LidarParams>(
            {.name = "lidar",
             .stream_key = lidar::stream_key,
             .band = sensor::Band::optical,
             .item_noun = "lidar scans",
             .curve_caption = "median target intensity (a missing target counted as 0)"},
            lidar_keys()) {}

 protected:
  std::shared_ptr<const sensor::ConfiguredSensor> configured(
      const LidarParams& p, const sensor::Context& context) const override {
    // Fog from the aperture on returns the integral of dr / r^2, which diverges at r = 0 unless
    // the overlap function takes the receiver's view to 0 there.
    if (p.overlap_range_m == 0.0 && context.chamber.sensor_gap_m == 0.0) {
      throw_invalid("lidar.overlap_range_m", p.overlap_range_m,
                    "> 0 with chamber.sensor_gap_m = 0: the fog then begins at the lidar, whose "
                    "return without an overlap function diverges there (the integral of dr / r^2)");
    }
    return std::make_shared<Configured>(p, context);
  }
};

}  // namespace

std::shared_ptr<const sensor::SensorKind> sensor_kind() { return std::make_shared<Kind>(); }

std::vector<sensor::RawKind> lidar_raw_kinds(const LidarParams& params, std::size_t layer_count) {
  const std::size_t beams = params.beam_count(), samples = params.samples_per_beam();
  sensor::RawAxis angle{"angle_deg", "deg", {}}, time{"time_s", "s", {}};
  for (std::size_t b = 0; b < beams; ++b) angle.values.push_back(params.beam_angle_deg(b));
  for (std::size_t k = 0; k < samples; ++k) {
    time.values.push_back(static_cast<double>(k) * params.sample_interval_ns * 1e-9);
  }
  std::vector<sensor::RawKind> kinds(3);
  kinds[raw_waveforms] = {
      .name = "waveforms",
      .description =
          "each beam's received waveform, receiver noise included, as the echo "
          "extraction sees it: beams x samples, sample k at round-trip time k dt "
          "(range c k dt / 2); the lidar equation in units of its system constant "
          "(docs/lidar.md)",
      .units = "1/(m^2 sr) (units of the system constant C)",
      .element = sensor::RawElement::float64,
      .dimensions = {"beam", "sample"},
      .shape = {beams, samples},
      .axes = {angle, time},
      .columns = {},
      .rows_per_item = 0,
      .attributes = {}};
  kinds[raw_echoes] = {.name = "echoes",
                       .description =
                           "every echo of the scan with its origin (lidar_echoes.csv); "
                           "attributed_range_m: the range of the peak of the return whose leading "
                           "edge made the echo, where its origin and layer are attributed; layer: "
                           "a fog echo's chamber layer (0 nearest the sensor), -1 for the others",
                       .units = "",
                       .element = sensor::RawElement::table,
                       .dimensions = {},
                       .shape = {},
                       .axes = {},
                       .columns = {{"beam", "", true, {}},
                                   {"angle_deg", "deg", false, {}},
                                   {"echo", "", true, {}},
                                   {"range_m", "m", false, {}},
                                   {"intensity", "", false, {}},
                                   {"origin", "", false, sensor::origin_labels()},
                                   {"attributed_range_m", "m", false, {}},
                                   {"layer", "", true, {}}},
                       .rows_per_item = beams * params.max_echoes,
                       .attributes = {}};
  // An echo takes the origin and layer of its beam's stretch that holds its attributed_range_m,
  // noise outside every stretch: the attribution the scan gave it. Per beam at most a target or
  // background stretch, the stretches of each layer's fog and one beyond: the size estimate's
  // rows.
  kinds[raw_origins] = {
      .name = "origins",
      .description =
          "the scan's ground truth: per beam the stretches of range whose noise-free parts give "
          "an echo attributed there an origin other than noise (target, fog, background), fog "
          "split by the chamber layer (0 nearest the sensor) whose fog contributes most; layer "
          "-1 where not fog; noise elsewhere",
      .units = "",
      .element = sensor::RawElement::table,
      .dimensions = {},
      .shape = {},
      .axes = {},
      .columns = {{"beam", "", true, {}},
                  {"start_m", "m", false, {}},
                  {"end_m", "m", false, {}},
                  {"origin", "", false, sensor::origin_labels()},
                  {"layer", "", true, {}}},
      .rows_per_item = (2 + layer_count) * beams,
      .attributes = {},
      .by_default = false};
  return kinds;
}

}  // namespace fogradar::lidar
