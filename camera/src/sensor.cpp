#include "fogradar/camera/sensor.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "fogradar/camera/spectral.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::camera {
namespace {

// The CPU time of a frame per pixel of the region of interest (reflectance, airlight, noise,
// encoding, histogram), from `fogradar run --threads 1` of one-sensor camera scenarios of 4096 x
// 4096 and 160 x 120 px on the project's 2-core VM (release build), 5 to 7 ns; the larger is taken
// (bench/estimate_calibration measures it again).
constexpr double frame_seconds_per_pixel = 7e-9;
// The rest of a run (setup_time), CPU seconds measured by bench/estimate_calibration besides the
// Mie sums: a camera's making (band quadrature, look-up tables, scene) and its result files (the
// histograms, the ROI images, JSON); its summary costs less than either.
constexpr double make_seconds = 7e-4;
constexpr double files_seconds = 4e-4;

// Each distinct fog resolved and its bulk optics at every Mie wavelength of the band
// (camera.mie_step_nm), as Camera makes them (and fog_report a layer's).
double fog_seconds(const CameraParams& p, const propagation::ChamberSpec& chamber) {
  const std::vector<double> wavelengths = mie_wavelengths_m(p.band, p.wavelength_nm, p.mie_step_nm);
  double seconds = 0.0;
  for (std::size_t i = 0; i < chamber.layers.size(); ++i) {
    std::size_t same = 0;
    while (same < i && chamber.layers[same].fog != chamber.layers[i].fog) ++same;
    if (same < i) continue;
    seconds += propagation::fog_resolution_seconds(chamber.layers[i].fog);
    for (const double wavelength_m : wavelengths)
      seconds += propagation::bulk_optics_seconds(chamber.layers[i].fog.droplets, wavelength_m);
  }
  return seconds;
}

// camera_roi_<step>.pgm: the first frame of each step, when camera.write_roi_images.
std::string roi_file_name(std::size_t step) {
  return "camera_roi_" + std::to_string(step) + ".pgm";
}

std::string counted_layers(std::size_t count) {
  return std::to_string(count) + (count == 1 ? " layer" : " layers");
}

class Report : public CameraReport {
 public:
  Report(const CameraParams& params, std::shared_ptr<const std::vector<CameraStepResult>> steps)
      : params_(params),
        steps_(std::move(steps)),
        summary_(summarize(params, *steps_)),
        table_(camera::step_table(summary_)) {}

  const std::vector<CameraStepResult>& steps() const override { return *steps_; }
  const CameraSummary& summary() const override { return summary_; }

  sensor::Verdict verdict() const override {
    sensor::Verdict v{.layers_to_failure = summary_.sensor_limit_layers,
                      .criterion = summary_.criterion,
                      .margin = {}};
    if (!v.layers_to_failure && !summary_.steps.empty()) {
      const CameraStepSummary& last = summary_.steps.back();
      v.margin = "target contrast " + stats::format_fixed(last.target_contrast, 3) + " (" +
                 stats::format_fixed(100.0 * last.relative_contrast, 1) +
                 " % of clear weather) at " + counted_layers(last.active_layers);
    }
    return v;
  }

  const sensor::StepTable& step_table() const override { return table_; }
  std::string table() const override { return summary_table(summary_); }
  nlohmann::json json() const override { return summary_json(summary_); }

  std::vector<sensor::ResultFile> files() const override {
    std::vector<sensor::ResultFile> files = {{"camera_histograms.csv", histograms_csv(summary_)},
                                             {"camera_summary.csv", table_.csv()},
                                             {"camera_summary.json", json().dump(2) + '\n'},
                                             {"camera_histograms.svg", histograms_svg(summary_)}};
    if (params_.write_roi_images) {
      for (const CameraStepResult& step : *steps_) {
        if (step.frames.empty() || step.frames.front().pixels.empty()) continue;
        files.push_back({roi_file_name(step.active_layers), roi_pgm(params_, step.frames.front())});
      }
    }
    return files;
  }

  // The target contrast over its noise-free clear-weather contrast.
  sensor::Curve curve() const override {
    sensor::Curve c{.metric = "contrast",
                    .active_layers = {},
                    .relative_value = {},
                    .limit = summary_.sensor_limit_layers};
    for (const CameraStepSummary& s : summary_.steps) {
      c.active_layers.push_back(static_cast<double>(s.active_layers));
      c.relative_value.push_back(s.relative_contrast);
    }
    return c;
  }

