// The 905 nm scanning lidar in the fog chamber (docs/lidar.md): built once per run from
// its parameters and the chamber, it resolves each layer's fog at 905 nm by Mie over the drop size
// distribution, and measures scans: per beam the received waveform (waveform.hpp), receiver noise,
// echo extraction, and each echo's origin from the simulation's ground truth.
//
// How experiment/ runs it (lidar/sensor.hpp), per step with `active` layers (all randomness from
// fogradar::sensor_stream(seed, stream_key, step, index)):
//   FogFluctuationSeries fog = lidar.fog_fluctuation(
//       sensor_stream(seed, stream_key, step, lidar.fog_series_index()));
//   for each scan s in [0, scans_per_step), on any thread:
//     RandomStream stream = sensor_stream(seed, stream_key, step, s);
//     step_result.scans[s] = lidar.measure(active, fog.scan(s), stream);
// The results depend on (seed, step, scan) only: byte-identical for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "fogradar/core/random.hpp"
#include "fogradar/core/stop.hpp"
#include "fogradar/lidar/fog_return.hpp"
#include "fogradar/lidar/params.hpp"
#include "fogradar/lidar/shapes.hpp"
#include "fogradar/lidar/waveform.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/sensor/origin.hpp"

namespace fogradar::lidar {

// The lidar's random streams: sensor_stream(seed, stream_key, step, index).
inline constexpr std::uint64_t stream_key = 1;

// What produced an echo (the sensors' one code table, sensor/origin.hpp): the noise-free
// contribution largest at the echo's attribution sample (attribution_sample, waveform.hpp: the
// peak of the return whose leading edge made the echo; target: the EVT; fog: the active layers'
// volume backscatter; background: a static shape), or noise when the largest is below the
// receiver noise's standard deviation (a false alarm). A fog echo also names the chamber layer
// whose fog contributes most there.
using sensor::Origin;
using sensor::to_string;

// The origin of a sample from its noise-free parts: the largest (ties to target, then fog), or
// noise when it is below `noise_std`.
Origin dominant_origin(double target, double fog, double background, double noise_std) noexcept;

// No chamber layer: the layer of an echo or a stretch whose origin is not fog.
inline constexpr std::int32_t no_layer = -1;

// A stretch of one beam's samples with one origin other than noise (and, for fog, one dominant
// layer): samples k with start_m <= c k dt / 2 < end_m (the sample's range, before the echo range's
// calibration).
struct OriginRun {
  std::uint32_t beam = 0;
  Origin origin = Origin::noise;
  double start_m = 0.0;
  double end_m = 0.0;
  // Fog: the index into chamber.layers (0 nearest the sensor) of the layer whose fog contributes
  // most to these samples; no_layer otherwise.
  std::int32_t layer = no_layer;
};

struct LidarEcho {
  std::uint32_t beam = 0;  // index into the scan, angle = beam_angle_deg(beam)
  std::uint8_t index = 0;  // 0 = first echo in range order
  Origin origin = Origin::noise;
  double range_m = 0.0;  // leading-edge crossing, calibrated (EchoDetector::range_offset_m)
  // c k dt / 2 of its attribution sample k (attribution_sample), where its origin and layer are
  // taken: the OriginRun holding it gives both.
  double attributed_range_m = 0.0;
  // min(saturation, scale * peak / threshold): the echo's largest sample, whichever return it
  // belongs to.
  double intensity = 0.0;
  std::int32_t layer = no_layer;  // fog: its OriginRun's layer; no_layer otherwise
};

// One scan. The per-scan quantities the summary needs are kept here so that a step's scans can be
// measured on any thread and summarised without the sensor.
struct LidarScan {
  std::vector<LidarEcho> echoes;  // ascending beam, then echo index
  // The beam through the target's centre ("40 consecutive points of the same angle", the study):
  double target_intensity = 0.0;      // its strongest target-origin echo; 0 when none (Fig. 6)
  bool target_detected = false;       // it has a target-origin echo
  bool fog_outshines_target = false;  // it has a fog-origin echo at least as intense as that
  std::size_t beams_through_fog = 0;  // beams crossing at least one active layer
  std::size_t beams_through_fog_with_fog_echo = 0;
  std::vector<double> first_echo_range_through_fog_m;  // first echo of each such beam with echoes
};

struct LidarStepResult {
  std::size_t active_layers = 0;
  std::vector<LidarScan> scans;
};

// Per-scan, per-layer optical-depth factors of one step (params.hpp, FogFluctuation).
struct FogFluctuationSeries {
  std::size_t layer_count = 0;
  std::vector<double> factors;  // factors[scan * layer_count + layer]
  std::span<const double> scan(std::size_t scan_index) const;
};

// A beam's noise-free waveform by ground-truth contribution, in units of C (waveform.hpp).
struct BeamWaveform {
  std::vector<double> target;
  std::vector<double> fog;
  std::vector<double> background;
  bool crosses_fog = false;  // through at least one active layer
  bool hits = false;         // some hard surface within max_range_m
};

class Lidar {
 public:
  // Validates both; resolves each layer's FogSpec at params.wavelength_m
  // (propagation::Fog::at_optical_wavelength): alpha = extinction, beta_pi = volume backscatter /
  // (4 pi). The static scene is the background segments followed by `room` (room_shapes(): the
  // hall's walls and objects in the scan plane), every one a background origin.
  Lidar(const LidarParams& params, const propagation::ChamberSpec& chamber,
        const propagation::SegelsteinTable& table, std::span<const Shape> room = {});

