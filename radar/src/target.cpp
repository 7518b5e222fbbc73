#include "fogradar/radar/target.hpp"

#include "fogradar/core/error.hpp"

namespace fogradar::radar {

KeyTable<TargetSpec> target_keys() {
  KeyTable<TargetSpec> keys("radar.target.");
  // The EVT's five centres have heights of their own and a steady RCS: these keys would do nothing.
  const auto is_point = [](const TargetSpec& t) { return t.model == TargetModel::point; };
  const std::string point_only =
      "with radar.target.model = \"point\" (the EVT's five centres have heights of their own and "
      "a steady RCS)";
  keys.choice("model", FOGRADAR_KEY_FIELD(model), target_model_names,
              "EVT rear as five scattering centres, or one point");
  keys.number("rcs_dbsm", FOGRADAR_KEY_FIELD(rcs_dbsm), closed(-60.0, 60.0),
              "mean RCS (sum over the EVT's centres)");
  // Any integer reaches the parser, which names the allowed set (0, 1, 3).
  keys.integer(
          "swerling", [](const TargetSpec& t) { return static_cast<std::int64_t>(t.swerling); },
          [](TargetSpec& t, std::int64_t v) {
            t.swerling = swerling_names.parse(std::to_string(v), "radar.target.swerling");
          },
          "integer 0, 1, 3", "point target fluctuation from measurement to measurement")
      .when(is_point, point_only);
  keys.number("height_m", FOGRADAR_KEY_FIELD(height_m), closed(0.0, 100.0),
              "point target height above the floor")
      .when(is_point, point_only);
  return keys;
}

Scene make_scene(const TargetSpec& target, const sensor::TargetWorld& world,
                 const propagation::RoomSpec& room, unsigned clutter_scatterers_per_bin) {
  Scene scene = target.model == TargetModel::evt ? evt_rear_scene(target.rcs_dbsm)
                                                 : point_target_scene(target.rcs_dbsm);
  if (target.model == TargetModel::point) {
    scene.centres.front().height_m = target.height_m;
    scene.centres.front().swerling = target.swerling;
  }
  scene.sensor_height_m = target.sensor_height_m;
  scene.floor.enabled = room.floor.present;
  FOGRADAR_CHECK(std::holds_alternative<propagation::ReflectionCoefficient>(room.floor.reflection));
  scene.floor.reflection_coefficient =
      std::get<propagation::ReflectionCoefficient>(room.floor.reflection).value;
  scene.micro_motion_std_m = world.micro_motion_std_m;
  for (ScatteringCentre& centre : scene.centres) {
    centre.radial_velocity_m_per_s = world.radial_velocity_m_per_s;
  }
  scene.clutter_scatterers_per_bin = clutter_scatterers_per_bin;
  return scene;
}

}  // namespace fogradar::radar
