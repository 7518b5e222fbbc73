#include "fogradar/experiment/scenario.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/files.hpp"
#include "toml_bytes.hpp"

namespace fogradar::experiment {
namespace detail {
std::string_view paper_scenario_text();
}  // namespace detail

namespace {

using ScenarioKey = Key<Scenario>;

// Line of each key read from the file, to point error messages at it.
using KeyLines = std::map<std::string, std::size_t>;

// Line 0: the message names the source and the key alone.
[[noreturn]] void throw_at(std::string_view source, std::size_t line, const std::string& key,
                           const std::string& message) {
  throw InvalidParameter(key, message, {std::string(source), line});
}

// A value as TOML writes it, for messages about a value of the wrong type. Arrays and tables are
// written here element by element: toml++ 3.3's formatter of a container holding 0.0 casts
// log10(0) to an integer (undefined behaviour; the fuzzer found it).
std::string as_written(const toml::node& node) {
  if (const toml::array* array = node.as_array()) {
    std::string text = "[";
    for (const toml::node& element : *array) {
      if (text.size() > 1) text += ", ";
      text += as_written(element);
    }
    return text + "]";
  }
  if (const toml::table* table = node.as_table()) {
    std::string text = "{";
    for (const auto& [key, value] : *table) {
      text += text.size() > 1 ? ", " : " ";
      text += std::string(key.str()) + " = " + as_written(value);
    }
    return text + " }";
  }
  std::ostringstream text;
  node.visit([&text](const auto& value) { text << value; });
  return text.str();
}

std::string format_toml_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string in_quotes(std::string_view text) { return "\"" + std::string(text) + "\""; }

std::string joined(const std::vector<std::string>& items, std::string_view separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : std::string(separator)) + item;
  return text;
}

// The range experiment.max_active_layers allows with `layer_count` layers in the chamber, given by
// chamber.layer_count or listed by [[chamber.layers]].
std::string integer_range_of_active(std::size_t layer_count, bool listed) {
  const std::string count = std::to_string(layer_count);
  if (!listed) return "an integer in [0, chamber.layer_count = " + count + "]";
  return "an integer in [0, " + count + "] (the layers [[chamber.layers]] lists)";
}

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
  keys.include(propagation::fog_keys("fog."), FOGRADAR_KEY_FIELD(fog));

  std::vector<std::string> names_quoted;
  for (const std::string& name : sensor_names) names_quoted.push_back(in_quotes(name));
  const std::string allowed =
      "a non-empty array of distinct names from " + joined(names_quoted, ", ");
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
  keys.integer("experiment.measurements_per_step",
               FOGRADAR_KEY_FIELD(experiment.measurements_per_step), 1, 1000000,
               "the study's series length: measurements per step of the sensors that take its "
               "measurements (the others count their own items)");
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

// The scenario's keys in file order, one table per part: the first sensor's, the experiment's, the
// other sensors'.
std::vector<KeyTable<Scenario>> key_parts(const std::vector<SensorSetting>& sensors) {
  std::vector<std::string> names;
  for (const SensorSetting& setting : sensors) names.emplace_back(setting.type->name());
  std::vector<KeyTable<Scenario>> parts;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (i == 1) parts.push_back(experiment_keys(names));
    KeyTable<Scenario> part;
    part.include(
        sensors[i].type->keys(), [i](auto& scenario) -> auto& {
          return scenario.sensors[i].params;
        });
    parts.push_back(std::move(part));
  }
  if (sensors.size() < 2) parts.push_back(experiment_keys(names));
  return parts;
}

}  // namespace

namespace detail {

// A section of the file (a TOML table) with its keys, in the order the file lists them.
struct Section {
  std::string name;
  std::size_t part = 0;  // of key_parts()
  std::vector<const Key<Scenario>*> keys;
};

// A scenario's keys and the file's layout of them, made once from its sensors (Scenario's
// constructor) and shared by its copies.
struct ScenarioKeys {
  explicit ScenarioKeys(const std::vector<SensorSetting>& sensors);

  std::vector<const sensor::SensorType*> types;  // the sensors they were made for, in order
  KeyTable<Scenario> all;                        // every key, in part order
  std::vector<Section> sections;
};

// A section belongs to the part that declares it first, the experiment's part before the sensors'
// (so [fog] is the experiment's although the radar declares fog.clutter_scatterers_per_bin); a
// section's own keys come first, keys other parts declare in it after them.
ScenarioKeys::ScenarioKeys(const std::vector<SensorSetting>& sensors) {
  for (const SensorSetting& setting : sensors) types.push_back(setting.type.get());
  const std::size_t experiment_part = sensors.empty() ? 0 : 1;
  std::vector<std::size_t> part_of;
  std::vector<KeyTable<Scenario>> parts = key_parts(sensors);
  for (std::size_t p = 0; p < parts.size(); ++p) {
    part_of.insert(part_of.end(), parts[p].keys().size(), p);
    all.append(std::move(parts[p]));
  }
  const std::vector<Key<Scenario>>& keys = all.keys();
  std::map<std::string, std::size_t, std::less<>> owner;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (part_of[i] == experiment_part) owner.emplace(keys[i].section(), experiment_part);
  }
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
  FOGRADAR_CHECK(keys.types.size() == s.sensors.size());
  for (std::size_t i = 0; i < s.sensors.size(); ++i) {
    FOGRADAR_CHECK(keys.types[i] == s.sensors[i].type.get());
  }
  return keys;
}

}  // namespace detail

