// The room's specular paths by the image method (room.hpp).
#include "fogradar/propagation/room.hpp"

#include <cmath>
#include <optional>

#include "fogradar/core/error.hpp"

namespace fogradar::propagation {
namespace {

// The room's side of the plane: +1 where the room has larger coordinates (floor, left wall).
double inward_sign(Surface surface) {
  return surface == Surface::floor || surface == Surface::left_wall ? 1.0 : -1.0;
}

// The grazing angle of a ray along `direction` (unit) at `plane`: asin |d · n|.
double grazing_angle_rad(const RoomPlane& plane, const Eigen::Vector3d& direction) {
  return std::asin(std::min(1.0, std::abs(direction[normal_axis(plane.surface)])));
}

}  // namespace

int normal_axis(Surface surface) {
  switch (surface) {
    case Surface::floor:
    case Surface::ceiling:
      return 2;
    case Surface::left_wall:
    case Surface::right_wall:
      return 1;
    case Surface::back_wall:
      return 0;
  }
  return 0;
}

std::optional<double> crossing_fraction(const RoomPlane& plane, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b) {
  const int axis = normal_axis(plane.surface);
  const double da = a[axis] - plane.position_m, db = b[axis] - plane.position_m;
  if (!(da * db < 0.0)) return std::nullopt;  // both on one side, or an end on the plane
  return da / (da - db);
}

Eigen::Vector3d inward_normal(const RoomPlane& plane) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[normal_axis(plane.surface)] = inward_sign(plane.surface);
  return n;
}

bool inside_room(std::span<const RoomPlane> planes, const Eigen::Vector3d& point) {
  for (const RoomPlane& plane : planes) {
    const double d = point[normal_axis(plane.surface)] - plane.position_m;
    if (inward_sign(plane.surface) * d < 0.0) return false;
  }
  return true;
}

Eigen::Vector3d mirrored(const RoomPlane& plane, const Eigen::Vector3d& point) {
  Eigen::Vector3d image = point;
  const int axis = normal_axis(plane.surface);
  image[axis] = 2.0 * plane.position_m - point[axis];
  return image;
}

std::vector<SpecularPath> specular_paths(std::span<const RoomPlane> planes,
                                         const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                         std::size_t max_order) {
  FOGRADAR_CHECK(max_order <= 2);
  FOGRADAR_CHECK(inside_room(planes, from) && inside_room(planes, to));
  std::vector<SpecularPath> paths;
  // The path through `sequence` (plane indices in the order the ray meets them), if it exists.
  const auto add = [&](const std::vector<std::size_t>& sequence) {
    // images[k]: `to` mirrored in the last k planes of the sequence, the last plane first.
    std::vector<Eigen::Vector3d> images{to};
    for (std::size_t k = sequence.size(); k-- > 0;)
      images.push_back(mirrored(planes[sequence[k]], images.back()));
    // Forward from the source: the line to the image of `to` in the planes still ahead crosses the
    // next plane at its reflection point.
    std::vector<Eigen::Vector3d> points;
    Eigen::Vector3d before = from;
    for (std::size_t k = 0; k < sequence.size(); ++k) {
      const RoomPlane& plane = planes[sequence[k]];
      const Eigen::Vector3d& ahead = images[sequence.size() - k];
      const std::optional<double> t = crossing_fraction(plane, before, ahead);
      if (!t) return;
      Eigen::Vector3d point = before + *t * (ahead - before);
      point[normal_axis(plane.surface)] = plane.position_m;  // exactly on the plane
      if (!inside_room(planes, point)) return;
      points.push_back(point);
      before = point;
    }
    SpecularPath path;
    path.planes = sequence;
    path.reflection_points = points;
    path.image = images.back();
    path.length_m = (path.image - from).norm();
    const Eigen::Vector3d& first = points.empty() ? to : points.front();
    const Eigen::Vector3d& last = points.empty() ? from : points.back();
    path.departure = (first - from).normalized();
    path.arrival = (to - last).normalized();
    Eigen::Vector3d start = from;
    for (std::size_t k = 0; k < sequence.size(); ++k) {
      path.grazing_rad.push_back(
          grazing_angle_rad(planes[sequence[k]], (points[k] - start).normalized()));
      start = points[k];
    }
    paths.push_back(std::move(path));
  };
  add({});
  if (max_order >= 1) {
    for (std::size_t p = 0; p < planes.size(); ++p) add({p});
  }
  if (max_order >= 2) {
    for (std::size_t p = 0; p < planes.size(); ++p) {
      for (std::size_t q = 0; q < planes.size(); ++q) {
        if (q != p) add({p, q});
      }
    }
  }
  return paths;
}

}  // namespace fogradar::propagation
