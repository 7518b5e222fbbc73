// The room's specular paths: the walls, floor and ceiling of a hall as axis-aligned planes, and
// the paths from one point to another that reflect off them, to second order, by the image method
// (Allen & Berkley 1979, J. Acoust. Soc. Am. 65, 943: the receiver mirrored in each plane of a
// path, the last plane first, lies on the straight line that leaves the source along the path; the
// path is as long as that line). Frame: x along the sensor's boresight toward the back wall, y to
// the right, z up, metres; its origin is the caller's (the sensor, or the floor below it).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace fogradar::propagation {

// The plane's normal axis, and which side of it the room is on.
enum class Surface {
  floor,       // z = position, the room above
  ceiling,     // z = position, the room below
  left_wall,   // y = position, the room to its right (+y)
  right_wall,  // y = position, the room to its left
  back_wall,   // x = position, the room in front of it (toward the sensor, -x)
};

struct RoomPlane {
  Surface surface = Surface::floor;
  double position_m = 0.0;  // its coordinate along its normal axis
};

// One specular path from `from` to `to`: the planes it reflects off in order (indices into the
// room's planes; none for the direct path), its reflection points, its length and its directions.
struct SpecularPath {
  std::vector<std::size_t> planes;
  std::vector<Eigen::Vector3d> reflection_points;
  // `to` mirrored in the path's planes, the last first: the straight line from `from` to it leaves
  // along `departure` and is as long as the path (`to` itself for the direct path).
  Eigen::Vector3d image;
  double length_m = 0.0;
  Eigen::Vector3d departure;  // unit vector leaving `from`
  Eigen::Vector3d arrival;    // unit vector of travel arriving at `to`
  // Per reflection, the grazing angle between the ray and the plane, rad in [0, pi/2].
  std::vector<double> grazing_rad;
};

// The coordinate axis the surface's plane is normal to: x 0, y 1, z 2.
int normal_axis(Surface surface);
// Where the segment a -> b crosses `plane` strictly between its ends, as the fraction t of the way
// (a + t (b - a) lies on it); none when both ends lie on one side or an end lies on the plane.
std::optional<double> crossing_fraction(const RoomPlane& plane, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b);
// The unit normal of `plane` pointing into the room.
Eigen::Vector3d inward_normal(const RoomPlane& plane);
// Whether `point` lies inside (or on) every plane's side of the room.
bool inside_room(std::span<const RoomPlane> planes, const Eigen::Vector3d& point);
// `point` mirrored in `plane`: its coordinate along the normal axis reflected, x' = 2 p - x.
Eigen::Vector3d mirrored(const RoomPlane& plane, const Eigen::Vector3d& point);

// Every specular path from `from` to `to` (both inside the room) with at most `max_order`
// reflections (0, 1 or 2), the direct path first, then by order and plane index. A sequence of
// planes gives a path where each reflection point lies on its plane inside the room, between the
// point before it and the image ahead (Allen & Berkley's validity test); a plane never follows
// itself.
std::vector<SpecularPath> specular_paths(std::span<const RoomPlane> planes,
                                         const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                         std::size_t max_order = 2);

}  // namespace fogradar::propagation
