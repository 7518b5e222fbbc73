// The memory a run needs, decided before anything large is allocated: `fogradar run` refuses a
// scenario whose estimate exceeds a limit (docs/scenario.md, "Memory limit") instead of allocating
// until the machine runs out or failing with std::bad_alloc part way through.
#pragma once

#include <cstddef>

#include "fogradar/experiment/scenario.hpp"

namespace fogradar::experiment {

// Peak memory of run_experiment plus write_outputs, by part. An upper estimate from the sizes of
// the buffers the chain keeps (radar/include/fogradar/radar/measurement.hpp, estimation.hpp,
// cfar.hpp, attribution.hpp), not a measurement; docs/scenario.md gives its ratio to measured peak
// RSS.
struct MemoryEstimate {
  unsigned threads = 0;              // worker threads the run will use
  std::size_t per_thread_bytes = 0;  // frame, detection mask, CFAR and estimation workspaces, tones
  std::size_t shared_bytes = 0;      // windows, window spectra, FFT plans, process baseline
  std::size_t records_bytes = 0;     // one MeasurementRecord per measurement
  // The lidar's and the camera's own estimates (lidar_memory_bytes, camera::memory_bytes), threads
  // included; 0 when they do not run.
  std::size_t lidar_bytes = 0;
  std::size_t camera_bytes = 0;
  std::size_t total_bytes() const {
    return threads * per_thread_bytes + shared_bytes + records_bytes + lidar_bytes + camera_bytes;
  }
};

// The threads run_experiment starts: `requested` (0: all hardware threads), at most one per item
// (radar measurements, lidar scans and camera frames together).
unsigned worker_threads(unsigned requested, std::size_t measurements);

// Estimate for `scenario` run with `requested_threads` (as RunOptions::threads). The scenario must
// be valid.
MemoryEstimate estimate_peak_memory(const Scenario& scenario, unsigned requested_threads);

// Half the physical memory (sysconf(_SC_PHYS_PAGES) x page size): the default limit.
std::size_t default_memory_limit_bytes();

// Throws InvalidParameter, when estimate_peak_memory(scenario, requested_threads) exceeds
// limit_bytes, naming the estimate, the limit, --threads and each running sensor's part with its
// keys and values: the radar's radar.samples_per_chirp, radar.chirps_per_frame and
// experiment.measurements_per_step, the lidar's lidar.scans_per_step and its beams
// (lidar.field_of_view_deg / lidar.angular_step_deg), the camera's camera.frames_per_step and
// camera.roi.width_px x camera.roi.height_px. Its field is the first key of the largest part
// ("radar.samples_per_chirp", "lidar.scans_per_step" or "camera.frames_per_step").
void require_memory_within(const Scenario& scenario, unsigned requested_threads,
                           std::size_t limit_bytes);

}  // namespace fogradar::experiment
