// The room's specular paths (propagation/room.hpp) against closed forms (the two-ray floor path,
// the paths between two parallel walls) and against the law of reflection, checked at every
// reflection point of every path of a hall without the image method.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "fogradar/propagation/room.hpp"
#include "validation.hpp"

namespace fogradar::propagation {
namespace {

using Eigen::Vector3d;
using testing::Tolerance;
using testing::validate;

// A hall as the study's could be: the sensor 0.5 m above a floor, walls 2 m to the left and 3 m to
// the right, a ceiling 4 m up and a back wall 12 m ahead.
std::vector<RoomPlane> hall() {
  return {{Surface::floor, -0.5},
          {Surface::ceiling, 3.5},
          {Surface::left_wall, -2.0},
          {Surface::right_wall, 3.0},
          {Surface::back_wall, 12.0}};
}

TEST(Room, FloorPathIsTheTwoRayPath) {
  // Two-ray model (Rappaport, Wireless Communications 2nd ed. §4.6): antennas at heights h_t and
  // h_r, ground distance d: the reflected path is sqrt(d^2 + (h_t + h_r)^2), at grazing angle
  // atan((h_t + h_r) / d), reflected at d h_t / (h_t + h_r) from the transmitter.
  const double h_t = 0.5, h_r = 0.8, d = 7.3;
  const std::vector<RoomPlane> floor{{Surface::floor, -h_t}};
  const std::vector<SpecularPath> paths =
      specular_paths(floor, Vector3d(0.0, 0.0, 0.0), Vector3d(d, 0.0, h_r - h_t));
  ASSERT_EQ(paths.size(), 2u);
  EXPECT_TRUE(paths[0].planes.empty());
  EXPECT_NEAR(paths[0].length_m, std::hypot(d, h_r - h_t), 1e-12);
  const SpecularPath& floor_path = paths[1];
  validate({.id = "propagation.room.two_ray.length",
            .group = "physics: room",
            .quantity = "floor path length",
            .unit = "m",
            .conditions = "h_t = 0.5 m, h_r = 0.8 m, d = 7.3 m",
            .reference = std::hypot(d, h_t + h_r),
            .source = "closed form: two-ray model, Rappaport 2nd ed. sec. 4.6",
            .value = floor_path.length_m,
            .tolerance = 1e-12,
            .kind = Tolerance::relative});
  EXPECT_NEAR(floor_path.grazing_rad[0], std::atan((h_t + h_r) / d), 1e-12);
  EXPECT_NEAR(floor_path.reflection_points[0].x(), d * h_t / (h_t + h_r), 1e-12);
  EXPECT_NEAR(floor_path.reflection_points[0].z(), -h_t, 0.0);
  // The receiver's image below the floor, as far below it as the receiver is above.
  EXPECT_LT((floor_path.image - Vector3d(d, 0.0, -h_t - h_r)).norm(), 1e-15);
  EXPECT_NEAR((floor_path.image - Vector3d::Zero()).norm(), floor_path.length_m, 0.0);
  // It leaves downward and arrives upward.
  EXPECT_LT(floor_path.departure.z(), 0.0);
  EXPECT_GT(floor_path.arrival.z(), 0.0);
}

TEST(Room, TwoParallelWallsGiveTheImagesOfAWaveguide) {
  // Between walls at y = -a and y = b, the source mirrored in the left wall then the right one lies
  // at y = 2b + 2a - y_s, in the right then the left at y = -2a - 2b + y_s (the images of a
  // parallel-plate guide): the lengths follow from the straight lines to them.
  const double a = 1.5, b = 2.5, d = 9.0;
  const std::vector<RoomPlane> walls{{Surface::left_wall, -a}, {Surface::right_wall, b}};
  const Vector3d from(0.0, 0.2, 0.0), to(d, -0.4, 0.0);
  const std::vector<SpecularPath> paths = specular_paths(walls, from, to);
  ASSERT_EQ(paths.size(), 5u);  // direct, left, right, left-right, right-left
  const auto length_to = [&](double image_y) { return std::hypot(d, to.y() - image_y); };
  EXPECT_NEAR(paths[1].length_m, length_to(-2.0 * a - from.y()), 1e-12);
  EXPECT_NEAR(paths[2].length_m, length_to(2.0 * b - from.y()), 1e-12);
  ASSERT_EQ(paths[3].planes, (std::vector<std::size_t>{0, 1}));
  EXPECT_NEAR(paths[3].length_m, length_to(2.0 * b + 2.0 * a + from.y()), 1e-12);
  ASSERT_EQ(paths[4].planes, (std::vector<std::size_t>{1, 0}));
  EXPECT_NEAR(paths[4].length_m, length_to(-2.0 * a - 2.0 * b + from.y()), 1e-12);
}

TEST(Room, EveryPathObeysTheLawOfReflection) {
  // Without images: the path's points, one after another, must join `from` to `to`, each
  // reflection point on its plane, the outgoing direction the incoming one mirrored in the plane
  // (angle of incidence = angle of reflection), and the segments must add up to the length.
  const std::vector<RoomPlane> planes = hall();
  const std::array<std::array<Vector3d, 2>, 3> ends{{
      {Vector3d(0.0, 0.0, 0.0), Vector3d(8.0, 0.3, 0.1)},    // sensor to target
      {Vector3d(0.0, 0.0, 0.0), Vector3d(3.0, -1.2, 1.9)},   // to a point near the left wall
      {Vector3d(1.0, 2.0, -0.3), Vector3d(11.0, -1.0, 2.5)}  // corner to corner
  }};
  for (const auto& [from, to] : ends) {
    const std::vector<SpecularPath> paths = specular_paths(planes, from, to);
    // A generic pair of points in a box open at one end: the direct path, one path off each of
    // the five planes and, of second order, both orders off each of the two parallel pairs and one
    // off each of the eight perpendicular pairs (a corner reflects a ray once whichever plane it
    // meets first).
    EXPECT_EQ(paths.size(), 1u + 5u + 4u + 8u);
    for (const SpecularPath& path : paths) {
      std::vector<Vector3d> points{from};
      points.insert(points.end(), path.reflection_points.begin(), path.reflection_points.end());
      points.push_back(to);
      double length_m = 0.0;
      for (std::size_t k = 0; k + 1 < points.size(); ++k)
        length_m += (points[k + 1] - points[k]).norm();
      EXPECT_NEAR(length_m, path.length_m, 1e-12 * length_m);
      EXPECT_LT((path.departure - (points[1] - from).normalized()).norm(), 1e-12);
      EXPECT_LT((path.arrival - (to - points[points.size() - 2]).normalized()).norm(), 1e-12);
      for (std::size_t k = 0; k < path.planes.size(); ++k) {
        const RoomPlane& plane = planes[path.planes[k]];
        const Vector3d n = inward_normal(plane);
        const Vector3d& at = points[k + 1];
        EXPECT_TRUE(inside_room(planes, at));
        EXPECT_DOUBLE_EQ(at.dot(n.cwiseAbs()), plane.position_m);
        const Vector3d in = (at - points[k]).normalized(), out = (points[k + 2] - at).normalized();
        const Vector3d reflected = in - 2.0 * in.dot(n) * n;
        EXPECT_LT((reflected - out).norm(), 1e-9) << "plane " << path.planes[k];
        EXPECT_NEAR(path.grazing_rad[k], std::asin(std::abs(in.dot(n))), 1e-12);
      }
    }
  }
}

TEST(Room, AOneBouncePathIsTheShortestWayViaItsPlane) {
  // Fermat's principle as a second method: the path via the back wall found by a direct search
  // over points of the wall (golden-section in y for each z, nested) is as long as the image's.
  const std::vector<RoomPlane> planes = hall();
  const Vector3d from(0.0, 0.0, 0.0), to(6.0, 1.0, 0.7);
  const RoomPlane& back = planes[4];
  const auto via = [&](double y, double z) {
    const Vector3d at(back.position_m, y, z);
    return (at - from).norm() + (to - at).norm();
  };
  const auto golden = [](auto f, double lo, double hi) {
    const double r = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int i = 0; i < 200; ++i) {
      const double a = hi - r * (hi - lo), b = lo + r * (hi - lo);
      (f(a) < f(b) ? hi : lo) = (f(a) < f(b) ? b : a);
    }
    return 0.5 * (lo + hi);
  };
  const auto best_over_y = [&](double z) {
    const double y = golden([&](double yy) { return via(yy, z); }, -2.0, 3.0);
    return via(y, z);
  };
  const double z = golden(best_over_y, -0.5, 3.5);
  const std::vector<SpecularPath> paths = specular_paths(planes, from, to, 1);
  const auto path = std::find_if(paths.begin(), paths.end(), [](const SpecularPath& p) {
    return p.planes == std::vector<std::size_t>{4};
  });
  ASSERT_NE(path, paths.end());
  EXPECT_NEAR(path->length_m, best_over_y(z), 1e-9);
}

TEST(Room, OrdersAreCounted) {
  const std::vector<RoomPlane> planes = hall();
  const Vector3d from(0.0, 0.0, 0.0), to(8.0, 0.3, 0.1);
  EXPECT_EQ(specular_paths(planes, from, to, 0).size(), 1u);
  EXPECT_EQ(specular_paths(planes, from, to, 1).size(), 6u);
  // No planes: the direct path alone.
  EXPECT_EQ(specular_paths({}, from, to).size(), 1u);
}

}  // namespace
}  // namespace fogradar::propagation
