// Per-step statistics of an experiment (Tukey box plot of the detected RCS values, shift against the
// 0-layer series) and the sensor limit: the study's assessment criterion, the number of active
// layers at which the sensor can no longer tell the target from the fog.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "fogradar/experiment/runner.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/median_interval.hpp"

namespace fogradar::experiment {

struct StepSummary {
  std::size_t active_layers = 0;
  std::size_t n = 0;           // measurements
  std::size_t detections = 0;  // with a target detection
  double detection_rate = 0.0;
  stats::BoxPlot rcs;          // of the detected rcs_dbsm values
  // Against the 0-layer series: median(this) - median(baseline) and the Mann-Whitney U p-value;
  // NaN for the baseline itself or when either series has no detection.
  double median_shift_db = 0.0;
  double p_value = 0.0;
  stats::Interval median_shift_ci95;  // distribution-free 95 % interval of the shift
  double median_snr_db = 0.0;
  double two_way_attenuation_db = 0.0;
  double confusion_rate = 0.0;  // measurements without a target or with fog rivalling it
};

struct ExperimentSummary {
  std::vector<StepSummary> steps;
  // First layer count at which fewer than half the measurements detect the target with no fog
  // detection at least as strong (docs/experiment.md); empty if the chamber never gets there.
  std::optional<std::size_t> sensor_limit_layers;
  // At the last step: median target SNR minus the CFAR threshold factor (dB), i.e. roughly how
  // much more two-way attenuation the median echo could take before it drops below the threshold.
  std::optional<double> attenuation_margin_db;
};

inline constexpr double sensor_limit_success_fraction = 0.5;

ExperimentSummary summarize(const ExperimentResult& result);

}  // namespace fogradar::experiment
