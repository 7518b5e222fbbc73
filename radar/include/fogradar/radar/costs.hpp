// The radar's cost models, for the run's estimates (its configured sensor's memory and cost):
// the peak memory of its part of a run and the CPU time of its work besides the frames.
#pragma once

#include <cstddef>

#include "fogradar/radar/sensor.hpp"

namespace fogradar::radar {

// Peak memory of the radar's part of a run, by part: an upper estimate from the sizes of the
// buffers the chain keeps (measurement.hpp, estimation.hpp, cfar.hpp, attribution.hpp), not a
// measurement; docs/scenario.md gives its ratio to measured peak RSS.
struct MemoryEstimate {
  std::size_t per_thread_bytes = 0;  // frame, detection mask, CFAR and estimation workspaces, tones
  std::size_t shared_bytes = 0;      // windows, window spectra, FFT plans
  std::size_t records_bytes = 0;     // per measurement: its record, detections and CSV rows
};
MemoryEstimate memory_estimate(const SensorParams& params, std::size_t measurements);

// The CPU time of the radar's work in a run besides its frames (sensor::SetupTime), from a cost
// model in parts whose constants bench/estimate_calibration measures (docs/scenario.md, "Time
// limit").
struct SetupCost {
  double fog_seconds = 0.0;          // the chamber: each distinct fog resolved and its Mie sum at
                                     // the sweep centre (propagation::bulk_optics_seconds)
  double chain_seconds = 0.0;        // the RadarChain's plans, windows and noise correlation
  double cfar_design_seconds = 0.0;  // its CFAR threshold factors (cfar_design.hpp)
  double summary_seconds = 0.0;      // each run's summary (box plots, Hodges-Lehmann pairs)
  double report_seconds = 0.0;       // the fog reports of summary.json and the result files
};
SetupCost setup_cost(const SensorParams& params, const sensor::Context& context);

}  // namespace fogradar::radar
