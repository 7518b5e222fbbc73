// The camera as a sensor of the experiment (sensor/sensor.hpp): its keys ([camera] and
// its sub-tables), one run on the chamber (the band's fog optics resolved once, the optics and
// exposure per step, one frame per item), and its result files camera_histograms.csv,
// camera_summary.csv, camera_summary.json, camera_histograms.svg and, when asked for,
// camera_roi_<step>.pgm.
#pragma once

#include <memory>
#include <vector>

#include "fogradar/camera/camera.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::camera {

// The camera's kind, for the registry.
std::shared_ptr<const sensor::SensorKind> sensor_kind();

// The camera's raw data per frame (docs/data-out.md): its grey image.
enum RawKindIndex : std::size_t { raw_images = 0 };

// What a run of the camera found: one result per step with the frames by index, and their summary.
class CameraReport : public sensor::SensorSummary {
 public:
  virtual const std::vector<CameraStepResult>& steps() const = 0;
  virtual const CameraSummary& summary() const = 0;
};

}  // namespace fogradar::camera
