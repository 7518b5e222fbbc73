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
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/experiment/raw.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

// One sensor instance of a run, as experiment.sensors names it: its name and random streams' key,
// its kind, configured for the scenario, made, and its run.
struct SensorRunEntry {
  std::string name;
  std::uint64_t stream_key = 0;
  std::shared_ptr<const sensor::SensorKind> kind;
  std::shared_ptr<const sensor::ConfiguredSensor> configured;
  std::shared_ptr<const sensor::Sensor> sensor;
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
  // item or inside a long one (StopToken), dropping it, and run_experiment throws
  // Interrupted. May be null.
  const std::atomic<bool>* stop = nullptr;
  // Where the items' raw data goes (its plan resolved for this scenario), or null for none.
  RawSinks* raw = nullptr;
};

// Thrown by run_experiment when RunOptions::stop was set: there is no partial result.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// What a sensor is made from, as text: its own keys and the chamber's, fog's and experiment's, as
// the resolved scenario writes them (the other sensors at their defaults). SensorCache's key.
std::string sensor_identity(const Scenario& scenario, const SensorSetting& setting);

// Sensors kept from one scenario for the next (a sweep's points): a scenario whose sensor keys and
// chamber, fog and experiment keys equal an earlier one's gets that sensor again, its optics,
// plans and tables made once. Holds the most recent few; safe to share between threads.
class SensorCache {
 public:
  static constexpr std::size_t capacity = 16;
  // The cached sensor, or one `configured` makes now (throws Stopped when `stop` is asked for while
  // it is made).
  std::shared_ptr<const sensor::Sensor> sensor(const Scenario& scenario,
                                               const SensorSetting& setting,
                                               const sensor::ConfiguredSensor& configured,
                                               const propagation::SegelsteinTable& water,
                                               const StopToken& stop = StopToken());

 private:
  std::mutex mutex_;
  std::vector<std::pair<std::string, std::shared_ptr<const sensor::Sensor>>> made_;  // newest last
};

// A scenario's sensors made once (sensor::Sensor: chamber, plans, CFAR design, optics), then run
// as often as wanted, whole or one item at a time. Const and safe to share between threads; every
// run is its own.
class Simulation {
 public:
  // Validates the scenario (InvalidParameter) and makes every sensor experiment.sensors names.
  explicit Simulation(Scenario scenario);
  // The same with a water table made once for many simulations, and sensors from `cache` where it
  // has them. When `stop` (RunOptions::stop) is set while a sensor is made (the radar's CFAR design
  // can take a while), throws Interrupted.
  Simulation(Scenario scenario, const propagation::SegelsteinTable& water, SensorCache* cache,
             const std::atomic<bool>* stop = nullptr);

  const Scenario& scenario() const { return scenario_; }
  const sensor::Context& context() const { return context_; }

  // Every item of every sensor, on RunOptions::threads threads. Throws Interrupted when stopped.
  ExperimentResult run(const RunOptions& options = {}) const;

  // One sensor's run for items measured one at a time (ItemRun); InvalidParameter naming "sensor"
  // for a sensor that does not run.
  SensorRunEntry begin_run(std::string_view sensor) const;

 private:
  Scenario scenario_;
  sensor::Context context_;
  std::vector<SensorRunEntry> sensors_;  // in experiment.sensors' order, without runs
};

// Items of one sensor measured one at a time, each exactly as a run measures it (the same random
// stream, the same numbers): the items of a step, or single items, with their raw data.
class ItemRun {
 public:
  ItemRun(const Simulation& simulation, std::string_view sensor);

  std::size_t steps() const { return steps_; }
  std::size_t items_per_step() const { return items_per_step_; }
  // The raw data kinds the sensor offers (sensor::ConfiguredSensor::raw_kinds).
  const std::vector<sensor::RawKind>& raw_kinds() const { return kinds_; }
  // Measures item `index` of step `step` into `raw` (may be null); InvalidParameter naming "step"
  // or "index" out of range. Prepares the step the first time one of its items is measured.
  void measure(std::size_t step, std::size_t index, sensor::RawSink* raw);

 private:
  SensorRunEntry entry_;
  std::uint64_t seed_ = 0;
  std::size_t steps_ = 0;
  std::size_t items_per_step_ = 0;
  std::vector<sensor::RawKind> kinds_;
  std::vector<bool> prepared_;
  std::unique_ptr<sensor::Worker> worker_;
};

// Runs the whole experiment (Simulation(scenario).run(options)). Throws InvalidParameter for an
// invalid or inconsistent scenario, Interrupted when stopped.
ExperimentResult run_experiment(const Scenario& scenario, const RunOptions& options = {});

// The items `fogradar run` measures, in words ("radar measurements, lidar scans and camera
// frames"), for progress.
std::string item_nouns(const Scenario& scenario);

}  // namespace fogradar::experiment
