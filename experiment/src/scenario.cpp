#include "fogradar/experiment/scenario.hpp"

#include <algorithm>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "scenario_parts.hpp"

namespace fogradar::experiment {
namespace detail {
std::string_view paper_scenario_text();
}  // namespace detail

using detail::parse_over;

SensorSetting::SensorSetting(std::shared_ptr<const sensor::SensorKind> of_kind,
                             std::unique_ptr<sensor::Params> values)
    : kind(std::move(of_kind)), params(std::move(values)) {}

SensorSetting::SensorSetting(const SensorSetting& other)
    : kind(other.kind), params(other.params ? other.params->clone() : nullptr) {}

SensorSetting& SensorSetting::operator=(const SensorSetting& other) {
  if (this != &other) *this = SensorSetting(other);
  return *this;
}

Scenario::Scenario(const SensorRegistry& registry) {
  for (const auto& kind : registry.kinds()) {
    sensors.emplace_back(kind, kind->defaults());
    experiment.sensors.emplace_back(kind->name());
  }
  keys_ = std::make_shared<const detail::ScenarioKeys>(sensors);
}

SensorSetting& Scenario::setting(std::string_view name) {
  for (SensorSetting& s : sensors) {
    if (s.kind->name() == name) return s;
  }
  throw_invalid("experiment.sensors", name, "a registered sensor");
}

const SensorSetting& Scenario::setting(std::string_view name) const {
  return const_cast<Scenario*>(this)->setting(name);
}

bool Scenario::runs(std::string_view name) const {
  return std::find(experiment.sensors.begin(), experiment.sensors.end(), name) !=
         experiment.sensors.end();
}

std::size_t Scenario::steps() const {
  return experiment.max_active_layers.value_or(chamber.layers_in_use()) + 1;
}

const KeyTable<Scenario>& Scenario::keys() const { return detail::keys_of(*this).all; }

// The keys in file order first, then what each sensor checks beyond its keys (a sensor's keys are
// checked twice: checks are cheap, the tables are made once).
void Scenario::validate() const {
  keys().check(*this);
  const sensor::Context shared = context();
  for (const SensorSetting& s : sensors) s.kind->configure(*s.params, shared);
}

propagation::ChamberSpec Scenario::chamber_spec() const {
  propagation::ChamberSpec spec;
  spec.sensor_gap_m = chamber.sensor_gap_m;
  spec.target_gap_m = chamber.target_gap_m;
  if (chamber.layers.empty()) {
    spec.layers.assign(chamber.layer_count,
                       propagation::FogLayerSpec{.length_m = chamber.layer_length_m, .fog = fog});
  } else {
    spec.layers = chamber.layers;
  }
  return spec;
}

std::vector<std::size_t> switching_sequence(const SwitchingOrder& order, std::size_t layer_count) {
  if (const auto* listed = std::get_if<std::vector<std::size_t>>(&order)) return *listed;
  std::vector<std::size_t> sequence(layer_count);
  std::iota(sequence.begin(), sequence.end(), std::size_t{0});
  if (std::get<SwitchingFrom>(order) == SwitchingFrom::target) {
    std::reverse(sequence.begin(), sequence.end());
  }
  return sequence;
}

sensor::Context Scenario::context() const {
  return {
      .chamber = chamber_spec(),
      .steps = steps(),
      .measurements_per_step = experiment.measurements_per_step,
      .seed = experiment.seed,
      .switching_order = switching_sequence(experiment.switching_order, chamber.layers_in_use())};
}

std::shared_ptr<const sensor::ConfiguredSensor> Scenario::configure(std::string_view name) const {
  const SensorSetting& s = setting(name);
  return s.kind->configure(*s.params, context());
}

std::string_view paper_scenario_toml() { return detail::paper_scenario_text(); }

Scenario paper_scenario(const SensorRegistry& registry) {
  return parse_over(Scenario(registry), paper_scenario_toml(), "paper.toml");
}

Scenario parse_scenario(std::string_view toml_text, std::string_view source_name,
                        const SensorRegistry& registry) {
  return parse_over(paper_scenario(registry), toml_text, source_name);
}

Scenario parse_scenario_over(const Scenario& base, std::string_view toml_text,
                             std::string_view source_name, LineNumbers line_numbers) {
  return parse_over(base, toml_text, source_name, line_numbers);
}

}  // namespace fogradar::experiment
