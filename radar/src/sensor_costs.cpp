// The radar's memory estimate and the cost of a run besides its frames (setup_cost).
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fogradar/propagation/fog.hpp"
#include "fogradar/propagation/room_spec.hpp"
#include "fogradar/radar/cfar_design.hpp"
#include "fogradar/radar/costs.hpp"
#include "fogradar/radar/window.hpp"

namespace fogradar::radar {
namespace {

constexpr std::size_t complex_bytes = sizeof(std::complex<double>);
constexpr std::size_t double_bytes = sizeof(double);
// Doppler transforms run on blocks of at most this many columns (fft.cpp, ColumnBlockFft).
constexpr std::size_t doppler_block_columns = 32;
// Objects whose rows the estimator interpolates in one pass (estimation.cpp).
constexpr std::size_t interpolation_batch = 4;

// The rest of a run (setup_cost), CPU seconds measured by bench/estimate_calibration: a chain's
// fixed part (its FFTW wisdom read, the scene) and its part per cell of the frame (windows, plans);
// a summary's part per measurement and per Hodges-Lehmann pair (n_k x n_0 per step); the result
// files' part per measurement (their CSV rows; the box plot and the JSON cost less than the rows).
constexpr double chain_seconds = 1.31e-3;
constexpr double chain_seconds_per_cell = 1.61e-9;
constexpr double summary_seconds_per_measurement = 4.5e-7;
constexpr double summary_seconds_per_pair = 6.4e-10;
constexpr double files_seconds_per_measurement = 7.8e-7;

}  // namespace

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
  const double per_step = static_cast<double>(params.measurements_per_step);
  const double steps = static_cast<double>(context.steps);
  return {
      .fog_seconds = fog_seconds,
      .chain_seconds = chain_seconds + cells * chain_seconds_per_cell,
      .cfar_design_seconds =
          r.cfar.shape == CfarShape::range
              ? cfar_design_seconds(
                    r.cfar, window_noise_correlation(make_window(r.window, r.samples_per_chirp),
                                                     cfar_correlation_lags(r.cfar)))
              : cfar_ring_design_seconds(
                    r.cfar,
                    window_noise_correlation(make_window(r.window, r.samples_per_chirp),
                                             cfar_correlation_lags(r.cfar)),
                    window_noise_correlation(make_window(r.window, r.chirps_per_frame),
                                             cfar_doppler_correlation_lags(r.cfar))),
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
  // The range-Doppler ring (CfarMapWorkspace): the map's power and thresholds, and its detections
  // (index per cell at most).
  const std::size_t ring = params.radar.cfar.shape == CfarShape::range_doppler
                               ? cells * (2 * double_bytes + sizeof(std::size_t))
                               : 0;
  const std::size_t cfar =
      one_row_cfar + CfarFourWorkspace::profiles * 5 * samples * double_bytes + one_row_cfar + ring;
  // Estimation: range kernels (re, im; two values per sample; a batch of objects), the batch's
  // Doppler columns, the rotated peak-search buffers (4 of the longer axis), and per axis a
  // Dirichlet table and an inverse DFT with 2n cosines and 2n sines each.
  const std::size_t estimation = 2 * interpolation_batch * 2 * samples * double_bytes +
                                 interpolation_batch * chirps * complex_bytes +
                                 4 * std::max(samples, chirps) * double_bytes +
                                 2 * 4 * (samples + chirps) * double_bytes;
  // The Doppler transform's packed block buffer.
  const std::size_t doppler_block = doppler_block_columns * chirps * complex_bytes;
  // Tones: every centre's paths (the EVT's five, each at most 41 in a room of five planes: direct,
  // 25 with one direct leg, 15 pairs of first-order legs), the room's own echoes (its objects and
  // back wall) plus the fog clutter, at most clutter_scatterers_per_bin per range bin of the
  // unambiguous range; twice for the vector's growth.
  const std::size_t tones =
      2 * sizeof(Tone) *
      (params.clutter_scatterers_per_bin * samples + 5 * 41 + propagation::max_room_objects + 1);
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

}  // namespace fogradar::radar
