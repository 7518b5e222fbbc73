// The property checker (docs/validation.md, "Property checker"): random valid scenarios
// (scenario_generator.hpp), each run in-process, and properties that must hold for every scenario,
// whatever its chamber, fogs, switching order, sensors and settings:
// - the result files are the same bytes at 1 and 2 threads;
// - every radar detection and lidar echo whose origin is fog lies inside a layer that is active at
//   its step (a radar fog detection inside the layer it names), every target-origin one at the
//   target, every radar ghost (multipath) at the range of one of the target's paths via the room's
//   planes (mirror images of at most second order, computed here), every radar room echo at the
//   back wall or an object, every lidar background echo on a background segment, a wall or an
//   object in its scan plane (the chamber and room as the generator laid them out, not as the run
//   reports them);
// - each sensor's fog loss does not decrease as layers come on (any order, any fogs: each layer's
//   extinction is >= 0), and every sensor reports the steps 0 .. max_active_layers;
// - the written scenario.toml reads back to the same text, and run from that text gives the same
//   result files.
// At its end the binary prints how many seeds drew a room and how many detections of each origin
// the origin check examined.
// Seeds: FOGRADAR_PROPERTY_SEEDS="first-last" (inclusive; default 0-24), so that ctest runs ranges
// of seeds in parallel and one seed reruns alone. A failure prints the seed and the scenario file,
// which `fogradar run --scenario` reads as it is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "scenario_generator.hpp"

namespace fogradar::property {
namespace {

using experiment::Scenario;
using Files = std::vector<sensor::ResultFile>;

struct SeedRange {
  std::uint64_t first = 0;
  std::uint64_t last = 24;
};

SeedRange seed_range() {
  SeedRange range;
  if (const char* text = std::getenv("FOGRADAR_PROPERTY_SEEDS")) {
    const std::string s = text;
    const std::size_t dash = s.find('-');
    range.first = std::stoull(s.substr(0, dash));
    range.last = dash == std::string::npos ? range.first : std::stoull(s.substr(dash + 1));
  }
  return range;
}

Files run_files(const Scenario& scenario, unsigned threads) {
  const experiment::Simulation simulation(scenario);
  const experiment::ExperimentResult result = simulation.run({.threads = threads, .progress = {}});
  return experiment::result_files(simulation.scenario(), experiment::summarize(result));
}

// One seed's scenario and its run at 1 and 2 threads, made once for every property of the seed.
struct Outcome {
  DrawnScenario drawn;
  std::string refused;  // why the drawn scenario could not be read or run ("" when it ran)
  Files one_thread, two_threads;

