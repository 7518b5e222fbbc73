// Every measurement's data out (DESIGN §11, docs/data-out.md): `fogradar run --raw FILE.h5` writes
// the raw data the sensors offer (sensor::RawKind: the radar's beat signal, range-Doppler map and
// detections, the lidar's waveforms and echoes, the camera's images) for the chosen kinds, steps
// and items into one HDF5 file: a group per sensor, each array kind a dataset [step, item, ...]
// chunked one item per chunk, each table kind a compound dataset of rows, with units and the
// resolved scenario as attributes and the axes as dimension scales. Its size is estimated and
// refused over a limit before the run, and the file is written like the result set: complete or
// not at all.
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

// The HDF5 file of one run, written while it runs. Construction refuses (InvalidParameter naming
// "--raw") a path that is a directory, a file fogradar did not write (fogradar never overwrites a
// file of yours), or one another run holds; it locks `.NAME.lock` beside it and creates the file
// under a temporary name there, with every group, dataset and attribute. Workers write their items
// through sinks; finish() writes the tables, closes and fsyncs the file, publish() renames it into
// place. Destruction before publish() removes the temporary file: an interrupted or failed run
// leaves the path as it was.
class RawFile {
 public:
  RawFile(const RawPlan& plan, const Scenario& scenario);
  ~RawFile();
  RawFile(const RawFile&) = delete;
  RawFile& operator=(const RawFile&) = delete;

  // The sink of item `index` of step `step` of the sensor at `sensor` in the plan, or null when
  // nothing of that item is kept. The sink lives until the item is measured.
  std::unique_ptr<sensor::RawSink> sink(std::size_t sensor, std::size_t step, std::size_t index);
  void finish();
  void publish();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fogradar::experiment