namespace {

using detail::Section;

bool is_key_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.';
}

// Positions where `key` occurs in `text` as a whole key, not as part of a longer one.
std::vector<std::size_t> key_positions(std::string_view text, std::string_view key) {
  std::vector<std::size_t> found;
  for (std::size_t at = text.find(key); at != std::string_view::npos; at = text.find(key, at + 1)) {
    const std::size_t end = at + key.size();
    const bool starts = at == 0 || !is_key_char(text[at - 1]);
    const bool ends = end == text.size() || !is_key_char(text[end]) ||
                      (text[end] == '.' && (end + 1 == text.size() || !is_key_char(text[end + 1])));
    if (starts && (key.back() == '.' || ends)) found.push_back(at);
  }
  return found;
}

// The lines of the other keys a combined check names, so every key involved can be found.
std::string other_key_lines(const std::string& message, const std::string& key,
                            const KeyLines& lines) {
  std::string listed;
  for (const auto& [other, line] : lines) {
    if (other == key || key_positions(message, other).empty()) continue;
    listed += (listed.empty() ? " (" : ", ") + other + " at line " + std::to_string(line);
  }
  return listed.empty() ? listed : listed + ")";
}

// An integer key's allowed values in `s`, checked and stated by the reader.
struct IntegerRange {
  std::int64_t low = 0;
  std::int64_t high = 0;
  std::string text;  // after "must be "
};

// `layers_in_file`: the layer count [[chamber.layers]] gives, read after [experiment].
IntegerRange integer_range(const ScenarioKey& key, const Scenario& s,
                           std::optional<std::size_t> layers_in_file) {
  if (key.name == "experiment.max_active_layers") {
    const std::size_t count = layers_in_file.value_or(s.chamber.layers_in_use());
    const bool listed = layers_in_file || !s.chamber.layers.empty();
    return {0, static_cast<std::int64_t>(count), integer_range_of_active(count, listed)};
  }
  // A key read through functions names its own set (target.swerling: 0, 1, 3).
  if (key.integer_low == std::numeric_limits<std::int64_t>::min()) {
    return {key.integer_low, key.integer_high, "an integer (" + key.allowed + ")"};
  }
  std::string text = "an integer in [" + std::to_string(key.integer_low) + ", " +
                     std::to_string(key.integer_high) + "]";
  if (key.integer_also) text += " " + key.integer_also(s);
  return {key.integer_low, key.integer_high, text};
}

// docs/scenario.md's allowed values as a message states them (no Markdown).
std::string plain(std::string text) {
  std::erase(text, '`');
  return text;
}

// The byte offset of 1-based `column` (counted in UTF-8 code points, as toml++ counts) in `line`.
std::size_t byte_of_column(std::string_view line, std::size_t column) {
  std::size_t at = 0;
  for (std::size_t c = 1; c < column && at < line.size(); ++c) {
    ++at;
    while (at < line.size() && (static_cast<unsigned char>(line[at]) & 0xC0U) == 0x80U) ++at;
  }
  return at;
}

// Reads a scenario file's tables into a Scenario by its keys.
class Reader {
 public:
  Reader(const toml::table& root, std::string_view text, std::string_view source,
         Scenario& scenario, LineNumbers line_numbers)
      : root_(root),
        text_(text),
        source_(source),
        scenario_(scenario),
        lines_shown_(line_numbers == LineNumbers::shown) {}

