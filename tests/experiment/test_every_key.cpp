// Every declared scenario key, driven by the key table (Scenario::keys(), core/keys.hpp), never by
// a list of names written here (docs/validation.md, "Every key"): each key in turn is set to valid
// values other than its value in a small base scenario, written to TOML and read back as a user's
// file would be, and run with all three sensors until one value changes what the run measured (its
// CSV files and PGM images: the JSON files and plots also state settings). A key must so change the
// run, or be refused with a message naming it, or be listed below with the reason it changes
// nothing there (a listed key that does change the run fails the test). A key that takes effect
// only with another's value (the radome's permittivity with a radome) is run with it and must be
// refused without it; the same holds after each switch of its section is turned (a boolean negated,
// a choice changed: the camera's noise keys with its noise off). Keys of arrays of tables are
// checked for every element: the layers of a layered base ([[chamber.layers]]) and the lidar's
// background segments. One test per top-level section, so that ctest runs them apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/core/keys.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"

namespace fogradar::experiment {
namespace {

using ScenarioKey = Key<Scenario>;

// The paper scenario made small: two layers, few measurements, scans and frames, a small ROI; and
// one lidar background segment, a screen on the right, whose keys the paper scenario does not give.
constexpr const char* uniform_base_toml = R"(
[chamber]
layer_count = 2

[[lidar.background]]
x0_m = 3.0
y0_m = 2.5
x1_m = 9.0
y1_m = 2.5
reflectivity = 0.4

[radar]
chirps_per_frame = 16
measurements_per_step = 3

[lidar]
scans_per_step = 2

[camera]
frames_per_step = 1
roi = { width_px = 32, height_px = 24, cell_px = 4 }
)";

// The same with two layers of their own, unlike each other, and two objects in the hall.
constexpr const char* layered_base_toml = R"(
[chamber]

[[chamber.layers]]
length_m = 1.0
fog = { lwc_g_per_m3 = 0.3 }

[[chamber.layers]]
length_m = 0.5
fog = { extinction_per_km = 600.0, temperature_c = 10.0 }

[[chamber.objects]]
shape = "cylinder"
x_m = 3.0
y_m = -1.2
radius_m = 0.3
height_m = 0.9
material = "plastic"

[[chamber.objects]]
shape = "plate"
x_m = 6.0
y_m = 1.2
width_m = 0.5
height_m = 1.0
yaw_deg = 10.0
material = "metal"

[radar]
chirps_per_frame = 16
measurements_per_step = 3

[lidar]
scans_per_step = 2

[camera]
frames_per_step = 1
roi = { width_px = 32, height_px = 24, cell_px = 4 }
)";

// A key's name with its array indices emptied ("chamber.layers[].fog.lwc_g_per_m3"), as
// docs/scenario.md names it: the lists below name keys so.
std::string generic_name(const std::string& name) {
  std::string generic;
  bool in_index = false;
  for (const char c : name) {
    if (c == '[') in_index = true;
    if (c == ']') in_index = false;
    if (!in_index || c == '[') generic += c;
  }
  return generic;
}

