// A scenario: everything one run of the study's methodology needs, as read from a TOML file: the
// chamber ([chamber]), its fog ([fog]), the methodology ([experiment]) and every registered
// sensor's own sections (the radar's [radar], [processing], [target]; [lidar]; [camera]), each
// sensor's parameters read and written by the keys it declares (sensor/sensor.hpp,
// core/keys.hpp). Keys carry their units in their names; docs/scenario.md lists them with
// defaults and ranges (`fogradar scenario --keys`). The paper scenario (examples/paper.toml) is
// compiled in and is the base every scenario file overrides.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "fogradar/core/keys.hpp"
#include "fogradar/experiment/registry.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

// The chamber as the scenario file gives it: n identical layers, all with the scenario's fog, or
// the layers [[chamber.layers]] lists, each of its own length and fog.
struct ChamberLayout {
  double sensor_gap_m = 2.0;
  std::size_t layer_count = 4;  // without [[chamber.layers]]
  double layer_length_m = 1.0;  // without [[chamber.layers]]
  double target_gap_m = 4.0;
  // [[chamber.layers]], from the sensor: each layer's length and fog ([fog] with the keys of the
  // layer's own `fog` table replacing its values). Empty: layer_count layers of layer_length_m.
  std::vector<propagation::FogLayerSpec> layers;

  std::size_t layers_in_use() const { return layers.empty() ? layer_count : layers.size(); }
};

// The order the layers are switched on in (experiment.switching_order): the study's, from the
// sensor; from the target; or the layer indices (0 at the sensor) in the order they come on.
enum class SwitchingFrom { sensor, target };
using SwitchingOrder = std::variant<SwitchingFrom, std::vector<std::size_t>>;

// The layer indices in the order they are switched on, for `layer_count` layers.
std::vector<std::size_t> switching_sequence(const SwitchingOrder& order, std::size_t layer_count);

struct ExperimentSpec {
  // Which sensors run, by name (experiment.sensors): non-empty, no repeats, each registered; each
  // sees the same chamber, and their results are reported in this order. Scenario's constructor
  // names every registered sensor.
  std::vector<std::string> sensors;
  std::size_t measurements_per_step = 200;
  // Steps k = 0 .. max_active_layers; none given: every layer of the chamber (Scenario::steps).
  std::optional<std::size_t> max_active_layers;
  SwitchingOrder switching_order = SwitchingFrom::sensor;
  std::uint64_t seed = 1;
};

struct Scenario;
namespace detail {
struct ScenarioKeys;
const ScenarioKeys& keys_of(const Scenario& scenario);
}  // namespace detail

// One registered sensor's parameters (its own struct, sensor::params_of); copies copy them.
struct SensorSetting {
  SensorSetting(std::shared_ptr<const sensor::SensorKind> of_kind,
                std::unique_ptr<sensor::Params> values);
  SensorSetting(const SensorSetting& other);
  SensorSetting& operator=(const SensorSetting& other);
  SensorSetting(SensorSetting&&) noexcept = default;
  SensorSetting& operator=(SensorSetting&&) noexcept = default;
  ~SensorSetting() = default;

  std::shared_ptr<const sensor::SensorKind> kind;
  std::unique_ptr<sensor::Params> params;
};

struct Scenario {
  // Every sensor of `registry` at its defaults, each of them running.
  explicit Scenario(const SensorRegistry& registry = standard_registry());

  ChamberLayout chamber;
  propagation::FogSpec fog;
  ExperimentSpec experiment;
  // Every registered sensor, in the registry's order; fixed by the constructor (the scenario's keys
  // are made for them).
  std::vector<SensorSetting> sensors;

  // The parameters of the sensor named `name`, as its own struct (throws std::bad_cast for another
  // struct, InvalidParameter for an unregistered name).
  template <class Params>
  Params& params(std::string_view name) {
    return sensor::params_of<Params>(*setting(name).params);
  }
  template <class Params>
  const Params& params(std::string_view name) const {
    return sensor::params_of<Params>(*setting(name).params);
  }
  SensorSetting& setting(std::string_view name);
  const SensorSetting& setting(std::string_view name) const;

  bool runs(std::string_view name) const;
  // Steps k = 0 .. experiment.max_active_layers, every layer of the chamber where it is not given.
  std::size_t steps() const;
  // Throws InvalidParameter naming the scenario key (e.g. "processing.cfar.training_cells").
  void validate() const;
  propagation::ChamberSpec chamber_spec() const;
  // What every sensor is given besides its own keys.
  sensor::Context context() const;
  // The sensor named `name` configured for this scenario (SensorKind::configure: InvalidParameter
  // naming the key its parameters break, its own or the chamber's).
  std::shared_ptr<const sensor::ConfiguredSensor> configure(std::string_view name) const;
  // Every key of the scenario, as the file lays them out: the first sensor's sections, then
  // [chamber], [fog] and [experiment], then the other sensors' (the paper scenario's order).
  const KeyTable<Scenario>& keys() const;

 private:
  friend const detail::ScenarioKeys& detail::keys_of(const Scenario&);
  std::shared_ptr<const detail::ScenarioKeys> keys_;  // made once, shared by copies
};

// The compiled-in paper scenario file (examples/paper.toml), verbatim.
std::string_view paper_scenario_toml();
Scenario paper_scenario(const SensorRegistry& registry = standard_registry());

// Reads a scenario file's text over the paper scenario. Malformed TOML, unknown keys or sections,
// wrong types and out-of-range values throw InvalidParameter whose message starts with
// "<source_name>:<line>: " and names the key; its field() is the key ("radar.tx_power_dbm").
Scenario parse_scenario(std::string_view toml_text, std::string_view source_name,
                        const SensorRegistry& registry = standard_registry());

// Whether a message points at the text's lines ("my.toml:12: ..."), or names the source and the
// key alone ("<dict>: radar.tx_power_dbm = 99.0: ..."): for a text fogradar wrote from what the
// user gave (a Python dict), whose lines the user never saw.
enum class LineNumbers { shown, hidden };

// Reads a scenario file's text over `base` instead: the keys it gives replace base's values (the
// Python module's Scenario.with_overrides). Errors as parse_scenario's.
Scenario parse_scenario_over(const Scenario& base, std::string_view toml_text,
                             std::string_view source_name,
                             LineNumbers line_numbers = LineNumbers::shown);

// Largest scenario file read: a scenario is a few kB; anything larger is refused before it is read.
inline constexpr std::size_t max_scenario_file_bytes = std::size_t{1} << 20;

// Reads a scenario file. A path that cannot be opened, that is not a regular file (a directory, a
// FIFO, a device) or that holds more than max_scenario_file_bytes throws InvalidParameter naming
// "--scenario"; nothing is read from it then, and a FIFO is never waited on.
Scenario load_scenario_file(const std::string& path,
                            const SensorRegistry& registry = standard_registry());

// The fully resolved scenario as TOML (every key that takes effect), so that a run can be repeated
// exactly: parse_scenario(to_toml(s)) == s.
std::string to_toml(const Scenario& scenario);

// The top-level sections of the scenario's keys, in file order ("radar", "processing", ...).
std::vector<std::string> top_level_sections(const Scenario& scenario);

// docs/scenario.md's table of the keys under top-level section `section` (with its sub-sections
// and arrays of tables): key (relative to the section), default (this scenario's value, "—" where
// the key takes no effect), allowed values and meaning, in Markdown. Throws InvalidParameter
// naming "--keys" for a section no key is in.
std::string key_table_markdown(const Scenario& defaults, std::string_view section);

}  // namespace fogradar::experiment
