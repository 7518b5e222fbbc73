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
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <vector>

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

// A value as TOML writes it, for messages about a value of the wrong type.
std::string as_written(const toml::node& node) {
  std::ostringstream text;
  node.visit([&text](const auto& value) { text << value; });
  return text.str();
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
  // One table of an array of tables, named `path` ("lidar.background[2]").
  Section(const toml::table* table, std::string path, std::string_view source, KeyLines& lines)
      : table_(table), path_(std::move(path)), source_(source), lines_(lines) {}

  void read(std::string_view key, double& out) {
    if (const toml::node* node = find(key)) {
      const std::optional<double> value = node->is_number() ? node->value<double>() : std::nullopt;
      if (!value)
        fail(*node, full(key), full(key) + " = " + as_written(*node) + ": must be a number");
      out = *value;
    }
  }

  // An integer key with its documented range (docs/scenario.md); ranges that depend on other keys
  // pass their widest bound here and are checked with those keys by Scenario::validate().
  template <class Integer>
  requires std::is_integral_v<Integer>
  // `also` states the bound that other keys set within [low, high].
  void read(std::string_view key, Integer& out, std::int64_t low, std::int64_t high,
            const std::string& also = "") {
    if (const toml::node* node = find(key)) {
      const std::string range = "an integer in [" + std::to_string(low) + ", " +
                                std::to_string(high) + "]" + (also.empty() ? "" : " " + also);
      if (!node->is_integer())
        fail(*node, full(key), full(key) + " = " + as_written(*node) + ": must be " + range);
      const std::int64_t value = *node->value<std::int64_t>();
      if (value < low || value > high) {
        fail(*node, full(key), full(key) + " = " + std::to_string(value) + ": must be " + range);
      }
      out = static_cast<Integer>(value);
    }
  }

  void read(std::string_view key, bool& out) {
    if (const toml::node* node = find(key)) {
      if (!node->is_boolean()) {
        fail(*node, full(key), full(key) + " = " + as_written(*node) + ": must be true or false");
      }
      out = *node->value<bool>();
    }
  }

  void read(std::string_view key, std::string& out) {
    if (const toml::node* node = find(key)) {
      if (!node->is_string())
        fail(*node, full(key), full(key) + " = " + as_written(*node) + ": must be a string");
      out = *node->value<std::string>();
    }
  }

  // An enumeration's name, absent when the key is not given; an empty string is given, and its
  // parser refuses it with the allowed names.
  void read(std::string_view key, std::optional<std::string>& out) {
    std::string text;
    if (find(key) == nullptr) return;
    read(key, text);
    out = text;
  }

  bool has(std::string_view key) const { return table_ != nullptr && table_->contains(key); }

  // A key's node, marked as read; null when the table does not give it.
  const toml::node* node(std::string_view key) { return find(key); }

  [[noreturn]] void fail_at(const toml::node& node, std::string_view key,
                            const std::string& message) const {
    fail(node, full(key), message);
  }

  // Throws at the second of `keys` the table gives, naming each given one and its line.
  void reject_more_than_one(std::initializer_list<std::string_view> keys,
                            std::string_view what) const {
    if (table_ == nullptr) return;
    std::string all;
    for (std::string_view key : keys) all += (all.empty() ? "" : ", ") + full(key);
    std::string given;
    bool seen = false;
    for (std::string_view key : keys) {
      const toml::node* node = table_->get(key);
      if (node == nullptr) continue;
      given += (given.empty() ? "" : " and ") + full(key) + " (line " +
               std::to_string(node->source().begin.line) + ")";
      if (seen) {
        fail(*node, full(key),
             given + " are both given: at most one " + std::string(what) + " of " + all +
                 " per scenario");
      }
      seen = true;
    }
  }

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
      if (node.is_table() && std::find(subtables.begin(), subtables.end(), name) != subtables.end())
        continue;
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

  [[noreturn]] void fail(const toml::node& node, const std::string& key,
                         const std::string& message) const {
    throw_at(source_, node.source().begin.line, key, message);
  }

  const toml::table* table_ = nullptr;
  std::string path_;
  std::string_view source_;
  KeyLines& lines_;
  std::set<std::string> read_;
};