 private:
  CameraParams params_;
  std::shared_ptr<const std::vector<CameraStepResult>> steps_;
  CameraSummary summary_;
  sensor::StepTable table_;
};

// The camera made for one scenario: its bands' fog optics on the chamber (Camera), made once.
class Made : public sensor::Sensor, public std::enable_shared_from_this<Made> {
 public:
  Made(const CameraParams& params, const sensor::Context& context,
       const propagation::SegelsteinTable& water)
      : context_(context), camera_(std::make_shared<const Camera>(params, context.chamber, water)) {
    for (std::size_t k = 0; k < context.steps; ++k) active_.push_back(context.active(k));
  }

  std::unique_ptr<sensor::SensorRun> begin_run() const override;

  const sensor::Context& context() const { return context_; }
  const std::shared_ptr<const Camera>& camera() const { return camera_; }
  const propagation::ActiveLayers& active(std::size_t step) const { return active_.at(step); }

 private:
  sensor::Context context_;
  std::shared_ptr<const Camera> camera_;
  std::vector<propagation::ActiveLayers> active_;
};

class Run : public sensor::SensorRun {
 public:
  explicit Run(std::shared_ptr<const Made> made)
      : made_(std::move(made)),
        camera_(made_->camera()),
        steps_(std::make_shared<std::vector<CameraStepResult>>(made_->context().steps)) {
    for (std::size_t k = 0; k < steps_->size(); ++k) {
      (*steps_)[k].active_layers = k;
      (*steps_)[k].frames.resize(camera_->params().frames_per_step);
    }
  }

  // The band's optics and the exposure: once per step, shared by its frames.
  void prepare_step(std::size_t step) override {
    (*steps_)[step].optics = camera_->step_optics(made_->active(step));
  }

  std::unique_ptr<sensor::Worker> make_worker() const override {
    return std::make_unique<FrameWorker>(*this);
  }

  std::unique_ptr<const sensor::SensorSummary> summarize() const override {
    return std::make_unique<Report>(camera_->params(), steps_);
  }

 private:
  class FrameWorker : public sensor::Worker {
   public:
    explicit FrameWorker(const Run& run) : run_(run) {}
    // No stop inside a frame: the largest, 4096 x 4096 px, takes about 0.12 s, and the runner looks
    // between frames.
    void measure(std::size_t step, std::size_t index, RandomStream& stream, sensor::RawSink* raw,
                 const StopToken&) override {
      CameraStepResult& result = (*run_.steps_)[step];
      const bool keep = run_.camera_->params().write_roi_images;
      const bool image = raw != nullptr && raw->wants(raw_images);
      CameraFrame& frame = result.frames[index];
      frame = run_.camera_->frame(result.optics, stream, keep || image);
      if (!image) return;
      raw->write(raw_images, std::span<const std::uint8_t>(frame.pixels));
      if (!keep) frame.pixels = {};
    }

   private:
    const Run& run_;
  };

  std::shared_ptr<const Made> made_;
  std::shared_ptr<const Camera> camera_;
  std::shared_ptr<std::vector<CameraStepResult>> steps_;
};

std::unique_ptr<sensor::SensorRun> Made::begin_run() const {
  return std::make_unique<Run>(shared_from_this());
}

class Configured : public sensor::ConfiguredSensor {
 public:
  Configured(const CameraParams& params, const sensor::Context& context)
      : p_(params), context_(context) {}

  std::size_t items_per_step() const override { return p_.frames_per_step; }

  sensor::MemoryPart memory(unsigned) const override {
    const CameraParams& p = p_;
    std::ostringstream detail;
    detail << "camera.frames_per_step = " << p.frames_per_step
           << " of camera.roi.width_px = " << p.roi.width_px
           << " x camera.roi.height_px = " << p.roi.height_px;
    return {.bytes = memory_bytes(p, context_.steps),
            .detail = detail.str(),
            .key = "camera.frames_per_step"};
  }

  sensor::Cost cost() const override { return {.item = item_time(), .setup = setup_time()}; }