  const LidarParams& params() const { return params_; }
  std::size_t beam_count() const { return beam_count_; }
  double beam_angle_deg(std::size_t beam) const;  // -fov/2 + beam step; 0 on boresight, + right
  std::size_t target_beam() const { return target_beam_; }  // nearest the EVT's centre
  std::size_t layer_count() const { return layers_.size(); }
  double layer_start_m(std::size_t layer) const;
  double layer_end_m(std::size_t layer) const;
  double layer_extinction_per_m(std::size_t layer) const;      // alpha at the wavelength
  double layer_backscatter_per_m_sr(std::size_t layer) const;  // beta_pi
  double target_range_m() const { return target_range_m_; }
  double threshold() const { return detector_.threshold; }  // waveform units
  double noise_std() const { return noise_std_; }
  // The window's water film out and back (lidar.window_water_film_m): every echo's factor.
  double window_two_way_transmittance() const { return window_two_way_transmittance_; }
  std::size_t samples_per_beam() const { return samples_; }
  // The static scene: the background segments, then the room's shapes.
  const std::vector<Shape>& shapes() const { return shapes_; }

  // The stream index of the step's fog series: scans_per_step (scans use 0 .. scans_per_step - 1).
  std::size_t fog_series_index() const { return params_.scans_per_step; }
  // The step's series for every layer of the chamber (active or not), scans_per_step scans.
  FogFluctuationSeries fog_fluctuation(RandomStream stream) const;

  // Noise-free waveform of one beam; `optical_depth_factors` has one factor per chamber layer.
  BeamWaveform waveform(std::size_t beam, const propagation::ActiveLayers& active,
                        std::span<const double> optical_depth_factors) const;

  // One scan: every beam's waveform plus Gaussian receiver noise (std noise_std()) drawn from
  // `stream`, echoes extracted, origins attributed. Beams that cross no active layer and hit
  // nothing get noise only. Given `waveforms` (beam_count() x samples_per_beam(), row-major), each
  // beam's received waveform, noise included, as the echo extraction sees it, goes into its row.
  // Given `origins`, it is filled with the scan's ground truth: every beam's stretches of samples
  // whose noise-free parts give an origin other than noise (the attribution an echo attributed
  // there gets), fog split where its dominant layer changes, ascending beam and range. Throws
  // InvalidParameter when `active` or the factors do not have one entry per layer, and Stopped,
  // before a beam, when `stop` says stop.
  LidarScan measure(const propagation::ActiveLayers& active,
                    std::span<const double> optical_depth_factors, RandomStream& stream,
                    std::span<double> waveforms = {}, const StopToken& stop = {},
                    std::vector<OriginRun>* origins = nullptr) const;

 private:
  struct Layer {
    double start_m;
    double end_m;
    double extinction_per_m;
    double backscatter_per_m_sr;
  };
  // The nearest hard surface along a beam, if any within max_range_m.
  struct Hit {
    bool found = false;
    bool is_target = false;
    double range_m = 0.0;
    double amplitude = 0.0;  // hard_target_peak with the two-way transmittance to it
  };
  // The beam's fog stretches (one per active layer it crosses before its hard surface, with that
  // layer's index in `stretch_layers`) and hit.
  Hit trace(std::size_t beam, const propagation::ActiveLayers& active,
            std::span<const double> optical_depth_factors, std::vector<FogStretch>& stretches,
            std::vector<std::int32_t>& stretch_layers) const;
  void check_inputs(const propagation::ActiveLayers& active,
                    std::span<const double> optical_depth_factors) const;

  LidarParams params_;
  std::vector<Shape> shapes_;
  std::vector<Layer> layers_;
  double target_range_m_ = 0.0;
  std::size_t beam_count_ = 0;
  std::size_t target_beam_ = 0;
  std::size_t samples_ = 0;
  WaveformGrid grid_;
  FogReturn fog_return_{WaveformGrid{}};
  EchoDetector detector_;
  double noise_std_ = 0.0;
  double window_two_way_transmittance_ = 1.0;  // the window's water film, out and back
};

}  // namespace fogradar::lidar
