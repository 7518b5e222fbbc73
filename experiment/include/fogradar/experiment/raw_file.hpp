// The HDF5 file of `fogradar run --raw FILE.h5` (docs/data-out.md): a group per
// sensor, each array kind a dataset [active_layers, item, ...] chunked one item per chunk, each
// table kind a compound dataset of rows, with units and the resolved scenario as attributes and the
// axes as dimension scales; written like the result set, complete or not at all. Its own library
// (fogradar::raw_file, linked by the command line) so that only what writes the file links
// libhdf5 (experiment/CMakeLists.txt).
#pragma once

#include <cstddef>
#include <memory>

#include "fogradar/experiment/raw.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

// The HDF5 file of one run, written while it runs. Construction refuses (InvalidParameter naming
// "--raw") a path that is a directory, a file fogradar did not write (fogradar never overwrites a
// file of yours), or one another run holds; it locks `.NAME.lock` beside it and creates the file
// under a temporary name there, with every group, dataset and attribute. Workers write their items
// through sinks; finish() writes the tables, closes and fsyncs the file, publish() renames it into
// place. Destruction before publish() removes the temporary file: an interrupted or failed run
// leaves the path as it was.
class RawFile : public RawSinks {
 public:
  RawFile(const RawPlan& plan, const Scenario& scenario);
  ~RawFile();
  RawFile(const RawFile&) = delete;
  RawFile& operator=(const RawFile&) = delete;

  // The sink of item `index` of step `step` of the sensor at `sensor` in the plan, or null when
  // nothing of that item is kept. The sink lives until the item is measured.
  std::unique_ptr<sensor::RawSink> sink(std::size_t sensor, std::size_t step,
                                        std::size_t index) override;
  void finish();
  void publish();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fogradar::experiment