void read_radar(const toml::table& root, std::string_view source, KeyLines& lines,
                radar::RadarParams& r) {
  Section s(root, "radar", source, lines);
  // Its value was the start of a down-chirp, which a reader of "carrier" could not know.
  s.reject_retired("carrier_frequency_hz",
                   "give the sweep centre as radar.centre_frequency_hz and the direction as "
                   "radar.sweep_direction = \"up\" | \"down\" (the old 77e9 meant a 77 -> 76 GHz "
                   "down-chirp: centre_frequency_hz = 76.5e9, sweep_direction = \"down\")");
  s.read("centre_frequency_hz", r.centre_frequency_hz);
  std::optional<std::string> direction;
  s.read("sweep_direction", direction);
  if (direction)
    r.sweep_direction = radar::parse_sweep_direction(*direction, "radar.sweep_direction");
  s.read("sweep_bandwidth_hz", r.sweep_bandwidth_hz);
  s.read("chirp_duration_s", r.chirp_duration_s);
  s.read("chirp_interval_s", r.chirp_interval_s);
  s.read("samples_per_chirp", r.samples_per_chirp, 16, 65536);
  s.read("sample_rate_hz", r.sample_rate_hz);
  s.read("chirps_per_frame", r.chirps_per_frame, 1, 16384);
  s.read("tx_power_dbm", r.tx_power_dbm);
  s.read("tx_gain_dbi", r.tx_gain_dbi);
  s.read("rx_gain_dbi", r.rx_gain_dbi);
  s.read("azimuth_beamwidth_deg", r.azimuth_beamwidth_deg);
  s.read("elevation_beamwidth_deg", r.elevation_beamwidth_deg);
  s.read("noise_figure_db", r.noise_figure_db);
  s.read("reference_temperature_k", r.reference_temperature_k);
  s.read("adc_bits", r.adc_bits, 0, 24);
  s.read("adc_full_scale_dbm", r.adc_full_scale_dbm);
  s.read("phase_noise_rms_rad", r.phase_noise_rms_rad);
  s.reject_unknown();
}

void read_processing(const toml::table& root, std::string_view source, KeyLines& lines,
                     radar::RadarParams& r) {
  Section s(root, "processing", source, lines);
  std::optional<std::string> window;
  s.read("window", window);
  if (window) r.window = radar::parse_window_type(*window, "processing.window");
  s.read("association_gate_m", r.association_gate_m);
  s.reject_unknown({"cfar"});

  Section c(root, "processing.cfar", source, lines);
  std::optional<std::string> kind;
  c.read("kind", kind);
  if (kind) r.cfar.kind = radar::parse_cfar_kind(*kind, "processing.cfar.kind");
  const std::string window_rule =
      "with 2 (processing.cfar.guard_cells + processing.cfar.training_cells) + 1 <= "
      "radar.samples_per_chirp = " +
      std::to_string(r.samples_per_chirp);
  c.read("guard_cells", r.cfar.guard_cells, 0, 32766, window_rule);
  c.read("training_cells", r.cfar.training_cells, 1, 32767, window_rule);
  c.read("false_alarm_probability", r.cfar.false_alarm_probability);
  c.read("os_rank", r.cfar.os_rank, 0, 65534,
         "and 0 or at most 2 x processing.cfar.training_cells = " +
             std::to_string(2 * r.cfar.training_cells));
  std::optional<std::string> design;
  c.read("threshold_design", design);
  if (design) {
    r.cfar.threshold_design =
        radar::parse_cfar_threshold_design(*design, "processing.cfar.threshold_design");
  }
  c.reject_unknown();
}

void read_target(const toml::table& root, std::string_view source, KeyLines& lines, TargetSpec& t) {
  Section s(root, "target", source, lines);
  std::optional<std::string> model;
  s.read("model", model);
  if (model == "evt") {
    t.model = TargetModel::evt;
  } else if (model == "point") {
    t.model = TargetModel::point;
  } else if (model) {
    throw_invalid("target.model", *model, "one of 'evt', 'point'");
  }
  s.read("rcs_dbsm", t.rcs_dbsm);
  // Any integer reaches the parser, which names the allowed set (0, 1, 3).
  std::int64_t swerling = static_cast<std::int64_t>(t.swerling);
  s.read("swerling", swerling, std::numeric_limits<std::int64_t>::min(),
         std::numeric_limits<std::int64_t>::max());
  t.swerling = radar::parse_swerling(std::to_string(swerling), "target.swerling");
  s.read("height_m", t.height_m);
  s.read("sensor_height_m", t.sensor_height_m);
  s.read("floor_multipath", t.floor_multipath);
  s.read("floor_reflection_coefficient", t.floor_reflection_coefficient);
  s.read("micro_motion_std_m", t.micro_motion_std_m);
  s.reject_unknown();
}

