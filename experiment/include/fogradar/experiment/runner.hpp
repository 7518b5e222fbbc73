// The study's methodology (paper sec. III-A): for k = 0 .. max_active_layers layers switched on in
// order from the sensor, a series of items per sensor of the scenario (radar measurements, each a
// full radar frame; lidar scans; camera frames), all on one chamber. Item (k, i) of a sensor draws
// from its own random stream sensor_stream(seed, sensor, k, i) (the radar's is RandomStream(seed,
// k, i)), and results are stored by index, so a run is bit-identical for any thread count and
// adding a sensor never changes another's numbers. One pool of threads takes the items of every
// sensor from one counter. Frames are streamed: only one per thread exists at a time.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "fogradar/camera/camera.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/radar/origin.hpp"

namespace fogradar::experiment {

// What the tracker reports for one measurement, with the simulation's ground truth beside it.
struct MeasurementRecord {
  // A detection inside the association gate (the strongest there): what a tracker associates.
  bool associated = false;
  radar::Origin associated_origin = radar::Origin::noise;  // only meaningful when associated
  // A target detection: associated, and the associated detection's origin is target. A fog or
  // noise detection in the gate is a false association and counts as a miss.
  bool detected = false;
  double range_m = 0.0;  // of the associated detection; only meaningful when associated
  double rcs_dbsm = 0.0;
  double snr_db = 0.0;
  // A fog-origin detection echoes at least as strongly (received power) as the target detection,
  // or there is no target detection at all: the sensor cannot tell target from fog.
  bool fog_rivals_target = false;
  std::size_t fog_detections = 0;  // fog-origin detections anywhere in the map
  std::size_t false_alarms = 0;    // noise-origin detections anywhere in the map
};

struct StepResult {
  std::size_t active_layers = 0;
  double two_way_attenuation_db = 0.0;  // to the target through the active layers
  std::vector<MeasurementRecord> records;
};

struct ExperimentResult {
  std::vector<SensorId> sensors;  // that ran, as experiment.sensors lists them
  // The radar's part; empty (and the two figures 0) when the radar does not run.
  std::vector<StepResult> steps;
  double cfar_threshold_db = 0.0;  // 10 log10(alpha): detection needs SNR above about this
  // The CFAR's design: P_fa times the cells it tests per frame (every cell of the map). Counts
  // cells; a detection is an 8-connected object of cells, so noise detections per frame come out
  // at most this (fewer where the window correlates neighbouring cells).
  double expected_false_alarm_cells_per_frame = 0.0;

  // The lidar's part when it ran: the sensor as built for the run (its result files need its
  // geometry and derived figures) and one result per step, scans by index.
  std::shared_ptr<const lidar::Lidar> lidar;
  std::vector<lidar::LidarStepResult> lidar_steps;
  // The camera's part when it ran: the sensor and one result per step, frames by index.
  std::shared_ptr<const camera::Camera> camera;
  std::vector<camera::CameraStepResult> camera_steps;
};

struct RunOptions {
  unsigned threads = 0;  // 0: all hardware threads
  // Called from worker threads with (items done, total), the items of every sensor counted; may be
  // empty.
  std::function<void(std::size_t, std::size_t)> progress;
  // When set (by another thread, e.g. one that waits for signals), the workers stop at their next
  // item and run_experiment throws Interrupted. May be null.
  const std::atomic<bool>* stop = nullptr;
};

// Thrown by run_experiment when RunOptions::stop was set: there is no partial result.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// Runs the whole experiment. Throws InvalidParameter for an invalid or inconsistent scenario,
// Interrupted when stopped.
ExperimentResult run_experiment(const Scenario& scenario, const RunOptions& options = {});

}  // namespace fogradar::experiment
