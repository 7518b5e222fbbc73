// The room a chamber stands in ([chamber.room] and [[chamber.objects]]), as every sensor sees it:
// the floor, two side walls, a ceiling and a back wall, each present or not, each reflecting with
// a material's Fresnel coefficients or a real amplitude coefficient; and static objects standing in
// the hall (cylinders such as the study's rain barrels, flat plates). Frame as room.hpp's: origin
// on the floor below the sensor, x along its boresight, y to the right, z up, metres.
#pragma once

#include <string_view>
#include <variant>
#include <vector>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/keys.hpp"
#include "fogradar/propagation/materials.hpp"
#include "fogradar/propagation/room.hpp"

namespace fogradar::propagation {

// A real amplitude reflection coefficient in [-1, 1], the same at every angle and polarisation.
struct ReflectionCoefficient {
  double value = -0.7;
};

// How a surface reflects: with a real coefficient, or with the Fresnel coefficients of a material
// (materials.hpp) at each ray's grazing angle, in the sensor's band and polarisation.
using SurfaceReflection = std::variant<ReflectionCoefficient, Material>;

struct SurfaceSpec {
  bool present = false;
  SurfaceReflection reflection = ReflectionCoefficient{};
  // Side walls: the lateral distance from the sensor's boresight line (left at y = -distance_m,
  // right at y = +distance_m). Back wall: the distance from the sensor along the boresight.
  // Ceiling: the height above the floor. The floor lies at z = 0 and reads none.
  double distance_m = 0.0;
};

enum class ObjectShape { cylinder, plate };
inline constexpr auto object_shape_names =
    enum_names<ObjectShape>({{ObjectShape::cylinder, "cylinder"}, {ObjectShape::plate, "plate"}});
constexpr std::string_view to_string(ObjectShape shape) noexcept {
  return object_shape_names.name(shape);
}

// A static object standing on the floor. A cylinder is vertical, its axis at (x_m, y_m). A plate
// is vertical, its centre line at (x_m, y_m), facing the sensor (normal along -x) when yaw_deg = 0,
// turned about the vertical by yaw_deg (+ toward +y).
struct RoomObject {
  ObjectShape shape = ObjectShape::cylinder;
  double x_m = 3.0;            // along the boresight from the sensor
  double y_m = -2.0;           // lateral, + right
  double base_height_m = 0.0;  // its bottom above the floor
  double height_m = 0.9;       // its vertical extent (a cylinder's length)
  double radius_m = 0.3;       // cylinder
  double width_m = 1.0;        // plate
  double yaw_deg = 0.0;        // plate
  Material material = Material::plastic;
};

inline constexpr std::size_t max_room_objects = 64;
inline constexpr double max_room_extent_m = 1000.0;

// The room of a chamber. The default is the floor alone, reflecting with -0.7 (smooth concrete near
// grazing incidence as a real coefficient), and no walls, ceiling or objects.
struct RoomSpec {
  SurfaceSpec floor{.present = true, .reflection = ReflectionCoefficient{-0.7}, .distance_m = 0.0};
  SurfaceSpec left_wall{.reflection = Material::concrete};
  SurfaceSpec right_wall{.reflection = Material::concrete};
  SurfaceSpec ceiling{.reflection = Material::concrete};
  SurfaceSpec back_wall{.reflection = Material::concrete};
  std::vector<RoomObject> objects;

  bool empty() const;  // no surface and no object
};

// The present surfaces as planes (room.hpp), in the order floor, left wall, right wall, ceiling,
// back wall; `surfaces` receives the spec of each, in the same order.
std::vector<RoomPlane> room_planes(const RoomSpec& room);
const SurfaceSpec& surface_spec(const RoomSpec& room, Surface surface);

// The keys of [chamber.room] under `prefix` ("chamber.room."): per surface a boolean (false: none;
// a table: present), and in its table `material` or `reflection_coefficient` (one of them) and
// `distance_m` or, for the ceiling, `height_m`.
KeyTable<RoomSpec> room_keys(std::string prefix);
// The keys of one [[chamber.objects]] element under `prefix` ("chamber.objects[2].").
KeyTable<RoomObject> room_object_keys(std::string prefix);

}  // namespace fogradar::propagation
