// Typed access to the study's three sensors of a scenario and of a run's summary, for the tests.
#pragma once

#include "fogradar/camera/sensor.hpp"
#include "fogradar/lidar/sensor.hpp"
#include "radar_sensor.hpp"

namespace fogradar::experiment {

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

inline const lidar::LidarReport& lidar_report(const ExperimentSummary& s) {
  return s.of<lidar::LidarReport>("lidar");
}
inline const camera::CameraReport& camera_report(const ExperimentSummary& s) {
  return s.of<camera::CameraReport>("camera");
}

}  // namespace fogradar::experiment
