// A scenario: everything one run of the study's methodology needs, as read from a TOML file: the
// world every sensor sees (the chamber [chamber], its fog [fog], the target [target]), the
// methodology ([experiment]) and each sensor instance's own section ([radar], [lidar], [camera],
// and any further instance of a kind, `[radar_24] kind = "radar"`), each instance's parameters read
// and written by the keys its kind declares (sensor/sensor.hpp, core/keys.hpp). Keys carry their
// units in their names; docs/scenario.md lists them with defaults and ranges (`fogradar scenario
// --keys`). The paper scenario (examples/paper.toml) is compiled in and is the base every scenario
// file overrides.
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
#include "fogradar/propagation/room_spec.hpp"
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
  // [chamber.room] and [[chamber.objects]]: the hall around the layers.
  propagation::RoomSpec room;

  std::size_t layers_in_use() const { return layers.empty() ? layer_count : layers.size(); }
};

// The order the layers are switched on in (experiment.switching_order): the study's, from the
// sensor; from the target; or the layer indices (0 at the sensor) in the order they come on.
enum class SwitchingFrom { sensor, target };
using SwitchingOrder = std::variant<SwitchingFrom, std::vector<std::size_t>>;

// The layer indices in the order they are switched on, for `layer_count` layers.
std::vector<std::size_t> switching_sequence(const SwitchingOrder& order, std::size_t layer_count);

struct ExperimentSpec {
  // Which sensor instances run, by name (experiment.sensors): non-empty, no repeats, each an
  // instance of the scenario; each sees the same chamber, and their results are reported in this
  // order. Scenario's constructor names every registered kind's instance.
  std::vector<std::string> sensors;
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

// One sensor instance: its name, its kind and its parameters (the kind's own struct,
// sensor::params_of); copies copy them. The instance named after its kind ("radar") is the kind's
// own, whose section is the kind's; any other ("radar_24") has a section of its own with the kind's
// keys under it.
struct SensorSetting {
  SensorSetting(std::string instance_name, std::shared_ptr<const sensor::SensorKind> of_kind,
                std::unique_ptr<sensor::Params> values);
  SensorSetting(const SensorSetting& other);
  SensorSetting& operator=(const SensorSetting& other);
  SensorSetting(SensorSetting&&) noexcept = default;
  SensorSetting& operator=(SensorSetting&&) noexcept = default;
  ~SensorSetting() = default;

  // Its random streams' key: its kind's. Every instance of a kind draws the same numbers for item
  // (k, i), so two instances with the same keys give the same results and two that differ in a key
  // differ by that key alone (common random numbers); no instance's numbers depend on which others
  // exist.
  std::uint64_t stream_key() const { return kind->stream_key(); }
  bool is_kinds_own() const { return name == kind->name(); }

  std::string name;
  std::shared_ptr<const sensor::SensorKind> kind;
  std::unique_ptr<sensor::Params> params;
};

// The rule for a sensor instance's name, as messages state it.
inline constexpr std::string_view instance_name_rule =
    "a name of lower-case letters, digits and '_' that starts with a letter and is no other "
    "section's";

// The instance configured for `context` (SensorKind::configure), its messages naming its own keys
// ("radar_24.samples_per_chirp" where the kind's name "radar.samples_per_chirp").
std::shared_ptr<const sensor::ConfiguredSensor> configure_instance(const SensorSetting& setting,
                                                                   const sensor::Context& context);

struct Scenario {
  // Every sensor of `registry` at its defaults, each of them running.
  explicit Scenario(const SensorRegistry& registry = standard_registry());

  ChamberLayout chamber;
  propagation::FogSpec fog;
  ExperimentSpec experiment;
  // The world's target: its floor, motion and water film ([target]), seen by every sensor.
  sensor::TargetWorld target;
  // Every sensor instance: the registered kinds' own, in the registry's order, then those
  // add_sensor() added. Change the list only through add_sensor (the scenario's keys are made for
  // it).
  std::vector<SensorSetting> sensors;

  // Adds an instance `name` of the kind named `kind`, at the kind's defaults (not running until
  // experiment.sensors names it). Throws InvalidParameter naming `key` for a name that breaks
  // instance_name_rule or is taken, or a kind that is not registered.
  void add_sensor(std::string_view name, std::string_view kind, std::string_view key);

  // The parameters of the sensor instance named `name`, as its own struct (throws std::bad_cast
  // for another struct, InvalidParameter for a name that is no instance).
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
  // Throws InvalidParameter naming the scenario key (e.g. "radar.processing.cfar.training_cells").
  void validate() const;
  propagation::ChamberSpec chamber_spec() const;
  // What every sensor is given besides its own keys.
  sensor::Context context() const;
  // The sensor named `name` configured for this scenario (SensorKind::configure: InvalidParameter
  // naming the key its parameters break, its own or the chamber's).
  std::shared_ptr<const sensor::ConfiguredSensor> configure(std::string_view name) const;
  // Every key of the scenario, as the file lays them out: the world's and the methodology's
  // sections ([chamber], [fog], [target], [experiment]), then each sensor instance's.
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
