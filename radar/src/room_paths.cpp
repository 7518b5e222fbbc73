#include "fogradar/radar/room_paths.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/propagation/room.hpp"
#include "fogradar/radar/object_rcs.hpp"

namespace fogradar::radar {
namespace {

using propagation::RoomPlane;
using propagation::Surface;

constexpr double degree_rad = pi / 180.0;
constexpr std::size_t max_surfaces = 5;

struct LegGeometry {
  double length_m;
  double pattern_amplitude;
};

// The straight line from the radar along `delta` (to a point or its image): its length and the
// one-way amplitude pattern sqrt(g_az g_el) of the Gaussian beam at its azimuth atan2(dy, dx) and
// elevation atan2(dz, hypot(dx, dy)).
LegGeometry leg_geometry(const Eigen::Vector3d& delta, const RadarParams& p) {
  const double horizontal_m = std::hypot(delta.x(), delta.y());
  const double azimuth = std::atan2(delta.y(), delta.x());
  const double elevation = std::atan2(delta.z(), horizontal_m);
  const double gain = gaussian_beam_power(azimuth, p.azimuth_beamwidth_deg * degree_rad) *
                      gaussian_beam_power(elevation, p.elevation_beamwidth_deg * degree_rad);
  return {std::hypot(horizontal_m, delta.z()), std::sqrt(gain)};
}

}  // namespace

Eigen::Vector3d polarisation_vector(const Eigen::Vector3d& direction, Polarisation polarisation) {
  Eigen::Vector3d h(-direction.y(), direction.x(), 0.0);
  // A vertical ray has no horizontal normal to it: y, as for a ray on boresight.
  if (h.norm() < 1e-12) h = Eigen::Vector3d::UnitY();
  if (direction.x() < 0.0) h = -h;
  h.normalize();
  if (polarisation == Polarisation::horizontal) return h;
  Eigen::Vector3d v = direction.cross(h).normalized();
  return v.z() < 0.0 ? Eigen::Vector3d(-v) : v;
}

std::complex<double> co_polar_reflection(const propagation::FresnelCoefficients& fresnel,
                                         const Eigen::Vector3d& incident,
                                         const Eigen::Vector3d& normal, Polarisation polarisation) {
  const Eigen::Vector3d across = incident.cross(normal);
  // Normal incidence: no plane of incidence; either polarisation reflects as TE does (TM = -TE in
  // this convention because p_r = -p_i there).
  if (across.norm() < 1e-12) return fresnel.te;
  const Eigen::Vector3d s = across.normalized();
  const Eigen::Vector3d reflected = incident - 2.0 * incident.dot(normal) * normal;
  const Eigen::Vector3d p_in = s.cross(incident);
  const Eigen::Vector3d p_out = s.cross(reflected);
  const Eigen::Vector3d e_in = polarisation_vector(incident, polarisation);
  const Eigen::Vector3d e_out = polarisation_vector(reflected, polarisation);
  return fresnel.te * (e_in.dot(s) * e_out.dot(s)) +
         fresnel.tm * (e_in.dot(p_in) * e_out.dot(p_out));
}

std::size_t one_way_legs(const Scene& scene, const Eigen::Vector3d& radar,
                         const Eigen::Vector3d& point, const RadarParams& params,
                         OneWayLegs& legs) {
  const std::size_t n = scene.surfaces.size();
  FOGRADAR_CHECK(n <= max_surfaces);
  std::array<RoomPlane, max_surfaces> plane_array;
  for (std::size_t i = 0; i < n; ++i) plane_array[i] = scene.surfaces[i].plane;
  const std::span<const RoomPlane> planes(plane_array.data(), n);
  std::size_t count = 0;
  // The path through the planes sequence[0 .. order), if it exists (specular_paths' test).
  const auto add = [&](std::array<std::size_t, 2> sequence, std::size_t order) {
    // images[j]: the point mirrored in the last j planes of the sequence, the last first.
    std::array<Eigen::Vector3d, 3> images;
    images[0] = point;
    for (std::size_t j = 1; j <= order; ++j)
      images[j] = propagation::mirrored(planes[sequence[order - j]], images[j - 1]);
    Eigen::Vector3d before = radar;
    for (std::size_t k = 0; k < order; ++k) {
      const RoomPlane& plane = planes[sequence[k]];
      const Eigen::Vector3d& ahead = images[order - k];
      const std::optional<double> t = propagation::crossing_fraction(plane, before, ahead);
      if (!t) return;
      Eigen::Vector3d hit = before + *t * (ahead - before);
      hit[propagation::normal_axis(plane.surface)] = plane.position_m;
      if (!propagation::inside_room(planes, hit)) return;
      before = hit;
    }
    const Eigen::Vector3d delta = images[order] - radar;
    const LegGeometry geometry = leg_geometry(delta, params);
    OneWayLeg& leg = legs[count++];
    leg.length_m = geometry.length_m;
    leg.pattern_amplitude = geometry.pattern_amplitude;
    leg.order = order;
    // The ray's direction on each segment: the departure direction with the component along each
    // plane's normal reversed at that plane.
    Eigen::Vector3d direction = delta / geometry.length_m;
    double real = 1.0;
    std::complex<double> material{1.0, 0.0};
    bool real_only = true;
    double x_sign = 1.0;
    for (std::size_t k = 0; k < order; ++k) {
      const SceneSurface& surface = scene.surfaces[sequence[k]];
      const int axis = propagation::normal_axis(surface.plane.surface);
      if (surface.permittivity) {
        const double grazing_rad = std::asin(std::min(1.0, std::abs(direction[axis])));
        material *= co_polar_reflection(
            propagation::fresnel_reflection(*surface.permittivity, grazing_rad), direction,
            propagation::inward_normal(surface.plane), params.polarisation);
        real_only = false;
      } else {
        real *= surface.reflection_coefficient;
      }
      if (surface.plane.surface == Surface::back_wall) x_sign = -x_sign;
      direction[axis] = -direction[axis];
    }
    leg.real_coefficient = real_only;
    leg.coefficient = real_only ? std::complex<double>(real, 0.0) : material * real;
    leg.length_rate_per_x_velocity = x_sign * delta.x() / geometry.length_m;
  };
  add({0, 0}, 0);
  for (std::size_t p = 0; p < n; ++p) add({p, 0}, 1);
  for (std::size_t p = 0; p < n; ++p) {
    for (std::size_t q = 0; q < n; ++q) {
      if (q != p) add({p, q}, 2);
    }
  }
  return count;
}

ObjectEcho object_echo(const SceneObject& scene_object, const Eigen::Vector3d& radar,
                       const RadarParams& params, double wavelength_m) {
  const propagation::RoomObject& object = scene_object.object;
  const double middle_m = object.base_height_m + 0.5 * object.height_m;
  ObjectEcho echo;
  Eigen::Vector3d delta;
  if (object.shape == propagation::ObjectShape::cylinder) {
    // The lit line faces the radar: the axis's horizontal distance less the radius.
    const double axis_m = std::hypot(object.x_m, object.y_m);
    const double near_m = axis_m - object.radius_m;
    delta = Eigen::Vector3d(object.x_m * near_m / axis_m, object.y_m * near_m / axis_m,
                            middle_m - radar.z());
    const double off_broadside_rad = std::atan2(radar.z() - middle_m, near_m);
    echo.rcs_m2 = cylinder_rcs_m2({.radius_m = object.radius_m, .length_m = object.height_m},
                                  wavelength_m, off_broadside_rad);
  } else {
    const double yaw_rad = object.yaw_deg * degree_rad;
    const Eigen::Vector3d centre(object.x_m, object.y_m, middle_m);
    delta = centre - radar;
    const Eigen::Vector3d to_radar = -delta.normalized();
    const Eigen::Vector3d normal(-std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
    const Eigen::Vector3d width(std::sin(yaw_rad), std::cos(yaw_rad), 0.0);
    // A thin plate returns from either face.
    const double off_normal_rad = std::acos(std::min(1.0, std::abs(to_radar.dot(normal))));
    const double tilt_azimuth_rad = std::atan2(to_radar.z(), to_radar.dot(width));
    echo.rcs_m2 = plate_rcs_m2({.width_m = object.width_m, .height_m = object.height_m},
                               wavelength_m, off_normal_rad, tilt_azimuth_rad);
  }
  const LegGeometry geometry = leg_geometry(delta, params);
  echo.range_m = geometry.length_m;
  echo.two_way_pattern = geometry.pattern_amplitude * geometry.pattern_amplitude;
  echo.rcs_m2 *= scene_object.reflectance;
  return echo;
}

double specular_plane_power_w(double tx_power_w, double tx_gain, double rx_gain,
                              double wavelength_m, double range_m) {
  const double friis = wavelength_m / (4.0 * pi * 2.0 * range_m);
  return tx_power_w * tx_gain * rx_gain * friis * friis;
}

}  // namespace fogradar::radar
