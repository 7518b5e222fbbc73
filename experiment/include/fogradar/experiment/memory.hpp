// The memory a run needs, decided before anything large is allocated: `fogradar run` refuses a
// scenario whose estimate exceeds a limit (docs/scenario.md, "Memory limit") instead of allocating
// until the machine runs out or failing with std::bad_alloc part way through.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "fogradar/experiment/scenario.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

// Code, the shared libraries' data, the Segelstein table and thread stacks as touched: the resident
// size of `fogradar run` on a 16 x 1 frame is about 8 MiB (docs/scenario.md); twice that for
// margin.
inline constexpr std::size_t process_baseline_bytes = std::size_t{16} << 20;

// Peak memory of run_experiment plus writing the results: each running sensor's own estimate
// (sensor::ConfiguredSensor::memory) with the threads the run starts, and the process itself. An
// upper estimate from buffer sizes, not a measurement; docs/scenario.md gives its ratio to measured
// peak RSS.
struct MemoryEstimate {
  struct Part {
    std::string sensor;
    sensor::MemoryPart memory;
  };
  unsigned threads = 0;  // worker threads the run will use
  std::vector<Part> sensors;
  std::size_t process_bytes = process_baseline_bytes;
  std::size_t total_bytes() const;
};

// The threads run_experiment starts: `requested` (0: all hardware threads), at most one per item
// (every running sensor's items together).
unsigned worker_threads(unsigned requested, std::size_t items);

// Estimate for `scenario` run with `requested_threads` (as RunOptions::threads). The scenario must
// be valid.
MemoryEstimate estimate_peak_memory(const Scenario& scenario, unsigned requested_threads);

// Half the physical memory (sysconf(_SC_PHYS_PAGES) x page size): the default limit.
std::size_t default_memory_limit_bytes();

// Throws InvalidParameter, when estimate_peak_memory(scenario, requested_threads) exceeds
// limit_bytes, naming the estimate, the limit, --threads and each running sensor's part with its
// keys and values (e.g. the radar's radar.samples_per_chirp, radar.chirps_per_frame and
// radar.measurements_per_step). Its field is the key of the largest part.
void require_memory_within(const Scenario& scenario, unsigned requested_threads,
                           std::size_t limit_bytes);

}  // namespace fogradar::experiment