// Keys that take effect only with others set (the radome's permittivity needs a radome): for each,
// those keys (in the same array element) and their values, as a file gives them. Each key is run
// with them set; without them it must be refused, or change the run there too.
using Needed = std::vector<std::pair<std::string, std::string>>;
const std::map<std::string, Needed>& enabled_by() {
  static const std::map<std::string, Needed> table{
      {"radar.adc_full_scale_dbm", {{"radar.adc_bits", "12"}}},
      {"radar.radome.relative_permittivity", {{"radar.radome.thickness_m", "0.003"}}},
      {"radar.radome.loss_tangent", {{"radar.radome.thickness_m", "0.003"}}},
      {"radar.processing.cfar.os_rank", {{"radar.processing.cfar.kind", "os"}}},
      {"radar.processing.cfar.doppler_guard_cells",
       {{"radar.processing.cfar.shape", "range_doppler"},
        {"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      {"radar.processing.cfar.doppler_training_cells",
       {{"radar.processing.cfar.shape", "range_doppler"},
        {"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      {"radar.target.swerling", {{"radar.target.model", "point"}}},
      {"radar.target.height_m", {{"radar.target.model", "point"}}},
      {"fog.droplets.diameter_m", {{"fog.droplets.distribution", "monodisperse"}}},
      {"fog.droplets.alpha", {{"fog.droplets.distribution", "modified_gamma"}}},
      {"fog.droplets.gamma", {{"fog.droplets.distribution", "modified_gamma"}}},
      {"fog.droplets.b_per_um_gamma", {{"fog.droplets.distribution", "modified_gamma"}}},
      {"chamber.layers[].fog.droplets.diameter_m",
       {{"chamber.layers[].fog.droplets.distribution", "monodisperse"}}},
      {"chamber.layers[].fog.droplets.alpha",
       {{"chamber.layers[].fog.droplets.distribution", "modified_gamma"}}},
      {"chamber.layers[].fog.droplets.gamma",
       {{"chamber.layers[].fog.droplets.distribution", "modified_gamma"}}},
      {"chamber.layers[].fog.droplets.b_per_um_gamma",
       {{"chamber.layers[].fog.droplets.distribution", "modified_gamma"}}},
      {"camera.wavelength_nm", {{"camera.band", "monochromatic"}}},
      {"camera.gamma", {{"camera.transfer", "gamma"}}},
      {"camera.exposure.auto_target_grey", {{"camera.exposure.mode", "auto"}}},
      {"chamber.objects[].radius_m", {{"chamber.objects[].shape", "cylinder"}}},
      {"chamber.objects[].width_m", {{"chamber.objects[].shape", "plate"}}},
      {"chamber.objects[].yaw_deg", {{"chamber.objects[].shape", "plate"}}},
      {"chamber.room.left_wall.material", {{"chamber.room.left_wall", "true"}}},
      // The lidar needs a wall's material (its diffuse reflectance): a coefficient wall runs
      // without it.
      {"chamber.room.left_wall.reflection_coefficient",
       {{"chamber.room.left_wall", "true"}, {"experiment.sensors", "[\"radar\", \"camera\"]"}}},
      {"chamber.room.left_wall.distance_m", {{"chamber.room.left_wall", "true"}}},
      {"chamber.room.right_wall.material", {{"chamber.room.right_wall", "true"}}},
      {"chamber.room.right_wall.reflection_coefficient",
       {{"chamber.room.right_wall", "true"}, {"experiment.sensors", "[\"radar\", \"camera\"]"}}},
      {"chamber.room.right_wall.distance_m", {{"chamber.room.right_wall", "true"}}},
      // Only the radar sees the ceiling, through a beam wide enough in elevation.
      {"chamber.room.ceiling.material",
       {{"chamber.room.ceiling", "true"}, {"radar.elevation_beamwidth_deg", "60"}}},
      {"chamber.room.ceiling.reflection_coefficient",
       {{"chamber.room.ceiling", "true"}, {"radar.elevation_beamwidth_deg", "60"}}},
      {"chamber.room.ceiling.height_m",
       {{"chamber.room.ceiling", "true"}, {"radar.elevation_beamwidth_deg", "60"}}},
      {"chamber.room.back_wall.material", {{"chamber.room.back_wall", "true"}}},
      {"chamber.room.back_wall.reflection_coefficient",
       {{"chamber.room.back_wall", "true"}, {"experiment.sensors", "[\"radar\", \"camera\"]"}}},
      {"chamber.room.back_wall.distance_m", {{"chamber.room.back_wall", "true"}}},
  };
  return table;
}

// Keys whose values other than the base's need other keys changed too, as a file gives them: a
// longer chirp needs a longer chirp interval; the water table holds only its own temperature; the
// CFAR's kind and guard cells change which cells detect only where some lie near the threshold.
const std::map<std::string, Needed>& room_for() {
  static const std::map<std::string, Needed> table{
      {"radar.chirp_duration_s", {{"radar.chirp_interval_s", "1e-4"}}},
      {"fog.water_model", {{"fog.temperature_c", "25"}}},
      {"chamber.layers[].fog.water_model", {{"chamber.layers[].fog.temperature_c", "25"}}},
      {"radar.processing.cfar.kind", {{"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      {"radar.processing.cfar.guard_cells",
       {{"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      {"radar.processing.cfar.threshold_design",
       {{"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      {"radar.processing.cfar.shape", {{"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      // The paper's hall holds only materials with a published diffuse reflectance at 550, 905
      // and 1550 nm: another wavelength needs a hall without them.
      {"lidar.wavelength_m", {{"chamber.room.left_wall", "false"}, {"chamber.objects", "[]"}}},
      // The range-Doppler ring's many cells hold its noise estimate steady: its size changes which
      // cells detect only where some lie near the threshold.
      {"radar.processing.cfar.training_cells",
       {{"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      {"radar.processing.cfar.doppler_guard_cells",
       {{"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      {"radar.processing.cfar.doppler_training_cells",
       {{"radar.processing.cfar.false_alarm_probability", "0.01"}}},
      // The back wall's default 30 m lie at the end of the lidar's record, 12 m within it.
      {"chamber.room.back_wall", {{"chamber.room.back_wall.distance_m", "12"}}},
  };
  return table;
}

// Keys that change nothing the base measures, each with the reason. A key listed here is run too,
// and must indeed change nothing.
const std::map<std::string, std::string>& no_effect() {
  static const std::map<std::string, std::string> table{};
  return table;
}

// Keys that change nothing once a switch of their section is turned ("key | switch = value"), each
// with the reason.
const std::map<std::string, std::string>& no_effect_when() {
  static const std::map<std::string, std::string> table{
      {"radar.processing.cfar.threshold_design | radar.processing.window = \"rectangular\"",
       "the rectangular window leaves the noise cells uncorrelated, for which the correlated "
       "design's factors are the independent ones"},
      {"lidar.scan_rate_hz | lidar.fog_fluctuation.log_std = 0.0",
       "the scan rate sets only the fog fluctuation's scan-to-scan correlation, which log_std = 0 "
       "turns off; it stays a property of the lidar, not refused"},
  };
  return table;
}

// One value of a key: as a file writes it, and how it is set.
struct Candidate {
  std::string toml;
  std::function<void(Scenario&)> set;
};

std::string toml_number(double v) {
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  std::string text(buffer, end);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string quoted(const std::string& text) { return "\"" + text + "\""; }

// A value as a file gives it ("12", "0.003", "os", "true") for a key of scalar type.
Candidate from_text(const ScenarioKey& key, const std::string& text) {
  switch (key.type) {
    case KeyType::number: {
      const double v = std::stod(text);
      return {toml_number(v), [&key, v](Scenario& s) { key.set_number(s, v); }};
    }
    case KeyType::integer: {
      const std::int64_t v = std::stoll(text);
      return {std::to_string(v), [&key, v](Scenario& s) { key.set_integer(s, v); }};
    }
    case KeyType::boolean: {
      const bool v = text == "true";
      return {text, [&key, v](Scenario& s) { key.set_boolean(s, v); }};
    }
    case KeyType::choice:
    case KeyType::order:
      return {quoted(text), [&key, text](Scenario& s) { key.set_text(s, text); }};
    case KeyType::name_list: {
      // An array of quoted names as a file gives it: the names between the quotes.
      std::vector<std::string> names;
      for (std::size_t open = text.find('"'); open != std::string::npos;
           open = text.find('"', text.find('"', open + 1) + 1)) {
        names.push_back(text.substr(open + 1, text.find('"', open + 1) - open - 1));
      }
      return {text, [&key, names](Scenario& s) { key.set_list(s, names); }};
    }
    case KeyType::table_array:
      if (text == "[]") return {text, [&key](Scenario& s) { key.array_resize(s, 0); }};
      ADD_FAILURE() << key.name << ": an array of tables given as text can only be empty, []";
      return {};
    default:
      ADD_FAILURE() << key.name << ": a value given as text needs a scalar key";
      return {};
  }
}

// Values to try, in order: near the key's value in `s` first (where it takes effect there), then
// across orders of magnitude. Those the scenario refuses are passed over.
std::vector<Candidate> candidates(const ScenarioKey& key, const Scenario& s, bool in_effect) {
  std::vector<Candidate> out;
  switch (key.type) {
    case KeyType::number: {
      const double v = in_effect ? key.get_number(s) : 0.0;
      std::vector<double> tries;
      if (v != 0.0) {
        tries = {v * 1.25, v * 0.8, v * 2.0, v * 0.5, v * 10.0, v * 0.1, -v, v + 1.0, v - 1.0};
      }
      for (const double t : {0.5, 0.1, 1e-2, 1e-3, 1e-4, 1e-6, 1.0, 2.0, 10.0, -0.5, -1.0, 0.0})
        tries.push_back(t);
      for (const double t : tries) {
        if (t != v)
          out.push_back({toml_number(t), [&key, t](Scenario& x) { key.set_number(x, t); }});
      }
      break;
    }
    case KeyType::integer: {
      const std::int64_t v = key.get_integer(s);
      std::set<std::int64_t> seen{v};
      for (const std::int64_t t : {v + 1, v - 1, v * 2, v / 2, std::int64_t{0}, std::int64_t{1},
                                   std::int64_t{2}, std::int64_t{3}}) {
        if (!seen.insert(t).second || t < key.integer_low || t > key.integer_high) continue;
        out.push_back({std::to_string(t), [&key, t](Scenario& x) { key.set_integer(x, t); }});
      }
      break;
    }
    case KeyType::boolean: {
      const bool v = key.get_boolean(s);
      out.push_back({v ? "false" : "true", [&key, v](Scenario& x) { key.set_boolean(x, !v); }});
      break;
    }
    case KeyType::choice: {
      const std::string v = key.get_text(s);
      for (const std::string& c : key.choices) {
        if (c != v) out.push_back(from_text(key, c));
      }
      break;
    }
    case KeyType::order: {
      const std::string v = key.get_text(s);
      for (const std::string& c : key.choices) {
        if (c != v) out.push_back(from_text(key, c));
      }
      // An order given by its indices: the layers from the middle out.
      std::vector<std::size_t> indices(key.index_count(s));
      for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = (i + 1) % indices.size();
      std::string text = "[";
      for (const std::size_t i : indices) text += (text.size() > 1 ? ", " : "") + std::to_string(i);
      out.push_back({text + "]", [&key, indices](Scenario& x) { key.set_indices(x, indices); }});
      break;
    }
    case KeyType::name_list: {
      std::vector<std::string> v = key.get_list(s);
      if (v.size() > 1) {
        std::vector<std::string> fewer(v.begin(), v.end() - 1);
        out.push_back(
            {"(without " + v.back() + ")", [&key, fewer](Scenario& x) { key.set_list(x, fewer); }});
      }
      std::reverse(v.begin(), v.end());
      out.push_back({"(reversed)", [&key, v](Scenario& x) { key.set_list(x, v); }});
      break;
    }
    case KeyType::table_array: {
      const std::size_t n = key.array_size(s);
      if (n > 0) {
        out.push_back(
            {"(without the last element)", [&key, n](Scenario& x) { key.array_resize(x, n - 1); }});
      }
      break;
    }
    case KeyType::retired:
      break;
  }
  return out;
}

// The scenario's keys, each element's of its arrays of tables included (tables kept alive here).
struct AllKeys {
  std::deque<KeyTable<Scenario>> element_tables;
  std::vector<const ScenarioKey*> keys;
};

void collect(const KeyTable<Scenario>& table, const Scenario& s, AllKeys& all) {
  for (const ScenarioKey& key : table.keys()) {
    all.keys.push_back(&key);
    if (key.type != KeyType::table_array) continue;
    for (std::size_t i = 0; i < key.array_size(s); ++i) {
      KeyTable<Scenario>& element = all.element_tables.emplace_back();
      key.array_element(i, element);
      collect(element, s, all);
    }
  }
}

std::unique_ptr<AllKeys> all_keys(const Scenario& s) {
  auto all = std::make_unique<AllKeys>();
  collect(s.keys(), s, *all);
  return all;
}

const ScenarioKey* find_key(const AllKeys& all, const std::string& name) {
  for (const ScenarioKey* key : all.keys) {
    if (key->name == name) return key;
  }
  return nullptr;
}

// What a run measured: the files of its records and tables (CSV) and images (PGM). The JSON files
// and the plots also state settings (captions, criteria, summary.json's "scenario"), so a key that
// changes only them may be recorded and still ignored; they are left out.
using Outputs = std::map<std::string, std::string>;

Outputs outputs(const Scenario& scenario) {
  const Simulation simulation(scenario);
  const ExperimentResult result = simulation.run({.threads = 1, .progress = {}});
  Outputs files;
  for (sensor::ResultFile& f : result_files(simulation.scenario(), summarize(result))) {
    if (f.name.ends_with(".csv") || f.name.ends_with(".pgm"))
      files.emplace(f.name, std::move(f.content));
  }
  return files;
}

std::string changed_files(const Outputs& a, const Outputs& b) {
  std::set<std::string> names;
  for (const auto& [name, content] : a) names.insert(name);
  for (const auto& [name, content] : b) names.insert(name);
  std::string changed;
  for (const std::string& name : names) {
    const auto in_a = a.find(name);
    const auto in_b = b.find(name);
    if (in_a == a.end() || in_b == b.end() || in_a->second != in_b->second)
      changed += (changed.empty() ? "" : " ") + name;
  }
  return changed;
}

class Base {
 public:
  Base(const char* toml, std::string name)
      : name_(std::move(name)), scenario_(parse_scenario(toml, name_)) {}
  Base(Scenario scenario, std::string name)
      : name_(std::move(name)), scenario_(std::move(scenario)) {}
  const std::string& name() const { return name_; }
  const Scenario& scenario() const { return scenario_; }
  const Outputs& files() {
    if (!files_) files_ = outputs(scenario_);
    return *files_;
  }

 private:
  std::string name_;
  Scenario scenario_;
  std::optional<Outputs> files_;
};

Base& uniform_base() {
  static Base base(uniform_base_toml, "uniform_base.toml");
  return base;
}
Base& layered_base() {
  static Base base(layered_base_toml, "layered_base.toml");
  return base;
}

// The element index of a key in an array of tables ("chamber.layers[1].fog..." -> "[1]"), to
// name its enabling keys in the same element.
std::string with_index_of(const std::string& pattern, const std::string& key_name) {
  const std::size_t open = key_name.find('[');
  if (open == std::string::npos) return pattern;
  const std::string index = key_name.substr(open, key_name.find(']') - open + 1);
  std::string name = pattern;
  const std::size_t at = name.find("[]");
  if (at != std::string::npos) name.replace(at, 2, index);
  return name;
}

std::string top_of(const std::string& name) { return name.substr(0, name.find_first_of(".[")); }

// The part of its section a key belongs to for the switches: the radar's chain and its view of the
// target are parts of their own, as they were sections of their own before they moved under
// [radar]. A switch is checked against the keys of its own part, which keeps the check's runs
// proportional to each part's switches times its keys rather than the whole radar section's.
std::string part_of(const std::string& name) {
  for (const char* part : {"radar.processing.", "radar.target."}) {
    if (name.starts_with(part)) return part;
  }
  return top_of(name);
}

// A file giving `key` = `value` over a base, for a key outside arrays of tables.
std::string snippet(const ScenarioKey& key, const std::string& value) {
  std::string text = "[";
  text.append(key.section()).append("]\n").append(key.short_name());
  return text.append(" = ").append(value).append("\n");
}

bool names_key(const InvalidParameter& e, const std::string& key) {
  return e.field() == key || std::string(e.what()).find(key) != std::string::npos;
}

// `base` with `with` set (keys named as in generic_name(), in the element of `key_name`).
Scenario with_keys(const Scenario& base, const Needed* with, const std::string& key_name) {
  Scenario s = base;
  if (with == nullptr) return s;
  const auto keys = all_keys(s);
  for (const auto& [pattern, value] : *with) {
    const std::string name = with_index_of(pattern, key_name);
    const ScenarioKey* other = find_key(*keys, name);
    if (other == nullptr) {
      ADD_FAILURE() << "key " << name << " (needed by " << key_name << ") is not declared";
      continue;
    }
    from_text(*other, value).set(s);
  }
  s.validate();
  return s;
}

const Needed* entry(const std::map<std::string, Needed>& table, const std::string& generic) {
  const auto found = table.find(generic);
  return found == table.end() ? nullptr : &found->second;
}

// One key over `base` with `with` set: the values of candidates() that the scenario accepts, each
// written, read back and run until one changes what the run measured. `listed`: the reason it
// changes nothing there, if it is listed (it must then change nothing).
void check_key(const std::string& name, Base& base, const Needed* with, const std::string* listed,
               std::vector<std::string>& log) {
  SCOPED_TRACE("key " + name + " over " + base.name() + (with ? " with the keys it needs" : ""));
  const Scenario enabled = with_keys(base.scenario(), with, name);
  const auto keys_of_enabled = all_keys(enabled);
  const ScenarioKey* key = find_key(*keys_of_enabled, name);
  ASSERT_NE(key, nullptr);
  // A key of a group of alternatives (fog density) selects itself when given.
  const bool in_effect = key->takes_effect(enabled);
  if (!in_effect && key->group.empty()) {
    ADD_FAILURE() << name << " takes no effect in the base (only " << key->applies_text
                  << "): give the keys that enable it in enabled_by()";
    return;
  }

  const Outputs before = with == nullptr ? base.files() : outputs(enabled);
  std::string tried;  // the values accepted, each with what it changed
  std::string refusals;
  std::size_t accepted = 0;
  for (const Candidate& c : candidates(*key, enabled, in_effect)) {
    Scenario s = enabled;
    std::optional<Scenario> read;
    try {
      c.set(s);
      if (!key->takes_effect(s)) continue;
      s.validate();
      const std::string text = to_toml(s);
      read = parse_scenario(text, "changed.toml");
      EXPECT_EQ(to_toml(*read), text) << "the written scenario does not read back";
      if (text == to_toml(enabled)) continue;
    } catch (const InvalidParameter& e) {
      refusals += "\n  " + c.toml + ": " + e.what();
      continue;
    }
    ++accepted;
    const std::string differ = changed_files(before, outputs(*read));
    tried += "\n  " + c.toml + ": " + (differ.empty() ? "nothing" : differ);
    if (!differ.empty()) {
      EXPECT_EQ(listed, nullptr) << name << " = " << c.toml << " changes " << differ
                                 << ", yet it is listed as changing nothing: " << *listed;
      log.push_back(name + " = " + c.toml + (with ? " (with the keys it needs)" : "") +
                    ": changes " + differ);
      return;
    }
  }
  if (accepted == 0) {
    ADD_FAILURE() << "no valid value of " << name << " other than its base value was found;"
                  << " refusals:" << refusals;
  } else if (listed == nullptr) {
    ADD_FAILURE() << name << " is accepted and recorded, and no value of it changes what the"
                  << " run measured:" << tried;
  } else {
    log.push_back(name + ": changes nothing (" + *listed + ")");
  }
}

// A key that takes no effect in `base` without the keys that enable it: a file giving it there
// is refused, naming it.
void check_refused_without(const std::string& name, Base& base, const Needed& enabling,
                           std::vector<std::string>& log) {
  SCOPED_TRACE("key " + name + " over " + base.name() + " without the keys that enable it");
  if (name.find('[') != std::string::npos) return;  // a file cannot give one element's key alone
  const Scenario enabled = with_keys(base.scenario(), &enabling, name);
  const auto keys_of_enabled = all_keys(enabled);
  const ScenarioKey* key = find_key(*keys_of_enabled, name);
  ASSERT_NE(key, nullptr);
  const std::vector<Candidate> values = candidates(*key, enabled, key->takes_effect(enabled));
  ASSERT_FALSE(values.empty());
  try {
    parse_scenario_over(base.scenario(), snippet(*key, values.front().toml), "not_enabled.toml");
    ADD_FAILURE() << name << " = " << values.front().toml << " was read where it takes no effect ("
                  << key->applies_text << ")";
  } catch (const InvalidParameter& e) {
    EXPECT_TRUE(names_key(e, name)) << e.what();
    log.push_back(name + ": refused without the keys that enable it (" + e.what() + ")");
  }
}

// A key of a table that a boolean of the table's name switches (chamber.room.left_wall): a file
// that gives the key gives the table, which switches it on.
bool is_switched_by_its_table(const ScenarioKey& key, const Scenario& s) {
  const auto keys = all_keys(s);
  const ScenarioKey* sw = find_key(*keys, std::string(key.section()));
  return sw != nullptr && sw->type == KeyType::boolean;
}

void check_switched_on_by_its_table(const std::string& name, Base& base,
                                    std::vector<std::string>& log) {
  SCOPED_TRACE("key " + name + " over " + base.name() + " in its own table alone");
  const auto keys = all_keys(base.scenario());
  const ScenarioKey* key = find_key(*keys, name);
  ASSERT_NE(key, nullptr);
  // The first value the scenario accepts (a wall must leave the target inside the room); where
  // none is (the base's lidar needs a wall's material), the refusal names the key.
  std::optional<Scenario> accepted;
  std::string refusal;
  for (const Candidate& c : candidates(*key, base.scenario(), false)) {
    try {
      accepted = parse_scenario_over(base.scenario(), snippet(*key, c.toml), "its_table.toml");
      break;
    } catch (const InvalidParameter& e) {
      EXPECT_TRUE(names_key(e, name)) << e.what();
      refusal = e.what();
    }
  }
  if (!accepted) {
    log.push_back(name + ": refused in its own table over the base (" + refusal + ")");
    return;
  }
  const Scenario& read = *accepted;
  const auto read_keys = all_keys(read);
  EXPECT_TRUE(find_key(*read_keys, std::string(key->section()))->get_boolean(read));
  EXPECT_TRUE(find_key(*read_keys, name)->takes_effect(read));
  log.push_back(name + ": its table switches " + std::string(key->section()) + " on");
}

void check_any_key(const ScenarioKey& key, Base& base, std::vector<std::string>& log) {
  const std::string generic = generic_name(key.name);
  if (key.type == KeyType::retired) {
    SCOPED_TRACE("key " + key.name + " over " + base.name());
    try {
      parse_scenario_over(base.scenario(), snippet(key, "1.0"), "retired.toml");
      ADD_FAILURE() << key.name << " is retired, yet a file giving it was read";
    } catch (const InvalidParameter& e) {
      EXPECT_TRUE(names_key(e, key.name)) << e.what();
      log.push_back(key.name + ": retired, refused");
    }
    return;
  }
  const auto listed_entry = no_effect().find(generic);
  const std::string* listed = listed_entry == no_effect().end() ? nullptr : &listed_entry->second;
  if (const Needed* enabling = entry(enabled_by(), generic)) {
    check_key(key.name, base, enabling, nullptr, log);
    if (key.takes_effect(base.scenario())) {
      check_key(key.name, base, nullptr, listed, log);
    } else if (is_switched_by_its_table(key, base.scenario())) {
      check_switched_on_by_its_table(key.name, base, log);
    } else {
      check_refused_without(key.name, base, *enabling, log);
    }
    return;
  }
  check_key(key.name, base, entry(room_for(), generic), listed, log);
}

class EveryKey : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryKey, IsRefusedOrChangesTheRunOrIsListed) {
  const std::string& top = GetParam();
  std::vector<std::string> log;
  std::size_t count = 0;
  for (Base* base : {&uniform_base(), &layered_base()}) {
    const auto keys = all_keys(base->scenario());
    for (const ScenarioKey* key : keys->keys) {
      if (top_of(key->name) != top) continue;
      // chamber.layers, chamber.objects and their elements' keys are checked on the layered base
      // (which has both), every other key on the uniform one.
      const bool layer_key =
          key->name.starts_with("chamber.layers") || key->name.starts_with("chamber.objects");
      if (layer_key != (base == &layered_base())) continue;
      ++count;
      check_any_key(*key, *base, log);
    }
  }
  EXPECT_GT(count, 0U);
  for (const std::string& line : log) std::cout << line << "\n";
}

// A file giving each (key, value), a section per table.
std::string file_of(const std::vector<std::pair<const ScenarioKey*, std::string>>& given) {
  std::map<std::string, std::string> sections;
  for (const auto& [key, value] : given)
    sections[std::string(key->section())] += std::string(key->short_name()) + " = " + value + "\n";
  std::string text;
  for (const auto& [section, lines] : sections) text += "[" + section + "]\n" + lines;
  return text;
}

// Numbers that switch a feature off (other switches are the boolean and choice keys).
const std::map<std::string, std::string>& off_values() {
  static const std::map<std::string, std::string> table{
      {"lidar.fog_fluctuation.log_std", "0"},
  };
  return table;
}

// The same with each switch of the section turned: every boolean key negated, every choice key set
// to each of its other choices in turn, and the numbers of off_values() set to them (the uniform
// base). Each other key of the section must then change the run, or be listed in
// no_effect_when() with the reason it does not (or in no_effect(), for a reason no switch of the
// section touches), or, where the switch leaves it no effect, be refused in a file that gives it
// with the switch.
TEST_P(EveryKey, AfterEachSwitchOfItsSection) {
#ifdef FOGRADAR_SANITIZE_BUILD
  GTEST_SKIP() << "every key after every switch of its section: run by the Release build only";
#endif
  const std::string& top = GetParam();
  Base& base = uniform_base();
  const auto keys = all_keys(base.scenario());
  std::vector<std::string> log;
  for (const ScenarioKey* sw : keys->keys) {
    if (top_of(sw->name) != top || sw->name.find('[') != std::string::npos) continue;
    if (!sw->takes_effect(base.scenario())) continue;
    std::vector<Candidate> turns;
    if (sw->type == KeyType::boolean || sw->type == KeyType::choice) {
      turns = candidates(*sw, base.scenario(), true);
    } else if (const auto off = off_values().find(sw->name); off != off_values().end()) {
      turns.push_back(from_text(*sw, off->second));
    }
    for (const Candidate& c : turns) {
      Scenario turned = base.scenario();
      try {
        c.set(turned);
        turned.validate();
      } catch (const InvalidParameter&) {
        continue;  // a choice that needs other keys changed too (the water table's temperature)
      }
      const std::string context = sw->name + " = " + c.toml;
      Base switched(turned, "the base with " + context);
      const auto switched_keys = all_keys(turned);
      for (const ScenarioKey* key : switched_keys->keys) {
        if (top_of(key->name) != top || part_of(key->name) != part_of(sw->name) ||
            key->name == sw->name) {
          continue;
        }
        // Arrays of tables are checked element by element above; a switch's own table cannot be
        // written beside `switch = false` (TOML has one value per name).
        if (key->type == KeyType::retired || key->type == KeyType::table_array ||
            key->name.find('[') != std::string::npos || key->section() == sw->name) {
          continue;
        }
        if (!key->takes_effect(turned)) {
          const ScenarioKey* before = find_key(*keys, key->name);
          if (before == nullptr || !before->takes_effect(base.scenario())) continue;
          SCOPED_TRACE("key " + key->name + " with " + context);
          const std::string value = candidates(*before, base.scenario(), true).front().toml;
          try {
            parse_scenario_over(base.scenario(), file_of({{sw, c.toml}, {before, value}}),
                                "switched_off.toml");
            ADD_FAILURE() << key->name << " = " << value << " was read with " << context
                          << ", where it takes no effect";
          } catch (const InvalidParameter& e) {
            EXPECT_TRUE(names_key(e, key->name)) << e.what();
            log.push_back(key->name + ": refused with " + context);
          }
          continue;
        }
        const std::string generic = generic_name(key->name);
        const auto listed_when = no_effect_when().find(generic + " | " + context);
        const auto listed = no_effect().find(generic);
        check_key(key->name, switched, entry(room_for(), generic),
                  listed_when != no_effect_when().end() ? &listed_when->second
                  : listed != no_effect().end()         ? &listed->second
                                                        : nullptr,
                  log);
      }
    }
  }
  for (const std::string& line : log) std::cout << line << "\n";
}

std::vector<std::string> sections() { return top_level_sections(Scenario()); }

INSTANTIATE_TEST_SUITE_P(Section, EveryKey, ::testing::ValuesIn(sections()),
                         [](const ::testing::TestParamInfo<std::string>& section) {
                           return section.param;
                         });

}  // namespace
}  // namespace fogradar::experiment
