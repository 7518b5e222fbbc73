#include "fogradar/radar/target.hpp"

#include <complex>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/propagation/materials.hpp"

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

namespace {

std::string surface_key(propagation::Surface surface) {
  switch (surface) {
    case propagation::Surface::floor:
      return "chamber.room.floor";
    case propagation::Surface::left_wall:
      return "chamber.room.left_wall";
    case propagation::Surface::right_wall:
      return "chamber.room.right_wall";
    case propagation::Surface::ceiling:
      return "chamber.room.ceiling";
    case propagation::Surface::back_wall:
      return "chamber.room.back_wall";
  }
  return "chamber.room";
}

// The material's permittivity at the radar's carrier; a material without radio data there is
// refused naming the key that chose it.
std::complex<double> permittivity_at(propagation::Material material, double frequency_hz,
                                     const std::string& material_key) {
  const propagation::FrequencyRangeGhz range = propagation::radio_frequency_range(material);
  const double ghz = frequency_hz / 1e9;
  if (!(ghz >= range.min_ghz && ghz <= range.max_ghz)) {
    throw_invalid(material_key, propagation::to_string(material),
                  "a material with radio data at radar.centre_frequency_hz = " +
                      message_number(frequency_hz) + " Hz; '" +
                      std::string(propagation::to_string(material)) + "' holds for [" +
                      message_number(range.min_ghz * 1e9) + ", " +
                      message_number(range.max_ghz * 1e9) + "] Hz (" +
                      std::string(propagation::radio_permittivity_source(material)) + ")");
  }
  return propagation::radio_permittivity(material, frequency_hz, "radar.centre_frequency_hz");
}

}  // namespace

Scene make_scene(const TargetSpec& target, const sensor::TargetWorld& world,
                 const propagation::RoomSpec& room, unsigned clutter_scatterers_per_bin,
                 double frequency_hz) {
  Scene scene = target.model == TargetModel::evt ? evt_rear_scene(target.rcs_dbsm)
                                                 : point_target_scene(target.rcs_dbsm);
  if (target.model == TargetModel::point) {
    scene.centres.front().height_m = target.height_m;
    scene.centres.front().swerling = target.swerling;
  }
  scene.sensor_height_m = target.sensor_height_m;
  const std::vector<propagation::RoomPlane> planes = propagation::room_planes(room);
  for (const propagation::RoomPlane& plane : planes) {
    const propagation::SurfaceSpec& spec = propagation::surface_spec(room, plane.surface);
    SceneSurface surface{.plane = plane,
                         .reflection_coefficient = 0.0,
                         .permittivity = std::nullopt,
                         .key = surface_key(plane.surface)};
    if (const auto* material = std::get_if<propagation::Material>(&spec.reflection)) {
      surface.permittivity = permittivity_at(*material, frequency_hz, surface.key + ".material");
    } else {
      surface.reflection_coefficient =
          std::get<propagation::ReflectionCoefficient>(spec.reflection).value;
    }
    scene.surfaces.push_back(std::move(surface));
  }
  for (std::size_t i = 0; i < room.objects.size(); ++i) {
    const propagation::RoomObject& object = room.objects[i];
    const std::string key = "chamber.objects[" + std::to_string(i) + "]";
    // The material's normal-incidence power reflectance |r|^2, r = (1 - sqrt(eps)) / (1 +
    // sqrt(eps)) (fresnel_reflection at grazing pi / 2).
    const std::complex<double> r =
        propagation::fresnel_reflection(
            permittivity_at(object.material, frequency_hz, key + ".material"), 0.5 * pi)
            .te;
    scene.objects.push_back({.object = object, .reflectance = std::norm(r), .key = key});
  }
  scene.micro_motion_std_m = world.micro_motion_std_m;
  for (ScatteringCentre& centre : scene.centres) {
    centre.radial_velocity_m_per_s = world.radial_velocity_m_per_s;
  }
  scene.clutter_scatterers_per_bin = clutter_scatterers_per_bin;
  return scene;
}

}  // namespace fogradar::radar
