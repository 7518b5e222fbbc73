// The camera of the study (sec. IV-C): Koschmieder (paper eq. 8) over the fog-only path in linear
// radiance, per wavelength over the camera's band, then a sensor pipeline (exposure, noise,
// clipping, transfer curve, 8-bit quantisation, grey conversion) and the region of interest's
// statistics. docs/camera.md derives every equation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fogradar/camera/params.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/sensor/step_table.hpp"

namespace fogradar::camera {

// The camera's random streams: sensor_stream(seed, stream_key, step, frame).
inline constexpr std::uint64_t stream_key = 2;

inline constexpr std::size_t grey_levels = 256;
using Histogram = std::array<std::uint64_t, grey_levels>;

// Band-integrated optics of one step (one set of active layers), per channel (1 for photopic and
// monochromatic, 3 for rgb): the weighted transmittance t_c = int S_c t / int S_c and the weighted
// path radiance factor a_c = int S_c omega (1 - t) / int S_c (L_s (1 - t) in units of L_a), and the
// exposure the step's frames use.
struct StepOptics {
  std::size_t active_layer_count = 0;
  std::vector<double> transmittance;    // t_c
  std::vector<double> airlight_factor;  // a_c
  double exposure_level = 0.0;          // linear signal of radiance L_a (fixed or auto)
  // Noise-free clear-weather references of the scene (the same at every step): the Weber contrast
  // of the target against the background, and the cell edges above the contrast threshold.
  double clear_contrast = 0.0;
  std::size_t clear_edges = 0;
};

// One frame of the ROI.
struct CameraFrame {
  Histogram histogram{};  // grey counts over the ROI
  double mean_grey = 0.0;
  double target_contrast = 0.0;  // Weber contrast of target vs background means, linearised
  std::size_t edges_above_threshold = 0;
  std::vector<std::uint8_t> pixels;  // row-major grey image; only when asked for (Camera::frame)
};

struct CameraStepResult {
  std::size_t active_layers = 0;
  StepOptics optics;
  std::vector<CameraFrame> frames;  // by frame index
};

struct CameraStepSummary {
  std::size_t active_layers = 0;
  std::size_t frames = 0;
  Histogram histogram{};  // summed over the step's frames
  double mean_grey = 0.0;
  double std_grey = 0.0;  // over every pixel of every frame
  double p05_grey = 0.0;  // 5 % and 95 % quantiles of the summed histogram
  double p95_grey = 0.0;
  double tonal_range = 0.0;            // p95 - p05
  double target_contrast = 0.0;        // mean over frames
  double relative_contrast = 0.0;      // target_contrast / clear-weather contrast
  double edges_above_threshold = 0.0;  // mean over frames
  std::size_t clear_edges = 0;         // edges above the threshold in the noise-free clear scene
  double transmittance = 0.0;          // band-weighted t of the first channel
};

struct CameraSummary {
  std::vector<CameraStepSummary> steps;
  double clear_contrast = 0.0;  // noise-free clear-weather Weber contrast of target vs background
  // First step's active layer count at which |target contrast| < contrast_threshold; none: not
  // reached.
  std::optional<std::size_t> sensor_limit_layers;
  std::string criterion;  // the limit criterion as text
};

class Camera {
 public:
  // Resolves every distinct layer fog at the band's wavelengths by Mie (once); builds the ROI
  // scene.
  Camera(const CameraParams& params, const propagation::ChamberSpec& chamber,
         const propagation::SegelsteinTable& table);

  const CameraParams& params() const { return params_; }
  // The same fog optics (no Mie again) with another scene, exposure and pipeline: `params` may
  // differ in every key but camera.band and camera.wavelength_nm (calibration, studies).
  Camera with_scene(const CameraParams& params) const;
  std::size_t layer_count() const { return layer_count_; }
  std::size_t channel_count() const { return channel_count_; }

