// Per-step statistics of an experiment (Tukey box plot of the target detections' RCS values, shift
// against the 0-layer series) and the sensor limit: the study's assessment criterion, the number of
// active layers at which the sensor can no longer tell the target from the fog.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "fogradar/camera/camera.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/lidar/summary.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/median_interval.hpp"

namespace fogradar::experiment {

struct StepSummary {
  std::size_t active_layers = 0;
  std::size_t n = 0;           // measurements
  std::size_t detections = 0;  // with a target detection (target origin, in the gate)
  double detection_rate = 0.0;
  // Measurements whose gate association is a fog or a noise detection (counted as misses).
  double false_association_rate = 0.0;
  double false_alarms_per_frame = 0.0;    // mean noise-origin detections per measurement
  double fog_detections_per_frame = 0.0;  // mean fog-origin detections per measurement
  stats::BoxPlot rcs;                     // of the target detections' rcs_dbsm values
  // Against the 0-layer series: the Hodges-Lehmann shift (median of all pairwise differences
  // x_i - y_j), its distribution-free 95 % interval (the inverted Mann-Whitney test) and the
  // Mann-Whitney U p-value; shift 0 and interval and p NaN for the baseline itself, all NaN when
  // either series has no target detection.
  double median_shift_db = 0.0;
  stats::Interval median_shift_ci95;
  double p_value = 0.0;
  double median_snr_db = 0.0;  // of the target detections
  double two_way_attenuation_db = 0.0;
  double confusion_rate = 0.0;  // measurements without a target detection or with fog rivalling it
};

struct ExperimentSummary {
  std::vector<SensorId> sensors;  // that ran
  // The radar's steps; empty when the radar did not run.
  std::vector<StepSummary> steps;
  // First layer count at which fewer than half the measurements detect the target (target origin)
  // with no fog-origin detection at least as strong (docs/scenario.md); empty if never reached.
  std::optional<std::size_t> sensor_limit_layers;
  // At the last step: median target SNR minus the CFAR threshold factor (dB), i.e. roughly how
  // much more two-way attenuation the median echo could take before it drops below the threshold.
  std::optional<double> attenuation_margin_db;
  double expected_false_alarm_cells_per_frame = 0.0;  // ExperimentResult's design figure

  std::optional<lidar::LidarSummary> lidar;          // when the lidar ran
  std::shared_ptr<const lidar::Lidar> lidar_sensor;  // the run's lidar: its files' derived figures
  std::optional<camera::CameraSummary> camera;       // when the camera ran
};

inline constexpr double sensor_limit_success_fraction = 0.5;

ExperimentSummary summarize(const ExperimentResult& result);

}  // namespace fogradar::experiment
