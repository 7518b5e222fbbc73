// Result files of `fogradar run` (docs/scenario.md, Results): samples.csv, summary.csv, summary.json,
// rcs_boxplot.svg, scenario.toml. All are rendered in memory first, then written to temporary files
// in the output directory and renamed into place, so a failed run leaves no partial result files.
#pragma once

#include <filesystem>
#include <string>

#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"

namespace fogradar::experiment {

inline constexpr const char* sensor_limit_criterion =
    "first active-layer count at which fewer than 50 % of the measurements detect the target "
    "(a target-origin detection within the association gate) with no fog-origin detection echoing "
    "at least as strongly";

std::string samples_csv(const ExperimentResult& result);
std::string summary_csv(const ExperimentSummary& summary);
std::string summary_json(const Scenario& scenario, const ExperimentSummary& summary);
// RCS box plots per step with the detection rate under them, the sensor limit marked, and title and
// caption from the scenario (target, chamber, fog as given, droplets, CFAR, n, seed).
std::string rcs_boxplot_svg(const Scenario& scenario, const ExperimentSummary& summary);
// The per-layer table printed by `fogradar run`.
std::string summary_table(const ExperimentSummary& summary);

// Creates `dir` if needed and checks that files can be created in it; throws InvalidParameter
// naming "--out" otherwise. Returns whether the directory was created by this call.
bool prepare_output_directory(const std::filesystem::path& dir);

// Writes the five files atomically (see above); throws InvalidParameter naming "--out" on failure.
void write_outputs(const std::filesystem::path& dir, const Scenario& scenario, const ExperimentResult& result,
                   const ExperimentSummary& summary);

}  // namespace fogradar::experiment