  void read() {
    const detail::ScenarioKeys& keys = detail::keys_of(scenario_);
    const std::vector<Section>& sections = keys.sections;
    for (const ScenarioKey& key : keys.all.keys()) {
      if (!key.group.empty()) groups_[key.group].emplace_back(key.short_name());
    }
    std::vector<std::string> top;
    for (const Section& s : sections) {
      declared_.insert(s.name);
      for (std::size_t dot = s.name.find('.'); dot != std::string::npos;
           dot = s.name.find('.', dot + 1)) {
        declared_.insert(s.name.substr(0, dot));
      }
      const std::string first = s.name.substr(0, s.name.find('.'));
      if (std::find(top.begin(), top.end(), first) == top.end()) top.push_back(first);
    }
    for (const auto& [name, node] : root_) {
      const std::string key(name.str());
      if (std::find(top.begin(), top.end(), key) == top.end()) {
        throw_at(source_, shown(node.source().begin.line), key,
                 "unknown section or key '" + key + "' (sections: " + joined(top, ", ") + ")");
      }
    }
    for (const Section& section : sections) {
      const toml::node* node = root_.at_path(section.name).node();
      if (node == nullptr) continue;
      const toml::table* table = node->as_table();
      if (table == nullptr) fail_not_table(*node, section.name);
      read_table(*table, section.name, section.keys);
    }
    // Arrays of tables come after every plain key, so that an element can start from them (a layer
    // of [[chamber.layers]] from [fog]).
    take_table_temperature("fog.", scenario_.fog);
    for (const auto& [key, node] : arrays_) read_array(*key, *node);
    for (std::size_t i = 0; i < scenario_.chamber.layers.size(); ++i) {
      // A layer starts without a length (NaN, "missing"): a NaN the file gives is its own value.
      const std::string length = "chamber.layers[" + std::to_string(i) + "].length_m";
      if (std::isnan(scenario_.chamber.layers[i].length_m) && lines_.contains(length)) {
        throw_at(source_, shown(lines_.at(length)), length,
                 length + " = " + typed_numbers_.at(length) + ": must be " +
                     open_closed(0.0, propagation::max_chamber_length_m).constraint());
      }
      take_table_temperature("chamber.layers[" + std::to_string(i) + "].fog.",
                             scenario_.chamber.layers[i].fog);
    }
    // A key read before the arrays may take effect only without them (chamber.layer_count).
    for (const ScenarioKey& key : keys.all.keys()) {
      const auto given = lines_.find(key.name);
      if (given == lines_.end() || !key.group.empty() || key.takes_effect(scenario_)) continue;
      throw_at(source_, shown(given->second), key.name,
               key.name + " is given: it takes effect only " + key.applies_text);
    }
  }

  const KeyLines& lines() const { return lines_; }

  // The water table has no temperature dependence: a fog that chooses it without a temperature
  // takes the table's own, as `fogradar fog --water-model segelstein` does, rather than the
  // paper scenario's assumed 20 C (which the table cannot use). A temperature the file gives is
  // checked as given.
  void take_table_temperature(const std::string& prefix, propagation::FogSpec& fog) const {
    if (lines_.contains(prefix + "water_model") && !lines_.contains(prefix + "temperature_c") &&
        fog.water_model == propagation::WaterModel::segelstein) {
      fog.temperature_c = propagation::segelstein_table_temperature_c;
    }
  }

  // The layer count [[chamber.layers]] gives, where the file lists layers (`layers = []` lists
  // none: the chamber is layer_count layers).
  std::optional<std::size_t> layers_in_file() const {
    const toml::array* layers = root_.at_path("chamber.layers").as_array();
    if (layers == nullptr || layers->empty()) return std::nullopt;
    return layers->size();
  }
  // The number each key was given as, as typed ("3e-7", "1e5", "0x10").
  const std::map<std::string, std::string>& typed_numbers() const { return typed_numbers_; }

 private:
  // A value as the file gives it: a number or an array on one line as typed, anything else as
  // TOML writes it.
  std::string typed(const toml::node& node) const {
    const toml::source_region& at = node.source();
    if (!(node.is_number() || node.is_array()) || at.begin.line == 0 ||
        at.end.line != at.begin.line) {
      return as_written(node);
    }
    std::string_view rest = text_;
    for (std::size_t line = 1; line < at.begin.line; ++line) {
      const std::size_t end = rest.find('\n');
      if (end == std::string_view::npos) return as_written(node);
      rest.remove_prefix(end + 1);
    }
    const std::string_view line = rest.substr(0, rest.find('\n'));
    const std::size_t begin = byte_of_column(line, at.begin.column);
    const std::size_t end = byte_of_column(line, at.end.column);
    if (end <= begin) return as_written(node);
    return std::string(line.substr(begin, end - begin));
  }

  // What `key` allows as its own message states it, for a value of the wrong type: `set` puts a
  // value no key allows into a copy of the scenario, whose setter or check then refuses it.
  // With `whole`, the scenario's own checks run too (a sensor's bounds across its keys).
  std::optional<std::string> refusal(const ScenarioKey& key,
                                     const std::function<void(Scenario&)>& set,
                                     bool whole = false) const {
    try {
      Scenario probe = scenario_;
      set(probe);
      key.check_alone(probe);
      if (whole) probe.validate();
    } catch (const InvalidParameter& e) {
      const std::string_view what = e.message(), must = ": must be ";
      const std::size_t at = what.find(must);
      if (e.field() == key.name && at != std::string_view::npos) {
        return std::string(what.substr(at + must.size()));
      }
    }
    return std::nullopt;
  }

