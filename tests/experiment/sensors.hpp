// Typed access to the study's three sensors of a scenario and of a run's summary, for the tests.
#pragma once

#include "fogradar/camera/sensor.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/lidar/sensor.hpp"
#include "fogradar/radar/sensor.hpp"

namespace fogradar::experiment {

inline radar::SensorParams& radar_of(Scenario& s) { return s.params<radar::SensorParams>("radar"); }
inline const radar::SensorParams& radar_of(const Scenario& s) {
  return s.params<radar::SensorParams>("radar");
}
inline lidar::LidarParams& lidar_of(Scenario& s) { return s.params<lidar::LidarParams>("lidar"); }
inline const lidar::LidarParams& lidar_of(const Scenario& s) {
  return s.params<lidar::LidarParams>("lidar");
}
inline camera::CameraParams& camera_of(Scenario& s) {
  return s.params<camera::CameraParams>("camera");
}
inline const camera::CameraParams& camera_of(const Scenario& s) {
  return s.params<camera::CameraParams>("camera");
}

// The radar's run: its chain and its records, step by step.
inline const radar::RadarRun& radar_run(const ExperimentResult& r) {
  return dynamic_cast<const radar::RadarRun&>(r.run("radar"));
}

inline const radar::RadarReport& radar_report(const ExperimentSummary& s) {
  return s.of<radar::RadarReport>("radar");
}
inline const lidar::LidarReport& lidar_report(const ExperimentSummary& s) {
  return s.of<lidar::LidarReport>("lidar");
}
inline const camera::CameraReport& camera_report(const ExperimentSummary& s) {
  return s.of<camera::CameraReport>("camera");
}

}  // namespace fogradar::experiment
