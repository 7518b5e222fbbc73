#include "fogradar/lidar/shapes.hpp"

#include <cmath>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/propagation/diffuse_reflectance.hpp"

namespace fogradar::lidar {
namespace {

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// The line p0 + lambda d against the beam t u: t = (p0 x d) / (u x d), lambda = (p0 x u) / (u x d);
// `bounded` keeps lambda in [0, 1].
ShapeHit intersect_line(double ux, double uy, double x0, double y0, double dx, double dy,
                        bool bounded) {
  const double denom = cross(ux, uy, dx, dy);
  if (denom == 0.0) return {};
  const double t = cross(x0, y0, dx, dy) / denom;
  const double lambda = cross(x0, y0, ux, uy) / denom;
  if (!(t > 0.0) || (bounded && (lambda < 0.0 || lambda > 1.0))) return {};
  return {.range_m = t, .cos_incidence = std::abs(denom) / std::hypot(dx, dy)};
}

void require_reflectivity(const std::string& field, double reflectivity) {
  require_in_range(field, reflectivity, 0.0, 1.0);
}

void require_distance(const std::string& field, double distance_m) {
  require_finite(field, distance_m);
  require_positive(field, distance_m);
}

void require_heights(const std::string& prefix, double z_min_m, double z_max_m) {
  require_finite(prefix + "z_min_m", z_min_m);
  require_finite(prefix + "z_max_m", z_max_m);
  if (!(z_max_m >= z_min_m)) {
    throw_invalid(prefix + "z_max_m", z_max_m,
                  ">= " + prefix + "z_min_m = " + message_number(z_min_m));
  }
}

// The scenario's keys of the room (experiment/'s scenario keys name them so).
constexpr std::string_view room_prefix = "chamber.room.";
constexpr std::string_view objects_prefix = "chamber.objects[";

// A wall's diffuse reflectance at the lidar's wavelength, from its material; a real amplitude
// coefficient describes a specular reflection only and is refused.
double wall_reflectivity(const propagation::SurfaceSpec& wall, std::string_view name,
                         double wavelength_m) {
  const std::string key = std::string(room_prefix) + std::string(name);
  if (const auto* coefficient = std::get_if<propagation::ReflectionCoefficient>(&wall.reflection)) {
    throw_invalid(key + ".reflection_coefficient", coefficient->value,
                  "replaced by " + key +
                      ".material for the lidar, which needs the wall's diffuse reflectance at its "
                      "wavelength and a real amplitude coefficient gives none (a wall switched on "
                      "with `true` alone takes one): a material with a published diffuse "
                      "reflectance, " +
                      propagation::diffuse_material_names());
  }
  return propagation::diffuse_reflectance(std::get<propagation::Material>(wall.reflection),
                                          wavelength_m, key + ".material", "lidar.wavelength_m");
}

}  // namespace

ShapeHit intersect(const SegmentShape& s, double ux, double uy) {
  return intersect_line(ux, uy, s.x0_m, s.y0_m, s.x1_m - s.x0_m, s.y1_m - s.y0_m, true);
}

ShapeHit intersect(const LineShape& l, double ux, double uy) {
  return intersect_line(ux, uy, l.x_m, l.y_m, l.direction_x, l.direction_y, false);
}

ShapeHit intersect(const CircleShape& c, double ux, double uy) {
  const double along = ux * c.centre_x_m + uy * c.centre_y_m;
  const double across = cross(ux, uy, c.centre_x_m, c.centre_y_m);
  const double half_chord_squared = c.radius_m * c.radius_m - across * across;
  if (half_chord_squared < 0.0) return {};
  const double half_chord = std::sqrt(half_chord_squared);
  const double t = along - half_chord;
  if (!(t > 0.0)) return {};
  return {.range_m = t, .cos_incidence = half_chord / c.radius_m};
}

ShapeHit intersect(const Shape& shape, double ux, double uy) {
  return std::visit([ux, uy](const auto& geometry) { return intersect(geometry, ux, uy); },
                    shape.geometry);
}

FirstHit first_hit(std::span<const Shape> shapes, double ux, double uy) {
  FirstHit first;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const ShapeHit hit = intersect(shapes[i], ux, uy);
    if (hit.range_m < first.hit.range_m) first = {.hit = hit, .shape = i};
  }
  return first;
}

std::vector<Shape> background_shapes(std::span<const BackgroundSegment> segments) {
  std::vector<Shape> shapes;
  shapes.reserve(segments.size());
  for (const BackgroundSegment& s : segments) {
    shapes.push_back(
        {.geometry = SegmentShape{s.x0_m, s.y0_m, s.x1_m, s.y1_m}, .reflectivity = s.reflectivity});
  }
  return shapes;
}

void ScanPlaneRoom::validate(std::string_view prefix) const {
  const std::string p(prefix);
  const auto wall = [&p](const std::optional<RoomWall>& w, const char* name) {
    if (!w) return;
    require_distance(p + name + ".distance_m", w->distance_m);
    require_reflectivity(p + name + ".reflectivity", w->reflectivity);
  };
  wall(left_wall, "left_wall");
  wall(right_wall, "right_wall");
  wall(back_wall, "back_wall");
  for (std::size_t i = 0; i < cylinders.size(); ++i) {
    const RoomCylinder& c = cylinders[i];
    const std::string at = p + "cylinders[" + std::to_string(i) + "].";
    require_finite(at + "centre_x_m", c.centre_x_m);
    require_finite(at + "centre_y_m", c.centre_y_m);
    require_distance(at + "radius_m", c.radius_m);
    const double centre_m = std::hypot(c.centre_x_m, c.centre_y_m);
    if (!(c.radius_m < centre_m)) {
      throw_invalid(at + "radius_m", c.radius_m,
                    "< the distance from the sensor to the axis, " + message_number(centre_m) +
                        " m (the sensor outside the cylinder)");
    }
    require_heights(at, c.z_min_m, c.z_max_m);
    require_reflectivity(at + "reflectivity", c.reflectivity);
  }
  for (std::size_t i = 0; i < plates.size(); ++i) {
    const RoomPlate& s = plates[i];
    const std::string at = p + "plates[" + std::to_string(i) + "].";
    require_finite(at + "x0_m", s.x0_m);
    require_finite(at + "y0_m", s.y0_m);
    require_finite(at + "x1_m", s.x1_m);
    require_finite(at + "y1_m", s.y1_m);
    if (s.x0_m == s.x1_m && s.y0_m == s.y1_m) {
      throw_invalid(at + "x1_m", s.x1_m, "a point other than (x0_m, y0_m): a plate of length > 0");
    }
    require_heights(at, s.z_min_m, s.z_max_m);
    require_reflectivity(at + "reflectivity", s.reflectivity);
  }
}