  // A NaN is outside every range: the range comes with the values of the keys it involves.
  std::string number_range(const ScenarioKey& key) const {
    const std::optional<std::string> range = refusal(key, [&key](Scenario& probe) {
      key.set_number(probe, std::numeric_limits<double>::quiet_NaN());
    });
    if (range && range->starts_with("finite and ")) return "a finite number " + range->substr(11);
    if (range) return "a number " + *range;
    const std::string allowed = plain(key.allowed);
    const bool interval = allowed.starts_with('[') || allowed.starts_with('(');
    return (interval ? "a number in " : "a number ") + allowed;
  }

  // A key whose bound involves other keys (processing.cfar.guard_cells) states its true range in
  // its check; the widest value the reader takes draws it out.
  std::optional<std::string> bound_by_others(const ScenarioKey& key) const {
    if (!key.integer_also) return std::nullopt;
    return refusal(
        key, [&key](Scenario& probe) { key.set_integer(probe, key.integer_high); }, true);
  }

  // The empty name is no choice's: the parser states the set.
  std::string choice_range(const ScenarioKey& key) const {
    const std::optional<std::string> range =
        refusal(key, [&key](Scenario& probe) { key.set_text(probe, ""); });
    return "a string, " + range.value_or("one of " + plain(key.allowed));
  }

  // A key read through functions (target.swerling) names its own set when given none of it.
  std::string integer_text(const ScenarioKey& key, const IntegerRange& range) const {
    if (key.integer_low != std::numeric_limits<std::int64_t>::min()) return range.text;
    const std::optional<std::string> own = refusal(key, [&key](Scenario& probe) {
      key.set_integer(probe, std::numeric_limits<std::int64_t>::min());
    });
    return own ? "an integer, " + *own : range.text;
  }

  // The keys a table of `section` takes, sub-tables included, for the messages that list them.
  std::set<std::string> keys_of_table(const std::string& section) const {
    std::set<std::string> known;
    for (const Section& s : detail::keys_of(scenario_).sections) {
      if (s.name != section) continue;
      for (const ScenarioKey* key : s.keys) {
        if (key->type != KeyType::retired) known.emplace(key->short_name());
      }
    }
    if (const auto nested = nested_keys_.find(section); nested != nested_keys_.end()) {
      known.insert(nested->second.begin(), nested->second.end());
    }
    for (const std::string& name : declared_) {
      if (name.size() > section.size() + 1 && name.starts_with(section + ".") &&
          name.find('.', section.size() + 1) == std::string::npos) {
        known.insert(name.substr(section.size() + 1));
      }
    }
    return known;
  }

  [[noreturn]] void fail(const toml::node& node, const std::string& key,
                         const std::string& message) const {
    throw_at(source_, shown(node.source().begin.line), key, message);
  }
  // A line for a message: 0 (none) where the text is not the user's own.
  std::size_t shown(std::size_t line) const { return lines_shown_ ? line : 0; }

  [[noreturn]] void fail_not_table(const toml::node& node, const std::string& section) const {
    const std::set<std::string> keys = keys_of_table(section);
    fail(node, section,
         section + " = " + typed(node) + ": must be a table [" + section + "] with keys " +
             joined(std::vector<std::string>(keys.begin(), keys.end()), ", "));
  }

  // Reads `keys` (all of section `section`) from `table`, then refuses what is left.
  void read_table(const toml::table& table, const std::string& section,
                  const std::vector<const ScenarioKey*>& keys) {
    std::set<std::string> known;
    for (const ScenarioKey* key : keys) {
      if (key->type != KeyType::retired) known.emplace(key->short_name());
    }
    std::set<std::string> subsections;
    for (const std::string& name : declared_) {
      if (name.size() > section.size() + 1 && name.starts_with(section + ".") &&
          name.find('.', section.size() + 1) == std::string::npos) {
        subsections.insert(name.substr(section.size() + 1));
      }
    }
    // A sub-table given a plain value is refused as that sub-table before any key is read, so
    // its message is the first one even where a key of the section is bad too.
    for (const auto& [name, node] : table) {
      const std::string key(name.str());
      if (!known.contains(key) && subsections.contains(key) && !node.is_table()) {
        fail_not_table(node, section + "." + key);
      }
    }
    for (const ScenarioKey* key : keys) {
      if (const toml::node* node = table.get(key->short_name())) read_key(*key, *node);
    }
    for (const auto& [name, node] : table) {
      const std::string key(name.str()), full = section + "." + key;
      if (known.contains(key) || subsections.contains(key)) continue;
      std::set<std::string> all = known;
      all.insert(subsections.begin(), subsections.end());
      std::string hint;
      for (const std::string& k : all) hint += " " + k;
      fail(node, full, "unknown key '" + full + "' (known keys of [" + section + "]:" + hint + ")");
    }
  }

