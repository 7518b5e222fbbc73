#include "fogradar/experiment/memory.hpp"

#include <unistd.h>

#include <algorithm>
#include <complex>
#include <cstdint>
#include <sstream>
#include <thread>

#include "fogradar/camera/camera.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/scene.hpp"

namespace fogradar::experiment {
namespace {

constexpr std::size_t complex_bytes = sizeof(std::complex<double>);
constexpr std::size_t double_bytes = sizeof(double);
// Code, the shared libraries' data, the Segelstein table and thread stacks as touched: the resident
// size of `fogradar run` on a 16 x 1 frame is about 8 MiB (docs/scenario.md); twice that for
// margin.
constexpr std::size_t process_baseline_bytes = std::size_t{16} << 20;
// Doppler transforms run on blocks of at most this many columns (radar/src/fft.cpp,
// ColumnBlockFft).
constexpr std::size_t doppler_block_columns = 32;
// Objects whose rows the estimator interpolates in one pass (radar/src/estimation.cpp).
constexpr std::size_t interpolation_batch = 4;

double mib(std::size_t bytes) {
  return static_cast<double>(bytes) / static_cast<double>(std::size_t{1} << 20);
}

}  // namespace

unsigned worker_threads(unsigned requested, std::size_t measurements) {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(
      std::min<std::size_t>(requested == 0 ? hardware : requested, measurements));
}

MemoryEstimate estimate_peak_memory(const Scenario& scenario, unsigned requested_threads) {
  const std::size_t samples = scenario.radar.samples_per_chirp,
                    chirps = scenario.radar.chirps_per_frame;
  const std::size_t cells = samples * chirps;
  const std::size_t steps = scenario.experiment.max_active_layers + 1;
  const bool radar = scenario.runs(SensorId::radar);
  const std::size_t measurements = radar ? steps * scenario.experiment.measurements_per_step : 0;
  // One pool takes every sensor's items (runner.cpp): the thread count follows from all of them.
  std::size_t items = measurements;
  if (scenario.runs(SensorId::lidar)) items += steps * scenario.lidar.scans_per_step;
  if (scenario.runs(SensorId::camera)) items += steps * scenario.camera.frames_per_step;
  MemoryEstimate e;
  e.threads = worker_threads(requested_threads, items);
  if (scenario.runs(SensorId::lidar))
    e.lidar_bytes = lidar::lidar_memory_bytes(scenario.lidar, steps, e.threads);
  if (scenario.runs(SensorId::camera))
    e.camera_bytes = camera::memory_bytes(scenario.camera, steps);

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
      one_row_cfar + radar::CfarFourWorkspace::profiles * 5 * samples * double_bytes + one_row_cfar;
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
  const std::size_t tones =
      2 * sizeof(radar::Tone) * (scenario.clutter_scatterers_per_bin * samples + 64);
  e.per_thread_bytes = radar ? frame + cfar + estimation + doppler_block + tones : 0;

  // Shared: the windows (range, Doppler, range pairs), both window spectra (16 x oversampled
  // complex tables, OriginClassifier) and the FFT plans (about two complex twiddles per point and
  // axis).
  const std::size_t windows = (3 * samples + chirps) * double_bytes;
  const std::size_t spectra = 16 * (samples + chirps + 2) * complex_bytes;
  const std::size_t plans = 2 * (samples + chirps) * complex_bytes;
  e.shared_bytes = windows + spectra + plans + process_baseline_bytes;

  e.records_bytes = measurements * sizeof(MeasurementRecord);
  return e;
}

std::size_t default_memory_limit_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_bytes = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_bytes <= 0) return SIZE_MAX;  // unknown: no default limit
  return static_cast<std::size_t>(pages) / 2 * static_cast<std::size_t>(page_bytes);
}

void require_memory_within(const Scenario& scenario, unsigned requested_threads,
                           std::size_t limit_bytes) {
  const MemoryEstimate estimate = estimate_peak_memory(scenario, requested_threads);
  if (estimate.total_bytes() <= limit_bytes) return;
  std::ostringstream out;
  out.precision(6);
  out << "the run needs an estimated " << mib(estimate.total_bytes()) << " MiB with --threads "
      << requested_threads << " (" << estimate.threads << " workers), more than the limit of "
      << mib(limit_bytes) << " MiB (--memory-limit-mib; default half the physical memory): ";
  const std::size_t radar_bytes =
      estimate.threads * estimate.per_thread_bytes + estimate.records_bytes;
  std::string field = "radar.samples_per_chirp";
  std::size_t largest = 0;
  if (scenario.runs(SensorId::radar)) {
    out << "radar " << mib(radar_bytes)
        << " MiB (radar.samples_per_chirp = " << scenario.radar.samples_per_chirp
        << " x radar.chirps_per_frame = " << scenario.radar.chirps_per_frame << ": "
        << estimate.threads << " x " << mib(estimate.per_thread_bytes)
        << " MiB frame workspace; experiment.measurements_per_step = "
        << scenario.experiment.measurements_per_step << ": " << mib(estimate.records_bytes)
        << " MiB per-measurement records), ";
    largest = radar_bytes;
  }
  if (scenario.runs(SensorId::lidar)) {
    out << "lidar " << mib(estimate.lidar_bytes)
        << " MiB (lidar.scans_per_step = " << scenario.lidar.scans_per_step << " of "
        << scenario.lidar.beam_count()
        << " beams: lidar.field_of_view_deg = " << scenario.lidar.field_of_view_deg
        << " / lidar.angular_step_deg = " << scenario.lidar.angular_step_deg << "), ";
    if (estimate.lidar_bytes > largest) {
      field = "lidar.scans_per_step";
      largest = estimate.lidar_bytes;
    }
  }
  if (scenario.runs(SensorId::camera)) {
    out << "camera " << mib(estimate.camera_bytes)
        << " MiB (camera.frames_per_step = " << scenario.camera.frames_per_step
        << " of camera.roi.width_px = " << scenario.camera.roi.width_px
        << " x camera.roi.height_px = " << scenario.camera.roi.height_px << "), ";
    if (estimate.camera_bytes > largest) field = "camera.frames_per_step";
  }
  out << mib(estimate.shared_bytes) << " MiB shared; reduce these";
  throw InvalidParameter(field, out.str());
}

}  // namespace fogradar::experiment
