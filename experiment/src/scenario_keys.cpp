// The scenario's keys: [chamber], [fog], [target] and [experiment], each sensor instance's, and
// the file's layout of every part's keys.
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "scenario_parts.hpp"

namespace fogradar::experiment {
namespace detail {

// The range experiment.max_active_layers allows with `layer_count` layers in the chamber, given by
// chamber.layer_count or listed by [[chamber.layers]].
std::string integer_range_of_active(std::size_t layer_count, bool listed) {
  const std::string count = std::to_string(layer_count);
  if (!listed) return "an integer in [0, chamber.layer_count = " + count + "]";
  return "an integer in [0, " + count + "] (the layers [[chamber.layers]] lists)";
}

}  // namespace detail

namespace {

using detail::in_quotes;
using detail::integer_range_of_active;
using detail::joined;
using detail::ScenarioKey;

// One layer of [[chamber.layers]]: its length and its fog, a table of [fog]'s keys.
KeyTable<propagation::FogLayerSpec> layer_keys(std::string prefix) {
  KeyTable<propagation::FogLayerSpec> keys(prefix);
  const Interval length = open_closed(0.0, propagation::max_chamber_length_m);
  Key<propagation::FogLayerSpec>& length_m =
      keys.number("length_m", FOGRADAR_KEY_FIELD(length_m), length, "required; f_i");
  // A layer read from a file starts without a length (NaN): a missing one is named as missing.
  length_m.check = [name = length_m.name, length,
                    in_range = std::move(length_m.check)](const propagation::FogLayerSpec& l) {
    if (!std::isnan(l.length_m)) return in_range(l);
    throw InvalidParameter(name, name +
                                     " is missing: every [[chamber.layers]] layer must give "
                                     "it, a number " +
                                     length.constraint());
  };
  keys.include(propagation::fog_keys(prefix + "fog."), FOGRADAR_KEY_FIELD(fog));
  return keys;
}

std::string_view switching_from_name(SwitchingFrom from) {
  return from == SwitchingFrom::sensor ? "sensor_first" : "target_first";
}

// [chamber], [fog] and [experiment]: the keys of the experiment itself.
KeyTable<Scenario> experiment_keys(const std::vector<std::string>& sensor_names) {
  KeyTable<Scenario> keys;
  keys.number("chamber.sensor_gap_m", FOGRADAR_KEY_FIELD(chamber.sensor_gap_m),
              closed(0.0, propagation::max_chamber_length_m),
              "l_s, sensor to the first layer (0: the first layer touches the sensor)");
  const auto uniform = [](const Scenario& s) { return s.chamber.layers.empty(); };
  const std::string uniform_text = "without [[chamber.layers]], which gives each layer's length";
  keys.integer("chamber.layer_count", FOGRADAR_KEY_FIELD(chamber.layer_count), 1,
               static_cast<std::int64_t>(propagation::max_chamber_layers),
               "switchable layers, all with the `[fog]` below")
      .when(uniform, uniform_text);
  keys.number("chamber.layer_length_m", FOGRADAR_KEY_FIELD(chamber.layer_length_m),
              open_closed(0.0, propagation::max_chamber_length_m), "f_i")
      .when(uniform, uniform_text);
  keys.number("chamber.target_gap_m", FOGRADAR_KEY_FIELD(chamber.target_gap_m),
              closed(0.0, propagation::max_chamber_length_m), "l_t, last layer to the target");
  ScenarioKey& layers = keys.table_array(
      "chamber.layers", FOGRADAR_KEY_FIELD(chamber.layers), &layer_keys,
      propagation::max_chamber_layers, "tables of `length_m` and `fog`",
      "the layers from the sensor, each of its own length and fog, in place of `layer_count` "
      "layers of `layer_length_m` with `[fog]`; a layer's `fog` is a table of `[fog]`'s keys "
      "(`fog = { lwc_g_per_m3 = 10.0 }`) replacing `[fog]`'s values for that layer");
  // Each layer starts from [fog] (read before the arrays of tables), so that its own `fog` table
  // states only where it differs.
  layers.array_resize = [](Scenario& s, std::size_t n) {
    s.chamber.layers.resize(
        n, propagation::FogLayerSpec{.length_m = std::numeric_limits<double>::quiet_NaN(),
                                     .fog = s.fog});
  };
  keys.include(propagation::room_keys("chamber.room."), FOGRADAR_KEY_FIELD(chamber.room));
  keys.at("chamber.room.back_wall.distance_m").within([](const Scenario& s) {
    const double target_m = s.chamber_spec().target_range_m();
    return CrossBound{.range = open_closed(target_m, propagation::max_room_extent_m),
                      .low_text = "the target's range = " + message_number(target_m),
                      .high_text = message_number(propagation::max_room_extent_m),
                      .note = ": the wall stands behind the target"};
  });
  keys.table_array("chamber.objects", FOGRADAR_KEY_FIELD(chamber.room.objects),
                   &propagation::room_object_keys, propagation::max_room_objects,
                   "tables of `shape`, position, size and `material`",
                   "static objects standing in the hall (the study's rain barrels): vertical "
                   "cylinders and plates; `objects = []` under [chamber]: none");
  keys.include(propagation::fog_keys("fog."), FOGRADAR_KEY_FIELD(fog));
  keys.include(sensor::target_world_keys(), FOGRADAR_KEY_FIELD(target));

  std::vector<std::string> names_quoted;
  for (const std::string& name : sensor_names) names_quoted.push_back(in_quotes(name));
  const std::string allowed = "a non-empty array of distinct names from " +
                              joined(names_quoted, ", ") +
                              " (the sensor instances: each kind's own, and those a section "
                              "names with `kind`)";
  ScenarioKey& sensors = keys.name_list(
      "experiment.sensors", [](const Scenario& s) { return s.experiment.sensors; },
      [](Scenario& s, const std::vector<std::string>& names) { s.experiment.sensors = names; },
      allowed,
      "the sensors that run, each on the same chamber and fog; results are reported in this "
      "order");
  sensors.choices = sensor_names;
  sensors.with_check([allowed, sensor_names](const Scenario& s) {
    const std::vector<std::string>& given = s.experiment.sensors;
    std::string listed;
    for (std::size_t i = 0; i < given.size(); ++i) {
      listed += (listed.empty() ? "[" : ", ") + given[i];
      const bool known =
          std::find(sensor_names.begin(), sensor_names.end(), given[i]) != sensor_names.end();
      if (!known || std::find(given.begin(), given.begin() + static_cast<std::ptrdiff_t>(i),
                              given[i]) != given.begin() + static_cast<std::ptrdiff_t>(i)) {
        throw_invalid("experiment.sensors", listed + ", ...]", allowed);
      }
    }
    if (given.empty()) throw_invalid("experiment.sensors", "[]", allowed);
  });
  // Its true upper bound is the chamber's layer count: the key's own bound is only the widest one
  // the reader accepts before it states that (chamber is read first), and the check states it too.
  // Not given, it follows the chamber: every layer. scenario.toml writes the value in force.
  ScenarioKey& active = keys.integer(
      "experiment.max_active_layers",
      [](const Scenario& s) { return static_cast<std::int64_t>(s.steps() - 1); },
      [](Scenario& s, std::int64_t v) {
        s.experiment.max_active_layers = static_cast<std::size_t>(v);
      },
      "", "steps k = 0 … max_active_layers; not given: every layer of the chamber");
  active.integer_low = 0;
  active.integer_high = static_cast<std::int64_t>(propagation::max_chamber_layers);
  active.check = [](const Scenario& s) {
    if (s.experiment.max_active_layers &&
        *s.experiment.max_active_layers > s.chamber.layers_in_use()) {
      throw_invalid("experiment.max_active_layers",
                    static_cast<double>(*s.experiment.max_active_layers),
                    integer_range_of_active(s.chamber.layers_in_use(), !s.chamber.layers.empty()));
    }
  };
  active.documented_as("integer [0, the layer count]");
  keys.order(
      "experiment.switching_order",
      [](const Scenario& s) -> std::string {
        const auto* from = std::get_if<SwitchingFrom>(&s.experiment.switching_order);
        return from ? std::string(switching_from_name(*from)) : std::string();
      },
      [](Scenario& s, std::string_view name) {
        if (name == "sensor_first") {
          s.experiment.switching_order = SwitchingFrom::sensor;
        } else if (name == "target_first") {
          s.experiment.switching_order = SwitchingFrom::target;
        } else {
          throw_invalid("experiment.switching_order", name,
                        "one of 'sensor_first', 'target_first', or an array naming each layer "
                        "index 0 … n−1 once");
        }
      },
      [](const Scenario& s) {
        const auto* listed = std::get_if<std::vector<std::size_t>>(&s.experiment.switching_order);
        return listed ? *listed : std::vector<std::size_t>{};
      },
      [](Scenario& s, const std::vector<std::size_t>& listed) {
        s.experiment.switching_order = listed;
      },
      [](const Scenario& s) { return s.chamber.layers_in_use(); }, {"sensor_first", "target_first"},
      "`sensor_first`, `target_first`, or an array naming each layer index 0 … n−1 once",
      "the order the layers are switched on in, step by step: from the sensor (the study's), "
      "from the target, or the layer indices (0 at the sensor) in the order they come on");
  // TOML integers are signed 64-bit: a larger seed could not be written to scenario.toml.
  keys.integer("experiment.seed", FOGRADAR_KEY_FIELD(experiment.seed), 0,
               std::numeric_limits<std::int64_t>::max(), "overridden by `--seed`");
  return keys;
}

// The `kind` of an instance other than its kind's own: read once, where the instance is added
// (the reader adds it before it reads the keys); a file may repeat it, not change it.
void add_kind_key(KeyTable<Scenario>& keys, const SensorSetting& setting, std::size_t i) {
  const std::string kind(setting.kind->name());
  keys.choice(
      setting.name + ".kind",
      [i](const Scenario& s) { return std::string(s.sensors[i].kind->name()); },
      [kind, key = setting.name + ".kind"](const Scenario&, std::string_view name) {
        if (name != kind) {
          throw_invalid(key, name, "'" + kind + "', the kind the instance was made with");
        }
      },
      {kind}, "the kind of this sensor instance: its keys are the kind's, under this section");
}

// The scenario's keys in file order, one table per part: the world's and the methodology's, then
// each sensor instance's (its kind's keys, under its own section).
std::vector<KeyTable<Scenario>> key_parts(const std::vector<SensorSetting>& sensors) {
  std::vector<std::string> names;
  for (const SensorSetting& setting : sensors) names.push_back(setting.name);
  std::vector<KeyTable<Scenario>> parts;
  parts.push_back(experiment_keys(names));
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const SensorSetting& setting = sensors[i];
    const auto params = [i](auto& scenario) -> auto& { return *scenario.sensors[i].params; };
    KeyTable<Scenario> part;
    if (setting.is_kinds_own()) {
      part.include(setting.kind->keys(), params);
    } else {
      add_kind_key(part, setting, i);
      part.include(
          setting.kind->keys().renamed(std::string(setting.kind->name()) + ".", setting.name + "."),
          params);
    }
    parts.push_back(std::move(part));
  }
  return parts;
}

}  // namespace

