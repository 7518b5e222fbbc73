// The radar's target as a scenario gives it (section [target], docs/scenario.md): the EVT rear or
// one point, its RCS and fluctuation, the floor multipath and micro-motion, and the scene the
// radar looks at made from it.
#pragma once

#include <string>
#include <string_view>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/keys.hpp"
#include "fogradar/radar/scene.hpp"

namespace fogradar::radar {

enum class TargetModel { evt, point };
inline constexpr auto target_model_names =
    enum_names<TargetModel>({{TargetModel::evt, "evt"}, {TargetModel::point, "point"}});
constexpr std::string_view to_string(TargetModel model) noexcept {
  return target_model_names.name(model);
}

struct TargetSpec {
  TargetModel model = TargetModel::evt;
  double rcs_dbsm = 10.0;
  Swerling swerling = Swerling::zero;  // point target only
  double height_m = 0.5;               // point target only
  double sensor_height_m = 0.5;
  bool floor_multipath = true;
  double floor_reflection_coefficient = -0.7;
  double micro_motion_std_m = 0.2e-3;
  // The whole target's radial velocity (+ receding): every centre's, every path's Doppler. Each
  // measurement starts with the target at the chamber's target range (a frame of 3.3 ms moves it
  // 6.6 cm at 20 m/s, under the 15 cm range resolution, which the synthesis does not model).
  double radial_velocity_m_per_s = 0.0;
  // A water film on the target's metal surfaces (the study's water-covered target), with the water
  // model and temperature of the fog nearest the target: every centre's RCS times the reflectance
  // of the film on a perfect conductor (propagation::conductor_film_loss_db).
  double water_film_m = 0.0;
};

// The keys of [target].
KeyTable<TargetSpec> target_keys();

// The scene of `target`: the EVT rear (evt_rear_scene) or one point (point_target_scene) at its
// height with its fluctuation, the floor and the micro-motion as given, and the fog clutter's
// scatterers per range bin.
Scene make_scene(const TargetSpec& target, unsigned clutter_scatterers_per_bin);

}  // namespace fogradar::radar