  void read_key(const ScenarioKey& key, const toml::node& node) {
    lines_[key.name] = node.source().begin.line;
    if (node.is_number() || key.type == KeyType::order) typed_numbers_[key.name] = typed(node);
    if (key.type == KeyType::retired) {
      fail(node, key.name, "'" + key.name + "' is no longer read: " + key.meaning);
    }
    if (!key.group.empty()) require_alone_in_group(key, node);
    if (key.group.empty() && !key.takes_effect(scenario_)) {
      fail(node, key.name,
           key.name + " = " + typed(node) + ": takes effect only " + key.applies_text);
    }
    if (key.type == KeyType::table_array) {
      arrays_.emplace_back(&key, &node);
      return;
    }
    const std::string given = key.name + " = " + typed(node) + ": must be ";
    switch (key.type) {
      case KeyType::number: {
        const std::optional<double> value = node.is_number() ? node.value<double>() : std::nullopt;
        if (!value) fail(node, key.name, given + number_range(key));
        key.set_number(scenario_, *value);
        return;
      }
      case KeyType::integer: {
        const IntegerRange range = integer_range(key, scenario_, layers_in_file());
        if (!node.is_integer()) fail(node, key.name, given + integer_text(key, range));
        const std::int64_t value = *node.value<std::int64_t>();
        if (value < range.low || value > range.high) {
          fail(node, key.name, given + bound_by_others(key).value_or(range.text));
        }
        key.set_integer(scenario_, value);
        return;
      }
      case KeyType::boolean:
        if (!node.is_boolean()) fail(node, key.name, given + "true or false");
        key.set_boolean(scenario_, *node.value<bool>());
        return;
      case KeyType::choice:
        if (!node.is_string()) fail(node, key.name, given + choice_range(key));
        key.set_text(scenario_, *node.value<std::string>());
        return;
      case KeyType::name_list:
        key.set_list(scenario_, names_of(key, node, given + key.allowed));
        return;
      case KeyType::order:
        read_order(key, node, given + plain(key.allowed));
        return;
      case KeyType::table_array:  // read last, above
        return;
      case KeyType::retired:
        return;
    }
  }

  void read_order(const ScenarioKey& key, const toml::node& node, const std::string& given) {
    if (node.is_string()) {
      key.set_text(scenario_, *node.value<std::string>());
      return;
    }
    const toml::array* array = node.as_array();
    if (array == nullptr || array->empty()) fail(node, key.name, given);
    std::vector<std::size_t> indices;
    for (const toml::node& element : *array) {
      const std::optional<std::int64_t> index =
          element.is_integer() ? element.value<std::int64_t>() : std::nullopt;
      if (!index || *index < 0) {
        fail(node, key.name, given + " (" + as_written(element) + " is no index)");
      }
      indices.push_back(static_cast<std::size_t>(*index));
    }
    key.set_indices(scenario_, indices);
  }

  // Two keys of one group in one table are alternatives: the second one given is refused.
  void require_alone_in_group(const ScenarioKey& key, const toml::node& node) {
    const std::string section(key.section());
    const auto [first, fresh] = given_in_group_.emplace(section + " " + key.group, key.name);
    if (fresh) return;
    std::vector<std::string> members;
    for (const std::string& member : groups_.at(key.group))
      members.push_back(section + "." + member);
    const auto at = [this](std::size_t line) {
      return lines_shown_ ? " (line " + std::to_string(line) + ")" : std::string();
    };
    fail(node, key.name,
         first->second + at(lines_.at(first->second)) + " and " + key.name +
             at(node.source().begin.line) + " are both given: at most one " + key.group + " of " + joined(members, ", ") +
             " per [" + section + "]");
  }

  std::vector<std::string> names_of(const ScenarioKey& key, const toml::node& node,
                                    const std::string& given) const {
    const toml::array* array = node.as_array();
    if (array == nullptr || array->empty()) fail(node, key.name, given);
    std::vector<std::string> names;
    for (const toml::node& element : *array) {
      if (!element.is_string())
        fail(node, key.name, given + " (" + as_written(element) + " is not a string)");
      const std::string name = *element.value<std::string>();
      if (std::find(key.choices.begin(), key.choices.end(), name) == key.choices.end()) {
        fail(node, key.name, given + " (\"" + name + "\" is no sensor)");
      }
      if (std::find(names.begin(), names.end(), name) != names.end()) {
        fail(node, key.name, given + " (\"" + name + "\" is named twice)");
      }
      names.push_back(name);
    }
    return names;
  }

