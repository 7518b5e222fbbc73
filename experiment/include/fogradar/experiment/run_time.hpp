// The time a run takes, estimated before anything runs: `fogradar run` prints it and refuses a
// scenario over --time-limit (docs/scenario.md, "Time limit") instead of working for hours, or for
// minutes past what its caller waits.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "fogradar/experiment/scenario.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

// A run's wall time from cost models: the process's own part (its start, the scenario read, the
// summary and the result files written, a constant), each running sensor's set-up
// (sensor::ConfiguredSensor::cost's setup: made, its steps prepared, summarised, its fog reports
// and files) and the chamber's part of summary.json, all on one thread; and each sensor's items
// times its own estimate of one (cost's item), shared by the threads the run starts. A cost
// model, not a measurement: docs/scenario.md ("Time limit") gives its ratio to measured wall times
// and the calibration that measured its constants.
struct TimeEstimate {
  struct Part {
    std::string sensor;
    std::size_t items = 0;  // of every step
    sensor::TimePart time;
    sensor::SetupTime setup;
    double cpu_seconds() const;  // of its items
    // Of its set-up in a `fogradar run`: made, run and reported.
    double setup_seconds() const;
  };
  unsigned threads = 0;  // worker threads the run will use
  std::vector<Part> sensors;
  double process_seconds = 0.0;  // the process's constant part (process_seconds())
  double chamber_seconds = 0.0;  // summary.json's chamber: each distinct fog at 550 nm
  double cpu_seconds() const;    // of every item
  // The items' CPU seconds shared by the threads, but never less than the longest item: one
  // thread measures an item.
  double items_wall_seconds() const;
  // Everything but the items, on one thread: the process, every sensor's set-up, the chamber.
  double setup_seconds() const;
  double wall_seconds() const;  // setup_seconds() + items_wall_seconds()
  // "193 ms on 2 threads (radar 1000 x 148 us, lidar 200 x 200 us, camera 50 x 134 us; set-up
  // and files 95.3 ms)", as `fogradar run` prints it.
  std::string text() const;
};

// What a process of fogradar costs beyond its modelled work (its start, the libraries loaded, the
// scenario read, the result set's directory written and synced): a constant measured by
// bench/estimate_calibration.
double process_seconds();

// Estimate for `scenario` run with `requested_threads` (as RunOptions::threads). The scenario must
// be valid.
TimeEstimate estimate_run_time(const Scenario& scenario, unsigned requested_threads);

// The wall time of `runs` run one after another in one process without result sets (a sweep's
// runs; the sweep's tables take the place of the result set): the process once; each run's items,
// its sensors' runs and summary.json's chamber never; and a sensor's making only where a
// SensorCache holds no equal sensor from a recent run.
struct RunsEstimate {
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;  // of every thread: the wall time's set-up plus every item
};
RunsEstimate estimate_runs(const std::vector<const Scenario*>& runs, unsigned requested_threads);

// Throws InvalidParameter, when estimate_run_time(scenario, requested_threads) exceeds
// limit_seconds, naming the estimate, --time-limit and each running sensor's part with its keys and
// values. Its field is the key that dominates: when a sensor's set-up is the largest part, its
// set-up's key (radar.processing.cfar.threshold_design); else, of the sensor whose items cost most,
// the key of its item size when one of its items alone exceeds the limit
// (lidar.sample_interval_ns), else that of its item count (lidar.scans_per_step).
void require_time_within(const Scenario& scenario, unsigned requested_threads,
                         double limit_seconds);

}  // namespace fogradar::experiment