namespace detail {

// A section belongs to the part that declares it first, the experiment's part before the sensors'
// (so [target] is the world's although the radar refuses its moved keys there); a section's own
// keys come first, keys other parts declare in it after them.
ScenarioKeys::ScenarioKeys(const std::vector<SensorSetting>& sensors) {
  for (const SensorSetting& setting : sensors) {
    kinds.push_back(setting.kind.get());
    names.push_back(setting.name);
  }
  std::vector<std::size_t> part_of;
  std::vector<KeyTable<Scenario>> parts = key_parts(sensors);
  for (std::size_t p = 0; p < parts.size(); ++p) {
    part_of.insert(part_of.end(), parts[p].keys().size(), p);
    all.append(std::move(parts[p]));
  }
  const std::vector<Key<Scenario>>& keys = all.keys();
  std::map<std::string, std::size_t, std::less<>> owner;
  for (std::size_t i = 0; i < keys.size(); ++i) owner.emplace(keys[i].section(), part_of[i]);
  const auto section_of = [&](std::string_view name) -> Section& {
    for (Section& s : sections) {
      if (s.name == name) return s;
    }
    return sections.emplace_back(Section{std::string(name), owner.find(name)->second, {}});
  };
  for (const bool own : {true, false}) {
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if ((owner.find(keys[i].section())->second == part_of[i]) == own) {
        section_of(keys[i].section()).keys.push_back(&keys[i]);
      }
    }
  }
}

const ScenarioKeys& keys_of(const Scenario& s) {
  FOGRADAR_CHECK(s.keys_ != nullptr);  // a moved-from scenario has none
  const ScenarioKeys& keys = *s.keys_;
  // The tables read and write sensors[i] by index.
  FOGRADAR_CHECK(keys.kinds.size() == s.sensors.size());
  for (std::size_t i = 0; i < s.sensors.size(); ++i) {
    FOGRADAR_CHECK(keys.kinds[i] == s.sensors[i].kind.get() && keys.names[i] == s.sensors[i].name);
  }
  return keys;
}

}  // namespace detail

}  // namespace fogradar::experiment
