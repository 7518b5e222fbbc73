#include "fogradar/radar/measurement.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/radar/cfar_design.hpp"

namespace fogradar::radar {

// The range CFAR runs along range in every Doppler row, so its cells are correlated by the range
// window (noise_correlation.hpp); the widest reference geometry spans guard + N cells. The
// range_doppler ring's cells are correlated by the Doppler window too.
RadarChain::RadarChain(const RadarParams& params, FftPlanner planner, const StopToken& stop)
    : params_(params),
      derived_(derive(params)),
      processor_(params, planner),
      cfar_(params.cfar,
            window_noise_correlation(processor_.range_window(), cfar_correlation_lags(params.cfar)),
            params.cfar.shape == CfarShape::range
                ? NoiseCorrelation{}
                : window_noise_correlation(processor_.doppler_window(),
                                           cfar_doppler_correlation_lags(params.cfar)),
            stop),
      origin_classifier_(processor_, params_, derived_) {}

void RadarChain::check_compatible(const Scene& scene, const propagation::Chamber& chamber) const {
  scene.validate();
  if (std::abs(chamber.frequency_hz() - params_.centre_frequency_hz) >
      1e-6 * params_.centre_frequency_hz) {
    throw_invalid(
        "chamber.frequency_hz", chamber.frequency_hz(),
        "equal to radar.centre_frequency_hz = " + std::to_string(params_.centre_frequency_hz));
  }
  for (std::size_t i = 0; i < scene.centres.size(); ++i) {
    const double along_m = chamber.target_range_m() + scene.centres[i].range_offset_m;
    // A centre at or behind the radar has no meaningful radar equation (R^-4 diverges at 0).
    if (!(along_m > 0.0)) {
      throw_invalid(
          "target.centres[" + std::to_string(i) + "].range_offset_m",
          scene.centres[i].range_offset_m,
          "> -" + std::to_string(chamber.target_range_m()) +
              " (minus the chamber's target range): the centre must lie in front of the radar");
    }
  }
  scene.check_room(chamber.target_range_m());
  // The target's and the room's own echoes must have their beat frequencies inside [0, fs): the
  // 1 m margin covers micro-motion and, at chamber scales, the floor's detour.
  const FarthestEcho farthest = farthest_echo(scene, chamber.target_range_m());
  const double farthest_m = std::max(chamber.target_range_m(), farthest.range_m);
  const double limit_m = derived_.max_range_m - 1.0;
  if (farthest_m > limit_m) {
    throw_invalid(farthest.key == "chamber.target_gap_m" ? "chamber.target_range_m" : farthest.key,
                  farthest.key == "chamber.target_gap_m" ? farthest_m : farthest.value,
                  "< the radar's unambiguous range minus 1 m = " + std::to_string(limit_m) +
                      " m (c fs / (2 S)); raise radar.sample_rate_hz or lower the range");
  }
}

MeasurementWorkspace RadarChain::make_workspace(const StopToken& stop) const {
  MeasurementWorkspace ws;
  // Zeroed in parts of 64 MiB within one allocation, so that a stop is seen between them.
  constexpr std::size_t part = std::size_t{1} << 22;
  const std::size_t values = params_.chirps_per_frame * params_.samples_per_chirp;
  ws.frame.reserve(values);
  while (ws.frame.size() < values) {
    stop.check();
    ws.frame.resize(std::min(values, ws.frame.size() + part));
  }
  ws.chirp.resize(params_.samples_per_chirp);
  return ws;
}

SynthesisReport RadarChain::synthesize_and_transform(const Scene& scene,
                                                     const propagation::Chamber& chamber,
                                                     const propagation::ActiveLayers& active,
                                                     RandomStream& rng, MeasurementWorkspace& ws,
                                                     const FrameTaps* taps,
                                                     const StopToken& stop) const {
  scene_tones(scene, chamber, active, params_, derived_, rng, ws.tones);
  const FrameWindow window = processor_.window();
  SynthesisReport report;
  if (taps != nullptr && (taps->beat || taps->signal || taps->noise)) {
    FrameParts parts;
    if (taps->signal) {
      ws.signal.resize(ws.frame.size());
      parts.signal = ws.signal;
    }
    if (taps->noise) {
      ws.noise.resize(ws.frame.size());
      parts.noise = ws.noise;
    }
    report = synthesize_frame(ws.tones, params_, derived_, rng, ws.frame, nullptr, nullptr, &parts,
                              stop);
    if (taps->beat) taps->beat(ws.frame);
    if (taps->signal) taps->signal(ws.signal);
    if (taps->noise) taps->noise(ws.noise);
    apply_frame_window(window, ws.frame);
    processor_.transform_windowed(ws.frame, ws.chirp);
  } else {
    const ChirpTransform by_chirp{.fft = &processor_.range_chirp_fft(), .chirp = ws.chirp};
    report = synthesize_frame(ws.tones, params_, derived_, rng, ws.frame, &window, &by_chirp,
                              nullptr, stop);
    if (report.range_transformed) {
      processor_.doppler_transform(ws.frame, stop);
    } else {
      processor_.transform_windowed(ws.frame, ws.chirp);
    }
  }
  if (taps != nullptr && taps->range_doppler) taps->range_doppler(ws.frame);
  return report;
}

SynthesisReport RadarChain::synthesize_and_process(const Scene& scene,
                                                   const propagation::Chamber& chamber,
                                                   const propagation::ActiveLayers& active,
                                                   RandomStream& rng,
                                                   MeasurementWorkspace& ws) const {
  const SynthesisReport report = synthesize_and_transform(scene, chamber, active, rng, ws, nullptr);
  ws.power.resize(ws.frame.size());
  squared_magnitudes(ws.frame, ws.power);
  return report;
}

void RadarChain::measure(const Scene& scene, const propagation::Chamber& chamber,
                         const propagation::ActiveLayers& active, RandomStream& rng,
                         MeasurementWorkspace& ws, Measurement& out) const {
  measure(scene, chamber, active, rng, ws, out, FrameTaps{});
}

void RadarChain::measure(const Scene& scene, const propagation::Chamber& chamber,
                         const propagation::ActiveLayers& active, RandomStream& rng,
                         MeasurementWorkspace& ws, Measurement& out, const FrameTaps& taps,
                         const StopToken& stop) const {
  stop.check();
  out.synthesis = synthesize_and_transform(scene, chamber, active, rng, ws, &taps, stop);
  stop.check();
  estimate_detections(ws.frame, processor_, cfar_, params_, derived_, ws.estimation, out.detections,
                      stop);
  origin_classifier_.attribute(ws.tones, out.detections, out.synthesis.clipped_samples > 0);
  out.target.reset();
  for (const Detection& detection : out.detections) {
    if (std::abs(detection.range_m - chamber.target_range_m()) > params_.association_gate_m)
      continue;
    if (!out.target || detection.received_power_w > out.target->received_power_w)
      out.target = detection;
  }
}

}  // namespace fogradar::radar
