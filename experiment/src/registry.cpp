#include "fogradar/experiment/registry.hpp"

#include <set>

#include "fogradar/camera/sensor.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/lidar/sensor.hpp"
#include "fogradar/radar/sensor.hpp"

namespace fogradar::experiment {

SensorRegistry::SensorRegistry(std::vector<std::shared_ptr<const sensor::SensorType>> types) {
  for (auto& type : types) add(std::move(type));
}

void SensorRegistry::add(std::shared_ptr<const sensor::SensorType> type) {
  FOGRADAR_CHECK(type != nullptr);
  std::set<std::string> keys;
  for (const auto& other : types_) {
    FOGRADAR_CHECK(other->name() != type->name());
    FOGRADAR_CHECK(other->stream_key() != type->stream_key());
    for (const Key<std::any>& key : other->keys().keys()) keys.insert(key.name);
  }
  for (const Key<std::any>& key : type->keys().keys()) FOGRADAR_CHECK(!keys.contains(key.name));
  types_.push_back(std::move(type));
}

std::shared_ptr<const sensor::SensorType> SensorRegistry::find(std::string_view name) const {
  for (const auto& type : types_) {
    if (type->name() == name) return type;
  }
  return nullptr;
}

std::vector<std::string> SensorRegistry::names() const {
  std::vector<std::string> names;
  for (const auto& type : types_) names.emplace_back(type->name());
  return names;
}

SensorRegistry standard_registry() {
  return SensorRegistry({radar::sensor_type(), lidar::sensor_type(), camera::sensor_type()});
}

}  // namespace fogradar::experiment
