// Values set over a scenario by key: the sensor instances a file makes, an element's keys, the keys
// a scenario takes, and the values a program gives read as a file's.
#include "fogradar/experiment/scenario_values.hpp"

#include <algorithm>
#include <charconv>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "scenario_parts.hpp"

namespace fogradar::experiment {
namespace detail {

// Adds the sensor instances the file's sections make (`[radar_24] kind = "radar"`), before any key
// is read: their keys are the scenario's from then on.
void add_instances(Scenario& s, const toml::table& root, std::string_view source_name,
                   LineNumbers line_numbers) {
  std::set<std::string> sections;
  for (const Section& section : keys_of(s).sections) {
    sections.insert(section.name.substr(0, section.name.find('.')));
  }
  for (const auto& [name, node] : root) {
    const std::string section(name.str());
    const toml::table* table = node.as_table();
    if (sections.contains(section) || table == nullptr || !table->contains("kind")) continue;
    const toml::node& kind = *table->get("kind");
    const std::size_t line = line_numbers == LineNumbers::shown ? kind.source().begin.line : 0;
    try {
      const std::optional<std::string> kind_name = kind.value<std::string>();
      if (!kind_name) {
        throw InvalidParameter(section + ".kind", section +
                                                      ".kind must be a string naming a "
                                                      "sensor kind, e.g. kind = \"radar\"");
      }
      s.add_sensor(section, *kind_name, section);
    } catch (const InvalidParameter& e) {
      throw_at(source_name, line, e.field(), e.message());
    }
  }
}

bool is_element_key(std::string_view key) { return key.find('[') != std::string_view::npos; }

// An element key needs its element in the base (the array's other elements and keys are the
// base's).
ElementKey element_key(const Scenario& base, const std::string& key) {
  const std::size_t open = key.find('['), close = key.find(']', open);
  const std::string array = key.substr(0, open);
  const ScenarioKey* table = nullptr;
  for (const ScenarioKey& k : base.keys().keys()) {
    if (k.name == array && k.type == KeyType::table_array) table = &k;
  }
  if (table == nullptr || close == std::string::npos || key.size() < close + 2 ||
      key[close + 1] != '.') {
    throw InvalidParameter(key, "'" + key +
                                    "' is no scenario key (an element's key is written "
                                    "array[i].key, e.g. chamber.layers[2].fog.lwc_g_per_m3)");
  }
  const std::string digits = key.substr(open + 1, close - open - 1);
  std::size_t index = 0;
  const auto [end, parsed] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
  const std::size_t count = table->array_size(base);
  if (parsed != std::errc() || end != digits.data() + digits.size() ||
      std::to_string(index) != digits || index >= count) {
    throw InvalidParameter(key, "'" + key + "': the base scenario's " + array + " has " +
                                    (count == 0 ? std::string("no elements")
                                                : "elements 0 … " + std::to_string(count - 1)) +
                                    "; a key of one element needs that element in the base");
  }
  ElementKey found;
  table->array_element(index, found.element);
  const std::vector<ScenarioKey>& keys = found.element.keys();
  found.at = static_cast<std::size_t>(std::find_if(keys.begin(), keys.end(),
                                                   [&](const ScenarioKey& k) {
                                                     return k.name == key &&
                                                            k.type != KeyType::retired &&
                                                            k.type != KeyType::table_array;
                                                   }) -
                                      keys.begin());
  if (found.at == keys.size()) {
    std::string known;
    const std::string prefix = array + "[" + digits + "].";
    for (const ScenarioKey& k : found.element.keys()) {
      known += ' ';
      known.append(k.name, prefix.size());
    }
    throw InvalidParameter(key, "'" + key + "' is no scenario key (keys of an element of " + array +
                                    ":" + known + ")");
  }
  return found;
}

}  // namespace detail

using detail::ScenarioKey;

void require_key(const Scenario& base, const std::string& key) {
  if (detail::is_element_key(key)) {
    detail::element_key(base, key);
    return;
  }
  std::string known;
  const std::string section = key.substr(0, key.rfind('.'));
  for (const ScenarioKey& k : base.keys().keys()) {
    if (k.name != key) {
      if (k.section() == section && k.type != KeyType::retired) (known += ' ') += k.short_name();
      continue;
    }
    if (k.type == KeyType::retired)
      throw InvalidParameter(key, "'" + key + "' is no longer read: " + k.meaning);
    return;
  }
  std::string sections;
  for (const std::string& top : top_level_sections(base))
    sections += (sections.empty() ? "" : ", ") + top;
  throw InvalidParameter(
      key, "'" + key + "' is no scenario key (" +
               (known.empty() ? "sections: " + sections : "keys of [" + section + "]:" + known) +
               ")");
}

namespace {

// A switch given together with keys of its table: `true` becomes the table they fill; `false`
// contradicts them and is refused, naming the switch.
toml::table switched_on(const toml::node& given_switch, std::string_view switch_key) {
  if (given_switch.value_or(false)) return {};
  throw InvalidParameter(std::string(switch_key),
                         std::string(switch_key) + " = false leaves out [" +
                             std::string(switch_key) +
                             "], but keys of that table are given too: give one or the other");
}

}  // namespace

Scenario set_values_over(const Scenario& base, const std::vector<KeyValue>& values,
                         std::string_view source) {
  // The keys of sections as a file's tables; an element's keys after the arrays, over the element.
  toml::table root;
  std::vector<KeyValue> element_values;
  for (const KeyValue& value : values) {
    if (detail::is_element_key(value.key)) {
      element_values.push_back(value);
      continue;
    }
    toml::table* table = &root;
    std::string_view rest = value.key;
    for (std::size_t dot = rest.find('.'); dot != std::string_view::npos; dot = rest.find('.')) {
      const std::string_view name = rest.substr(0, dot);
      // A section's name is no key's (require_key), but for a switch: a boolean key whose name is
      // a table's (chamber.room.left_wall), which a file switches on by giving the table.
      if (toml::node* given = table->get(name); given != nullptr && given->is_boolean()) {
        const std::size_t switch_length =
            static_cast<std::size_t>(rest.data() - value.key.data()) + dot;
        table->insert_or_assign(name, switched_on(*given, value.key.substr(0, switch_length)));
      }
      table = table->emplace<toml::table>(name).first->second.as_table();
      FOGRADAR_CHECK(table != nullptr);
      rest.remove_prefix(dot + 1);
    }
    if (const toml::node* given = table->get(rest);
        given != nullptr && given->is_table() && value.value->is_boolean()) {
      switched_on(*value.value, value.key);  // its table's keys switch it on already
      continue;
    }
    value.value->visit([&](const auto& node) { table->insert_or_assign(rest, node); });
  }
  return detail::read_over(base, root, "", source, LineNumbers::hidden, element_values);
}

}  // namespace fogradar::experiment