void read_chamber(const toml::table& root, std::string_view source, KeyLines& lines,
                  ChamberLayout& c) {
  Section s(root, "chamber", source, lines);
  s.read("sensor_gap_m", c.sensor_gap_m);
  s.read("layer_count", c.layer_count, 1, 1000);
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
  } else if (distribution == "advection" || distribution == "radiation" ||
             distribution == "modified_gamma") {
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

void read_fog(const toml::table& root, std::string_view source, KeyLines& lines,
              propagation::FogSpec& fog, unsigned& clutter_scatterers_per_bin) {
  Section s(root, "fog", source, lines);
  s.reject_more_than_one({"lwc_g_per_m3", "extinction_per_km", "visibility_m"}, "fog density");
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
  std::optional<std::string> model;
  s.read("water_model", model);
  if (model) fog.water_model = propagation::parse_water_model(*model, "fog.water_model");
  s.read("clutter_scatterers_per_bin", clutter_scatterers_per_bin, 1, 64);
  s.reject_unknown({"droplets"});
  read_droplets(root, source, lines, fog.droplets);
}

const std::string sensors_allowed =
    "a non-empty array of distinct names from \"radar\", \"lidar\", \"camera\"";

std::vector<SensorId> read_sensors(Section& s) {
  const toml::node* node = s.node("sensors");
  if (node == nullptr) return {};
  const std::string given =
      "experiment.sensors = " + as_written(*node) + ": must be " + sensors_allowed;
  const toml::array* array = node->as_array();
  if (array == nullptr || array->empty()) s.fail_at(*node, "sensors", given);
  std::vector<SensorId> sensors;
  for (const toml::node& element : *array) {
    const std::optional<std::string> name = element.value<std::string>();
    if (!element.is_string())
      s.fail_at(*node, "sensors", given + " (" + as_written(element) + " is not a string)");
    const auto known = std::find_if(std::begin(all_sensors), std::end(all_sensors),
                                    [&](SensorId id) { return sensor_name(id) == *name; });
    if (known == std::end(all_sensors)) {
      s.fail_at(*node, "sensors", given + " (\"" + *name + "\" is no sensor)");
    }
    if (std::find(sensors.begin(), sensors.end(), *known) != sensors.end()) {
      s.fail_at(*node, "sensors", given + " (\"" + *name + "\" is named twice)");
    }
    sensors.push_back(*known);
  }
  return sensors;
}

void read_experiment(const toml::table& root, std::string_view source, KeyLines& lines,
                     ExperimentSpec& e) {
  Section s(root, "experiment", source, lines);
  if (std::vector<SensorId> sensors = read_sensors(s); !sensors.empty())
    e.sensors = std::move(sensors);
  s.read("measurements_per_step", e.measurements_per_step, 1, 1000000);
  // Its upper bound is chamber.layer_count, checked with that key by Scenario::validate().
  s.read("max_active_layers", e.max_active_layers, 0, std::numeric_limits<std::int64_t>::max());
  s.read("seed", e.seed, 0, std::numeric_limits<std::int64_t>::max());
  s.reject_unknown();
}

void read_lidar_background(Section& lidar_section, std::string_view source, KeyLines& lines,
                           std::vector<lidar::BackgroundSegment>& background) {
  const toml::node* node = lidar_section.node("background");
  if (node == nullptr) return;
  const toml::array* array = node->as_array();
  const std::string wanted =
      "lidar.background: must be an array of tables [[lidar.background]] with keys "
      "x0_m, y0_m, x1_m, y1_m, reflectivity";
  if (array == nullptr) lidar_section.fail_at(*node, "background", wanted);
  background.clear();
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::table* table = (*array)[i].as_table();
    if (table == nullptr) lidar_section.fail_at((*array)[i], "background", wanted);
    Section s(table, "lidar.background[" + std::to_string(i) + "]", source, lines);
    lidar::BackgroundSegment segment;
    s.read("x0_m", segment.x0_m);
    s.read("y0_m", segment.y0_m);
    s.read("x1_m", segment.x1_m);
    s.read("y1_m", segment.y1_m);
    s.read("reflectivity", segment.reflectivity);
    s.reject_unknown();
    background.push_back(segment);
  }
}

