#include "fogradar/experiment/scenario.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "toml_bytes.hpp"

namespace fogradar::experiment {
namespace detail {
std::string_view paper_scenario_text();
}  // namespace detail

namespace {

// Line of each key read from the file, to point error messages at it.
using KeyLines = std::map<std::string, std::size_t>;

[[noreturn]] void throw_at(std::string_view source, std::size_t line, const std::string& key,
                           const std::string& message) {
  std::ostringstream out;
  out << source << ':' << line << ": " << message;
  throw InvalidParameter(key, out.str());
}

// Reads the keys of one TOML table into typed fields; anything left unread is an unknown key.
class Section {
 public:
  Section(const toml::table& root, std::string path, std::string_view source, KeyLines& lines)
      : path_(std::move(path)), source_(source), lines_(lines) {
    const toml::node* node = root.at_path(path_).node();
    if (node == nullptr) return;
    table_ = node->as_table();
    if (table_ == nullptr) fail(*node, path_, "[" + path_ + "] must be a table");
  }

  void read(std::string_view key, double& out) {
    if (const toml::node* node = find(key)) {
      const std::optional<double> value = node->is_number() ? node->value<double>() : std::nullopt;
      if (!value) fail(*node, full(key), full(key) + " must be a number");
      out = *value;
    }
  }

  template <class Unsigned>
    requires std::is_unsigned_v<Unsigned>
  void read(std::string_view key, Unsigned& out) {
    if (const toml::node* node = find(key)) {
      if (!node->is_integer()) fail(*node, full(key), full(key) + " must be an integer");
      const std::int64_t value = *node->value<std::int64_t>();
      if (value < 0 || static_cast<std::uint64_t>(value) > std::numeric_limits<Unsigned>::max()) {
        fail(*node, full(key), full(key) + " = " + std::to_string(value) + ": must be in [0, " +
                                   std::to_string(std::numeric_limits<Unsigned>::max()) + "]");
      }
      out = static_cast<Unsigned>(value);
    }
  }

  void read(std::string_view key, bool& out) {
    if (const toml::node* node = find(key)) {
      if (!node->is_boolean()) fail(*node, full(key), full(key) + " must be true or false");
      out = *node->value<bool>();
    }
  }

  void read(std::string_view key, std::string& out) {
    if (const toml::node* node = find(key)) {
      if (!node->is_string()) fail(*node, full(key), full(key) + " must be a string");
      out = *node->value<std::string>();
    }
  }

  bool has(std::string_view key) const { return table_ != nullptr && table_->contains(key); }

  // Throws if the table holds `old_key`, a key that is no longer read, saying what replaced it.
  void reject_retired(std::string_view old_key, const std::string& replacement) const {
    if (table_ == nullptr) return;
    if (const toml::node* node = table_->get(old_key)) {
      fail(*node, full(old_key), "'" + full(old_key) + "' is no longer read: " + replacement);
    }
  }

  // Throws for the first key of this table that was not read and is not an expected sub-table.
  void reject_unknown(std::initializer_list<std::string_view> subtables = {}) const {
    if (table_ == nullptr) return;
    for (const auto& [key, node] : *table_) {
      const std::string name(key.str());
      if (read_.count(name)) continue;
      if (node.is_table() && std::find(subtables.begin(), subtables.end(), name) != subtables.end()) continue;
      fail(node, full(name), "unknown key '" + full(name) + "'" + known_keys_hint());
    }
  }

 private:
  const toml::node* find(std::string_view key) {
    read_.insert(std::string(key));
    if (table_ == nullptr) return nullptr;
    const toml::node* node = table_->get(key);
    if (node != nullptr) lines_[full(key)] = node->source().begin.line;
    return node;
  }

  std::string full(std::string_view key) const { return path_ + "." + std::string(key); }

  std::string known_keys_hint() const {
    std::string hint = " (known keys of [" + path_ + "]:";
    for (const std::string& key : read_) hint += " " + key;
    return hint + ")";
  }

