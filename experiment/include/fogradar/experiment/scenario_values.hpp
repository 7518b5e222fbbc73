// Values a program sets over a scenario by key (a sweep's axes, its draws): read through the
// scenario's key table with the scenario reader's checks and messages, as if a file gave them.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <string_view>
#include <vector>

#include "fogradar/experiment/scenario.hpp"

namespace fogradar::experiment {

// A key's full name as a scenario file's reader names it ("fog.lwc_g_per_m3", or one element's,
// "chamber.layers[2].fog.lwc_g_per_m3") and its value.
struct KeyValue {
  std::string key;
  const toml::node* value = nullptr;
};

// Refuses a key `scenario` does not take: InvalidParameter naming `key`, with the keys of its
// section (or the scenario's sections), or, for an element's key, the elements `scenario` has.
void require_key(const Scenario& scenario, const std::string& key);

// `base` with `values` set: a key of [section] as that section's key in a file, a key of one
// element of an array of tables as that element's (the array's other elements are base's). Every
// check of the scenario reader applies, and its messages name the key and `source` without a line.
Scenario set_values_over(const Scenario& base, const std::vector<KeyValue>& values,
                         std::string_view source);

}  // namespace fogradar::experiment