void read_lidar(const toml::table& root, std::string_view source, KeyLines& lines,
                lidar::LidarParams& l) {
  Section s(root, "lidar", source, lines);
  s.read("wavelength_m", l.wavelength_m);
  s.read("field_of_view_deg", l.field_of_view_deg);
  s.read("angular_step_deg", l.angular_step_deg);
  s.read("scan_rate_hz", l.scan_rate_hz);
  s.read("scans_per_step", l.scans_per_step, 1, 100000);
  s.read("min_range_m", l.min_range_m);
  s.read("max_range_m", l.max_range_m);
  s.read("pulse_width_ns", l.pulse_width_ns);
  s.read("sample_interval_ns", l.sample_interval_ns);
  s.read("overlap_range_m", l.overlap_range_m);
  s.read("threshold_range_m", l.threshold_range_m);
  s.read("threshold_reflectivity", l.threshold_reflectivity);
  s.read("false_alarm_probability", l.false_alarm_probability);
  s.read("max_echoes", l.max_echoes, 1, 8);
  s.read("min_echo_separation_m", l.min_echo_separation_m);
  s.read("intensity_scale", l.intensity_scale);
  s.read("intensity_saturation", l.intensity_saturation);
  s.read("target_width_m", l.target_width_m);
  s.read("target_offset_m", l.target_offset_m);
  s.read("target_reflectivity", l.target_reflectivity);
  s.read("fog_width_m", l.fog_width_m);
  read_lidar_background(s, source, lines, l.background);
  s.reject_unknown({"fog_fluctuation"});

  Section f(root, "lidar.fog_fluctuation", source, lines);
  f.read("log_std", l.fog_fluctuation.log_std);
  f.read("correlation_time_s", l.fog_fluctuation.correlation_time_s);
  f.reject_unknown();
}

void read_camera_region(const toml::table& root, const std::string& path, std::string_view source,
                        KeyLines& lines, camera::RegionParams& region) {
  Section s(root, path, source, lines);
  s.read("median_reflectance", region.median_reflectance);
  s.read("log_sigma", region.log_sigma);
  s.reject_unknown();
}