  // An array of tables replaces the scenario's whole array; each element starts from its defaults
  // (a layer of [[chamber.layers]] from [fog]).
  void read_array(const ScenarioKey& key, const toml::node& node) {
    KeyTable<Scenario> first;
    key.array_element(0, first);
    std::vector<std::string> element_keys;
    const std::size_t prefix = key.name.size() + std::string_view("[0].").size();
    for (const ScenarioKey& k : first.keys()) {
      const std::string name = k.name.substr(prefix, k.name.find('.', prefix) - prefix);
      if (std::find(element_keys.begin(), element_keys.end(), name) == element_keys.end()) {
        element_keys.push_back(name);
      }
    }
    const std::string wanted = key.name + ": must be an array of tables [[" + key.name +
                               "]] with keys " + joined(element_keys, ", ");
    const toml::array* array = node.as_array();
    if (array == nullptr) fail(node, key.name, wanted);
    if (array->size() > key.array_max) {
      fail(node, key.name, wanted + ", at most " + std::to_string(key.array_max));
    }
    key.array_resize(scenario_, 0);
    key.array_resize(scenario_, array->size());
    for (std::size_t i = 0; i < array->size(); ++i) {
      const toml::table* table = (*array)[i].as_table();
      if (table == nullptr) fail((*array)[i], key.name, wanted);
      lines_[key.name + "[" + std::to_string(i) + "]"] = (*array)[i].source().begin.line;
      KeyTable<Scenario> element;
      key.array_element(i, element);
      std::vector<const ScenarioKey*> keys;
      for (const ScenarioKey& k : element.keys()) keys.push_back(&k);
      const std::string section = key.name + "[" + std::to_string(i) + "]";
      declare_nested(section, keys);
      read_nested(*table, section, keys);
    }
  }

  // An element's keys in `section` and its sub-tables (a layer's `fog`, its `fog.droplets`), each
  // by the next part of its name after `section`.
  static std::map<std::string, std::vector<const ScenarioKey*>> by_child(
      const std::string& section, const std::vector<const ScenarioKey*>& keys) {
    std::map<std::string, std::vector<const ScenarioKey*>> children;
    for (const ScenarioKey* key : keys) {
      const std::string_view rest = std::string_view(key->name).substr(section.size() + 1);
      const std::size_t dot = rest.find('.');
      children[dot == std::string_view::npos ? std::string() : std::string(rest.substr(0, dot))]
          .push_back(key);
    }
    return children;
  }

  // Makes an element's sub-tables known, for the messages that list a table's keys.
  void declare_nested(const std::string& section, const std::vector<const ScenarioKey*>& keys) {
    for (const auto& [child, child_keys] : by_child(section, keys)) {
      if (child.empty()) {
        for (const ScenarioKey* key : child_keys) {
          nested_keys_[section].emplace(key->short_name());
        }
        continue;
      }
      declared_.insert(section + "." + child);
      declare_nested(section + "." + child, child_keys);
    }
  }

  void read_nested(const toml::table& table, const std::string& section,
                   const std::vector<const ScenarioKey*>& keys) {
    const auto children = by_child(section, keys);
    const auto own = children.find("");
    read_table(table, section,
               own == children.end() ? std::vector<const ScenarioKey*>{} : own->second);
    for (const auto& [child, child_keys] : children) {
      if (child.empty()) continue;
      const toml::node* node = table.get(child);
      if (node == nullptr) continue;
      // read_table refused a sub-table given a plain value.
      read_nested(*node->as_table(), section + "." + child, child_keys);
    }
  }

  const toml::table& root_;
  std::string_view text_;
  std::string_view source_;
  Scenario& scenario_;
  bool lines_shown_;
  KeyLines lines_;
  std::map<std::string, std::string> typed_numbers_;
  std::set<std::string> declared_;                          // every section and its parents
  std::map<std::string, std::vector<std::string>> groups_;  // group -> its keys' short names
  std::map<std::string, std::string> given_in_group_;       // "section group" -> the key given
  std::map<std::string, std::set<std::string>> nested_keys_;  // an element's table -> its keys
  std::vector<std::pair<const ScenarioKey*, const toml::node*>> arrays_;  // read last
};

// A key's value as scenario.toml writes it.
std::string toml_value(const ScenarioKey& key, const Scenario& s) {
  switch (key.type) {
    case KeyType::number:
      return format_toml_number(key.get_number(s));
    case KeyType::integer:
      return std::to_string(key.get_integer(s));
    case KeyType::boolean:
      return key.get_boolean(s) ? "true" : "false";
    case KeyType::choice:
      return in_quotes(key.get_text(s));
    case KeyType::name_list: {
      std::vector<std::string> names;
      for (const std::string& name : key.get_list(s)) names.push_back(in_quotes(name));
      return "[" + joined(names, ", ") + "]";
    }
    case KeyType::order: {
      const std::vector<std::size_t> indices = key.get_indices(s);
      if (indices.empty()) return in_quotes(key.get_text(s));
      std::vector<std::string> listed;
      for (const std::size_t i : indices) listed.push_back(std::to_string(i));
      return "[" + joined(listed, ", ") + "]";
    }
    case KeyType::table_array:
      return key.array_size(s) == 0 ? "[]" : "";
    case KeyType::retired:
      return "";
  }
  return "";
}

