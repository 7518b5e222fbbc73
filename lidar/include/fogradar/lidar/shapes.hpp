// The lidar's static scene in its scan plane as shapes: segments (the `[[lidar.background]]`
// segments, a flat plate), infinite lines (a hall's walls) and circles (a vertical cylinder's cross
// section, the rain barrels), each a Lambertian surface of one reflectivity at the lidar's
// wavelength; the beam's first hit on them; and the room, described by its walls and objects,
// turned into shapes at the scan's height.
//
// Frame as params.hpp: the sensor at the origin, x along its boresight, y to its right, metres; a
// beam leaves the origin along u = (cos a, sin a), a the beam's angle (+ to the right).
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "fogradar/lidar/params.hpp"
#include "fogradar/propagation/room_spec.hpp"

namespace fogradar::lidar {

// The segment from (x0_m, y0_m) to (x1_m, y1_m).
struct SegmentShape {
  double x0_m = 0.0;
  double y0_m = 0.0;
  double x1_m = 0.0;
  double y1_m = 0.0;
};

// The infinite line through (x_m, y_m) along (direction_x, direction_y) (any non-zero length).
struct LineShape {
  double x_m = 0.0;
  double y_m = 0.0;
  double direction_x = 1.0;
  double direction_y = 0.0;
};

// The circle of `radius_m` about (centre_x_m, centre_y_m); the sensor outside it.
struct CircleShape {
  double centre_x_m = 0.0;
  double centre_y_m = 0.0;
  double radius_m = 0.0;
};

struct Shape {
  std::variant<SegmentShape, LineShape, CircleShape> geometry;
  double reflectivity = 0.0;  // Lambertian, at the lidar's wavelength, in [0, 1]
};

// Where a beam meets a shape: the range along the beam and the cosine of the angle between the
// beam and the surface's normal there (the Lambertian return's cos(incidence)); range infinite when
// it misses.
struct ShapeHit {
  double range_m = std::numeric_limits<double>::infinity();
  double cos_incidence = 0.0;
};

// The beam from the origin along the unit vector (ux, uy) against one shape, in front of the sensor
// only (range > 0). A segment or line: t u = p0 + lambda d (lambda in [0, 1] for a segment), cos
// incidence = |u x d| / |d|. A circle: the nearer root of |t u - c| = r, t = u.c - sqrt(r^2 - |u x
// c|^2), cos incidence = sqrt(r^2 - |u x c|^2) / r (the normal is radial); a tangent beam hits at
// grazing incidence, cos 0.
ShapeHit intersect(const SegmentShape& segment, double ux, double uy);
ShapeHit intersect(const LineShape& line, double ux, double uy);
ShapeHit intersect(const CircleShape& circle, double ux, double uy);
ShapeHit intersect(const Shape& shape, double ux, double uy);

// The first of `shapes` the beam meets: the nearest hit, the earlier shape on a tie; `shape` is its
// index, none when the beam meets nothing.
struct FirstHit {
  ShapeHit hit;
  std::optional<std::size_t> shape;
};
FirstHit first_hit(std::span<const Shape> shapes, double ux, double uy);

// The `[[lidar.background]]` segments as shapes, in order.
std::vector<Shape> background_shapes(std::span<const BackgroundSegment> segments);

// A wall of the hall: a vertical plane at `distance_m` from the sensor (side walls: laterally,
// from its boresight line; the back wall: along the boresight), floor to ceiling, so every scan
// height meets it.
struct RoomWall {
  double distance_m = 0.0;
  double reflectivity = 0.0;
};

// A vertical cylinder standing in the hall (a rain barrel): its axis at (centre_x_m, centre_y_m),
// from z_min_m to z_max_m (heights in the frame the scan height is given in).
struct RoomCylinder {
  double centre_x_m = 0.0;
  double centre_y_m = 0.0;
  double radius_m = 0.0;
  double z_min_m = 0.0;
  double z_max_m = 0.0;
  double reflectivity = 0.0;
};

// A vertical flat plate: its bottom edge from (x0_m, y0_m) to (x1_m, y1_m), from z_min_m to
// z_max_m.
struct RoomPlate {
  double x0_m = 0.0;
  double y0_m = 0.0;
  double x1_m = 0.0;
  double y1_m = 0.0;
  double z_min_m = 0.0;
  double z_max_m = 0.0;
  double reflectivity = 0.0;
};

// The hall as the lidar's scan plane sees it (the floor and the ceiling, parallel to a
// horizontal scan, are never hit by its ray beams). The sensor stands inside: between the walls,
// before the back wall and outside every cylinder.
struct ScanPlaneRoom {
  std::optional<RoomWall> left_wall;   // the line y = -distance_m
  std::optional<RoomWall> right_wall;  // the line y = +distance_m
  std::optional<RoomWall> back_wall;   // the line x = +distance_m
  std::vector<RoomCylinder> cylinders;
  std::vector<RoomPlate> plates;

  // Throws InvalidParameter naming `prefix` + the field ("room.left_wall.distance_m",
  // "room.cylinders[1].radius_m") and the allowed range: distances and radii > 0 and finite, the
  // sensor outside every cylinder, z_min_m <= z_max_m, reflectivities in [0, 1], a plate of
  // non-zero length.
  void validate(std::string_view prefix = "room.") const;
};

// The scenario's room (sensor::Context::room: [chamber.room], [[chamber.objects]]) as the lidar at
// params.height_m meets it: the left, right and back walls, and the objects whose height range
// holds the scan height, each with its material's diffuse reflectance at params.wavelength_m
// (propagation::diffuse_reflectance). A cylinder spans base_height_m to base_height_m + height_m;
// a plate's bottom edge runs from its centre +-width_m/2 along (sin yaw, cos yaw) (yaw turns its
// normal from -x toward +y). The floor and the ceiling, parallel to the horizontal scan, are never
// met and need no reflectance. Throws InvalidParameter naming the scenario's key: a wall given by
// chamber.room.<wall>.reflection_coefficient (no diffuse reflectance), a wall's or an object's
// material without a published sample (chamber.room.left_wall.material,
// chamber.objects[2].material), lidar.wavelength_m farther than 10 nm from every tabulated
// wavelength, lidar.height_m not below chamber.room.ceiling.height_m, and a cylinder the scan
// crosses that holds the lidar (chamber.objects[2].radius_m).
ScanPlaneRoom scan_plane_room(const propagation::RoomSpec& room, const LidarParams& params);

// The room's shapes in the plane of a scan at `scan_height_m`: each wall as a line (left, right,
// back), each cylinder whose [z_min_m, z_max_m] holds the scan height as a circle, each plate
// whose height range holds it as a segment, in that order. Validates the room first.
std::vector<Shape> room_shapes(const ScanPlaneRoom& room, double scan_height_m);

}  // namespace fogradar::lidar
