// The study's methodology (paper sec. III-A): for k = 0 .. max_active_layers layers switched on in
// order from the sensor, a series of items per sensor of the scenario (radar measurements, lidar
// scans, camera frames: whatever each registered sensor measures), all on one chamber. Item (k, i)
// of a sensor draws from its own random stream sensor_stream(seed, its stream key, k, i), and
// results are stored by index, so a run is bit-identical for any thread count and adding a sensor
// never changes another's numbers. One pool of threads takes the items of every sensor from one
// counter. Frames are streamed: only one per thread exists at a time.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/experiment/raw.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

// One sensor of a run, as experiment.sensors names it.
struct SensorRunEntry {
  std::shared_ptr<const sensor::SensorType> type;
  std::shared_ptr<sensor::SensorRun> run;
};

struct ExperimentResult {
  std::vector<SensorRunEntry> sensors;  // that ran, in experiment.sensors' order

  // The run of the sensor named `name` (InvalidParameter when it did not run).
  const sensor::SensorRun& run(std::string_view name) const;
};

struct RunOptions {
  unsigned threads = 0;  // 0: all hardware threads
  // Called from worker threads with (items done, total), the items of every sensor counted; may be
  // empty.
  std::function<void(std::size_t, std::size_t)> progress;
  // When set (by another thread, e.g. one that waits for signals), the workers stop at their next
  // item and run_experiment throws Interrupted. May be null.
  const std::atomic<bool>* stop = nullptr;
  // Where the items' raw data goes (its plan resolved for this scenario), or null for none.
  RawFile* raw = nullptr;
};

// Thrown by run_experiment when RunOptions::stop was set: there is no partial result.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// Runs the whole experiment. Throws InvalidParameter for an invalid or inconsistent scenario,
// Interrupted when stopped.
ExperimentResult run_experiment(const Scenario& scenario, const RunOptions& options = {});

// The items `fogradar run` measures, in words ("radar measurements, lidar scans and camera
// frames"), for progress.
std::string item_nouns(const Scenario& scenario);

}  // namespace fogradar::experiment