  // The band's optics and the exposure for one set of active layers (deterministic, no noise):
  // computed once per step, shared by that step's frames.
  StepOptics step_optics(const propagation::ActiveLayers& active) const;
  // One frame: draws shot and read noise from `stream` (experiment/ passes
  // sensor_stream(seed, stream_key, step, frame)). The grey image is kept in CameraFrame::pixels
  // when `keep_pixels` (camera.write_roi_images, or the run's raw data asks for it).
  CameraFrame frame(const StepOptics& optics, RandomStream& stream, bool keep_pixels) const;
  CameraFrame frame(const StepOptics& optics, RandomStream& stream) const {
    return frame(optics, stream, params_.write_roi_images);
  }
  // The frames of one step from sensor_stream(seed, camera, step, index), index = frame: what
  // experiment/ does frame by frame; for tests and benchmarks.
  CameraStepResult measure_step(std::size_t step, const propagation::ActiveLayers& active,
                                std::uint64_t seed) const;

  // Noise-free, unquantised ROI mean grey for the optics (the model's prediction of the mean).
  double expected_mean_grey(const StepOptics& optics) const;
  // Noise-free clear-weather Weber contrast of the target against the background (linear).
  double clear_contrast() const;
  // Edges of the cell grid whose noise-free clear-weather Weber contrast is above the threshold.
  std::size_t clear_edge_count() const;

  // Per-wavelength optics of layer i's fog at the band's nodes (for docs and tests).
  const std::vector<double>& band_wavelengths_m() const { return wavelengths_m_; }
  const std::vector<double>& layer_extinction_per_m(std::size_t layer) const;

 private:
  struct Cell {
    std::size_t x0, y0;  // first pixel
    double reflectance;
    bool target;
  };

  void build_scene();
  // Grey level of a linear signal (full scale 1): round(255 encode(linear)) by the thresholds.
  std::uint8_t quantise(double linear) const;

  CameraParams params_;
  std::size_t layer_count_ = 0;
  std::size_t channel_count_ = 1;
  std::vector<double> layer_lengths_m_;
  std::vector<double> wavelengths_m_;            // band nodes
  std::vector<std::vector<double>> weights_;     // [channel][node], quadrature x sensitivity
  std::vector<std::size_t> layer_fog_;           // layer -> distinct fog index
  std::vector<std::vector<double>> extinction_;  // [fog][node], 1/m
  std::vector<std::vector<double>> albedo_;      // [fog][node]
  std::vector<double> window_transmittance_;     // [node], the window's water film, one way
  std::vector<Cell> cells_;
  std::size_t cells_x_ = 0;
  std::size_t cells_y_ = 0;
  std::array<double, grey_levels - 1> thresholds_{};
  std::array<double, grey_levels> grey_linear_{};
  std::array<std::uint8_t, 4096> bucket_levels_{};  // grey level at linear b / 4096
};

// Per-step statistics and the sensor limit (stats/ for the statistics).
CameraSummary summarize(const CameraParams& params, const std::vector<CameraStepResult>& steps);

// Result files as strings.
std::string histograms_csv(
    const CameraSummary& summary);  // camera_histograms.csv: active_layers,grey_level,count
// The per-step statistics as typed columns: camera_summary.csv (step_table(s).csv()), the steps of
// summary_json, and the columns of summary_table.
sensor::StepTable step_table(const CameraSummary& summary);
nlohmann::json summary_json(const CameraSummary& summary);  // the object summary.json embeds
std::string histograms_svg(const CameraSummary& summary);   // camera_histograms.svg (Fig. 7)
std::string roi_pgm(const CameraParams& params, const CameraFrame& frame);  // binary PGM (P5)
std::string summary_table(const CameraSummary& summary);                    // the terminal table

// Bytes the run holds for the camera: frames x (histogram + optional image) per step.
std::size_t memory_bytes(const CameraParams& params, std::size_t step_count);

}  // namespace fogradar::camera
