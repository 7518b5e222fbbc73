// A scenario: everything one run of the study's methodology needs, as read from a TOML file with
// the sections [radar], [processing], [target], [chamber], [fog], [experiment] and one section per
// further sensor (docs/scenario.md). Keys carry their units in their names; docs/scenario.md lists
// them with defaults and ranges. The paper scenario (examples/paper.toml) is compiled in and is the
// base every scenario file overrides.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/camera/params.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/lidar/params.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/scene.hpp"

namespace fogradar::experiment {

enum class TargetModel { evt, point };

struct TargetSpec {
  TargetModel model = TargetModel::evt;
  double rcs_dbsm = 10.0;
  radar::Swerling swerling = radar::Swerling::zero;  // point target only
  double height_m = 0.5;                             // point target only
  double sensor_height_m = 0.5;
  bool floor_multipath = true;
  double floor_reflection_coefficient = -0.7;
  double micro_motion_std_m = 0.2e-3;
};

// The chamber as the scenario file gives it: n identical layers, all with the scenario's fog.
struct ChamberLayout {
  double sensor_gap_m = 2.0;
  std::size_t layer_count = 4;
  double layer_length_m = 1.0;
  double target_gap_m = 4.0;
};

// The sensors a scenario can run, by their scenario names ("radar", "lidar", "camera"), in the
// order their results are reported.
inline constexpr SensorId all_sensors[] = {SensorId::radar, SensorId::lidar, SensorId::camera};
std::string_view sensor_name(SensorId sensor);

struct ExperimentSpec {
  // Which sensors run (experiment.sensors): non-empty, no repeats; each sees the same chamber.
  std::vector<SensorId> sensors = {SensorId::radar};
  std::size_t measurements_per_step = 200;
  std::size_t max_active_layers = 4;  // steps k = 0 .. max_active_layers
  std::uint64_t seed = 1;
};

struct Scenario {
  radar::RadarParams radar;
  TargetSpec target;
  ChamberLayout chamber;
  propagation::FogSpec fog;
  unsigned clutter_scatterers_per_bin = 4;
  ExperimentSpec experiment;
  lidar::LidarParams lidar;     // [lidar], keys = field names (docs/lidar.md)
  camera::CameraParams camera;  // [camera], keys = field names (docs/camera.md)

  // Throws InvalidParameter naming the scenario key (e.g. "processing.cfar.training_cells").
  void validate() const;
  bool runs(SensorId sensor) const;
  propagation::ChamberSpec chamber_spec() const;
  radar::Scene scene() const;
};

// The compiled-in paper scenario file (examples/paper.toml), verbatim.
std::string_view paper_scenario_toml();
Scenario paper_scenario();

// Reads a scenario file's text over the paper scenario. Malformed TOML, unknown keys or sections,
// wrong types and out-of-range values throw InvalidParameter whose message starts with
// "<source_name>:<line>: " and names the key; its field() is the key ("radar.tx_power_dbm").
Scenario parse_scenario(std::string_view toml_text, std::string_view source_name);

// Largest scenario file read: a scenario is a few kB; anything larger is refused before it is read.
inline constexpr std::size_t max_scenario_file_bytes = std::size_t{1} << 20;

// Reads a scenario file. A path that cannot be opened, that is not a regular file (a directory, a
// FIFO, a device) or that holds more than max_scenario_file_bytes throws InvalidParameter naming
// "--scenario"; nothing is read from it then, and a FIFO is never waited on.
Scenario load_scenario_file(const std::string& path);

// The fully resolved scenario as TOML (every key), so that a run can be repeated exactly:
// parse_scenario(to_toml(s)) == s.
std::string to_toml(const Scenario& scenario);

}  // namespace fogradar::experiment
