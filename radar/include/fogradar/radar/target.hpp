// The radar's target: its own view of it (section [radar.target], docs/scenario.md: the EVT rear or
// one point, its RCS and fluctuation), the world's target it sits in (the floor, micro-motion,
// velocity and water film of [target], sensor::TargetWorld), and the scene the radar looks at made
// from them.
#pragma once

#include <string>
#include <string_view>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/keys.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/sensor/sensor.hpp"

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
  double sensor_height_m = 0.5;        // the radar's mounting height (radar.height_m)
};

// The keys of [radar.target]: the radar's view of the target (model, RCS, fluctuation).
KeyTable<TargetSpec> target_keys();

// The scene of `target`: the EVT rear (evt_rear_scene) or one point (point_target_scene) at its
// height with its fluctuation, in `world` (its micro-motion and velocity) and `room` (its present
// surfaces and objects, a material's permittivity taken at the radar's carrier `frequency_hz`: a
// material without radio data there is refused naming its key), and the fog clutter's scatterers
// per range bin.
Scene make_scene(const TargetSpec& target, const sensor::TargetWorld& world,
                 const propagation::RoomSpec& room, unsigned clutter_scatterers_per_bin,
                 double frequency_hz);

}  // namespace fogradar::radar
