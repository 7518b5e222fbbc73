#include "scenario_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>
#include <random>
#include <string_view>

#include "fogradar/core/constants.hpp"

namespace fogradar::property {
namespace {

// Draws with the case's own generator; numbers are rounded to four significant digits so that a
// failing scenario reads easily (every range below lies inside its key's declared range with room
// for that rounding).
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : rng_(seed) {}

  double uniform(double low, double high) {
    return round4(std::uniform_real_distribution<double>(low, high)(rng_));
  }
  double log_uniform(double low, double high) {
    return round4(
        std::exp(std::uniform_real_distribution<double>(std::log(low), std::log(high))(rng_)));
  }
  std::int64_t integer(std::int64_t low, std::int64_t high) {
    return std::uniform_int_distribution<std::int64_t>(low, high)(rng_);
  }
  bool chance(double p) { return std::bernoulli_distribution(p)(rng_); }
  template <class T>
  const T& pick(const std::vector<T>& options) {
    return options[static_cast<std::size_t>(
        integer(0, static_cast<std::int64_t>(options.size()) - 1))];
  }
  template <class T>
  void shuffle(std::vector<T>& v) {
    std::shuffle(v.begin(), v.end(), rng_);
  }

 private:
  static double round4(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", x);
    return std::strtod(text, nullptr);
  }
  std::mt19937_64 rng_;
};

std::string number(double x) {
  char text[32];
  for (int digits = 1; digits <= 17; ++digits) {  // shortest text that reads back to x
    std::snprintf(text, sizeof text, "%.*g", digits, x);
    if (std::strtod(text, nullptr) == x) break;
  }
  std::string s = text;
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  return s;
}
std::string quoted(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  out.push_back('"');
  out.append(s);
  out.push_back('"');
  return out;
}

// TOML text section by section, in the order the sections are first named.
class Toml {
 public:
  void set(const std::string& section, const std::string& key, const std::string& value) {
    if (!lines_.contains(section)) order_.push_back(section);
    lines_[section] += key + " = " + value + "\n";
  }
  void set(const std::string& section, const std::string& key, double value) {
    set(section, key, number(value));
  }
  void set_integer(const std::string& section, const std::string& key, std::int64_t value) {
    set(section, key, std::to_string(value));
  }
  void set_boolean(const std::string& section, const std::string& key, bool value) {
    set(section, key, std::string(value ? "true" : "false"));
  }
  void append_table(const std::string& array, const std::string& body) {
    tables_ += "\n[[" + array + "]]\n" + body;
  }
  std::string text() const {
    std::string out;
    for (const std::string& section : order_)
      out += "[" + section + "]\n" + lines_.at(section) + "\n";
    return out + tables_;
  }

