// The study's methodology (paper sec. III-A): for k = 0 .. max_active_layers layers switched on in
// order from the sensor, a series of measurements, each a full radar frame. Measurement (k, i) draws
// from its own random stream RandomStream(seed, k, i), and results are stored by index, so a run is
// bit-identical for any thread count. Frames are streamed: only one per thread exists at a time.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "fogradar/experiment/scenario.hpp"

namespace fogradar::experiment {

// What the tracker reports for one measurement.
struct MeasurementRecord {
  bool detected = false;  // a detection inside the association gate
  double range_m = 0.0;   // only meaningful when detected
  double rcs_dbsm = 0.0;
  double snr_db = 0.0;
  // A detection inside an active fog layer echoes at least as strongly (received power) as the
  // tracked target, or there is no target detection at all: the sensor cannot tell target from fog.
  bool fog_rivals_target = false;
  std::size_t fog_detections = 0;  // detections inside active fog layers
};

struct StepResult {
  std::size_t active_layers = 0;
  double two_way_attenuation_db = 0.0;  // to the target through the active layers
  std::vector<MeasurementRecord> records;
};

struct ExperimentResult {
  std::vector<StepResult> steps;
  double cfar_threshold_db = 0.0;  // 10 log10(alpha): detection needs SNR above about this
};

struct RunOptions {
  unsigned threads = 0;  // 0: all hardware threads
  // Called from worker threads with (measurements done, total); may be empty.
  std::function<void(std::size_t, std::size_t)> progress;
};

// Runs the whole experiment. Throws InvalidParameter for an invalid or inconsistent scenario.
ExperimentResult run_experiment(const Scenario& scenario, const RunOptions& options = {});

}  // namespace fogradar::experiment
