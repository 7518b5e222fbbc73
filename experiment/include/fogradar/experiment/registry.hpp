// The one place that names the sensors (docs/architecture.md): the registry of sensor kinds a
// scenario can run. Everything else in experiment/ and cli/ loops over it. A fourth sensor is a
// folder that implements sensor::SensorKind and one line in standard_registry(), with the build's
// lines docs/architecture.md lists ("Adding a sensor kind"); a test can add its own with add().
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

class SensorRegistry {
 public:
  SensorRegistry() = default;
  explicit SensorRegistry(std::vector<std::shared_ptr<const sensor::SensorKind>> kinds);

  // Appends a sensor kind. Throws InternalError when its name or stream key is already taken or
  // one of its keys is another's.
  void add(std::shared_ptr<const sensor::SensorKind> kind);

  const std::vector<std::shared_ptr<const sensor::SensorKind>>& kinds() const { return kinds_; }
  // Null when no sensor has this name.
  std::shared_ptr<const sensor::SensorKind> find(std::string_view name) const;
  std::vector<std::string> names() const;

 private:
  std::vector<std::shared_ptr<const sensor::SensorKind>> kinds_;
};

// The study's sensors, in the order their sections are written and their results reported: the
// radar, the lidar, the camera.
SensorRegistry standard_registry();

}  // namespace fogradar::experiment
