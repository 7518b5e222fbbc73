// The scenario's parts shared by its files: the key layout, the TOML text helpers, the reader's
// entry and its error relocation.
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/scenario_values.hpp"

namespace fogradar::experiment::detail {

using ScenarioKey = Key<Scenario>;

// Line of each key read from the file, to point error messages at it.
using KeyLines = std::map<std::string, std::size_t>;

// A section of the file (a TOML table) with its keys, in the order the file lists them.
struct Section {
  std::string name;
  std::size_t part = 0;  // of key_parts()
  std::vector<const Key<Scenario>*> keys;

  // A section of retired keys alone ([processing]) is read, to name where they went, and is
  // neither written nor documented.
  bool retired() const {
    return std::all_of(keys.begin(), keys.end(),
                       [](const Key<Scenario>* key) { return key->type == KeyType::retired; });
  }
};

// A scenario's keys and the file's layout of them, made once from its sensors (Scenario's
// constructor) and shared by its copies.
struct ScenarioKeys {
  explicit ScenarioKeys(const std::vector<SensorSetting>& sensors);

  std::vector<const sensor::SensorKind*> kinds;  // the instances they were made for, in order
  std::vector<std::string> names;
  KeyTable<Scenario> all;  // every key, in part order
  std::vector<Section> sections;
};

// scenario_keys.cpp

// The range experiment.max_active_layers allows with `layer_count` layers in the chamber, given by
// chamber.layer_count or listed by [[chamber.layers]].
std::string integer_range_of_active(std::size_t layer_count, bool listed);

// scenario_writer.cpp

std::string format_toml_number(double value);
std::string in_quotes(std::string_view text);
std::string joined(const std::vector<std::string>& items, std::string_view separator);
// A key's value as scenario.toml writes it.
std::string toml_value(const ScenarioKey& key, const Scenario& s);

// scenario_errors.cpp

// Line 0: the message names the source and the key alone.
[[noreturn]] void throw_at(std::string_view source, std::size_t line, const std::string& key,
                           const std::string& message);
// Rethrows a check's error `e` from reading `source`, pointed at the line of its key as the file
// gave it (`lines`), with the number as the file typed it (`typed_numbers`).
[[noreturn]] void relocate(const InvalidParameter& e, std::string_view source,
                           const KeyLines& lines,
                           const std::map<std::string, std::string>& typed_numbers);

// scenario_values.cpp

// A key of one element of an array of tables ("chamber.layers[2].fog.lwc_g_per_m3"): the element's
// keys (the table keeps them) and the one named.
struct ElementKey {
  KeyTable<Scenario> element;
  std::size_t at = 0;
  const ScenarioKey& key() const { return element.keys()[at]; }
};

bool is_element_key(std::string_view key);
// `key` in `s`'s key table; refuses it (InvalidParameter naming `key`) where `s` has no such
// element or the element no such key.
ElementKey element_key(const Scenario& s, const std::string& key);

// Adds the sensor instances the sections of `root` make (`[radar_24] kind = "radar"`).
void add_instances(Scenario& s, const toml::table& root, std::string_view source_name,
                   LineNumbers line_numbers);

// scenario_reader.cpp

// Reads `toml_text` over `base`: keys the file gives replace the base's values.
Scenario parse_over(Scenario s, std::string_view toml_text, std::string_view source_name,
                    LineNumbers line_numbers = LineNumbers::shown);
// Reads `root`, a file's tables (`text`: the file, empty for tables a program built), over `s`,
// then `element_values`, keys of one element each, over the elements in force.
Scenario read_over(Scenario s, const toml::table& root, std::string_view text,
                   std::string_view source_name, LineNumbers line_numbers,
                   const std::vector<KeyValue>& element_values);

}  // namespace fogradar::experiment::detail
