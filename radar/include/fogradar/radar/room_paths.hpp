// The radar's paths through the room: the one-way image paths from the radar to a point, each with
// its length, the antenna's Gaussian pattern at its departure and the co-polar reflection
// coefficient of each plane it meets; the co-polar coefficient of one reflection off a material;
// and the room's own echoes (an object by its closed-form RCS, the back wall's specular return).
// Frame: room_spec.hpp's (x along the boresight, y to the right, z up; the radar at (0, 0, h)).
#pragma once

#include <Eigen/Core>
#include <array>
#include <complex>
#include <cstddef>
#include <span>

#include "fogradar/propagation/materials.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/scene.hpp"

namespace fogradar::radar {

// The unit vector of the radar's polarisation for a ray travelling along `direction` (unit):
// horizontal, h = +-(-d_y, d_x, 0) normalised, the sign that makes h_y >= 0 for a ray along +-x
// (y on boresight, either way); vertical, v = d x h with v_z >= 0 (z on boresight). A ray and its
// reverse share the vector, so a path and its reverse see one polarisation (reciprocity).
Eigen::Vector3d polarisation_vector(const Eigen::Vector3d& direction, Polarisation polarisation);

// The co-polar amplitude reflection coefficient of a smooth surface of Fresnel coefficients
// `fresnel` (materials.hpp: TE and TM, the ground-reflection convention, both -1 at grazing) for
// a ray arriving along `incident` (unit) on a plane of unit normal `normal`: the field e (the
// polarisation_vector) splits into its TE part along s = d_i x n / |d_i x n| and its TM part along
// p_i = s x d_i; the reflected field r_TE (e.s) s + r_TM (e.p_i) p_r (p_r = s x d_r, d_r = d_i -
// 2 (d_i.n) n) projected on the polarisation_vector of d_r:
//   r = r_TE (e.s)(e_r.s) + r_TM (e.p_i)(e_r.p_r)
// (Balanis, Advanced Engineering Electromagnetics, 2nd ed., sec. 5.3; the cross-polar part is
// neglected). On the floor or ceiling horizontal polarisation is TE, r = r_TE; on a side wall at
// grazing it is TM, r = r_TM; at normal incidence r = r_TE for either.
std::complex<double> co_polar_reflection(const propagation::FresnelCoefficients& fresnel,
                                         const Eigen::Vector3d& incident,
                                         const Eigen::Vector3d& normal, Polarisation polarisation);

// One one-way path from the radar to a point via the room (the direct path has no reflection).
struct OneWayLeg {
  double length_m = 0.0;
  // sqrt(g_az g_el) of the Gaussian beam at the departure direction, as the radar leaves it (and,
  // by reciprocity, receives along it).
  double pattern_amplitude = 0.0;
  // The product of its reflections' co-polar coefficients; exactly real (and equal to the product
  // of the real coefficients, taken in order) when no surface on it is a material.
  std::complex<double> coefficient{1.0, 0.0};
  bool real_coefficient = true;
  // The leg's length changes by this times the point's velocity along +x: the x component of its
  // departure direction, negated once per back-wall reflection (the point's image moves the other
  // way).
  double length_rate_per_x_velocity = 0.0;
  std::size_t order = 0;  // reflections
};

// At most 5 planes: the direct path, 5 of first order, 20 of second.
inline constexpr std::size_t max_one_way_legs = 26;
using OneWayLegs = std::array<OneWayLeg, max_one_way_legs>;

// The one-way paths from `radar` to `point` through the scene's surfaces (at most 5), with at most
// two reflections, in specular_paths' order (propagation/room.hpp: direct, then by order and
// plane index) and by its validity test; returns their count. The geometry of each is that of the
// line from the radar to the point's image. Allocates nothing.
std::size_t one_way_legs(const Scene& scene, const Eigen::Vector3d& radar,
                         const Eigen::Vector3d& point, const RadarParams& params, OneWayLegs& legs);

// The echo of a static object standing in the room, seen from `radar`: its range (to a
// cylinder's lit line at mid-height, to a plate's centre), its two-way pattern g_az g_el at that
// direction and its RCS: the perfectly conducting closed form (object_rcs.hpp; a cylinder's tilt
// from broadside is the elevation of the radar seen from its mid-height, a plate's normal points
// along (-cos yaw, sin yaw, 0)) times the material's normal-incidence power reflectance.
struct ObjectEcho {
  double range_m = 0.0;
  double two_way_pattern = 0.0;
  double rcs_m2 = 0.0;
};
ObjectEcho object_echo(const SceneObject& object, const Eigen::Vector3d& radar,
                       const RadarParams& params, double wavelength_m);

// The power of a plane's specular return at normal incidence from range R, without |Gamma|^2: the
// radar's image in the plane transmits to it from 2 R away, P = P_t G_t G_r (lambda / (4 pi 2 R))^2
// (Friis 1946, Proc. IRE 34, 254; the radar equation with sigma = pi R^2 for the infinite plane).
double specular_plane_power_w(double tx_power_w, double tx_gain, double rx_gain,
                              double wavelength_m, double range_m);

}  // namespace fogradar::radar
