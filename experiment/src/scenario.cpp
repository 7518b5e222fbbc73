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

namespace {

// Another instance of a kind: the kind's sensor, whose memory and time estimates name the
// instance's keys (a limit's refusal points at "radar_24.measurements_per_step").
class RenamedSensor : public sensor::ConfiguredSensor {
 public:
  RenamedSensor(std::shared_ptr<const sensor::ConfiguredSensor> kinds, std::string from,
                std::string to)
      : kinds_(std::move(kinds)), from_(std::move(from)), to_(std::move(to)) {}

  std::size_t items_per_step() const override { return kinds_->items_per_step(); }
  sensor::Cost cost() const override {
    sensor::Cost c = kinds_->cost();
    for (std::string* text :
         {&c.item.detail, &c.item.key, &c.item.items_key, &c.setup.detail, &c.setup.key}) {
      *text = renamed(*text);
    }
    return c;
  }
  sensor::MemoryPart memory(unsigned threads) const override {
    sensor::MemoryPart part = kinds_->memory(threads);
    part.detail = renamed(part.detail);
    part.key = renamed(part.key);
    return part;
  }
  std::vector<sensor::RawKind> raw_kinds() const override { return kinds_->raw_kinds(); }
  sensor::FogReport fog_report(const propagation::FogSpec& fog, double layer_length_m,
                               const propagation::SegelsteinTable& water) const override {
    return kinds_->fog_report(fog, layer_length_m, water);
  }
  std::shared_ptr<const sensor::Sensor> make(const propagation::SegelsteinTable& water,
                                             const StopToken& stop) const override {
    return kinds_->make(water, stop);
  }

 private:
  std::string renamed(const std::string& text) const {
    return with_section_renamed(text, from_, to_);
  }

  std::shared_ptr<const sensor::ConfiguredSensor> kinds_;
  std::string from_, to_;
};

}  // namespace

std::shared_ptr<const sensor::ConfiguredSensor> configure_instance(const SensorSetting& s,
                                                                   const sensor::Context& context) {
  if (s.is_kinds_own()) return s.kind->configure(*s.params, context);
  const std::string from = std::string(s.kind->name()) + ".", to = s.name + ".";
  try {
    return std::make_shared<RenamedSensor>(s.kind->configure(*s.params, context), from, to);
  } catch (const InvalidParameter& e) {
    throw with_section_renamed(e, from, to);
  }
}

SensorSetting::SensorSetting(std::string instance_name,
                             std::shared_ptr<const sensor::SensorKind> of_kind,
                             std::unique_ptr<sensor::Params> values)
    : name(std::move(instance_name)), kind(std::move(of_kind)), params(std::move(values)) {}

SensorSetting::SensorSetting(const SensorSetting& other)
    : name(other.name), kind(other.kind), params(other.params ? other.params->clone() : nullptr) {}

SensorSetting& SensorSetting::operator=(const SensorSetting& other) {
  if (this != &other) *this = SensorSetting(other);
  return *this;
}

Scenario::Scenario(const SensorRegistry& registry) {
  for (const auto& kind : registry.kinds()) {
    sensors.emplace_back(std::string(kind->name()), kind, kind->defaults());
    experiment.sensors.emplace_back(kind->name());
  }
  keys_ = std::make_shared<const detail::ScenarioKeys>(sensors);
}

void Scenario::add_sensor(std::string_view name, std::string_view kind, std::string_view key) {
  const auto of_kind = std::find_if(sensors.begin(), sensors.end(), [kind](const SensorSetting& s) {
    return s.kind->name() == kind;
  });
  if (of_kind == sensors.end()) {
    std::string kinds;
    for (const SensorSetting& s : sensors) {
      if (s.is_kinds_own()) kinds += (kinds.empty() ? "'" : ", '") + s.name + "'";
    }
    throw_invalid(std::string(key) + ".kind", kind, "one of " + kinds);
  }
  const bool well_formed = !name.empty() && name.front() >= 'a' && name.front() <= 'z' &&
                           std::all_of(name.begin(), name.end(), [](char c) {
                             return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
                           });
  // Every section, those of retired keys too ([processing] names where its keys went).
  const auto taken = [this, name] {
    for (const detail::Section& s : detail::keys_of(*this).sections) {
      if (s.name.substr(0, s.name.find('.')) == name) return true;
    }
    return false;
  };
  if (!well_formed || taken()) {
    throw InvalidParameter(std::string(key), "[" + std::string(name) +
                                                 "]: a sensor instance's "
                                                 "section must be " +
                                                 std::string(instance_name_rule));
  }
  sensors.emplace_back(std::string(name), of_kind->kind, of_kind->kind->defaults());
  keys_ = std::make_shared<const detail::ScenarioKeys>(sensors);
}

SensorSetting& Scenario::setting(std::string_view name) {
  for (SensorSetting& s : sensors) {
    if (s.name == name) return s;
  }
  throw_invalid("experiment.sensors", name, "a sensor instance of the scenario");
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
// checked twice: checks are cheap, the tables are made once), told whether it runs.
void Scenario::validate() const {
  keys().check(*this);
  sensor::Context shared = context();
  for (const SensorSetting& s : sensors) {
    shared.runs = runs(s.name);
    configure_instance(s, shared);
  }
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
      .target = target,
      .room = chamber.room,
      .steps = steps(),
      .seed = experiment.seed,
      .switching_order = switching_sequence(experiment.switching_order, chamber.layers_in_use()),
      .runs = true};
}

std::shared_ptr<const sensor::ConfiguredSensor> Scenario::configure(std::string_view name) const {
  return configure_instance(setting(name), context());
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
