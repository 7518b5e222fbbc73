#include "fogradar/radar/target.hpp"

#include "fogradar/core/error.hpp"

namespace fogradar::radar {

KeyTable<TargetSpec> target_keys() {
  KeyTable<TargetSpec> keys("target.");
  // The EVT's five centres have heights of their own and a steady RCS: these keys would do nothing.
  const auto is_point = [](const TargetSpec& t) { return t.model == TargetModel::point; };
  const std::string point_only =
      "with target.model = \"point\" (the EVT's five centres have heights of their own and a "
      "steady RCS)";
  keys.choice("model", FOGRADAR_KEY_FIELD(model), target_model_names,
              "EVT rear as five scattering centres, or one point");
  keys.number("rcs_dbsm", FOGRADAR_KEY_FIELD(rcs_dbsm), closed(-60.0, 60.0),
              "mean RCS (sum over the EVT's centres)");
  // Any integer reaches the parser, which names the allowed set (0, 1, 3).
  keys.integer(
          "swerling", [](const TargetSpec& t) { return static_cast<std::int64_t>(t.swerling); },
          [](TargetSpec& t, std::int64_t v) {
            t.swerling = swerling_names.parse(std::to_string(v), "target.swerling");
          },
          "integer 0, 1, 3", "point target fluctuation from measurement to measurement")
      .when(is_point, point_only);
  keys.number("height_m", FOGRADAR_KEY_FIELD(height_m), closed(0.0, 100.0),
              "point target height above the floor")
      .when(is_point, point_only);
  keys.number("sensor_height_m", FOGRADAR_KEY_FIELD(sensor_height_m), closed(0.0, 100.0),
              "radar height; boresight is horizontal");
  keys.boolean("floor_multipath", FOGRADAR_KEY_FIELD(floor_multipath), "two-ray floor reflection");
  keys.number("floor_reflection_coefficient", FOGRADAR_KEY_FIELD(floor_reflection_coefficient),
              closed(-1.0, 1.0), "real amplitude reflection coefficient of the floor")
      .when([](const TargetSpec& t) { return t.floor_multipath; },
            "with target.floor_multipath = true");
  keys.number("micro_motion_std_m", FOGRADAR_KEY_FIELD(micro_motion_std_m), closed(0.0, 0.1),
              "rms line-of-sight jitter of each centre per measurement");
  keys.number(
      "radial_velocity_m_per_s", FOGRADAR_KEY_FIELD(radial_velocity_m_per_s), closed(-300.0, 300.0),
      "the whole target's radial velocity, + receding; beyond the radar's unambiguous "
      "velocity λ/(4 T_i) (19.0 m/s for the paper radar) the estimate folds into it and the "
      "run warns");
  keys.number("water_film_m", FOGRADAR_KEY_FIELD(water_film_m), closed(0.0, 0.01),
              "water film on the target's metal surfaces (the study's water-covered target), with "
              "the water model and temperature of the last layer's fog");
  return keys;
}

Scene make_scene(const TargetSpec& target, unsigned clutter_scatterers_per_bin) {
  Scene scene = target.model == TargetModel::evt ? evt_rear_scene(target.rcs_dbsm)
                                                 : point_target_scene(target.rcs_dbsm);
  if (target.model == TargetModel::point) {
    scene.centres.front().height_m = target.height_m;
    scene.centres.front().swerling = target.swerling;
  }
  scene.sensor_height_m = target.sensor_height_m;
  scene.floor.enabled = target.floor_multipath;
  scene.floor.reflection_coefficient = target.floor_reflection_coefficient;
  scene.micro_motion_std_m = target.micro_motion_std_m;
  for (ScatteringCentre& centre : scene.centres) {
    centre.radial_velocity_m_per_s = target.radial_velocity_m_per_s;
  }
  scene.clutter_scatterers_per_bin = clutter_scatterers_per_bin;
  return scene;
}

}  // namespace fogradar::radar
