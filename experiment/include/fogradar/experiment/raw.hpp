// Every measurement's data out (docs/data-out.md): which of the raw data the sensors
// offer (sensor::RawKind) a run keeps — the kinds, steps and items `fogradar run --raw FILE.h5
// --raw-select --raw-steps --raw-items` choose — with its size estimated and refused over a limit
// before the run, and where the kept items go while it runs (RawSinks: the HDF5 file of
// raw_file.hpp, or memory for the Python module).
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/experiment/scenario.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

// What the user asked for (the options as typed are checked by resolve_raw).
struct RawRequest {
  std::filesystem::path path;  // --raw
  std::string kinds;           // --raw-select: "radar.beat,lidar.echoes"; empty: every kind
  std::string steps;           // --raw-steps: "0,4", "0-2,4"; empty: every step
  std::string items;           // --raw-items; empty: the first ten (fewer where there are)
  double limit_mib = 4096.0;   // --raw-limit-mib
};

// The request resolved against a scenario: per running sensor, the kinds, steps and items kept.
struct RawPlan {
  struct Sensor {
    std::string name;
    std::vector<sensor::RawKind> kinds;  // the sensor's kinds (raw_kinds)
    std::vector<std::size_t> chosen;     // indices into `kinds`
    std::vector<std::size_t> items;      // item indices kept (below the sensor's count)
  };
  std::filesystem::path path;
  std::vector<Sensor> sensors;     // in experiment.sensors' order; those with nothing chosen too
  std::vector<std::size_t> steps;  // step indices kept, ascending
  std::size_t bytes = 0;           // estimated size of the data
};

// Checks the options against the scenario (throws InvalidParameter naming "--raw-select",
// "--raw-steps" or "--raw-items" with the value as typed and what is allowed, or "--raw-limit-mib"
// when the estimate exceeds the limit, naming the estimate and the options that set it). A list
// is comma-separated indices and ranges "a-b".
RawPlan resolve_raw(const Scenario& scenario, const RawRequest& request);

// Where the items' raw data goes during a run (RunOptions::raw): the sink of item `index` of step
// `step` of the sensor at `sensor` (its position in experiment.sensors), or null when nothing of
// that item is kept. Called from the worker threads; a sink lives until its item is measured.
class RawSinks {
 public:
  virtual ~RawSinks() = default;
  virtual std::unique_ptr<sensor::RawSink> sink(std::size_t sensor, std::size_t step,
                                                std::size_t index) = 0;
};

}  // namespace fogradar::experiment