  [[noreturn]] void fail(const toml::node& node, const std::string& key, const std::string& message) const {
    throw_at(source_, node.source().begin.line, key, message);
  }

  const toml::table* table_ = nullptr;
  std::string path_;
  std::string_view source_;
  KeyLines& lines_;
  std::set<std::string> read_;
};

// Enumerations as strings: unknown names name the key and the allowed values.
template <class Parse>
void read_enum(Section& section, std::string_view key, Parse parse, const std::string& full_key) {
  std::string text;
  section.read(key, text);
  if (!text.empty()) parse(text, full_key);
}

void read_radar(const toml::table& root, std::string_view source, KeyLines& lines, radar::RadarParams& r) {
  Section s(root, "radar", source, lines);
  // Its value was the start of a down-chirp, which a reader of "carrier" could not know.
  s.reject_retired("carrier_frequency_hz",
                   "give the sweep centre as radar.centre_frequency_hz and the direction as "
                   "radar.sweep_direction = \"up\" | \"down\" (the old 77e9 meant a 77 -> 76 GHz "
                   "down-chirp: centre_frequency_hz = 76.5e9, sweep_direction = \"down\")");
  s.read("centre_frequency_hz", r.centre_frequency_hz);
  std::string direction;
  s.read("sweep_direction", direction);
  if (!direction.empty())
    r.sweep_direction = radar::parse_sweep_direction(direction, "radar.sweep_direction");
  s.read("sweep_bandwidth_hz", r.sweep_bandwidth_hz);
  s.read("chirp_duration_s", r.chirp_duration_s);
  s.read("chirp_interval_s", r.chirp_interval_s);
  s.read("samples_per_chirp", r.samples_per_chirp);
  s.read("sample_rate_hz", r.sample_rate_hz);
  s.read("chirps_per_frame", r.chirps_per_frame);
  s.read("tx_power_dbm", r.tx_power_dbm);
  s.read("tx_gain_dbi", r.tx_gain_dbi);
  s.read("rx_gain_dbi", r.rx_gain_dbi);
  s.read("azimuth_beamwidth_deg", r.azimuth_beamwidth_deg);
  s.read("elevation_beamwidth_deg", r.elevation_beamwidth_deg);
  s.read("noise_figure_db", r.noise_figure_db);
  s.read("reference_temperature_k", r.reference_temperature_k);
  s.read("adc_bits", r.adc_bits);
  s.read("adc_full_scale_dbm", r.adc_full_scale_dbm);
  s.read("phase_noise_rms_rad", r.phase_noise_rms_rad);
  s.reject_unknown();
}

void read_processing(const toml::table& root, std::string_view source, KeyLines& lines, radar::RadarParams& r) {
  Section s(root, "processing", source, lines);
  std::string window;
  s.read("window", window);
  if (!window.empty()) r.window = radar::parse_window_type(window, "processing.window");
  s.read("association_gate_m", r.association_gate_m);
  s.reject_unknown({"cfar"});

  Section c(root, "processing.cfar", source, lines);
  std::string kind;
  c.read("kind", kind);
  if (!kind.empty()) r.cfar.kind = radar::parse_cfar_kind(kind, "processing.cfar.kind");
  c.read("guard_cells", r.cfar.guard_cells);
  c.read("training_cells", r.cfar.training_cells);
  c.read("false_alarm_probability", r.cfar.false_alarm_probability);
  c.read("os_rank", r.cfar.os_rank);
  std::string design;
  c.read("threshold_design", design);
  if (!design.empty()) {
    r.cfar.threshold_design = radar::parse_cfar_threshold_design(design, "processing.cfar.threshold_design");
  }
  c.reject_unknown();
}

void read_target(const toml::table& root, std::string_view source, KeyLines& lines, TargetSpec& t) {
  Section s(root, "target", source, lines);
  std::string model;
  s.read("model", model);
  if (model == "evt") {
    t.model = TargetModel::evt;
  } else if (model == "point") {
    t.model = TargetModel::point;
  } else if (!model.empty()) {
    throw_invalid("target.model", model, "one of 'evt', 'point'");
  }
  s.read("rcs_dbsm", t.rcs_dbsm);
  unsigned swerling = static_cast<unsigned>(t.swerling);
  s.read("swerling", swerling);
  t.swerling = radar::parse_swerling(std::to_string(swerling), "target.swerling");
  s.read("height_m", t.height_m);
  s.read("sensor_height_m", t.sensor_height_m);
  s.read("floor_multipath", t.floor_multipath);
  s.read("floor_reflection_coefficient", t.floor_reflection_coefficient);
  s.read("micro_motion_std_m", t.micro_motion_std_m);
  s.reject_unknown();
}

void read_chamber(const toml::table& root, std::string_view source, KeyLines& lines, ChamberLayout& c) {
  Section s(root, "chamber", source, lines);
  s.read("sensor_gap_m", c.sensor_gap_m);
  s.read("layer_count", c.layer_count);
  s.read("layer_length_m", c.layer_length_m);
  s.read("target_gap_m", c.target_gap_m);
  s.reject_unknown();
}

void read_droplets(const toml::table& root, std::string_view source, KeyLines& lines,
                   propagation::DropSizeDistribution& droplets) {
  Section s(root, "fog.droplets", source, lines);
  std::string distribution(propagation::distribution_name(droplets));
  s.read("distribution", distribution);
  if (distribution == "lognormal") {
    propagation::Lognormal d = std::holds_alternative<propagation::Lognormal>(droplets)
                                   ? std::get<propagation::Lognormal>(droplets)
                                   : propagation::Lognormal{};
    s.read("median_diameter_m", d.median_diameter_m);
    s.read("geometric_std", d.geometric_std);
    droplets = d;
  } else if (distribution == "monodisperse") {
    propagation::Monodisperse d = std::holds_alternative<propagation::Monodisperse>(droplets)
                                      ? std::get<propagation::Monodisperse>(droplets)
                                      : propagation::Monodisperse{};
    s.read("diameter_m", d.diameter_m);
    droplets = d;
  } else if (distribution == "advection" || distribution == "radiation" || distribution == "modified_gamma") {
    propagation::ModifiedGamma d = distribution == "advection"   ? propagation::advection_fog()
                                   : distribution == "radiation" ? propagation::radiation_fog()
                                   : std::holds_alternative<propagation::ModifiedGamma>(droplets)
                                       ? std::get<propagation::ModifiedGamma>(droplets)
                                       : propagation::ModifiedGamma{};
    s.read("alpha", d.alpha);
    s.read("gamma", d.gamma);
    s.read("b_per_um_gamma", d.b_per_um_gamma);
    droplets = d;
  } else {
    throw_invalid("fog.droplets.distribution", distribution,
                  "one of 'lognormal', 'monodisperse', 'advection', 'radiation', 'modified_gamma'");
  }
  s.reject_unknown();
}

void read_fog(const toml::table& root, std::string_view source, KeyLines& lines, propagation::FogSpec& fog,
              unsigned& clutter_scatterers_per_bin) {
  Section s(root, "fog", source, lines);
  const int given = int{s.has("lwc_g_per_m3")} + int{s.has("extinction_per_km")} + int{s.has("visibility_m")};
  if (given > 1) {
    throw_invalid("fog", "lwc_g_per_m3, extinction_per_km, visibility_m",
                  "at most one of these fog densities per scenario");
  }
  if (s.has("lwc_g_per_m3")) {
    propagation::LiquidWaterContent d;
    s.read("lwc_g_per_m3", d.g_per_m3);
    fog.density = d;
  } else if (s.has("extinction_per_km")) {
    propagation::OpticalExtinction d;
    s.read("extinction_per_km", d.per_km);
    fog.density = d;
  } else if (s.has("visibility_m")) {
    propagation::Visibility d;
    s.read("visibility_m", d.m);
    fog.density = d;
  }
  // Mark the alternatives as known keys even when absent.
  double unused = 0.0;
  s.read("lwc_g_per_m3", unused);
  s.read("extinction_per_km", unused);
  s.read("visibility_m", unused);
  s.read("temperature_c", fog.temperature_c);
  std::string model;
  s.read("water_model", model);
  if (!model.empty()) fog.water_model = propagation::parse_water_model(model, "fog.water_model");
  s.read("clutter_scatterers_per_bin", clutter_scatterers_per_bin);
  s.reject_unknown({"droplets"});
  read_droplets(root, source, lines, fog.droplets);
}

void read_experiment(const toml::table& root, std::string_view source, KeyLines& lines, ExperimentSpec& e) {
  Section s(root, "experiment", source, lines);
  s.read("measurements_per_step", e.measurements_per_step);
  s.read("max_active_layers", e.max_active_layers);
  s.read("seed", e.seed);
  s.reject_unknown();
}

// Validation errors name library fields; the user wrote scenario keys.
std::string scenario_key(const std::string& field) {
  static const std::pair<std::string_view, std::string_view> renames[] = {
      {"radar.window", "processing.window"},
      {"radar.association_gate_m", "processing.association_gate_m"},
      {"cfar.", "processing.cfar."},
      {"target.clutter_scatterers_per_bin", "fog.clutter_scatterers_per_bin"},
      {"chamber.layers[", "chamber.layer_length_m"},
      {"chamber.layers", "chamber.layer_count"},
      {"chamber.target_range_m", "chamber.target_gap_m"},
  };
  for (const auto& [from, to] : renames) {
    if (field.rfind(from, 0) != 0) continue;
    if (from.back() == '.') return std::string(to) + field.substr(from.size());
    return std::string(to);
  }
  return field;
}

std::string format_toml_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

}  // namespace

std::string_view paper_scenario_toml() { return detail::paper_scenario_text(); }

void Scenario::validate() const {
  radar.validate();
  require_in_range("target.rcs_dbsm", target.rcs_dbsm, -60.0, 60.0);
  require_in_range("target.height_m", target.height_m, 0.0, 100.0);
  require_in_range("experiment.measurements_per_step", static_cast<double>(experiment.measurements_per_step),
                   1.0, 1e6);
  require_in_range("chamber.layer_count", static_cast<double>(chamber.layer_count), 1.0, 1000.0);
  require_in_range("experiment.max_active_layers", static_cast<double>(experiment.max_active_layers), 0.0,
                   static_cast<double>(chamber.layer_count));
  // TOML integers are signed 64-bit: a larger seed could not be written to scenario.toml.
  require_in_range("experiment.seed", static_cast<double>(experiment.seed), 0.0, 9.2233720368547e18);
  chamber_spec().validate();
  scene().validate();
}

propagation::ChamberSpec Scenario::chamber_spec() const {
  propagation::ChamberSpec spec;
  spec.sensor_gap_m = chamber.sensor_gap_m;
  spec.target_gap_m = chamber.target_gap_m;
  spec.layers.assign(chamber.layer_count, propagation::FogLayerSpec{.length_m = chamber.layer_length_m, .fog = fog});
  return spec;
}

radar::Scene Scenario::scene() const {
  radar::Scene scene = target.model == TargetModel::evt ? radar::evt_rear_scene(target.rcs_dbsm)
                                                        : radar::point_target_scene(target.rcs_dbsm);
  if (target.model == TargetModel::point) {
    scene.centres.front().height_m = target.height_m;
    scene.centres.front().swerling = target.swerling;
  }
  scene.sensor_height_m = target.sensor_height_m;
  scene.floor.enabled = target.floor_multipath;
  scene.floor.reflection_coefficient = target.floor_reflection_coefficient;
  scene.micro_motion_std_m = target.micro_motion_std_m;
  scene.clutter_scatterers_per_bin = clutter_scatterers_per_bin;
  return scene;
}

namespace {

// Reads `toml_text` over `base`: keys the file gives replace the base's values.
Scenario parse_over(Scenario s, std::string_view toml_text, std::string_view source_name) {
  detail::require_toml_safe_bytes(toml_text, source_name);
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw_at(source_name, e.source().begin.line, "toml", std::string("malformed TOML: ") + std::string(e.description()));
  }
  static const std::set<std::string_view> sections = {"radar", "processing", "target", "chamber", "fog", "experiment"};
  for (const auto& [key, node] : root) {
    if (!sections.count(key.str())) {
      throw_at(source_name, node.source().begin.line, std::string(key.str()),
               "unknown section or key '" + std::string(key.str()) +
                   "' (sections: radar, processing, target, chamber, fog, experiment)");
    }
  }