 private:
  std::vector<std::string> order_;
  std::map<std::string, std::string> lines_;
  std::string tables_;
};

// A fog's keys as an inline table's entries or as [fog] lines: one density key (the group's
// alternatives), the droplets, and the water model with a temperature it allows.
std::vector<std::pair<std::string, std::string>> draw_fog(Draw& d) {
  std::vector<std::pair<std::string, std::string>> keys;
  switch (d.integer(0, 3)) {
    case 0:
      keys.emplace_back("lwc_g_per_m3", number(d.uniform(0.0, 3.0)));
      break;
    case 1:
      keys.emplace_back("extinction_per_km", number(d.uniform(0.0, 3000.0)));
      break;
    case 2:
      keys.emplace_back("visibility_m", number(d.log_uniform(1.0, 1000.0)));
      break;
    default:
      keys.emplace_back("lwc_g_per_m3", number(0.0));
      break;  // an air gap
  }
  if (d.chance(0.5)) {
    keys.emplace_back("water_model", quoted("segelstein"));
    keys.emplace_back("temperature_c", number(25.0));
  } else {
    keys.emplace_back("water_model", quoted("liebe"));
    keys.emplace_back("temperature_c", number(d.uniform(-20.0, 50.0)));
  }
  std::string droplets;
  switch (d.integer(0, 4)) {
    case 0:
      droplets = "distribution = \"lognormal\", median_diameter_m = " +
                 number(d.log_uniform(0.5e-6, 20e-6)) +
                 ", geometric_std = " + number(d.uniform(1.1, 2.5));
      break;
    case 1:
      droplets =
          "distribution = \"monodisperse\", diameter_m = " + number(d.log_uniform(1e-6, 50e-6));
      break;
    case 2:
      droplets = "distribution = \"advection\"";
      break;
    case 3:
      droplets = "distribution = \"radiation\"";
      break;
    default: {
      // Mode radius (alpha / (b gamma))^(1/gamma) of 1-10 um, within the key's 500 um.
      const double alpha = d.uniform(1.0, 6.0);
      const double gamma = d.uniform(0.5, 2.0);
      const double mode_um = d.uniform(1.0, 10.0);
      const double b = alpha / (gamma * std::pow(mode_um, gamma));
      droplets = "distribution = \"modified_gamma\", alpha = " + number(alpha) +
                 ", gamma = " + number(gamma) + ", b_per_um_gamma = " + number(b);
    }
  }
  keys.emplace_back("droplets", "{ " + droplets + " }");
  return keys;
}

double mainlobe_half_width_bins(std::string_view window) {
  // First null of the window's spectrum: rectangular 1 bin, Hann and Hamming 2, the four-term
  // Blackman-Harris 4; the Dolph-Chebyshev window at its deep sidelobe level about as wide.
  if (window == "rectangular") return 1.0;
  if (window == "hann" || window == "hamming") return 2.0;
  return 4.0;
}

bool runs(const DrawnScenario& out, std::string_view sensor) {
  return std::find(out.sensors.begin(), out.sensors.end(), sensor) != out.sensors.end();
}

// The materials with radio data at the radar's carrier (the ranges of ITU-R P.2040-3's fits, of
// water's and plastic's models: propagation/materials.cpp) and, with `optical`, a USGS sample for
// the lidar too (docs/lidar.md).
std::vector<std::string> materials(double centre_hz, bool optical) {
  struct Material {
    const char* name;
    double min_ghz, max_ghz;
    bool optical;
  };
  static constexpr Material all[] = {
      {"concrete", 1.0, 100.0, true},      {"brick", 1.0, 40.0, true},
      {"plasterboard", 1.0, 100.0, false}, {"wood", 0.001, 100.0, true},
      {"glass", 0.1, 100.0, false},        {"ceiling_board", 1.0, 100.0, false},
      {"chipboard", 1.0, 100.0, true},     {"plywood", 1.0, 40.0, true},
      {"marble", 1.0, 60.0, false},        {"floorboard", 50.0, 100.0, false},
      {"metal", 1.0, 100.0, true},         {"water", 0.001, 1000.0, true},
      {"plastic", 10.0, 300.0, true}};
  std::vector<std::string> names;
  const double ghz = centre_hz / 1e9;
  for (const Material& m : all) {
    if (ghz >= m.min_ghz && ghz <= m.max_ghz && (m.optical || !optical)) names.emplace_back(m.name);
  }
  return names;
}

// The longest one-way path from the radar at height `radar_height_m` to any image of order <= 2
// of `p` in the room's planes. The room is a box, so an image mirrors each coordinate
// independently: x in the back wall (x' = 2 X - x), y in the side walls (-2 L - y, 2 R - y and,
// off both, y +- 2 (L + R)), z in the floor and ceiling (-z, 2 H - z, z +- 2 H), orders adding up.
double longest_image_path_m(const RoomGeometry& room, const Point3& p, double radar_height_m) {
  struct Image {
    double value;
    int order;
  };
  std::vector<Image> xs{{p.x_m, 0}}, ys{{p.y_m, 0}}, zs{{p.z_m - radar_height_m, 0}};
  const double l = room.left_wall_m, r = room.right_wall_m, h = room.ceiling_m;
  if (room.back_wall_m > 0.0) xs.push_back({2.0 * room.back_wall_m - p.x_m, 1});
  if (l > 0.0) ys.push_back({-2.0 * l - p.y_m, 1});
  if (r > 0.0) ys.push_back({2.0 * r - p.y_m, 1});
  if (l > 0.0 && r > 0.0) {
    ys.push_back({p.y_m + 2.0 * (l + r), 2});
    ys.push_back({p.y_m - 2.0 * (l + r), 2});
  }
  if (room.floor) zs.push_back({-p.z_m - radar_height_m, 1});
  if (h > 0.0) zs.push_back({2.0 * h - p.z_m - radar_height_m, 1});
  if (room.floor && h > 0.0) {
    zs.push_back({p.z_m + 2.0 * h - radar_height_m, 2});
    zs.push_back({p.z_m - 2.0 * h - radar_height_m, 2});
  }
  double longest_m = 0.0;
  for (const Image& x : xs) {
    for (const Image& y : ys) {
      for (const Image& z : zs) {
        if (x.order + y.order + z.order > 2) continue;
        longest_m = std::max(longest_m,
                             std::sqrt(x.value * x.value + y.value * y.value + z.value * z.value));
      }
    }
  }
  return longest_m;
}

// The room: the floor as drawn before (a real coefficient, or now and then a material), then in
// three cases of four each other surface with probability 0.35 and 0-4 objects; written to `t` and
// recorded in out.room. Returns the lidar wavelength the room needs (905 or 1550 nm: the lidar runs
// and sees walls or objects), 0 when it needs none.
double draw_room(Draw& d, Toml& t, DrawnScenario& out, double floor_coefficient, double centre_hz,
                 double radar_max_range_m) {
  RoomGeometry& room = out.room;
  const bool lidar = runs(out, "lidar");
  out.lidar_height_m = d.uniform(0.2, 1.5);
  t.set("lidar", "height_m", out.lidar_height_m);
  const bool point = out.target_centres.size() == 1;
  double lateral_m = 0.0, top_m = 0.0;
  for (const Point3& c : out.target_centres) {
    lateral_m = std::max(lateral_m, std::abs(c.y_m));
    top_m = std::max(top_m, c.z_m);
  }
  const double r = out.target_range_m;
  const double tol_m = (out.window_mainlobe_half_width_bins + 1.0) * out.range_bin_m;
  // No echo of the room may fold: the radar refuses a back wall or an object past its unambiguous
  // range less 1 m, and the check's reference needs the ghosts' main lobes inside it too.
  const double limit_m = radar_max_range_m - 1.0 - tol_m;

  // A wall's reflection: what the lidar sees must be a material with optical data.
  const auto reflection = [&](const std::string& section, bool seen_by_lidar) {
    if (!seen_by_lidar && d.chance(0.5)) {
      t.set(section, "reflection_coefficient", d.uniform(-1.0, 1.0));
    } else {
      t.set(section, "material", quoted(d.pick(materials(centre_hz, seen_by_lidar))));
    }
  };
  const bool floor_material = room.floor && d.chance(0.3);
  // A quarter of the seeds keep the bare hall (the floor as drawn, nothing else), the space the
  // checker walked before it drew rooms.
  const bool furnished = d.chance(0.75);
  if (furnished && d.chance(0.35)) room.left_wall_m = d.uniform(point ? 0.3 : 1.0, 6.0);
  if (furnished && d.chance(0.35)) room.right_wall_m = d.uniform(point ? 0.3 : 1.0, 6.0);
  if (furnished && d.chance(0.35)) {
    room.ceiling_m =
        d.uniform(std::max({out.radar_height_m, out.lidar_height_m, top_m}) + 0.3, 6.0);
  }
  if (furnished && d.chance(0.35)) {
    room.back_wall_m = d.uniform(r + out.target_depth_m + 0.3, r + out.target_depth_m + 6.0);
  }
  // Surfaces whose ghosts would fold are left out, the farthest reaching first.
  const auto fits = [&] {
    if (room.back_wall_m > limit_m) return false;
    for (const Point3& c : out.target_centres) {
      if (longest_image_path_m(room, c, out.radar_height_m) > limit_m) return false;
    }
    return true;
  };
  for (double* surface :
       {&room.back_wall_m, &room.ceiling_m, &room.right_wall_m, &room.left_wall_m}) {
    if (!fits()) *surface = 0.0;
  }
  if (!fits()) room.floor = false;

  if (room.floor) {
    if (floor_material) {
      t.set("chamber.room.floor", "material", quoted(d.pick(materials(centre_hz, false))));
    } else {
      t.set("chamber.room.floor", "reflection_coefficient", floor_coefficient);
    }
  } else {
    t.set_boolean("chamber.room", "floor", false);
  }
  const struct {
    const char* name;
    const char* distance_key;
    double distance_m;
    bool seen_by_lidar;
  } surfaces[] = {{"left_wall", "distance_m", room.left_wall_m, lidar},
                  {"right_wall", "distance_m", room.right_wall_m, lidar},
                  {"ceiling", "height_m", room.ceiling_m, false},
                  {"back_wall", "distance_m", room.back_wall_m, lidar}};
  for (const auto& s : surfaces) {
    const std::string section = std::string("chamber.room.") + s.name;
    if (s.distance_m > 0.0) {
      t.set(section, s.distance_key, s.distance_m);
      reflection(section, s.seen_by_lidar);
    } else {
      t.set_boolean("chamber.room", s.name, false);
    }
  }

  // Objects: most clear of the target and the boresight where the room leaves a band beside them,
  // the others anywhere inside the room in front of the sensors.
  const double clear_m =
      std::max(lateral_m + 0.3,
               lidar ? std::abs(out.lidar_target_offset_m) + 0.5 * out.lidar_target_width_m : 0.0);
  for (std::int64_t i = furnished ? d.integer(0, 4) : 0; i > 0; --i) {
    RoomGeometry::Object o;
    o.cylinder = d.chance(0.5);
    o.height_m = d.uniform(0.2, 1.5);
    o.base_height_m = d.chance(0.7) ? 0.0 : d.uniform(0.0, 0.5);
    if (o.cylinder) {
      o.radius_m = d.uniform(0.05, 0.4);
    } else {
      o.width_m = d.uniform(0.2, 1.5);
      o.yaw_deg = d.uniform(-90.0, 90.0);
    }
    const double extent_m = o.cylinder ? o.radius_m : 0.5 * o.width_m;
    const double left_m = (room.left_wall_m > 0.0 ? room.left_wall_m : 6.0) - extent_m - 0.05;
    const double right_m = (room.right_wall_m > 0.0 ? room.right_wall_m : 6.0) - extent_m - 0.05;
    const double near_x_m = extent_m + 0.3;
    const double far_x_m =
        std::min(room.back_wall_m > 0.0 ? room.back_wall_m - extent_m - 0.05 : r + 4.0, r + 4.0);
    const bool clear = d.chance(0.7);
    const double side = d.chance(0.5) ? 1.0 : -1.0;
    const double inner_m = clear ? clear_m + extent_m : -(side > 0.0 ? left_m : right_m);
    const double outer_m = side > 0.0 ? right_m : left_m;
    o.x_m = d.uniform(near_x_m, std::max(near_x_m, far_x_m));
    o.y_m = side * d.uniform(inner_m, std::max(inner_m, outer_m));
    if (room.ceiling_m > 0.0) {
      o.height_m = std::min(o.height_m, room.ceiling_m - 0.05 - o.base_height_m);
    }
    // An object the room cannot hold as drawn, or whose echo would fold, is not placed.
    const double middle_m = o.base_height_m + 0.5 * o.height_m;
    const double far_m =
        std::hypot(std::hypot(o.x_m, o.y_m) + extent_m, middle_m - out.radar_height_m);
    const bool inside = far_x_m > near_x_m && o.y_m >= -left_m && o.y_m <= right_m &&
                        o.height_m >= 0.05 &&
                        (room.ceiling_m == 0.0 || o.base_height_m + o.height_m < room.ceiling_m);
    const bool away = std::hypot(o.x_m, o.y_m) - extent_m > tol_m + 0.3 && far_m < limit_m;
    if (!inside || !away) continue;
    std::string body = "shape = " + quoted(o.cylinder ? "cylinder" : "plate") +
                       "\nx_m = " + number(o.x_m) + "\ny_m = " + number(o.y_m) +
                       "\nbase_height_m = " + number(o.base_height_m) +
                       "\nheight_m = " + number(o.height_m) + "\n";
    body += o.cylinder
                ? "radius_m = " + number(o.radius_m) + "\n"
                : "width_m = " + number(o.width_m) + "\nyaw_deg = " + number(o.yaw_deg) + "\n";
    body += "material = " + quoted(d.pick(materials(centre_hz, lidar))) + "\n";
    t.append_table("chamber.objects", body);
    room.objects.push_back(o);
  }
  if (room.objects.empty()) t.set("chamber", "objects", "[]");
  const bool lidar_sees_room = lidar && (room.left_wall_m > 0.0 || room.right_wall_m > 0.0 ||
                                         room.back_wall_m > 0.0 || !room.objects.empty());
  return lidar_sees_room ? d.pick(std::vector<double>{905e-9, 1550e-9}) : 0.0;
}

}  // namespace

