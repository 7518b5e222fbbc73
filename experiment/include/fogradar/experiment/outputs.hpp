// Result files of `fogradar run` (docs/scenario.md, Results): every sensor's own files (prefixed
// with its name), summary.json (every sensor's summary and limit), scenario.toml and benchmark.svg.
// The output directory is the run's result set and is replaced whole: the files are written to a
// sibling staging directory, which then takes the directory's place in one rename
// (docs/scenario.md, Results; docs/architecture.md, Contracts).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

class PathLock;

// Whether a result set can hold a file of this name: summary.json, scenario.toml, benchmark.svg,
// or a sensor instance's file, which carries the instance's name as its prefix
// ("radar_24_summary.csv": a name of instance_name_rule's letters, then '_' and the rest).
bool is_result_file_name(std::string_view name);

// The record a result set holds of its files (their names, sorted, one a line): only the files it
// lists (and is_result_file_name allows) are the set's, replaced with it; any other file in the
// directory is the user's, even one whose name a sensor could have written (camera_roi_<step>.pgm).
inline constexpr std::string_view record_file_name = ".fogradar-files";

// Every sensor's per-step table under its name, in the order the sensors ran (what `fogradar run`
// prints).
std::string sensor_tables(const ExperimentSummary& summary);
// The benchmark lines `fogradar run` prints after the sensors' tables: per sensor its layers to
// failure (or its margin) and its criterion.
std::string benchmark_table(const ExperimentSummary& summary);

// summary.json: the resolved scenario, and per sensor its limit, criterion, margin and summary.
std::string summary_json(const Scenario& scenario, const ExperimentSummary& summary);
// benchmark.svg: per sensor that ran, its metric relative to clear weather against active layers,
// each sensor's limit marked by a dashed line.
std::string benchmark_svg(const Scenario& scenario, const ExperimentSummary& summary);

// The result files of the sensors that ran, each under its instance's name, and the run's own.
// Throws InternalError for a sensor's file whose name does not begin with its kind's name and '_'.
std::vector<sensor::ResultFile> result_files(const Scenario& scenario,
                                             const ExperimentSummary& summary);

// The output directory of one run, held from before the run until its result set is in place.
// Construction refuses (InvalidParameter naming "--out") a `dir` that is not a directory, that
// holds anything but an earlier set's files (those its record_file_name lists and
// is_result_file_name allows, or in a set written before sets were recorded, one holding
// summary.json, the names fogradar wrote then; so no file of the user's is ever deleted), or that
// another run holds; it then creates missing
// parents, takes the lock (`.NAME.lock` beside `dir`, flock) and creates the staging directory
// `.NAME.tmp-<pid>-<random>` beside `dir`. Destruction removes the staging directory, the lock
// file and, unless a set was put in place, the parents it created, whatever happened: a failed or
// interrupted run leaves the previous set untouched and no directory of its own.
class OutputDirectory {
 public:
  explicit OutputDirectory(std::filesystem::path dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Writes `files` and the record of their names into the staging directory and fsyncs them and
  // it; then, unless `abandon()` returns true, swaps the staging directory with `dir` in one step
  // (renameat2 RENAME_EXCHANGE; a plain rename where `dir` does not exist yet), fsyncs the parent
  // and deletes the previous set (the files found to be its, checked again before the swap).
  // Returns false when abandoned (nothing replaced); throws InvalidParameter naming "--out" when a
  // step before the swap fails, leaving `dir` as it was.
  bool replace(const std::vector<sensor::ResultFile>& files,
               const std::function<bool()>& abandon = {});

 private:
  void release() noexcept;

  std::filesystem::path dir_, parent_, staging_;
  std::unique_ptr<PathLock> lock_;
  std::vector<std::filesystem::path> created_;  // missing parents of `dir`, deepest first
};

}  // namespace fogradar::experiment