  KeyLines lines;
  try {
    read_radar(root, source_name, lines, s.radar);
    read_processing(root, source_name, lines, s.radar);
    read_target(root, source_name, lines, s.target);
    read_chamber(root, source_name, lines, s.chamber);
    read_fog(root, source_name, lines, s.fog, s.clutter_scatterers_per_bin);
    read_experiment(root, source_name, lines, s.experiment);
    s.validate();
  } catch (const InvalidParameter& e) {
    if (std::string_view(e.what()).rfind(std::string(source_name) + ":", 0) == 0) throw;
    // A range or enumeration error: point at the key as the user wrote it, and its line.
    const std::string key = scenario_key(e.field());
    std::string message = e.what();
    if (message.rfind(e.field(), 0) == 0) message = key + message.substr(e.field().size());
    const auto line = lines.find(key);
    if (line == lines.end()) throw InvalidParameter(key, std::string(source_name) + ": " + message);
    throw_at(source_name, line->second, key, message);
  }
  return s;
}

}  // namespace

Scenario paper_scenario() { return parse_over(Scenario{}, paper_scenario_toml(), "paper.toml"); }

Scenario parse_scenario(std::string_view toml_text, std::string_view source_name) {
  return parse_over(paper_scenario(), toml_text, source_name);
}

