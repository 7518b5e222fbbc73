// The scenario file's reader: its TOML tables into a Scenario by its keys.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "scenario_parts.hpp"
#include "toml_bytes.hpp"

namespace fogradar::experiment {
namespace detail {
namespace {

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
  // A key read through functions names its own set (radar.target.swerling: 0, 1, 3).
  if (key.integer_low == std::numeric_limits<std::int64_t>::min()) {
    return {key.integer_low, key.integer_high, "an integer (" + key.allowed + ")"};
  }
  return {key.integer_low, key.integer_high,
          "an integer in [" + std::to_string(key.integer_low) + ", " +
              std::to_string(key.integer_high) + "]"};
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
         Scenario& scenario, LineNumbers line_numbers, const std::vector<KeyValue>& element_values)
      : root_(root),
        text_(text),
        source_(source),
        scenario_(scenario),
        lines_shown_(line_numbers == LineNumbers::shown),
        element_values_(element_values) {}

  void read() {
    const detail::ScenarioKeys& keys = detail::keys_of(scenario_);
    const std::vector<Section>& sections = keys.sections;
    for (const ScenarioKey& key : keys.all.keys()) {
      if (!key.group.empty()) groups_[key.group].emplace_back(key.short_name());
    }
    for (const Section& s : sections) {
      for (const ScenarioKey& key : keys.all.keys()) {
        if (key.type == KeyType::boolean && key.name == s.name) switches_.insert(s.name);
      }
    }
    std::vector<std::string> top, shown_top;
    for (const Section& s : sections) {
      declared_.insert(s.name);
      for (std::size_t dot = s.name.find('.'); dot != std::string::npos;
           dot = s.name.find('.', dot + 1)) {
        declared_.insert(s.name.substr(0, dot));
      }
      const std::string first = s.name.substr(0, s.name.find('.'));
      if (std::find(top.begin(), top.end(), first) == top.end()) top.push_back(first);
      if (!s.retired() && std::find(shown_top.begin(), shown_top.end(), first) == shown_top.end()) {
        shown_top.push_back(first);
      }
    }
    for (const auto& [name, node] : root_) {
      const std::string key(name.str());
      if (std::find(top.begin(), top.end(), key) == top.end()) {
        throw_at(source_, shown(node.source().begin.line), key,
                 "unknown section or key '" + key + "' (sections: " + joined(shown_top, ", ") +
                     "; a further sensor instance gives its kind: [" + key + "] kind = \"radar\")");
      }
    }
    for (const Section& section : sections) {
      const toml::node* node = root_.at_path(section.name).node();
      if (node == nullptr) continue;
      const toml::table* table = node->as_table();
      if (table == nullptr) {
        // `floor = false`: the switch of the sub-table, read with its parent's keys.
        if (switches_.contains(section.name)) continue;
        fail_not_table(*node, section.name);
      }
      read_table(*table, section.name, section.keys);
    }
    // Arrays of tables come after every plain key, so that an element can start from them (a layer
    // of [[chamber.layers]] from [fog]).
    take_table_temperature("fog.", scenario_.fog);
    for (const auto& [key, node] : arrays_) read_array(*key, *node);
    for (const KeyValue& value : element_values_) {
      elements_.push_back(element_key(scenario_, value.key));
      read_key(elements_.back().key(), *value.value);
    }
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

  // A key whose bound involves other keys (radar.processing.cfar.guard_cells) states its true range
  // in its check; the widest value the reader takes draws it out.
  std::optional<std::string> bound_by_others(const ScenarioKey& key) const {
    if (!key.cross_check) return std::nullopt;
    return refusal(
        key, [&key](Scenario& probe) { key.set_integer(probe, key.integer_high); }, true);
  }

  // The empty name is no choice's: the parser states the set.
  std::string choice_range(const ScenarioKey& key) const {
    const std::optional<std::string> range =
        refusal(key, [&key](Scenario& probe) { key.set_text(probe, ""); });
    return "a string, " + range.value_or("one of " + plain(key.allowed));
  }

  // A key read through functions (radar.target.swerling) names its own set when given none of it.
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
        if (!node.is_integer()) {
          fail(node, key.name, given + bound_by_others(key).value_or(integer_text(key, range)));
        }
        const std::int64_t value = *node.value<std::int64_t>();
        if (value < range.low || value > range.high) {
          fail(node, key.name, given + bound_by_others(key).value_or(range.text));
        }
        key.set_integer(scenario_, value);
        return;
      }
      case KeyType::boolean:
        // A switch that names a sub-table (chamber.room.floor) is switched on by that table,
        // whose keys its own section reads.
        if (node.is_table() && switches_.contains(key.name)) {
          key.set_boolean(scenario_, true);
          return;
        }
        if (!node.is_boolean()) {
          fail(node, key.name,
               given + (switches_.contains(key.name) ? "false, or a table [" + key.name + "]"
                                                     : "true or false"));
        }
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
             at(node.source().begin.line) + " are both given: at most one " + key.group + " of " +
             joined(members, ", ") + " per [" + section + "]");
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
  std::set<std::string> switches_;  // boolean keys that switch a sub-table of their name
  std::set<std::string> declared_;  // every section and its parents
  std::map<std::string, std::vector<std::string>> groups_;    // group -> its keys' short names
  std::map<std::string, std::string> given_in_group_;         // "section group" -> the key given
  std::map<std::string, std::set<std::string>> nested_keys_;  // an element's table -> its keys
  std::vector<std::pair<const ScenarioKey*, const toml::node*>> arrays_;  // read last
  const std::vector<KeyValue>& element_values_;                           // after the arrays
  std::deque<ElementKey> elements_;                                       // their keys
};

}  // namespace

Scenario read_over(Scenario s, const toml::table& root, std::string_view text,
                   std::string_view source_name, LineNumbers line_numbers,
                   const std::vector<KeyValue>& element_values) {
  add_instances(s, root, source_name, line_numbers);
  Reader reader(root, text, source_name, s, line_numbers, element_values);
  try {
    reader.read();
    s.validate();
  } catch (const InvalidParameter& e) {
    // Without line numbers, the other keys a message names are not pointed at either.
    relocate(e, source_name, line_numbers == LineNumbers::shown ? reader.lines() : KeyLines{},
             reader.typed_numbers());
  }
  return s;
}

// Reads `toml_text` over `base`: keys the file gives replace the base's values.
Scenario parse_over(Scenario s, std::string_view toml_text, std::string_view source_name,
                    LineNumbers line_numbers) {
  detail::require_toml_safe_bytes(toml_text, source_name);
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw_at(source_name, e.source().begin.line, "toml",
             std::string("malformed TOML: ") + std::string(e.description()));
  }
  return read_over(std::move(s), root, toml_text, source_name, line_numbers, {});
}

}  // namespace detail
}  // namespace fogradar::experiment