std::vector<Shape> room_shapes(const ScanPlaneRoom& room, double scan_height_m) {
  room.validate();
  require_finite("scan_height_m", scan_height_m);
  std::vector<Shape> shapes;
  if (room.left_wall) {
    shapes.push_back({.geometry = LineShape{0.0, -room.left_wall->distance_m, 1.0, 0.0},
                      .reflectivity = room.left_wall->reflectivity});
  }
  if (room.right_wall) {
    shapes.push_back({.geometry = LineShape{0.0, room.right_wall->distance_m, 1.0, 0.0},
                      .reflectivity = room.right_wall->reflectivity});
  }
  if (room.back_wall) {
    shapes.push_back({.geometry = LineShape{room.back_wall->distance_m, 0.0, 0.0, 1.0},
                      .reflectivity = room.back_wall->reflectivity});
  }
  const auto crosses = [scan_height_m](double z_min_m, double z_max_m) {
    return scan_height_m >= z_min_m && scan_height_m <= z_max_m;
  };
  for (const RoomCylinder& c : room.cylinders) {
    if (!crosses(c.z_min_m, c.z_max_m)) continue;
    shapes.push_back({.geometry = CircleShape{c.centre_x_m, c.centre_y_m, c.radius_m},
                      .reflectivity = c.reflectivity});
  }
  for (const RoomPlate& s : room.plates) {
    if (!crosses(s.z_min_m, s.z_max_m)) continue;
    shapes.push_back(
        {.geometry = SegmentShape{s.x0_m, s.y0_m, s.x1_m, s.y1_m}, .reflectivity = s.reflectivity});
  }
  return shapes;
}

ScanPlaneRoom scan_plane_room(const propagation::RoomSpec& room, const LidarParams& params) {
  const double height_m = params.height_m;
  if (room.ceiling.present && !(height_m < room.ceiling.distance_m)) {
    throw_invalid("lidar.height_m", height_m,
                  "< chamber.room.ceiling.height_m = " + message_number(room.ceiling.distance_m) +
                      " (the lidar inside the hall)");
  }
  ScanPlaneRoom plane;
  const auto wall = [&params](const propagation::SurfaceSpec& spec,
                              std::string_view name) -> std::optional<RoomWall> {
    if (!spec.present) return std::nullopt;
    return RoomWall{.distance_m = spec.distance_m,
                    .reflectivity = wall_reflectivity(spec, name, params.wavelength_m)};
  };
  plane.left_wall = wall(room.left_wall, "left_wall");
  plane.right_wall = wall(room.right_wall, "right_wall");
  plane.back_wall = wall(room.back_wall, "back_wall");
  for (std::size_t i = 0; i < room.objects.size(); ++i) {
    const propagation::RoomObject& o = room.objects[i];
    const std::string key = std::string(objects_prefix) + std::to_string(i) + "].";
    const double reflectivity = propagation::diffuse_reflectance(
        o.material, params.wavelength_m, key + "material", "lidar.wavelength_m");
    const double z_min_m = o.base_height_m, z_max_m = o.base_height_m + o.height_m;
    if (!(height_m >= z_min_m && height_m <= z_max_m)) continue;
    switch (o.shape) {
      case propagation::ObjectShape::cylinder: {
        const double axis_m = std::hypot(o.x_m, o.y_m);
        if (!(o.radius_m < axis_m)) {
          throw_invalid(key + "radius_m", o.radius_m,
                        "< the lidar's distance from the cylinder's axis, " +
                            message_number(axis_m) + " m, where the scan at lidar.height_m = " +
                            message_number(height_m) + " m crosses it (the lidar outside it)");
        }
        plane.cylinders.push_back({.centre_x_m = o.x_m,
                                   .centre_y_m = o.y_m,
                                   .radius_m = o.radius_m,
                                   .z_min_m = z_min_m,
                                   .z_max_m = z_max_m,
                                   .reflectivity = reflectivity});
        break;
      }
      case propagation::ObjectShape::plate: {
        // Its normal n = (-cos yaw, sin yaw); its width runs along (sin yaw, cos yaw), across n.
        const double yaw_rad = o.yaw_deg * pi / 180.0;
        const double half_x = 0.5 * o.width_m * std::sin(yaw_rad);
        const double half_y = 0.5 * o.width_m * std::cos(yaw_rad);
        plane.plates.push_back({.x0_m = o.x_m - half_x,
                                .y0_m = o.y_m - half_y,
                                .x1_m = o.x_m + half_x,
                                .y1_m = o.y_m + half_y,
                                .z_min_m = z_min_m,
                                .z_max_m = z_max_m,
                                .reflectivity = reflectivity});
        break;
      }
    }
  }
  return plane;
}

}  // namespace fogradar::lidar
