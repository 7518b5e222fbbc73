// One radar measurement (one frame) of a scene in the fog chamber: the entry point the experiment
// drives. The chain object holds everything made once (FFT plans, windows, CFAR threshold) and is
// immutable, so one chain serves all threads; each thread brings its own workspace and stream.
#pragma once

#include <complex>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "fogradar/core/random.hpp"
#include "fogradar/core/stop.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/radar/attribution.hpp"
#include "fogradar/radar/estimation.hpp"
#include "fogradar/radar/processing.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/radar/synthesis.hpp"

namespace fogradar::radar {

struct Measurement {
  std::vector<Detection> detections;  // each with its origin (and, for fog, its layer)
  // The strongest detection within the association gate around the chamber's target range, or
  // nothing: a missed detection is reported as such, never as a made-up value (docs/scenario.md).
  // This is what a tracker associates, whatever its origin: a noise or fog detection in the gate is
  // a false association, which the caller tells from target->origin.
  std::optional<Detection> target;
  SynthesisReport synthesis;
};

struct MeasurementWorkspace {
  ComplexVector frame;
  ComplexVector chirp;        // one chirp, for the range FFT chirp by chirp (ChirpTransform)
  std::vector<double> power;  // filled by synthesize_and_process only; measure does not need it
  std::vector<Tone> tones;
  EstimationWorkspace estimation;
  // The beat's parts, sized when a tap asks for them (FrameTaps::signal, noise).
  std::vector<std::complex<double>> signal, noise;
};

// What RadarChain::measure shows of a frame on its way (raw data, docs/data-out.md): the beat
// signal as synthesised (chirps x samples, chirp-major, before the window), its two parts
// (synthesis.hpp, FrameParts: the thermal noise as drawn, and the rest) and the complex
// range-Doppler map (Doppler rows in FFT order x range columns; the CFAR sees its |.|^2). An empty
// tap costs nothing; with a beat, signal or noise tap the frame is windowed and range transformed
// after the synthesis instead of during it, which gives the same bits (synthesis.hpp,
// transform_windowed).
struct FrameTaps {
  std::function<void(std::span<const std::complex<double>>)> beat;
  std::function<void(std::span<const std::complex<double>>)> signal;
  std::function<void(std::span<const std::complex<double>>)> noise;
  std::function<void(std::span<const std::complex<double>>)> range_doppler;
};

class RadarChain {
 public:
  // Throws Stopped when `stop` is asked for while the CFAR threshold is designed.
  explicit RadarChain(const RadarParams& params, FftPlanner planner = FftPlanner::shipped_wisdom,
                      const StopToken& stop = StopToken());

  const RadarParams& params() const { return params_; }
  const RadarDerived& derived() const { return derived_; }
  const RangeDopplerProcessor& processor() const { return processor_; }
  const CfarDetector& cfar() const { return cfar_; }
  const OriginClassifier& origin_classifier() const { return origin_classifier_; }

  // Validates the scene, then throws InvalidParameter if the chamber was resolved at another
  // frequency than the radar's sweep centre ("chamber.frequency_hz"), a centre lies at or behind
  // the radar ("target.centres[i].range_offset_m"), or the scene reaches beyond the radar's
  // unambiguous range minus 1 m ("chamber.target_range_m").
  void check_compatible(const Scene& scene, const propagation::Chamber& chamber) const;

  // Throws Stopped, nothing kept, when `stop` says stop while the frame's buffer is zeroed (a
  // 65536 x 4096 frame's 4 GiB take seconds).
  MeasurementWorkspace make_workspace(const StopToken& stop = {}) const;

  // Synthesise, process and estimate one frame, and attribute each detection to its origin from the
  // frame's tones (OriginClassifier); `out` is overwritten (its buffers reused).
  void measure(const Scene& scene, const propagation::Chamber& chamber,
               const propagation::ActiveLayers& active, RandomStream& rng,
               MeasurementWorkspace& workspace, Measurement& out) const;
  // The same, showing the frame to `taps` on its way; throws Stopped, `out` part written, when
  // `stop` says stop: looked at before the frame, between the Doppler FFT's column blocks and
  // between the estimator's objects.
  void measure(const Scene& scene, const propagation::Chamber& chamber,
               const propagation::ActiveLayers& active, RandomStream& rng,
               MeasurementWorkspace& workspace, Measurement& out, const FrameTaps& taps,
               const StopToken& stop = {}) const;

  // Only the synthesis and processing stages: leaves the range-Doppler map in workspace.frame and
  // its power in workspace.power (for tests and benchmarks of the map itself).
  SynthesisReport synthesize_and_process(const Scene& scene, const propagation::Chamber& chamber,
                                         const propagation::ActiveLayers& active, RandomStream& rng,
                                         MeasurementWorkspace& workspace) const;

 private:
  // Synthesis and the transforms: the range-Doppler map in workspace.frame.
  SynthesisReport synthesize_and_transform(const Scene& scene, const propagation::Chamber& chamber,
                                           const propagation::ActiveLayers& active,
                                           RandomStream& rng, MeasurementWorkspace& workspace,
                                           const FrameTaps* taps, const StopToken& stop = {}) const;

  RadarParams params_;
  RadarDerived derived_;
  RangeDopplerProcessor processor_;
  CfarDetector cfar_;
  OriginClassifier origin_classifier_;
};

}  // namespace fogradar::radar