  std::vector<sensor::RawKind> raw_kinds() const override {
    const CameraParams& p = p_;
    std::vector<sensor::RawKind> kinds(1);
    kinds[raw_images] = {
        .name = "images",
        .description =
            "every frame's grey image of the region of interest, row-major, as the "
            "histograms count it (camera_roi_<step>.pgm holds the first)",
        .units = "grey level",
        .element = sensor::RawElement::uint8,
        .dimensions = {"y", "x"},
        .shape = {p.roi.height_px, p.roi.width_px},
        .axes = {},
        .columns = {},
        .rows_per_item = 0,
        .attributes = {}};
    return kinds;
  }

  // The layer's band-weighted transmittance t (the camera's own band quadrature), the band's
  // effective extinction -ln t / L and the one-way loss -10 log10 t.
  sensor::FogReport fog_report(const propagation::FogSpec& spec, double layer_length_m,
                               const propagation::SegelsteinTable& water) const override {
    const CameraParams& p = p_;
    propagation::ChamberSpec chamber;
    chamber.layers = {propagation::FogLayerSpec{.length_m = layer_length_m, .fog = spec}};
    const Camera camera(p, chamber, water);
    const double t = camera.step_optics(propagation::ActiveLayers{true}).transmittance.front();
    const double extinction = -std::log(t) / layer_length_m;
    const double loss_db = -10.0 * std::log10(t);
    const auto number_or_null = [](double v) {
      return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    };
    std::ostringstream line;
    line << "  camera (" << to_string(p.band) << ")       transmittance " << t
         << " (effective extinction " << extinction << " 1/m), 1-way loss " << loss_db << " dB";
    return {.json = {{"band", std::string(to_string(p.band))},
                     {"extinction_per_m", number_or_null(extinction)},
                     {"transmittance_per_layer", t},
                     {"one_way_loss_db_per_layer", number_or_null(loss_db)}},
            .line = line.str()};
  }

  std::shared_ptr<const sensor::Sensor> make(const propagation::SegelsteinTable& water,
                                             const StopToken& stop) const override {
    stop.check();
    return std::make_shared<Made>(p_, context_, water);
  }

 private:
  sensor::TimePart item_time() const {
    const CameraParams& p = p_;
    std::ostringstream detail;
    detail << "camera.roi.width_px = " << p.roi.width_px
           << " x camera.roi.height_px = " << p.roi.height_px << " px";
    return {
        .item_seconds =
            static_cast<double>(p.roi.width_px * p.roi.height_px) * frame_seconds_per_pixel,
        .detail = detail.str(),
        .key = p.roi.width_px >= p.roi.height_px ? "camera.roi.width_px" : "camera.roi.height_px",
        .items_key = "camera.frames_per_step"};
  }

  sensor::SetupTime setup_time() const {
    const CameraParams& p = p_;
    const double fogs = fog_seconds(p, context_.chamber);
    std::ostringstream detail;
    detail.precision(3);
    detail << "fog optics at " << mie_wavelengths_m(p.band, p.wavelength_nm, p.mie_step_nm).size()
           << " wavelengths (camera.band = " << to_string(p.band)
           << ", camera.mie_step_nm = " << p.mie_step_nm << "): " << fogs << " s";
    return {.make_seconds = fogs + make_seconds,
            .run_seconds = 0.0,
            .report_seconds = fogs + make_seconds + files_seconds,
            .detail = detail.str(),
            .key = "camera.mie_step_nm"};
  }

  CameraParams p_;
  sensor::Context context_;
};

class Kind : public sensor::Kind<CameraParams> {
 public:
  Kind()
      : sensor::Kind<CameraParams>({.name = "camera",
                                    .stream_key = camera::stream_key,
                                    .band = sensor::Band::optical,
                                    .item_noun = "camera frames",
                                    .curve_caption = "target contrast"},
                                   camera_keys()) {}

 protected:
  std::shared_ptr<const sensor::ConfiguredSensor> configured(
      const CameraParams& p, const sensor::Context& context) const override {
    return std::make_shared<Configured>(p, context);
  }
};

}  // namespace

std::shared_ptr<const sensor::SensorKind> sensor_kind() { return std::make_shared<Kind>(); }

}  // namespace fogradar::camera