DrawnScenario draw_scenario(std::uint64_t seed) {
  Draw d(seed);
  Toml t;
  DrawnScenario out;
  out.seed = seed;

  // Sensors: a non-empty subset in a random order.
  std::vector<std::string> all{"radar", "lidar", "camera"};
  d.shuffle(all);
  const auto sensor_count = static_cast<std::size_t>(d.integer(1, 3));
  out.sensors.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(sensor_count));

  // Radar frame: the samples fill the chirp, so the range bin is c / (2 B) and the unambiguous
  // range c N / (2 B).
  const double centre_hz = d.uniform(20e9, 100e9);
  const double chirp_s = d.uniform(20e-6, 60e-6);
  const double interval_s = chirp_s * d.uniform(1.0, 1.5);
  const std::int64_t samples = d.pick(std::vector<std::int64_t>{64, 128, 256, 512});
  const double sample_rate_hz = static_cast<double>(samples) / chirp_s * 1.001;

  // Chamber: n identical layers or [[chamber.layers]] of their own lengths and fogs.
  const auto layer_count = static_cast<std::size_t>(d.integer(1, 6));
  const bool listed = d.chance(0.5);
  const double sensor_gap_m = d.uniform(0.0, 4.0);
  const double target_gap_m = d.uniform(0.0, 4.0);
  std::vector<double> lengths(layer_count);
  const double uniform_length_m = d.uniform(0.2, 3.0);
  for (double& l : lengths) l = listed ? d.uniform(0.2, 3.0) : uniform_length_m;
  double at_m = sensor_gap_m;
  for (const double l : lengths) {
    out.layers.push_back({at_m, at_m + l});
    at_m += l;
  }
  out.target_range_m = at_m + target_gap_m;
  t.set("chamber", "sensor_gap_m", sensor_gap_m);
  t.set("chamber", "target_gap_m", target_gap_m);
  if (!listed) {
    t.set_integer("chamber", "layer_count", static_cast<std::int64_t>(layer_count));
    t.set("chamber", "layer_length_m", uniform_length_m);
  }
  for (const auto& [key, value] : draw_fog(d)) t.set("fog", key, value);
  t.set_integer("radar", "clutter_scatterers_per_bin", d.integer(1, 8));
  std::string layer_tables;
  if (listed) {
    for (const double l : lengths) {
      std::string body = "length_m = " + number(l) + "\n";
      if (d.chance(0.7)) {
        std::string fog;
        for (const auto& [key, value] : draw_fog(d))
          fog += (fog.empty() ? "" : ", ") + key + " = " + value;
        body += "fog = { " + fog + " }\n";
      }
      layer_tables += "\n[[chamber.layers]]\n" + body;
    }
  }

  // The radar's bandwidth keeps the chamber within 2/3 of its unambiguous range.
  const double max_bandwidth_hz =
      std::min(2e9, speed_of_light_m_per_s * static_cast<double>(samples) /
                        (2.0 * 1.5 * out.target_range_m * 1.01));
  const double bandwidth_hz =
      d.log_uniform(std::min(0.2e9, max_bandwidth_hz) * 0.5, max_bandwidth_hz);
  out.range_bin_m = speed_of_light_m_per_s / (2.0 * bandwidth_hz);
  t.set("radar", "centre_frequency_hz", centre_hz);
  t.set("radar", "sweep_direction", quoted(d.chance(0.5) ? "up" : "down"));
  t.set("radar", "sweep_bandwidth_hz", bandwidth_hz);
  t.set("radar", "chirp_duration_s", chirp_s);
  t.set("radar", "chirp_interval_s", interval_s);
  t.set_integer("radar", "samples_per_chirp", samples);
  t.set("radar", "sample_rate_hz", sample_rate_hz);
  const std::int64_t chirps = d.integer(4, 16);
  t.set_integer("radar", "chirps_per_frame", chirps);
  t.set("radar", "tx_power_dbm", d.uniform(-10.0, 30.0));
  t.set("radar", "noise_figure_db", d.uniform(5.0, 20.0));
  out.ideal_adc = d.chance(0.5);
  if (!out.ideal_adc) {
    t.set_integer("radar", "adc_bits", d.integer(6, 16));
    t.set("radar", "adc_full_scale_dbm", d.uniform(-60.0, -10.0));
  }
  out.phase_noise = d.chance(0.25);
  if (out.phase_noise) t.set("radar", "phase_noise_rms_rad", d.uniform(0.001, 0.05));
  if (d.chance(0.5)) {
    t.set("radar.radome", "thickness_m", d.uniform(0.5e-3, 5e-3));
    t.set("radar.radome", "relative_permittivity", d.uniform(2.0, 5.0));
    t.set("radar.radome", "loss_tangent", d.uniform(0.0, 0.05));
  }
  if (d.chance(0.3)) t.set("radar.radome", "water_film_m", d.uniform(0.0, 1e-4));

  const std::string window = d.pick(
      std::vector<std::string>{"rectangular", "hann", "hamming", "blackman_harris", "chebyshev"});
  out.window = window;
  out.window_mainlobe_half_width_bins = mainlobe_half_width_bins(window);
  t.set("radar.processing", "window", quoted(window));
  t.set("radar.processing", "association_gate_m", d.uniform(0.2, 1.0));
  const std::string kind = d.pick(std::vector<std::string>{"ca", "go", "so", "os"});
  const std::int64_t guard = d.integer(0, 4);
  const std::int64_t training = d.integer(2, std::min<std::int64_t>(12, (samples - 1) / 2 - guard));
  t.set("radar.processing.cfar", "kind", quoted(kind));
  t.set_integer("radar.processing.cfar", "guard_cells", guard);
  t.set_integer("radar.processing.cfar", "training_cells", training);
  t.set("radar.processing.cfar", "false_alarm_probability", d.log_uniform(1e-7, 1e-3));
  if (kind == "os" && d.chance(0.5))
    t.set_integer("radar.processing.cfar", "os_rank", d.integer(1, 2 * training));
  const bool correlated = d.chance(0.5);
  t.set("radar.processing.cfar", "threshold_design",
        quoted(correlated ? "correlated" : "independent"));

  const bool point = d.chance(0.5);
  const double sensor_height_m = d.uniform(0.2, 1.5);
  double centre_height_m = 0.85;  // the EVT's highest centre
  t.set("radar.target", "model", quoted(point ? "point" : "evt"));
  if (point) {
    t.set_integer("radar.target", "swerling", d.pick(std::vector<std::int64_t>{0, 1, 3}));
    centre_height_m = d.uniform(0.0, 1.5);
    t.set("radar.target", "height_m", centre_height_m);
  }
  out.target_depth_m = point ? 0.0 : 0.30;  // the EVT's rear light centres, 30 cm behind
  out.radar_height_m = sensor_height_m;
  if (point) {
    out.target_centres = {{out.target_range_m, 0.0, centre_height_m}};
  } else {
    // docs/radar.md: (+0, 0, 0.55), (+0.05, +-0.75, 0.45), (+0.30, +-0.65, 0.85) m.
    for (const Point3& c :
         {Point3{0.0, 0.0, 0.55}, Point3{0.05, -0.75, 0.45}, Point3{0.05, 0.75, 0.45},
          Point3{0.30, -0.65, 0.85}, Point3{0.30, 0.65, 0.85}})
      out.target_centres.push_back({out.target_range_m + c.x_m, c.y_m, c.z_m});
  }
  t.set("radar.target", "rcs_dbsm", d.uniform(-10.0, 20.0));
  t.set("radar", "height_m", sensor_height_m);
  // The floor's draw; it is written with the rest of the room, drawn last.
  out.room.floor = d.chance(0.5);
  const double floor_coefficient = out.room.floor ? d.uniform(-1.0, 1.0) : 0.0;
  t.set("target", "micro_motion_std_m", d.uniform(0.0, 1e-3));
  const double wavelength_m = speed_of_light_m_per_s / centre_hz;
  const double unambiguous_m_per_s = wavelength_m / (4.0 * interval_s);
  out.target_velocity_m_per_s =
      d.chance(0.3) ? 0.0 : d.uniform(-0.9 * unambiguous_m_per_s, 0.9 * unambiguous_m_per_s);
  t.set("target", "radial_velocity_m_per_s", out.target_velocity_m_per_s);
  out.range_resolution_m = speed_of_light_m_per_s / (2.0 * bandwidth_hz);
  out.max_unambiguous_m_per_s = unambiguous_m_per_s;
  out.coupling_s = centre_hz * chirp_s / bandwidth_hz;
  if (d.chance(0.3)) t.set("target", "water_film_m", d.uniform(0.0, 1e-4));

  // Experiment.
  std::string sensors;
  for (const std::string& s : out.sensors) sensors += (sensors.empty() ? "" : ", ") + quoted(s);
  t.set("experiment", "sensors", "[" + sensors + "]");
  t.set_integer("radar", "measurements_per_step", d.integer(1, 6));
  // Not given, the run goes to every layer of the chamber.
  out.max_active_layers = layer_count;
  if (d.chance(0.7)) {
    out.max_active_layers =
        static_cast<std::size_t>(d.integer(0, static_cast<std::int64_t>(layer_count)));
    t.set_integer("experiment", "max_active_layers",
                  static_cast<std::int64_t>(out.max_active_layers));
  }
  out.switching.resize(layer_count);
  std::iota(out.switching.begin(), out.switching.end(), std::size_t{0});
  switch (d.integer(0, 2)) {
    case 0:
      t.set("experiment", "switching_order", quoted("sensor_first"));
      break;
    case 1:
      std::reverse(out.switching.begin(), out.switching.end());
      t.set("experiment", "switching_order", quoted("target_first"));
      break;
    default: {
      d.shuffle(out.switching);
      std::string list;
      for (const std::size_t i : out.switching)
        list += (list.empty() ? "" : ", ") + std::to_string(i);
      t.set("experiment", "switching_order", "[" + list + "]");
    }
  }
  t.set_integer("experiment", "seed", d.integer(0, std::int64_t{1} << 40));

  // Lidar: a few beams around boresight, a few scans.
  // Written with the room, which may ask for one of the lidar's tabulated wavelengths.
  const double drawn_lidar_wavelength_m = d.uniform(0.8e-6, 1.6e-6);
  t.set("lidar", "field_of_view_deg", d.uniform(0.0, 20.0));
  t.set("lidar", "angular_step_deg", d.uniform(0.25, 2.0));
  t.set("lidar", "scan_rate_hz", d.uniform(10.0, 100.0));
  t.set_integer("lidar", "scans_per_step", d.integer(1, 3));
  t.set("lidar", "max_range_m", std::ceil(out.target_range_m) + d.uniform(2.0, 10.0));
  const double pulse_ns = d.uniform(2.0, 10.0);
  const double sample_ns = d.uniform(0.2, 0.5 * pulse_ns);
  out.lidar_pulse_width_s = pulse_ns * 1e-9;
  out.lidar_sample_interval_s = sample_ns * 1e-9;
  t.set("lidar", "pulse_width_ns", pulse_ns);
  t.set("lidar", "sample_interval_ns", sample_ns);
  t.set("lidar", "threshold_range_m", d.uniform(10.0, 50.0));
  t.set("lidar", "false_alarm_probability", d.log_uniform(1e-7, 1e-3));
  t.set_integer("lidar", "max_echoes", d.integer(1, 8));
  out.lidar_min_echo_separation_m = d.uniform(0.2, 2.0);
  t.set("lidar", "min_echo_separation_m", out.lidar_min_echo_separation_m);
  out.lidar_target_width_m = d.uniform(0.5, 3.0);
  out.lidar_target_offset_m = d.uniform(-1.0, 1.0);
  out.lidar_fog_width_m = d.uniform(0.5, 10.0);
  t.set("lidar", "target_width_m", out.lidar_target_width_m);
  t.set("lidar", "target_offset_m", out.lidar_target_offset_m);
  t.set("lidar", "target_reflectivity", d.uniform(0.05, 0.9));
  t.set("lidar", "fog_width_m", out.lidar_fog_width_m);
  if (d.chance(0.3)) t.set("lidar", "window_water_film_m", d.uniform(1e-6, 1e-4));
  t.set("lidar.fog_fluctuation", "log_std", d.uniform(0.0, 0.5));
  t.set("lidar.fog_fluctuation", "correlation_time_s", d.uniform(0.1, 2.0));
  std::string background;
  for (std::int64_t i = d.integer(1, 3); i > 0; --i) {
    const double x0 = d.uniform(0.5, out.target_range_m + 2.0);
    const double y0 = d.uniform(-5.0, 5.0);
    const double x1 = x0 + d.uniform(-3.0, 3.0);
    const double y1 = y0 + (d.chance(0.5) ? 0.6 : d.uniform(-3.0, 3.0));
    out.lidar_background.push_back({x0, y0, x1, y1});
    background += "\n[[lidar.background]]\nx0_m = " + number(x0) + "\ny0_m = " + number(y0) +
                  "\nx1_m = " + number(x1) + "\ny1_m = " + number(y1) +
                  "\nreflectivity = " + number(d.uniform(0.0, 1.0)) + "\n";
  }

  // Camera: small frames.
  const std::string band = d.pick(std::vector<std::string>{"photopic", "rgb", "monochromatic"});
  t.set("camera", "band", quoted(band));
  if (band == "monochromatic") t.set("camera", "wavelength_nm", d.uniform(400.0, 1000.0));
  const double mie_step_nm = d.uniform(40.0, 160.0);
  if (band != "monochromatic") t.set("camera", "mie_step_nm", mie_step_nm);
  const bool gamma = d.chance(0.5);
  t.set("camera", "transfer", quoted(gamma ? "gamma" : "srgb"));
  if (gamma) t.set("camera", "gamma", d.uniform(1.0, 4.0));
  t.set_integer("camera", "frames_per_step", d.integer(1, 2));
  t.set("camera", "contrast_threshold", d.uniform(0.01, 0.2));
  if (d.chance(0.3)) t.set("camera", "window_water_film_m", d.uniform(1e-6, 1e-4));
  t.set_boolean("camera", "write_roi_images", d.chance(0.3));
  const bool automatic = d.chance(0.5);
  t.set("camera.exposure", "mode", quoted(automatic ? "auto" : "fixed"));
  if (automatic) {
    t.set("camera.exposure", "auto_target_grey", d.uniform(20.0, 200.0));
  } else {
    t.set("camera.exposure", "ambient_level", d.uniform(0.01, 0.2));
  }
  const bool noise = d.chance(0.7);
  t.set_boolean("camera.noise", "enabled", noise);
  const double full_well_electrons = d.log_uniform(1e3, 1e5);
  const double read_noise_electrons = d.uniform(0.0, 20.0);
  if (noise) {
    t.set("camera.noise", "full_well_electrons", full_well_electrons);
    t.set("camera.noise", "read_noise_electrons", read_noise_electrons);
  }
  const std::int64_t width = d.integer(16, 64);
  const std::int64_t height = d.integer(16, 64);
  t.set_integer("camera.roi", "width_px", width);
  t.set_integer("camera.roi", "height_px", height);
  t.set_integer("camera.roi", "cell_px", d.integer(2, std::min(width, height) / 2));
  t.set("camera.roi", "target_fraction", d.uniform(0.2, 0.9));
  t.set("camera.roi.target", "median_reflectance", d.uniform(0.05, 1.0));
  t.set("camera.roi.target", "log_sigma", d.uniform(0.0, 1.0));
  t.set("camera.roi.background", "median_reflectance", d.uniform(0.05, 1.0));
  t.set("camera.roi.background", "log_sigma", d.uniform(0.0, 1.0));

  // The CFAR's shape is drawn last, so that every draw above is what it was before the shape
  // existed.
  if (d.chance(0.25)) {
    t.set("radar.processing.cfar", "shape", quoted("range_doppler"));
    const std::int64_t doppler_guard = d.integer(0, 1);
    // 2 (g_d + n_d) + 1 <= rows - 1
    const std::int64_t rows_left = (chirps - 2) / 2 - doppler_guard;
    t.set_integer("radar.processing.cfar", "doppler_guard_cells", doppler_guard);
    t.set_integer("radar.processing.cfar", "doppler_training_cells",
                  d.integer(0, std::min<std::int64_t>(2, rows_left)));
  }

  const double lidar_wavelength_m =
      draw_room(d, t, out, floor_coefficient, centre_hz,
                speed_of_light_m_per_s * sample_rate_hz * chirp_s / (2.0 * bandwidth_hz));
  t.set("lidar", "wavelength_m",
        lidar_wavelength_m > 0.0 ? lidar_wavelength_m : drawn_lidar_wavelength_m);

  out.toml = "# property checker, seed " + std::to_string(seed) + "\n" + t.text() + layer_tables +
             background;
  return out;
}

}  // namespace fogradar::property