// A check's message "<key> = <value>: must be ..." with the number as the file typed it, where it
// gave one (a check writes the double it holds: "3e-07" for 3e-7, "100000" for 1e5).
std::string as_typed(const std::string& message, const std::string& key,
                     const std::map<std::string, std::string>& typed_numbers) {
  const auto typed = typed_numbers.find(key);
  const std::string head = key + " = ";
  if (typed == typed_numbers.end() || !message.starts_with(head)) return message;
  const std::size_t end = message.find(": ", head.size());
  if (end == std::string::npos || message[head.size()] == '\'') return message;
  return head + typed->second + message.substr(end);
}

// Reads `toml_text` over `base`: keys the file gives replace the base's values.
Scenario parse_over(Scenario s, std::string_view toml_text, std::string_view source_name,
                    LineNumbers line_numbers = LineNumbers::shown) {
  detail::require_toml_safe_bytes(toml_text, source_name);
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw_at(source_name, e.source().begin.line, "toml",
             std::string("malformed TOML: ") + std::string(e.description()));
  }
  Reader reader(root, toml_text, source_name, s, line_numbers);
  try {
    reader.read();
    s.validate();
  } catch (const InvalidParameter& e) {
    // Without line numbers, the other keys a message names are not pointed at either.
    const KeyLines& lines = line_numbers == LineNumbers::shown ? reader.lines() : KeyLines{};
    // A reader's error already names its key and line; it may name keys read before it.
    if (e.location().source == source_name) {
      throw InvalidParameter(e.field(), e.message() + other_key_lines(e.message(), e.field(), lines),
                             e.location());
    }
    // A range check: point at the key as the user wrote it, and its line.
    const std::string& key = e.field();
    const std::string message =
        as_typed(e.message(), key, reader.typed_numbers()) + other_key_lines(e.message(), key, lines);
    // A key the file does not give keeps its paper value; a check combining it with keys the file
    // gives points at the first of those.
    std::size_t line = 0;
    std::size_t within = 0;  // the longest table given that holds the key: a layer of an array
    for (const auto& [table, table_line] : lines) {
      if (key.size() > table.size() && key.starts_with(table) && key[table.size()] == '.' &&
          table.size() > within) {
        within = table.size();
        line = table_line;
      }
    }
    if (const auto given = lines.find(key); given != lines.end()) {
      line = given->second;
    } else if (line == 0) {
      for (const auto& [other, other_line] : lines) {
        if (!key_positions(e.message(), other).empty() && (line == 0 || other_line < line))
          line = other_line;
      }
    }
    throw_at(source_name, line, key, message);
  }
  return s;
}

// A default as docs/scenario.md shows it.
std::string doc_value(const ScenarioKey& key, const Scenario& s) {
  if (!key.takes_effect(s)) return "—";
  switch (key.type) {
    case KeyType::number:
      return "`" + doc_number(key.get_number(s)) + "`";
    case KeyType::table_array:
      return std::to_string(key.array_size(s)) + " tables";
    case KeyType::retired:
      return "—";
    default:
      return "`" + toml_value(key, s) + "`";
  }
}

std::string table_row(const ScenarioKey& key, std::string_view name, const std::string& value) {
  return "| `" + std::string(name) + "` | " + value + " | " + key.allowed + " | " + key.meaning +
         " |\n";
}

}  // namespace

Scenario::Scenario(const SensorRegistry& registry) {
  for (const auto& type : registry.types()) {
    sensors.push_back({type, type->default_params()});
    experiment.sensors.emplace_back(type->name());
  }
  keys_ = std::make_shared<const detail::ScenarioKeys>(sensors);
}

