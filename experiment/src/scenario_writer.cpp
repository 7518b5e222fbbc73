// A scenario written out: as TOML (the resolved scenario.toml) and as docs/scenario.md's key
// tables.
#include <algorithm>
#include <charconv>
#include <set>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "scenario_parts.hpp"

namespace fogradar::experiment {
namespace detail {

std::string format_toml_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

namespace {

// `inner` between `open` and `close`, built by appending: GCC 12 warns (-Wrestrict, a false
// positive) on "literal" + std::string&& once it inlines the insertion.
std::string enclosed(std::string_view open, std::string_view inner, std::string_view close) {
  std::string text;
  text.reserve(open.size() + inner.size() + close.size());
  text.append(open).append(inner).append(close);
  return text;
}

}  // namespace

std::string in_quotes(std::string_view text) { return enclosed("\"", text, "\""); }

std::string joined(const std::vector<std::string>& items, std::string_view separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : std::string(separator)) + item;
  return text;
}

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
      return enclosed("[", joined(names, ", "), "]");
    }
    case KeyType::order: {
      const std::vector<std::size_t> indices = key.get_indices(s);
      if (indices.empty()) return in_quotes(key.get_text(s));
      std::vector<std::string> listed;
      for (const std::size_t i : indices) listed.push_back(std::to_string(i));
      return enclosed("[", joined(listed, ", "), "]");
    }
    case KeyType::table_array:
      return key.array_size(s) == 0 ? "[]" : "";
    case KeyType::retired:
      return "";
  }
  return "";
}

}  // namespace detail

namespace {

using detail::joined;
using detail::ScenarioKey;
using detail::Section;
using detail::toml_value;

// A default as docs/scenario.md shows it.
std::string doc_value(const ScenarioKey& key, const Scenario& s) {
  if (!key.takes_effect(s)) return "—";
  switch (key.type) {
    case KeyType::number:
      return detail::enclosed("`", doc_number(key.get_number(s)), "`");
    case KeyType::table_array:
      return std::to_string(key.array_size(s)) + " tables";
    case KeyType::retired:
      return "—";
    default:
      return detail::enclosed("`", toml_value(key, s), "`");
  }
}

std::string table_row(const ScenarioKey& key, std::string_view name, const std::string& value) {
  return "| `" + std::string(name) + "` | " + value + " | " + key.allowed + " | " + key.meaning +
         " |\n";
}

}  // namespace

std::string to_toml(const Scenario& s) {
  const std::vector<Section>& sections = detail::keys_of(s).sections;
  std::vector<std::string> blocks;
  // Arrays of tables follow the last section of the part that declares them.
  std::vector<std::string> arrays;
  // A boolean key that switches the sub-table of its name (chamber.room.floor): written `false`
  // when off; when on, its table says so.
  const auto switch_of = [&](const std::string& name) -> const ScenarioKey* {
    for (const Section& other : sections) {
      for (const ScenarioKey* key : other.keys) {
        if (key->type == KeyType::boolean && key->name == name) return key;
      }
    }
    return nullptr;
  };
  const auto flush_arrays = [&] {
    blocks.insert(blocks.end(), arrays.begin(), arrays.end());
    arrays.clear();
  };
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const Section& section = sections[i];
    const bool part_ends = i + 1 == sections.size() || sections[i + 1].part != section.part;
    if (section.retired()) {
      if (part_ends) flush_arrays();
      continue;
    }
    const ScenarioKey* switched_by = switch_of(section.name);
    if (switched_by != nullptr && !switched_by->get_boolean(s)) {
      if (part_ends) flush_arrays();
      continue;
    }
    std::string block = "[" + section.name + "]\n";
    for (const ScenarioKey* key : section.keys) {
      if (key->type == KeyType::retired || !key->takes_effect(s)) continue;
      if (key->type == KeyType::boolean && key->get_boolean(s) &&
          std::any_of(sections.begin(), sections.end(),
                      [&](const Section& other) { return other.name == key->name; })) {
        continue;
      }
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
    if (part_ends) flush_arrays();
  }
  return "# fogradar resolved scenario: every key, as used by the run\n\n" + joined(blocks, "\n");
}

std::vector<std::string> top_level_sections(const Scenario& s) {
  std::vector<std::string> top;
  for (const Section& section : detail::keys_of(s).sections) {
    if (section.retired()) continue;
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
