// Result files of `fogradar run` (docs/scenario.md, Results): the radar's samples.csv, summary.csv,
// rcs_boxplot.svg; summary.json (every sensor's summary and limit) and scenario.toml; each further
// sensor's files prefixed with its name; benchmark.svg. The output directory is the run's result
// set and is replaced whole: the files are written to a sibling staging directory, which then takes
// the directory's place in one rename (docs/scenario.md, Results; docs/architecture.md, Contracts).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"

namespace fogradar::experiment {

inline constexpr const char* sensor_limit_criterion =
    "first active-layer count at which fewer than 50 % of the measurements detect the target "
    "(a target-origin detection within the association gate) with no fog-origin detection echoing "
    "at least as strongly";

inline constexpr const char* radar_criterion_short =
    "target detected (no fog detection as strong) in < 50 % of the measurements";

// One sensor's line of the study's benchmark: its criterion and the layers to failure, or how far
// from failure it stayed.
struct SensorVerdict {
  SensorId sensor = SensorId::radar;
  std::string criterion;
  std::optional<std::size_t> sensor_limit_layers;
  std::string margin;  // when the limit is not reached: the sensor's margin at the last step
};
std::vector<SensorVerdict> sensor_verdicts(const ExperimentSummary& summary);
// Every sensor's per-step table under its name, in the order the sensors ran (what `fogradar run`
// prints).
std::string sensor_tables(const ExperimentSummary& summary);
// The benchmark lines `fogradar run` prints after the sensors' tables.
std::string benchmark_table(const ExperimentSummary& summary);

// Every fixed name a result set can hold (of every sensor); with camera_roi_<step>.pgm (ROI images,
// camera.write_roi_images) these are the result file names, and an output directory holding only
// result files is an earlier result set.
const std::vector<std::string>& result_file_names();
bool is_result_file_name(const std::string& name);

std::string samples_csv(const ExperimentResult& result);
std::string summary_csv(const ExperimentSummary& summary);
std::string summary_json(const Scenario& scenario, const ExperimentSummary& summary);
// RCS box plots per step with the detection rate under them, the sensor limit marked, and title and
// caption from the scenario (target, chamber, fog as given, droplets, CFAR, n, seed).
std::string rcs_boxplot_svg(const Scenario& scenario, const ExperimentSummary& summary);
// benchmark.svg: per sensor that ran, its metric relative to clear weather (radar: median target
// RCS as a power ratio; lidar: median target intensity, a missing target counted as 0; camera:
// target contrast) against active layers, each sensor's limit marked by a dashed line.
std::string benchmark_svg(const Scenario& scenario, const ExperimentSummary& summary);
// The radar's per-layer table printed by `fogradar run`.
std::string summary_table(const ExperimentSummary& summary);

// The result files of the scenario's sensors as {name, content}.
std::vector<std::pair<std::string, std::string>> result_files(const Scenario& scenario,
                                                              const ExperimentResult& result,
                                                              const ExperimentSummary& summary);

// The output directory of one run, held from before the run until its result set is in place.
// Construction refuses (InvalidParameter naming "--out") a `dir` that is not a directory, that
// holds anything but result files, result_file_names() (so no file of the user's is ever deleted),
// or that another run holds; it then takes the lock (`.NAME.lock` beside `dir`, flock) and creates
// the staging directory
// `.NAME.tmp-<pid>-<random>` beside `dir`. Destruction removes the staging directory (and the lock
// file) whatever happened: a failed or interrupted run leaves the previous set untouched.
class OutputDirectory {
 public:
  explicit OutputDirectory(std::filesystem::path dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Writes `files` into the staging directory and fsyncs them and it; then, unless `abandon()`
  // returns true, swaps the staging directory with `dir` in one step (renameat2 RENAME_EXCHANGE; a
  // plain rename where `dir` does not exist yet), fsyncs the parent and deletes the previous set.
  // Returns false when abandoned (nothing replaced); throws InvalidParameter naming "--out" when a
  // step before the swap fails, leaving `dir` as it was.
  bool replace(const std::vector<std::pair<std::string, std::string>>& files,
               const std::function<bool()>& abandon = {});

 private:
  std::filesystem::path dir_, parent_, lock_path_, staging_;
  int lock_fd_ = -1;
};

}  // namespace fogradar::experiment