Scenario load_scenario_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw_invalid("--scenario", path, "a readable TOML file");
  std::ostringstream text;
  text << file.rdbuf();
  return parse_scenario(text.str(), path);
}

std::string to_toml(const Scenario& s) {
  std::ostringstream out;
  const auto num = [](double v) { return format_toml_number(v); };
  const auto str = [](std::string_view v) {
    std::string quoted(1, '"');
    quoted.append(v).push_back('"');
    return quoted;
  };
  const radar::RadarParams& r = s.radar;
  out << "# fogradar resolved scenario: every key, as used by the run\n\n"
      << "[radar]\n"
      << "centre_frequency_hz = " << num(r.centre_frequency_hz) << '\n'
      << "sweep_direction = " << str(radar::to_string(r.sweep_direction)) << '\n'
      << "sweep_bandwidth_hz = " << num(r.sweep_bandwidth_hz) << '\n'
      << "chirp_duration_s = " << num(r.chirp_duration_s) << '\n'
      << "chirp_interval_s = " << num(r.chirp_interval_s) << '\n'
      << "samples_per_chirp = " << r.samples_per_chirp << '\n'
      << "sample_rate_hz = " << num(r.sample_rate_hz) << '\n'
      << "chirps_per_frame = " << r.chirps_per_frame << '\n'
      << "tx_power_dbm = " << num(r.tx_power_dbm) << '\n'
      << "tx_gain_dbi = " << num(r.tx_gain_dbi) << '\n'
      << "rx_gain_dbi = " << num(r.rx_gain_dbi) << '\n'
      << "azimuth_beamwidth_deg = " << num(r.azimuth_beamwidth_deg) << '\n'
      << "elevation_beamwidth_deg = " << num(r.elevation_beamwidth_deg) << '\n'
      << "noise_figure_db = " << num(r.noise_figure_db) << '\n'
      << "reference_temperature_k = " << num(r.reference_temperature_k) << '\n'
      << "adc_bits = " << r.adc_bits << '\n'
      << "adc_full_scale_dbm = " << num(r.adc_full_scale_dbm) << '\n'
      << "phase_noise_rms_rad = " << num(r.phase_noise_rms_rad) << "\n\n"
      << "[processing]\n"
      << "window = " << str(radar::to_string(r.window)) << '\n'
      << "association_gate_m = " << num(r.association_gate_m) << "\n\n"
      << "[processing.cfar]\n"
      << "kind = " << str(radar::to_string(r.cfar.kind)) << '\n'
      << "guard_cells = " << r.cfar.guard_cells << '\n'
      << "training_cells = " << r.cfar.training_cells << '\n'
      << "false_alarm_probability = " << num(r.cfar.false_alarm_probability) << '\n'
      << "os_rank = " << r.cfar.os_rank << '\n'
      << "threshold_design = " << str(radar::to_string(r.cfar.threshold_design)) << "\n\n";
  const TargetSpec& t = s.target;
  out << "[target]\n"
      << "model = " << str(t.model == TargetModel::evt ? "evt" : "point") << '\n'
      << "rcs_dbsm = " << num(t.rcs_dbsm) << '\n'
      << "swerling = " << radar::to_string(t.swerling) << '\n'
      << "height_m = " << num(t.height_m) << '\n'
      << "sensor_height_m = " << num(t.sensor_height_m) << '\n'
      << "floor_multipath = " << (t.floor_multipath ? "true" : "false") << '\n'
      << "floor_reflection_coefficient = " << num(t.floor_reflection_coefficient) << '\n'
      << "micro_motion_std_m = " << num(t.micro_motion_std_m) << "\n\n"
      << "[chamber]\n"
      << "sensor_gap_m = " << num(s.chamber.sensor_gap_m) << '\n'
      << "layer_count = " << s.chamber.layer_count << '\n'
      << "layer_length_m = " << num(s.chamber.layer_length_m) << '\n'
      << "target_gap_m = " << num(s.chamber.target_gap_m) << "\n\n"
      << "[fog]\n";
  struct Density {
    std::string operator()(const propagation::LiquidWaterContent& d) const {
      return "lwc_g_per_m3 = " + format_toml_number(d.g_per_m3);
    }
    std::string operator()(const propagation::OpticalExtinction& d) const {
      return "extinction_per_km = " + format_toml_number(d.per_km);
    }
    std::string operator()(const propagation::Visibility& d) const {
      return "visibility_m = " + format_toml_number(d.m);
    }
  };
  out << std::visit(Density{}, s.fog.density) << '\n'
      << "temperature_c = " << num(s.fog.temperature_c) << '\n'
      << "water_model = " << str(propagation::to_string(s.fog.water_model)) << '\n'
      << "clutter_scatterers_per_bin = " << s.clutter_scatterers_per_bin << "\n\n"
      << "[fog.droplets]\n";
  struct Droplets {
    std::string operator()(const propagation::Monodisperse& d) const {
      return "distribution = \"monodisperse\"\ndiameter_m = " + format_toml_number(d.diameter_m) + "\n";
    }
    std::string operator()(const propagation::Lognormal& d) const {
      return "distribution = \"lognormal\"\nmedian_diameter_m = " + format_toml_number(d.median_diameter_m) +
             "\ngeometric_std = " + format_toml_number(d.geometric_std) + "\n";
    }
    std::string operator()(const propagation::ModifiedGamma& d) const {
      return "distribution = \"modified_gamma\"\nalpha = " + format_toml_number(d.alpha) +
             "\ngamma = " + format_toml_number(d.gamma) + "\nb_per_um_gamma = " + format_toml_number(d.b_per_um_gamma) +
             "\n";
    }
  };
  out << std::visit(Droplets{}, s.fog.droplets) << '\n'
      << "[experiment]\n"
      << "measurements_per_step = " << s.experiment.measurements_per_step << '\n'
      << "max_active_layers = " << s.experiment.max_active_layers << '\n'
      << "seed = " << s.experiment.seed << '\n';
  return out.str();
}

}  // namespace fogradar::experiment
