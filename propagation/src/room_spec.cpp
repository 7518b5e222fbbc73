// The room a chamber stands in, and its keys (room_spec.hpp).
#include "fogradar/propagation/room_spec.hpp"

#include <string>

#include "fogradar/core/error.hpp"

namespace fogradar::propagation {
namespace {

// One surface's keys: its name, its plane, the name of its distance key and the distance `true`
// alone gives it.
struct SurfaceKey {
  std::string name;
  Surface surface;
  std::string distance_name;  // "distance_m", the ceiling's "height_m"; empty for the floor
  double default_distance_m;
  std::string distance_meaning;
};

// The room's spec of `surface`, const or not as the room is.
template <class Room>
auto& surface_in(Room& room, Surface surface) {
  switch (surface) {
    case Surface::floor:
      return room.floor;
    case Surface::left_wall:
      return room.left_wall;
    case Surface::right_wall:
      return room.right_wall;
    case Surface::ceiling:
      return room.ceiling;
    case Surface::back_wall:
      return room.back_wall;
  }
  return room.floor;
}

SurfaceSpec& surface_of(RoomSpec& room, Surface surface) { return surface_in(room, surface); }

void add_surface_keys(KeyTable<RoomSpec>& keys, const SurfaceKey& s) {
  const std::string full = keys.prefix() + s.name;
  const Surface surface = s.surface;
  const double default_distance_m = s.default_distance_m;
  keys.boolean(
          s.name, [surface](const RoomSpec& r) { return surface_spec(r, surface).present; },
          [surface, default_distance_m](RoomSpec& r, bool present) {
            SurfaceSpec& spec = surface_of(r, surface);
            if (present && !spec.present && spec.distance_m == 0.0) {
              spec.distance_m = default_distance_m;
            }
            spec.present = present;
          },
          s.distance_name.empty()
              ? "`false`: no floor; a table [" + full + "]: the floor at z = 0 with its keys"
              : "`false`: none; a table [" + full + "]: present, with its keys (`true` alone: at " +
                    std::to_string(static_cast<int>(default_distance_m)) + " m, of concrete)")
      .documented_as("`false`, or a table");
  const auto present = [surface](const RoomSpec& r) { return surface_spec(r, surface).present; };
  const std::string when_present = "with " + full + " present";
  const auto holds_material = [surface](const RoomSpec& r) {
    const SurfaceSpec& spec = surface_spec(r, surface);
    return spec.present && std::holds_alternative<Material>(spec.reflection);
  };
  const auto holds_coefficient = [surface](const RoomSpec& r) {
    const SurfaceSpec& spec = surface_spec(r, surface);
    return spec.present && std::holds_alternative<ReflectionCoefficient>(spec.reflection);
  };
  const std::string one_reflection = when_present + " and not its other reflection (" + full +
                                     ".material or " + full + ".reflection_coefficient) given";
  keys.choice(
          s.name + ".material",
          // Read only where the surface holds a material, but safe anywhere (the key tests read
          // every key): the empty name otherwise.
          [surface](const RoomSpec& r) {
            const auto* material = std::get_if<Material>(&surface_spec(r, surface).reflection);
            return material != nullptr ? std::string(to_string(*material)) : std::string();
          },
          [surface, key = full + ".material"](RoomSpec& r, std::string_view text) {
            surface_of(r, surface).reflection = material_names.parse(text, key);
          },
          material_names.names(),
          "the surface's material: for the radar its Fresnel coefficients at each ray's grazing "
          "angle and the radar's polarisation (ITU-R P.2040-3), for the lidar its diffuse "
          "reflectance at the lidar's wavelength (USGS splib07a)")
      .when(holds_material, one_reflection)
      .in_group(s.name + " reflection");
  keys.number(
          s.name + ".reflection_coefficient",
          [surface](const RoomSpec& r) {
            return std::get<ReflectionCoefficient>(surface_spec(r, surface).reflection).value;
          },
          [surface](RoomSpec& r, double v) {
            surface_of(r, surface).reflection = ReflectionCoefficient{v};
          },
          closed(-1.0, 1.0), "or: a real amplitude reflection coefficient, every angle and band")
      .when(holds_coefficient, one_reflection)
      .in_group(s.name + " reflection");
  if (s.distance_name.empty()) return;
  keys.number(
          s.name + "." + s.distance_name,
          [surface](const RoomSpec& r) { return surface_spec(r, surface).distance_m; },
          [surface](RoomSpec& r, double v) { surface_of(r, surface).distance_m = v; },
          open_closed(0.0, max_room_extent_m), s.distance_meaning)
      .when(present, when_present);
}

}  // namespace

bool RoomSpec::empty() const {
  return !floor.present && !left_wall.present && !right_wall.present && !ceiling.present &&
         !back_wall.present && objects.empty();
}

const SurfaceSpec& surface_spec(const RoomSpec& room, Surface surface) {
  return surface_in(room, surface);
}

std::vector<RoomPlane> room_planes(const RoomSpec& room) {
  std::vector<RoomPlane> planes;
  if (room.floor.present) planes.push_back({Surface::floor, 0.0});
  if (room.left_wall.present) planes.push_back({Surface::left_wall, -room.left_wall.distance_m});
  if (room.right_wall.present) planes.push_back({Surface::right_wall, room.right_wall.distance_m});
  if (room.ceiling.present) planes.push_back({Surface::ceiling, room.ceiling.distance_m});
  if (room.back_wall.present) planes.push_back({Surface::back_wall, room.back_wall.distance_m});
  return planes;
}

KeyTable<RoomSpec> room_keys(std::string prefix) {
  KeyTable<RoomSpec> keys(std::move(prefix));
  add_surface_keys(keys, {"floor", Surface::floor, "", 0.0, ""});
  add_surface_keys(keys, {"left_wall", Surface::left_wall, "distance_m", 3.0,
                          "the wall's lateral distance from the sensor's boresight line, left"});
  add_surface_keys(keys, {"right_wall", Surface::right_wall, "distance_m", 3.0,
                          "the wall's lateral distance from the sensor's boresight line, right"});
  add_surface_keys(
      keys, {"ceiling", Surface::ceiling, "height_m", 5.0, "the ceiling's height above the floor"});
  add_surface_keys(keys, {"back_wall", Surface::back_wall, "distance_m", 30.0,
                          "the wall's distance from the sensor along the boresight, behind the "
                          "target"});
  return keys;
}

KeyTable<RoomObject> room_object_keys(std::string prefix) {
  KeyTable<RoomObject> keys(std::move(prefix));
  const auto is = [](ObjectShape shape) {
    return [shape](const RoomObject& o) { return o.shape == shape; };
  };
  keys.choice("shape", FOGRADAR_KEY_FIELD(shape), object_shape_names,
              "a vertical cylinder (a rain barrel) or a vertical flat plate");
  keys.number("x_m", FOGRADAR_KEY_FIELD(x_m), closed(-max_room_extent_m, max_room_extent_m),
              "its centre along the sensor's boresight");
  keys.number("y_m", FOGRADAR_KEY_FIELD(y_m), closed(-max_room_extent_m, max_room_extent_m),
              "its centre across the boresight, + right");
  keys.number("base_height_m", FOGRADAR_KEY_FIELD(base_height_m), closed(0.0, max_room_extent_m),
              "its bottom above the floor");
  keys.number("height_m", FOGRADAR_KEY_FIELD(height_m), open_closed(0.0, max_room_extent_m),
              "its vertical extent (a cylinder's length)");
  keys.number("radius_m", FOGRADAR_KEY_FIELD(radius_m), open_closed(0.0, max_room_extent_m),
              "the cylinder's radius")
      .when(is(ObjectShape::cylinder), "with shape = \"cylinder\"");
  keys.number("width_m", FOGRADAR_KEY_FIELD(width_m), open_closed(0.0, max_room_extent_m),
              "the plate's horizontal width")
      .when(is(ObjectShape::plate), "with shape = \"plate\"");
  keys.number("yaw_deg", FOGRADAR_KEY_FIELD(yaw_deg), closed(-90.0, 90.0),
              "the plate's turn about the vertical from facing the sensor, + toward +y")
      .when(is(ObjectShape::plate), "with shape = \"plate\"");
  keys.choice("material", FOGRADAR_KEY_FIELD(material), material_names,
              "its material (the rain barrels': `plastic`, white HDPE): for the radar its "
              "normal-incidence reflectance, for the lidar its diffuse reflectance");
  return keys;
}

}  // namespace fogradar::propagation