  const std::string* file(const std::string& name) const {
    for (const sensor::ResultFile& f : one_thread) {
      if (f.name == name) return &f.content;
    }
    return nullptr;
  }
};

const Outcome& outcome(std::uint64_t seed) {
  static std::map<std::uint64_t, std::unique_ptr<Outcome>> made;
  std::unique_ptr<Outcome>& slot = made[seed];
  if (!slot) {
    slot = std::make_unique<Outcome>();
    slot->drawn = draw_scenario(seed);
    try {
      const Scenario scenario = experiment::parse_scenario(slot->drawn.toml, "property.toml");
      slot->one_thread = run_files(scenario, 1);
      slot->two_threads = run_files(scenario, 2);
    } catch (const std::exception& e) {
      slot->refused = e.what();
    }
  }
  return *slot;
}

std::string describe(const DrawnScenario& drawn) {
  return "property case seed " + std::to_string(drawn.seed) +
         " (rerun: FOGRADAR_PROPERTY_SEEDS=" + std::to_string(drawn.seed) +
         " test_property); its scenario file:\n" + drawn.toml;
}

// A CSV file's rows as maps from column name to text.
std::vector<std::map<std::string, std::string>> read_csv(const std::string& text) {
  std::vector<std::map<std::string, std::string>> rows;
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> header;
  const auto split = [](const std::string& l) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream cells_in(l);
    while (std::getline(cells_in, cell, ',')) cells.push_back(cell);
    if (!l.empty() && l.back() == ',') cells.emplace_back();
    return cells;
  };
  if (!std::getline(in, line)) return rows;
  header = split(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

// The layers active at step k: the first k of the switching sequence.
std::vector<LayerGeometry> active_layers(const DrawnScenario& d, std::size_t k) {
  std::vector<LayerGeometry> active;
  for (std::size_t j = 0; j < k && j < d.switching.size(); ++j)
    active.push_back(d.layers[d.switching[j]]);
  return active;
}

// What the origin check examined over the seeds this process ran, printed at its end (the
// property checker's coverage: docs/validation.md).
struct Examined {
  std::size_t seeds = 0, rooms = 0, refused = 0;
  std::map<std::string, std::size_t> radar, lidar;
};
Examined& examined() {
  static Examined e;
  return e;
}
class PrintExamined : public ::testing::Environment {
 public:
  void TearDown() override {
    const Examined& e = examined();
    std::string line = "property checker: " + std::to_string(e.seeds) + " seeds checked, " +
                       std::to_string(e.rooms) + " with a room (walls, ceiling or objects), " +
                       std::to_string(e.refused) + " refused; radar detections";
    for (const auto& [origin, n] : e.radar) line += " " + origin + " " + std::to_string(n);
    line += "; lidar echoes";
    for (const auto& [origin, n] : e.lidar) line += " " + origin + " " + std::to_string(n);
    std::printf("%s\n", line.c_str());
  }
};
const auto* const print_examined = ::testing::AddGlobalTestEnvironment(new PrintExamined);

// Mirror-image geometry for the radar's paths via the room, written here apart from the radar's
// room_paths.cpp: a plane is its unit normal n and offset c (the points with n.p = c), and the
// image of p in it is p - 2 (n.p - c) n (Born & Wolf, Principles of Optics, the plane mirror).
struct Plane {
  double nx, ny, nz, c;
};
Point3 mirror(const Point3& p, const Plane& s) {
  const double twice = 2.0 * (s.nx * p.x_m + s.ny * p.y_m + s.nz * p.z_m - s.c);
  return {p.x_m - twice * s.nx, p.y_m - twice * s.ny, p.z_m - twice * s.nz};
}
std::vector<Plane> room_planes(const RoomGeometry& room) {
  std::vector<Plane> planes;
  if (room.floor) planes.push_back({0.0, 0.0, 1.0, 0.0});
  if (room.left_wall_m > 0.0) planes.push_back({0.0, 1.0, 0.0, -room.left_wall_m});
  if (room.right_wall_m > 0.0) planes.push_back({0.0, 1.0, 0.0, room.right_wall_m});
  if (room.ceiling_m > 0.0) planes.push_back({0.0, 0.0, 1.0, room.ceiling_m});
  if (room.back_wall_m > 0.0) planes.push_back({1.0, 0.0, 0.0, room.back_wall_m});
  return planes;
}

// A two-way path of a target centre via the room: out along one one-way path and back along
// another, each from the radar to an image of the centre in at most two planes, two reflections in
// all, the direct path both ways excluded: its range (L_out + L_back) / 2, and the range the
// range-Doppler coupling correction may move it by when its velocity folds.
struct RoomPath {
  double range_m = 0.0;
  double fold_m = 0.0;
};
std::vector<RoomPath> room_paths(const DrawnScenario& d, const Point3& centre) {
  const std::vector<Plane> planes = room_planes(d.room);
  struct Leg {
    double length_m, rate;  // rate: d length / d x of the centre
    int order;
  };
  const auto leg = [&](const auto& image_of, int order) {
    // The length's rate by a central difference over +-0.1 mm of the centre along x.
    const auto length = [&](double dx) {
      const Point3 i = image_of(Point3{centre.x_m + dx, centre.y_m, centre.z_m});
      return std::sqrt(i.x_m * i.x_m + i.y_m * i.y_m +
                       (i.z_m - d.radar_height_m) * (i.z_m - d.radar_height_m));
    };
    return Leg{length(0.0), (length(1e-4) - length(-1e-4)) / 2e-4, order};
  };
  std::vector<Leg> legs{leg([](const Point3& p) { return p; }, 0)};
  for (const Plane& a : planes)
    legs.push_back(leg([&](const Point3& p) { return mirror(p, a); }, 1));
  for (const Plane& a : planes) {
    for (const Plane& b : planes) {
      if (&a == &b) continue;
      legs.push_back(leg([&](const Point3& p) { return mirror(mirror(p, a), b); }, 2));
    }
  }
  // The centre moves along x at the speed that gives its direct path the radial velocity v.
  const double speed = d.target_velocity_m_per_s / legs[0].rate;
  const double period = 2.0 * d.max_unambiguous_m_per_s;
  std::vector<RoomPath> paths;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    for (std::size_t j = i; j < legs.size(); ++j) {
      if ((i == 0 && j == 0) || legs[i].order + legs[j].order > 2) continue;
      const double velocity = 0.5 * speed * (legs[i].rate + legs[j].rate);
      const double misread = period * std::round(velocity / period);
      paths.push_back(
          {0.5 * (legs[i].length_m + legs[j].length_m), std::abs(misread) * d.coupling_s});
    }
  }
  return paths;
}

double direct_range_m(const DrawnScenario& d, const Point3& c) {
  return std::sqrt(c.x_m * c.x_m + c.y_m * c.y_m +
                   (c.z_m - d.radar_height_m) * (c.z_m - d.radar_height_m));
}

// A plate's bottom edge in the scan plane: its width about its centre along (sin yaw, cos yaw).
DrawnScenario::Segment plate_segment(const RoomGeometry::Object& o) {
  const double yaw = o.yaw_deg * pi / 180.0;
  const double ux = 0.5 * o.width_m * std::sin(yaw), uy = 0.5 * o.width_m * std::cos(yaw);
  return {o.x_m - ux, o.y_m - uy, o.x_m + ux, o.y_m + uy};
}

double distance_to_segment(double x, double y, const DrawnScenario::Segment& s) {
  const double dx = s.x1_m - s.x0_m;
  const double dy = s.y1_m - s.y0_m;
  const double length2 = dx * dx + dy * dy;
  const double u =
      length2 > 0.0 ? std::clamp(((x - s.x0_m) * dx + (y - s.y0_m) * dy) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(x - (s.x0_m + u * dx), y - (s.y0_m + u * dy));
}

class ScenarioProperty : public ::testing::TestWithParam<std::uint64_t> {
 protected:
  const Outcome& ran() {
    const Outcome& o = outcome(GetParam());
    if (!o.refused.empty())
      ADD_FAILURE() << "the drawn scenario was refused or failed: " << o.refused;
    return o;
  }
};

TEST_P(ScenarioProperty, SameBytesAtOneAndTwoThreads) {
  const Outcome& o = ran();
  SCOPED_TRACE(describe(o.drawn));
  if (!o.refused.empty()) return;
  ASSERT_EQ(o.one_thread.size(), o.two_threads.size());
  for (std::size_t i = 0; i < o.one_thread.size(); ++i) {
    EXPECT_EQ(o.one_thread[i].name, o.two_threads[i].name);
    EXPECT_TRUE(o.one_thread[i].content == o.two_threads[i].content)
        << o.one_thread[i].name << " differs between 1 and 2 threads";
  }
}

// A radar detection's range is its peak cell's, interpolated: a tone reaches the cells of its
// window's main lobe, so a peak dominated by fog, ghosts or the room lies within the main lobe's
// half width (plus one cell for the interpolation) of one of its tones; fog scatterers lie only in
// active layers, ghosts at the half round trips of the room's paths, room echoes at the back wall
// and the objects. A lidar echo's range is its leading edge, which precedes
// the surface or layer that makes it by at most the pulse's rise, less than its full length c tau
// (two FWHM range lengths), plus a sample.
TEST_P(ScenarioProperty, DetectionOriginsMatchTheChamberAtTheirStep) {
  const Outcome& o = ran();
  SCOPED_TRACE(describe(o.drawn));
  ++examined().seeds;
  examined().rooms += o.drawn.room.drawn() ? 1 : 0;
  examined().refused += o.refused.empty() ? 0 : 1;
  if (!o.refused.empty()) return;
  const DrawnScenario& d = o.drawn;
  // Every radar scenario, whatever its ADC, phase noise and window: sidelobe, clipping and noise
  // detections are not checked against the geometry (they lie anywhere by nature).
  if (const std::string* csv = o.file("radar_detections.csv")) {
    const double tol_m = (d.window_mainlobe_half_width_bins + 1.0) * d.range_bin_m;
    double nearest_direct_m = INFINITY, farthest_direct_m = 0.0;
    std::vector<RoomPath> paths;
    for (const Point3& c : d.target_centres) {
      nearest_direct_m = std::min(nearest_direct_m, direct_range_m(d, c));
      farthest_direct_m = std::max(farthest_direct_m, direct_range_m(d, c));
      for (const RoomPath& p : room_paths(d, c)) paths.push_back(p);
    }
    double longest_path_m = 0.0, largest_fold_m = 0.0;
    for (const RoomPath& p : paths) {
      longest_path_m = std::max(longest_path_m, p.range_m);
      largest_fold_m = std::max(largest_fold_m, p.fold_m);
    }
    // The room's own echoes: a cylinder's from its lit line at mid-height (its surface's normal
    // points at the radar there: the specular point of a convex body), a plate's from its centre
    // (the middle of its physical-optics integral, symmetric about it); the back wall's from its
    // foot of the perpendicular, at its distance.
    std::vector<double> room_echoes_m;
    if (d.room.back_wall_m > 0.0) room_echoes_m.push_back(d.room.back_wall_m);
    for (const RoomGeometry::Object& ob : d.room.objects) {
      const double dz = ob.base_height_m + 0.5 * ob.height_m - d.radar_height_m;
      const double across_m = std::hypot(ob.x_m, ob.y_m) - (ob.cylinder ? ob.radius_m : 0.0);
      room_echoes_m.push_back(std::hypot(across_m, dz));
    }
    for (const auto& row : read_csv(*csv)) {
      ++examined().radar[row.at("origin")];
      const auto k = static_cast<std::size_t>(std::stoul(row.at("active_layers")));
      const double range_m = std::stod(row.at("range_m"));
      const std::string& origin = row.at("origin");
      const std::string where = "radar detection at step " + row.at("active_layers") + ", item " +
                                row.at("item") + ", range " + row.at("range_m") + " m, origin " +
                                origin;
      if (origin == "fog") {
        bool inside = false;
        for (const LayerGeometry& l : active_layers(d, k)) {
          inside = inside || (range_m >= l.start_m - tol_m && range_m <= l.end_m + tol_m);
        }
        EXPECT_TRUE(inside) << where << ": outside every layer active at that step (+-" << tol_m
                            << " m)";
        // Its layer: one active at the step, and holding the detection's range.
        const int layer_code = std::stoi(row.at("layer"));
        ASSERT_GE(layer_code, 0) << where << ": a fog detection without its layer";
        const auto layer = static_cast<std::size_t>(layer_code);
        bool active = false;
        for (std::size_t j = 0; j < k && j < d.switching.size(); ++j)
          active = active || d.switching[j] == layer;
        EXPECT_TRUE(active) << where << ": layer " << layer << " is not active at that step";
        if (active) {
          const LayerGeometry& l = d.layers[layer];
          EXPECT_TRUE(range_m >= l.start_m - tol_m && range_m <= l.end_m + tol_m)
              << where << ": outside its layer " << layer << " [" << l.start_m << ", " << l.end_m
              << "] m (+-" << tol_m << " m)";
        }
      } else {
        EXPECT_EQ(row.at("layer"), "-1") << where << ": a layer on a detection not of fog";
      }
      if (origin == "target") {
        // Its direct paths, and the paths via the room it cannot resolve from them (scene.hpp: a
        // half length within the range resolution of the direct path's).
        EXPECT_GE(range_m, nearest_direct_m - tol_m)
            << where << ": before the target's nearest centre at " << nearest_direct_m << " m";
        EXPECT_LE(range_m, farthest_direct_m + d.range_resolution_m + tol_m)
            << where << ": behind the target's farthest centre at " << farthest_direct_m
            << " m and its unresolved room paths";
      } else if (origin == "multipath") {
        ASSERT_FALSE(paths.empty()) << where << ": a ghost in a room without planes";
        EXPECT_GE(range_m, nearest_direct_m - tol_m)
            << where << ": before the target's nearest direct path, " << nearest_direct_m << " m";
        EXPECT_LE(range_m, longest_path_m + largest_fold_m + tol_m)
            << where << ": behind the longest second-order path, " << longest_path_m << " m";
        double miss_m = INFINITY;
        for (const RoomPath& p : paths)
          miss_m = std::min(miss_m, std::abs(range_m - p.range_m) - p.fold_m);
        EXPECT_LE(miss_m, tol_m) << where << ": at no path's range (the nearest " << miss_m
                                 << " m beyond its fold, +-" << tol_m << " m)";
      } else if (origin == "room") {
        ASSERT_FALSE(room_echoes_m.empty()) << where << ": a room echo without back wall or object";
        double miss_m = INFINITY;
        for (const double e : room_echoes_m) miss_m = std::min(miss_m, std::abs(range_m - e));
        EXPECT_LE(miss_m, tol_m) << where << ": at no object's or back wall's range (nearest "
                                 << miss_m << " m off, +-" << tol_m << " m)";
      }
    }
  }
  // Every lidar echo is checked, merged ones included. The range checked is the one the echo
  // reports, range_m (its leading edge, the range a user reads in lidar_echoes.csv), not its
  // attributed_range_m (where the origin is taken; the raw echoes carry it, and
  // tests/python/raw_h5_check.py checks it against the ground truth): the origin and layer are
  // attributed at the peak of the return whose leading edge made the echo (lidar/waveform.hpp,
  // attribution_sample), so the reported range must lie on that return, before its surface or
  // layer by at most the pulse's rise. That is the stronger claim: an attribution at any later
  // sample of the echo (its strongest, say) would pass at the attributed range and fail here.
  if (const std::string* csv = o.file("lidar_echoes.csv")) {
    const double tol_m =
        speed_of_light_m_per_s * (d.lidar_pulse_width_s + 0.5 * d.lidar_sample_interval_s);
    // The static scene in the scan plane: the background segments, the walls (lines), the
    // objects whose height range holds the scan height (a cylinder's circle, a plate's segment).
    std::vector<DrawnScenario::Segment> segments = d.lidar_background;
    struct Circle {
      double x_m, y_m, radius_m;
    };
    std::vector<Circle> circles;
    for (const RoomGeometry::Object& ob : d.room.objects) {
      if (d.lidar_height_m < ob.base_height_m || d.lidar_height_m > ob.base_height_m + ob.height_m)
        continue;
      if (ob.cylinder) {
        circles.push_back({ob.x_m, ob.y_m, ob.radius_m});
      } else {
        segments.push_back(plate_segment(ob));
      }
    }
    const auto off_static_scene_m = [&](double x, double y) {
      double nearest_m = INFINITY;
      for (const auto& s : segments) nearest_m = std::min(nearest_m, distance_to_segment(x, y, s));
      for (const Circle& c : circles)
        nearest_m = std::min(nearest_m, std::abs(std::hypot(x - c.x_m, y - c.y_m) - c.radius_m));
      if (d.room.left_wall_m > 0.0)
        nearest_m = std::min(nearest_m, std::abs(y + d.room.left_wall_m));
      if (d.room.right_wall_m > 0.0)
        nearest_m = std::min(nearest_m, std::abs(y - d.room.right_wall_m));
      if (d.room.back_wall_m > 0.0)
        nearest_m = std::min(nearest_m, std::abs(x - d.room.back_wall_m));
      return nearest_m;
    };
    for (const auto& row : read_csv(*csv)) {
      ++examined().lidar[row.at("origin")];
      const auto k = static_cast<std::size_t>(std::stoul(row.at("active_layers")));
      const double range_m = std::stod(row.at("range_m"));
      const double angle = std::stod(row.at("angle_deg")) * pi / 180.0;
      const double x = range_m * std::cos(angle);
      const double y = range_m * std::sin(angle);
      const std::string& origin = row.at("origin");
      const int layer = std::stoi(row.at("layer"));
      const std::string where = "lidar echo at step " + row.at("active_layers") + ", scan " +
                                row.at("item") + ", angle " + row.at("angle_deg") + " deg, range " +
                                row.at("range_m") + " m, origin " + origin + ", layer " +
                                row.at("layer");
      if (origin == "fog") {
        bool inside = false;
        for (const LayerGeometry& l : active_layers(d, k)) {
          inside = inside || (x >= l.start_m - tol_m && x <= l.end_m + tol_m);
        }
        EXPECT_TRUE(inside) << where << ": outside every layer active at that step (+-" << tol_m
                            << " m)";
        EXPECT_LE(std::abs(y), 0.5 * d.lidar_fog_width_m + tol_m)
            << where << ": beside the fog bank";
        // Its layer: one of the chamber's, switched on by this step, and holding the echo.
        ASSERT_GE(layer, 0) << where << ": a fog echo without its layer";
        ASSERT_LT(static_cast<std::size_t>(layer), d.layers.size()) << where << ": no such layer";
        bool active = false;
        for (std::size_t j = 0; j < k && j < d.switching.size(); ++j)
          active = active || d.switching[j] == static_cast<std::size_t>(layer);
        EXPECT_TRUE(active) << where << ": its layer is not active at that step";
        const LayerGeometry& l = d.layers[static_cast<std::size_t>(layer)];
        EXPECT_TRUE(x >= l.start_m - tol_m && x <= l.end_m + tol_m)
            << where << ": outside its layer [" << l.start_m << ", " << l.end_m << "] m (+-"
            << tol_m << " m)";
      } else {
        EXPECT_EQ(layer, -1) << where << ": a layer for an echo that is not fog";
      }
      if (origin == "target") {
        EXPECT_NEAR(x, d.target_range_m, tol_m) << where << ": not at the target's range";
        EXPECT_LE(std::abs(y - d.lidar_target_offset_m), 0.5 * d.lidar_target_width_m + tol_m)
            << where << ": beside the target";
      } else if (origin == "background") {
        EXPECT_LE(off_static_scene_m(x, y), tol_m)
            << where << ": on no background segment, wall or object in the scan plane";
      }
    }
  }
}

// Each layer's extinction is >= 0, so whatever the order and the fogs, a step with one layer more
// has at least the fog loss of the step before: the radar's two-way attenuation does not fall, the
// lidar's eq. 4 intensity (the clear echo times tau^2 of each active layer) and the camera's
// transmittance do not rise.
TEST_P(ScenarioProperty, AttenuationNeverDecreasesWithActiveLayers) {
  const Outcome& o = ran();
  SCOPED_TRACE(describe(o.drawn));
  if (!o.refused.empty()) return;
  const std::string* text = o.file("summary.json");
  ASSERT_NE(text, nullptr);
  const nlohmann::json summary = nlohmann::json::parse(*text);
  struct Loss {
    const char* sensor;
    const char* field;
    int sign;  // +1: a loss (must not fall); -1: a transmitted share (must not rise)
  };
  for (const Loss& loss :
       {Loss{"radar", "two_way_attenuation_db", +1}, Loss{"lidar", "eq4_intensity", -1},
        Loss{"camera", "transmittance", -1}}) {
    if (!summary["sensors"].contains(loss.sensor)) continue;
    const nlohmann::json& steps = summary["sensors"][loss.sensor]["summary"]["steps"];
    ASSERT_EQ(steps.size(), o.drawn.max_active_layers + 1) << loss.sensor << " steps";
    for (std::size_t k = 0; k < steps.size(); ++k) {
      EXPECT_EQ(steps[k]["active_layers"].get<std::size_t>(), k) << loss.sensor;
      if (k == 0) continue;
      const double before = steps[k - 1][loss.field].get<double>();
      const double now = steps[k][loss.field].get<double>();
      if (loss.sign > 0) {
        EXPECT_GE(now, before) << loss.sensor << " " << loss.field << " falls from step " << k - 1
                               << " to " << k;
      } else {
        EXPECT_LE(now, before) << loss.sensor << " " << loss.field << " rises from step " << k - 1
                               << " to " << k;
      }
    }
  }
}

TEST_P(ScenarioProperty, WrittenScenarioReadsBackToTheSameBytes) {
  const Outcome& o = ran();
  SCOPED_TRACE(describe(o.drawn));
  if (!o.refused.empty()) return;
  const std::string* written = o.file("scenario.toml");
  ASSERT_NE(written, nullptr);
  const Scenario again = experiment::parse_scenario(*written, "scenario.toml");
  EXPECT_EQ(experiment::to_toml(again), *written);
  const Files rerun = run_files(again, 1);
  ASSERT_EQ(rerun.size(), o.one_thread.size());
  for (std::size_t i = 0; i < rerun.size(); ++i) {
    EXPECT_EQ(rerun[i].name, o.one_thread[i].name);
    EXPECT_TRUE(rerun[i].content == o.one_thread[i].content)
        << rerun[i].name << " differs when run from the written scenario.toml";
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, ScenarioProperty,
                         ::testing::Range(seed_range().first, seed_range().last + 1));

}  // namespace
}  // namespace fogradar::property