SensorSetting& Scenario::setting(std::string_view name) {
  for (SensorSetting& s : sensors) {
    if (s.type->name() == name) return s;
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
  for (const SensorSetting& s : sensors) s.type->validate(s.params, shared);
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

Scenario load_scenario_file(const std::string& path, const SensorRegistry& registry) {
  const std::string wanted = "a readable regular TOML file of at most " +
                             std::to_string(max_scenario_file_bytes) + " bytes (1 MiB)";
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it unread.
  const detail::Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  const int fd = file.fd;
  if (fd < 0) throw_invalid("--scenario", path, wanted + " (" + std::strerror(errno) + ")");
  struct stat info {};
  if (::fstat(fd, &info) != 0)
    throw_invalid("--scenario", path, wanted + " (" + std::strerror(errno) + ")");
  if (!S_ISREG(info.st_mode)) {
    const char* kind = S_ISDIR(info.st_mode)    ? "a directory"
                       : S_ISFIFO(info.st_mode) ? "a FIFO"
                       : S_ISCHR(info.st_mode)  ? "a character device"
                       : S_ISBLK(info.st_mode)  ? "a block device"
                       : S_ISSOCK(info.st_mode) ? "a socket"
                                                : "not a regular file";
    throw_invalid("--scenario", path, wanted + "; it is " + kind);
  }
  if (static_cast<std::uintmax_t>(info.st_size) > max_scenario_file_bytes) {
    throw_invalid("--scenario", path,
                  wanted + "; it holds " + std::to_string(info.st_size) + " bytes");
  }
  std::string text(static_cast<std::size_t>(info.st_size), '\0');
  std::size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw_invalid("--scenario", path, wanted + " (" + std::strerror(errno) + ")");
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  text.resize(got);
  return parse_scenario(text, path, registry);
}

std::string to_toml(const Scenario& s) {
  const std::vector<Section>& sections = detail::keys_of(s).sections;
  std::vector<std::string> blocks;
  // Arrays of tables follow the last section of the part that declares them.
  std::vector<std::string> arrays;
  const auto flush_arrays = [&] {
    blocks.insert(blocks.end(), arrays.begin(), arrays.end());
    arrays.clear();
  };
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const Section& section = sections[i];
    std::string block = "[" + section.name + "]\n";
    for (const ScenarioKey* key : section.keys) {
      if (key->type == KeyType::retired || !key->takes_effect(s)) continue;
      if (key->type == KeyType::table_array && key->array_size(s) > 0) {
        for (std::size_t e = 0; e < key->array_size(s); ++e) {
          KeyTable<Scenario> element;
          key->array_element(e, element);
          std::string table = "[[" + key->name + "]]\n";
          // A sub-table's keys by their dotted names relative to the element ("fog.lwc_g_per_m3").
          const std::size_t prefix = key->name.size() + 3 + std::to_string(e).size();
          for (const ScenarioKey& k : element.keys()) {
            if (!k.takes_effect(s)) continue;
            table += k.name.substr(prefix) + " = " + toml_value(k, s) + "\n";
          }
          arrays.push_back(table);
        }
        continue;
      }
      block += std::string(key->short_name()) + " = " + toml_value(*key, s) + "\n";
    }
    blocks.push_back(block);
    if (i + 1 == sections.size() || sections[i + 1].part != section.part) flush_arrays();
  }
  return "# fogradar resolved scenario: every key, as used by the run\n\n" + joined(blocks, "\n");
}

std::vector<std::string> top_level_sections(const Scenario& s) {
  std::vector<std::string> top;
  for (const Section& section : detail::keys_of(s).sections) {
    const std::string first = section.name.substr(0, section.name.find('.'));
    if (std::find(top.begin(), top.end(), first) == top.end()) top.push_back(first);
  }
  return top;
}

std::string key_table_markdown(const Scenario& defaults, std::string_view top) {
  const std::string prefix = std::string(top) + ".";
  std::string rows;
  for (const Section& section : detail::keys_of(defaults).sections) {
    if (section.name != top && !section.name.starts_with(prefix)) continue;
    for (const ScenarioKey* key : section.keys) {
      if (key->type == KeyType::retired) continue;
      const std::string_view name = std::string_view(key->name).substr(prefix.size());
      rows += table_row(*key, name, doc_value(*key, defaults));
      if (key->type != KeyType::table_array) continue;
      KeyTable<Scenario> element;
      key->array_element(0, element);
      std::set<std::string> tables;  // an element's sub-tables, one row each
      const std::size_t from = key->name.size() + std::string_view("[0].").size();
      for (const ScenarioKey& k : element.keys()) {
        const std::string relative = k.name.substr(from);
        const std::size_t dot = relative.find('.');
        if (dot == std::string::npos) {
          rows += table_row(k, std::string(name) + "[]." + relative, "—");
          continue;
        }
        const std::string table = relative.substr(0, dot);
        if (!tables.insert(table).second) continue;
        rows += "| `" + std::string(name) + "[]." + table + "` | `[" + table +
                "]` | a table of `[" + table + "]`'s keys | this element's own `[" + table +
                "]`: the keys it gives replace `[" + table + "]`'s values |\n";
      }
    }
  }
  if (rows.empty()) {
    throw_invalid("--keys", top,
                  "a section of the scenario: " + joined(top_level_sections(defaults), ", "));
  }
  return "| key | default | allowed | meaning |\n|---|---|---|---|\n" + rows;
}

}  // namespace fogradar::experiment