void read_camera(const toml::table& root, std::string_view source, KeyLines& lines,
                 camera::CameraParams& c) {
  Section s(root, "camera", source, lines);
  std::optional<std::string> band, transfer;
  s.read("band", band);
  if (band) c.band = camera::parse_band(*band, "camera.band");
  s.read("wavelength_nm", c.wavelength_nm);
  s.read("mie_step_nm", c.mie_step_nm);
  s.read("transfer", transfer);
  if (transfer) c.transfer = camera::parse_transfer_curve(*transfer, "camera.transfer");
  s.read("gamma", c.gamma);
  s.read("frames_per_step", c.frames_per_step, 1, 100000);
  s.read("contrast_threshold", c.contrast_threshold);
  s.read("write_roi_images", c.write_roi_images);
  s.reject_unknown({"exposure", "noise", "roi"});

  Section e(root, "camera.exposure", source, lines);
  std::optional<std::string> mode;
  e.read("mode", mode);
  if (mode) c.exposure.mode = camera::parse_exposure_mode(*mode, "camera.exposure.mode");
  e.read("ambient_level", c.exposure.ambient_level);
  e.read("auto_target_grey", c.exposure.auto_target_grey);
  e.reject_unknown();

  Section n(root, "camera.noise", source, lines);
  n.read("enabled", c.noise.enabled);
  n.read("full_well_electrons", c.noise.full_well_electrons);
  n.read("read_noise_electrons", c.noise.read_noise_electrons);
  n.reject_unknown();

  Section r(root, "camera.roi", source, lines);
  r.read("width_px", c.roi.width_px, 8, 4096);
  r.read("height_px", c.roi.height_px, 8, 4096);
  r.read("cell_px", c.roi.cell_px, 2, 2048,
         "with 2 x camera.roi.cell_px <= camera.roi.width_px and camera.roi.height_px");
  r.read("target_fraction", c.roi.target_fraction);
  r.reject_unknown({"target", "background"});
  read_camera_region(root, "camera.roi.target", source, lines, c.roi.target);
  read_camera_region(root, "camera.roi.background", source, lines, c.roi.background);
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

// Library fields that other keys' messages name, as the scenario's keys.
std::string scenario_keys_in(std::string message) {
  static const std::pair<std::string_view, std::string_view> renames[] = {
      {"radar.window", "processing.window"},
      {"radar.association_gate_m", "processing.association_gate_m"},
      {"cfar.", "processing.cfar."},
      {"target.clutter_scatterers_per_bin", "fog.clutter_scatterers_per_bin"},
  };
  for (const auto& [from, to] : renames) {
    const std::vector<std::size_t> positions = key_positions(message, from);
    for (auto at = positions.rbegin(); at != positions.rend(); ++at)
      message.replace(*at, from.size(), to);
  }
  return message;
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

// Closes the scenario file however reading it ends.
struct FileDescriptor {
  int fd;
  explicit FileDescriptor(int descriptor) : fd(descriptor) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

std::string format_toml_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

}  // namespace

std::string_view paper_scenario_toml() { return detail::paper_scenario_text(); }

std::string_view sensor_name(SensorId sensor) {
  switch (sensor) {
    case SensorId::radar:
      return "radar";
    case SensorId::lidar:
      return "lidar";
    case SensorId::camera:
      return "camera";
  }
  return "unknown";
}

bool Scenario::runs(SensorId sensor) const {
  return std::find(experiment.sensors.begin(), experiment.sensors.end(), sensor) !=
         experiment.sensors.end();
}

void Scenario::validate() const {
  std::string names;
  for (std::size_t i = 0; i < experiment.sensors.size(); ++i) {
    const SensorId sensor = experiment.sensors[i];
    names += (names.empty() ? "[" : ", ") + std::string(sensor_name(sensor));
    if (std::find(experiment.sensors.begin(),
                  experiment.sensors.begin() + static_cast<std::ptrdiff_t>(i),
                  sensor) != experiment.sensors.begin() + static_cast<std::ptrdiff_t>(i) ||
        sensor_name(sensor) == "unknown") {
      throw_invalid("experiment.sensors", names + ", ...]", sensors_allowed);
    }
  }
  if (experiment.sensors.empty()) throw_invalid("experiment.sensors", "[]", sensors_allowed);
  radar.validate();
  require_in_range("target.rcs_dbsm", target.rcs_dbsm, -60.0, 60.0);
  require_in_range("target.height_m", target.height_m, 0.0, 100.0);
  require_in_range("experiment.measurements_per_step",
                   static_cast<double>(experiment.measurements_per_step), 1.0, 1e6);
  require_in_range("chamber.layer_count", static_cast<double>(chamber.layer_count), 1.0, 1000.0);
  if (experiment.max_active_layers > chamber.layer_count) {
    throw_invalid(
        "experiment.max_active_layers", static_cast<double>(experiment.max_active_layers),
        "an integer in [0, chamber.layer_count = " + std::to_string(chamber.layer_count) + "]");
  }
  // TOML integers are signed 64-bit: a larger seed could not be written to scenario.toml.
  constexpr auto max_seed = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  if (experiment.seed > max_seed) {
    throw_invalid("experiment.seed", std::to_string(experiment.seed),
                  "an integer in [0, " + std::to_string(max_seed) + "]");
  }
  chamber_spec().validate();
  lidar.validate();
  camera.validate();
  const radar::Scene target_scene = scene();
  target_scene.validate();
  // Every echo's beat must lie inside [0, fs) with the 1 m margin RadarChain keeps (docs/radar.md).
  double farthest_m = chamber_spec().target_range_m();
  for (const radar::ScatteringCentre& centre : target_scene.centres) {
    farthest_m = std::max(farthest_m, chamber_spec().target_range_m() + centre.range_offset_m);
  }
  const double limit_m = radar::derive(radar).max_range_m - 1.0;
  if (farthest_m > limit_m) {
    std::ostringstream constraint;
    constraint.precision(10);
    constraint
        << "such that the target's farthest echo, chamber.sensor_gap_m + chamber.layer_count x "
           "chamber.layer_length_m + chamber.target_gap_m (+ the EVT's depth) = "
        << farthest_m
        << " m, lies within the unambiguous range minus 1 m, c x radar.sample_rate_hz x "
           "radar.chirp_duration_s / (2 x radar.sweep_bandwidth_hz) - 1 = "
        << limit_m << " m";
    throw_invalid("chamber.target_gap_m", chamber.target_gap_m, constraint.str());
  }
}

propagation::ChamberSpec Scenario::chamber_spec() const {
  propagation::ChamberSpec spec;
  spec.sensor_gap_m = chamber.sensor_gap_m;
  spec.target_gap_m = chamber.target_gap_m;
  spec.layers.assign(chamber.layer_count,
                     propagation::FogLayerSpec{.length_m = chamber.layer_length_m, .fog = fog});
  return spec;
}

radar::Scene Scenario::scene() const {
  radar::Scene scene = target.model == TargetModel::evt
                           ? radar::evt_rear_scene(target.rcs_dbsm)
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
    throw_at(source_name, e.source().begin.line, "toml",
             std::string("malformed TOML: ") + std::string(e.description()));
  }
  static const std::set<std::string_view> sections = {"radar", "processing", "target", "chamber",
                                                      "fog",   "experiment", "lidar",  "camera"};
  for (const auto& [key, node] : root) {
    if (!sections.count(key.str())) {
      throw_at(
          source_name, node.source().begin.line, std::string(key.str()),
          "unknown section or key '" + std::string(key.str()) +
              "' (sections: radar, processing, target, chamber, fog, experiment, lidar, camera)");
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
    read_lidar(root, source_name, lines, s.lidar);
    read_camera(root, source_name, lines, s.camera);
    s.validate();
  } catch (const InvalidParameter& e) {
    // A reader's error already names its key and line; it may name keys read before it.
    if (std::string_view(e.what()).rfind(std::string(source_name) + ":", 0) == 0) {
      throw InvalidParameter(e.field(), e.what() + other_key_lines(e.what(), e.field(), lines));
    }
    // A range or enumeration error: point at the key as the user wrote it, and its line.
    const std::string key = scenario_key(e.field());
    std::string message = e.what();
    if (message.rfind(e.field(), 0) == 0) message = key + message.substr(e.field().size());
    message = scenario_keys_in(message);
    message += other_key_lines(message, key, lines);
    // A key the file does not give keeps its paper value; a check combining it with keys the file
    // gives points at the first of those.
    std::size_t line = 0;
    if (const auto given = lines.find(key); given != lines.end()) {
      line = given->second;
    } else {
      for (const auto& [other, other_line] : lines) {
        if (!key_positions(message, other).empty() && (line == 0 || other_line < line))
          line = other_line;
      }
    }
    if (line == 0) throw InvalidParameter(key, std::string(source_name) + ": " + message);
    throw_at(source_name, line, key, message);
  }
  return s;
}

}  // namespace

Scenario paper_scenario() { return parse_over(Scenario{}, paper_scenario_toml(), "paper.toml"); }

Scenario parse_scenario(std::string_view toml_text, std::string_view source_name) {
  return parse_over(paper_scenario(), toml_text, source_name);
}

Scenario load_scenario_file(const std::string& path) {
  const std::string wanted = "a readable regular TOML file of at most " +
                             std::to_string(max_scenario_file_bytes) + " bytes (1 MiB)";
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it unread.
  const FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
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
  return parse_scenario(text, path);
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
      return "distribution = \"monodisperse\"\ndiameter_m = " + format_toml_number(d.diameter_m) +
             "\n";
    }
    std::string operator()(const propagation::Lognormal& d) const {
      return "distribution = \"lognormal\"\nmedian_diameter_m = " +
             format_toml_number(d.median_diameter_m) +
             "\ngeometric_std = " + format_toml_number(d.geometric_std) + "\n";
    }
    std::string operator()(const propagation::ModifiedGamma& d) const {
      return "distribution = \"modified_gamma\"\nalpha = " + format_toml_number(d.alpha) +
             "\ngamma = " + format_toml_number(d.gamma) +
             "\nb_per_um_gamma = " + format_toml_number(d.b_per_um_gamma) + "\n";
    }
  };
  out << std::visit(Droplets{}, s.fog.droplets) << '\n'
      << "[experiment]\n"
      << "sensors = [";
  for (std::size_t i = 0; i < s.experiment.sensors.size(); ++i) {
    out << (i == 0 ? "" : ", ") << str(sensor_name(s.experiment.sensors[i]));
  }
  out << "]\n"
      << "measurements_per_step = " << s.experiment.measurements_per_step << '\n'
      << "max_active_layers = " << s.experiment.max_active_layers << '\n'
      << "seed = " << s.experiment.seed << '\n';

  const lidar::LidarParams& l = s.lidar;
  out << "\n[lidar]\n"
      << "wavelength_m = " << num(l.wavelength_m) << '\n'
      << "field_of_view_deg = " << num(l.field_of_view_deg) << '\n'
      << "angular_step_deg = " << num(l.angular_step_deg) << '\n'
      << "scan_rate_hz = " << num(l.scan_rate_hz) << '\n'
      << "scans_per_step = " << l.scans_per_step << '\n'
      << "min_range_m = " << num(l.min_range_m) << '\n'
      << "max_range_m = " << num(l.max_range_m) << '\n'
      << "pulse_width_ns = " << num(l.pulse_width_ns) << '\n'
      << "sample_interval_ns = " << num(l.sample_interval_ns) << '\n'
      << "overlap_range_m = " << num(l.overlap_range_m) << '\n'
      << "threshold_range_m = " << num(l.threshold_range_m) << '\n'
      << "threshold_reflectivity = " << num(l.threshold_reflectivity) << '\n'
      << "false_alarm_probability = " << num(l.false_alarm_probability) << '\n'
      << "max_echoes = " << l.max_echoes << '\n'
      << "min_echo_separation_m = " << num(l.min_echo_separation_m) << '\n'
      << "intensity_scale = " << num(l.intensity_scale) << '\n'
      << "intensity_saturation = " << num(l.intensity_saturation) << '\n'
      << "target_width_m = " << num(l.target_width_m) << '\n'
      << "target_offset_m = " << num(l.target_offset_m) << '\n'
      << "target_reflectivity = " << num(l.target_reflectivity) << '\n'
      << "fog_width_m = " << num(l.fog_width_m) << '\n';
  if (l.background.empty()) out << "background = []\n";
  out << "\n[lidar.fog_fluctuation]\n"
      << "log_std = " << num(l.fog_fluctuation.log_std) << '\n'
      << "correlation_time_s = " << num(l.fog_fluctuation.correlation_time_s) << '\n';
  for (const lidar::BackgroundSegment& b : l.background) {
    out << "\n[[lidar.background]]\n"
        << "x0_m = " << num(b.x0_m) << '\n'
        << "y0_m = " << num(b.y0_m) << '\n'
        << "x1_m = " << num(b.x1_m) << '\n'
        << "y1_m = " << num(b.y1_m) << '\n'
        << "reflectivity = " << num(b.reflectivity) << '\n';
  }

  const camera::CameraParams& c = s.camera;
  const auto region = [&](const char* name, const camera::RegionParams& p) {
    out << "\n[camera.roi." << name << "]\n"
        << "median_reflectance = " << num(p.median_reflectance) << '\n'
        << "log_sigma = " << num(p.log_sigma) << '\n';
  };
  out << "\n[camera]\n"
      << "band = " << str(camera::to_string(c.band)) << '\n'
      << "wavelength_nm = " << num(c.wavelength_nm) << '\n'
      << "mie_step_nm = " << num(c.mie_step_nm) << '\n'
      << "transfer = " << str(camera::to_string(c.transfer)) << '\n'
      << "gamma = " << num(c.gamma) << '\n'
      << "frames_per_step = " << c.frames_per_step << '\n'
      << "contrast_threshold = " << num(c.contrast_threshold) << '\n'
      << "write_roi_images = " << (c.write_roi_images ? "true" : "false") << "\n\n"
      << "[camera.exposure]\n"
      << "mode = " << str(camera::to_string(c.exposure.mode)) << '\n'
      << "ambient_level = " << num(c.exposure.ambient_level) << '\n'
      << "auto_target_grey = " << num(c.exposure.auto_target_grey) << "\n\n"
      << "[camera.noise]\n"
      << "enabled = " << (c.noise.enabled ? "true" : "false") << '\n'
      << "full_well_electrons = " << num(c.noise.full_well_electrons) << '\n'
      << "read_noise_electrons = " << num(c.noise.read_noise_electrons) << "\n\n"
      << "[camera.roi]\n"
      << "width_px = " << c.roi.width_px << '\n'
      << "height_px = " << c.roi.height_px << '\n'
      << "cell_px = " << c.roi.cell_px << '\n'
      << "target_fraction = " << num(c.roi.target_fraction) << '\n';
  region("target", c.roi.target);
  region("background", c.roi.background);
  return out.str();
}

}  // namespace fogradar::experiment
