#include "fogradar/experiment/registry.hpp"

#include <set>

#include "fogradar/core/error.hpp"

namespace fogradar::experiment {

SensorRegistry::SensorRegistry(std::vector<std::shared_ptr<const sensor::SensorKind>> kinds) {
  for (auto& kind : kinds) add(std::move(kind));
}

void SensorRegistry::add(std::shared_ptr<const sensor::SensorKind> kind) {
  FOGRADAR_CHECK(kind != nullptr);
  std::set<std::string> keys;
  for (const auto& other : kinds_) {
    FOGRADAR_CHECK(other->name() != kind->name());
    FOGRADAR_CHECK(other->stream_key() != kind->stream_key());
    for (const Key<sensor::Params>& key : other->keys().keys()) keys.insert(key.name);
  }
  for (const Key<sensor::Params>& key : kind->keys().keys()) {
    FOGRADAR_CHECK(!keys.contains(key.name));
  }
  kinds_.push_back(std::move(kind));
}

std::shared_ptr<const sensor::SensorKind> SensorRegistry::find(std::string_view name) const {
  for (const auto& kind : kinds_) {
    if (kind->name() == name) return kind;
  }
  return nullptr;
}

std::vector<std::string> SensorRegistry::names() const {
  std::vector<std::string> names;
  for (const auto& kind : kinds_) names.emplace_back(kind->name());
  return names;
}

}  // namespace fogradar::experiment
