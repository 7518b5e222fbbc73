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

// Each running sensor's items times its own estimate of one (sensor::SensorType::item_time), shared
// by the threads the run starts. The items alone: the process's start, the sensors' set-up (Mie
// sums, FFT plans) and writing the results add about 0.1 s to a paper-sized run. A cost model, not
// a measurement: docs/performance.md gives its ratio to measured wall times.
struct TimeEstimate {
  struct Part {
    std::string sensor;
    std::size_t items = 0;  // of every step
    sensor::TimePart time;
    double cpu_seconds() const;
  };
  unsigned threads = 0;  // worker threads the run will use
  std::vector<Part> sensors;
  double cpu_seconds() const;
  // The CPU seconds shared by the threads, but never less than the longest item: one thread
  // measures an item.
  double wall_seconds() const;
  // "31.7 s on 1 thread (lidar 1 x 31.7 s)", as `fogradar run` prints it.
  std::string text() const;
};

// Estimate for `scenario` run with `requested_threads` (as RunOptions::threads). The scenario must
// be valid.
TimeEstimate estimate_run_time(const Scenario& scenario, unsigned requested_threads);

// Throws InvalidParameter, when estimate_run_time(scenario, requested_threads) exceeds
// limit_seconds, naming the estimate, --time-limit and each running sensor's part with its keys and
// values. Its field is the key that dominates: that of the largest part's item size when one of
// its items alone exceeds the limit (lidar.sample_interval_ns), else that of its item count
// (lidar.scans_per_step).
void require_time_within(const Scenario& scenario, unsigned requested_threads,
                         double limit_seconds);

}  // namespace fogradar::experiment
