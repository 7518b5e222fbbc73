#include "fogradar/radar/scene.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/radar/room_paths.hpp"

namespace fogradar::radar {
namespace {

// Complex amplitude of a path of length L and power P at the start of the frame: sqrt(P) times the
// phase of its dechirped echo (echo_phase_at_chirp_start_rad).
std::complex<double> path_amplitude(double power_w, double path_length_m, const RadarDerived& d) {
  return std::polar(std::sqrt(power_w), echo_phase_at_chirp_start_rad(path_length_m, d));
}

// RCS of one measurement for the centre's Swerling model (mean preserved).
double fluctuated_rcs_m2(const ScatteringCentre& centre, RandomStream& rng) {
  switch (centre.swerling) {
    case Swerling::zero:
      return centre.rcs_m2;
    case Swerling::one:
      return centre.rcs_m2 * rng.exponential();
    case Swerling::three:
      // Chi-square with 4 degrees of freedom, unit mean: the mean of two unit exponentials.
      return centre.rcs_m2 * 0.5 * (rng.exponential() + rng.exponential());
  }
  return centre.rcs_m2;
}

// A centre's two-way paths are the pairs (out, back) of its one-way legs of total order <= 2; a
// pair and its reverse have one length, coefficient, pattern and Doppler, so each unordered pair is
// one tone counted twice. Bistatic radar equation per pair: P = Pt Gt Gr lambda^2 sigma / ((4 pi)^3
// r1^2 r2^2) (Skolnik, Radar Handbook 3rd ed., ch. 26, the two-ray model's leg pairs).
void add_centre_paths(const Scene& scene, const ScatteringCentre& centre, double target_range_m,
                      const propagation::Chamber& chamber, const propagation::ActiveLayers& active,
                      const RadarParams& p, const RadarDerived& d, RandomStream& rng,
                      std::vector<Tone>& tones) {
  const double rcs_m2 = fluctuated_rcs_m2(centre, rng);
  const double jitter_m = scene.micro_motion_std_m * rng.normal();
  const double along_m = target_range_m + centre.range_offset_m + jitter_m;
  OneWayLegs legs;
  const std::size_t count =
      one_way_legs(scene, Eigen::Vector3d(0.0, 0.0, scene.sensor_height_m),
                   Eigen::Vector3d(along_m, centre.lateral_m, centre.height_m), p, legs);
  const OneWayLeg& direct = legs[0];
  // Each leg's range rate for the centre moving along the boresight at the speed that gives its
  // direct path the centre's radial velocity v; the direct leg's is v itself.
  const double v = centre.radial_velocity_m_per_s;
  std::array<double, max_one_way_legs> rate;
  rate[0] = v;
  for (std::size_t i = 1; i < count; ++i) {
    rate[i] = v == 0.0
                  ? 0.0
                  : v * (legs[i].length_rate_per_x_velocity / direct.length_rate_per_x_velocity);
  }
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = i; j < count; ++j) {
      const OneWayLeg& out = legs[i];
      const OneWayLeg& back = legs[j];
      if (out.order + back.order > 2) continue;
      const double twice = i == j ? 1.0 : 2.0;
      const double geometric_mean_range_m = std::sqrt(out.length_m * back.length_m);
      const double power_w = received_power_w(d.tx_power_w, d.tx_gain, d.rx_gain, d.wavelength_m,
                                              rcs_m2, geometric_mean_range_m);
      const double pattern = out.pattern_amplitude * back.pattern_amplitude;
      const double length_m = out.length_m + back.length_m;
      const double transmittance = chamber.two_way_transmittance(0.5 * length_m, active) *
                                   scene.radome_two_way_transmittance *
                                   scene.target_film_reflectance;
      const std::complex<double> echo = path_amplitude(power_w * transmittance, length_m, d);
      const std::complex<double> amplitude =
          out.real_coefficient && back.real_coefficient
              ? twice * (out.coefficient.real() * back.coefficient.real()) * pattern * echo
              : twice * (out.coefficient * back.coefficient) * pattern * echo;
      const double velocity = 0.5 * (rate[i] + rate[j]);
      // A path the radar cannot resolve from the direct one in range or velocity is the target's
      // echo; one it resolves is a ghost.
      const bool resolved = std::abs(0.5 * length_m - direct.length_m) >= d.range_resolution_m ||
                            std::abs(velocity - v) >= d.velocity_resolution_m_per_s;
      tones.push_back(
          {length_m, amplitude, velocity,
           i == 0 && j == 0 ? Origin::target : (resolved ? Origin::multipath : Origin::target),
           -1});
    }
  }
}

// The room's own echoes, static: the back wall's specular return (the radar's image in it) and
// each object by its closed-form RCS, along their direct paths, through the fog of the chamber's
// layers up to their range (the layers fill the hall's cross-section here) and the radome.
void add_room_echoes(const Scene& scene, const propagation::Chamber& chamber,
                     const propagation::ActiveLayers& active, const RadarParams& p,
                     const RadarDerived& d, std::vector<Tone>& tones) {
  const Eigen::Vector3d radar(0.0, 0.0, scene.sensor_height_m);
  for (const SceneSurface& surface : scene.surfaces) {
    if (surface.plane.surface != propagation::Surface::back_wall) continue;
    const double range_m = surface.plane.position_m;
    const std::complex<double> gamma =
        surface.permittivity ? propagation::fresnel_reflection(*surface.permittivity, 0.5 * pi).te
                             : std::complex<double>(surface.reflection_coefficient, 0.0);
    const double power_w =
        specular_plane_power_w(d.tx_power_w, d.tx_gain, d.rx_gain, d.wavelength_m, range_m) *
        chamber.two_way_transmittance(range_m, active) * scene.radome_two_way_transmittance;
    tones.push_back(
        {2.0 * range_m, gamma * path_amplitude(power_w, 2.0 * range_m, d), 0.0, Origin::room, -1});
  }
  for (const SceneObject& object : scene.objects) {
    const ObjectEcho echo = object_echo(object, radar, p, d.wavelength_m);
    const double power_w = received_power_w(d.tx_power_w, d.tx_gain, d.rx_gain, d.wavelength_m,
                                            echo.rcs_m2, echo.range_m) *
                           chamber.two_way_transmittance(echo.range_m, active) *
                           scene.radome_two_way_transmittance;
    tones.push_back({2.0 * echo.range_m,
                     echo.two_way_pattern * path_amplitude(power_w, 2.0 * echo.range_m, d), 0.0,
                     Origin::room, -1});
  }
}

// Fog volume clutter: each range bin inside an active layer holds sigma = eta Omega (b^3 - a^3) / 3
// (the chamber's volume integral), split over point scatterers at uniform random ranges in the bin,
// each with a complex Gaussian amplitude (Rayleigh magnitude, uniform phase) drawn per measurement.
void add_fog_clutter(const Scene& scene, const propagation::Chamber& chamber,
                     const propagation::ActiveLayers& active, const RadarDerived& d,
                     RandomStream& rng, std::vector<Tone>& tones) {
  const double bin_m = d.range_bin_m;
  const unsigned per_bin = scene.clutter_scatterers_per_bin;
  for (std::size_t i = 0; i < chamber.layer_count(); ++i) {
    if (!active[i]) continue;
    const propagation::LayerOptics& layer = chamber.layer(i);
    if (layer.optics.volume_backscatter_m2_per_m3 <= 0.0) continue;
    for (double a = std::max(layer.start_m, bin_m); a < layer.end_m; a += bin_m) {
      const double b = std::min(a + bin_m, layer.end_m);
      const double sigma_m2 =
          chamber.backscatter_cross_section_m2(a, b, d.beam_solid_angle_sr, active);
      for (unsigned s = 0; s < per_bin; ++s) {
        const double range_m = a + (b - a) * rng.uniform();
        const double mean_power_w = received_power_w(d.tx_power_w, d.tx_gain, d.rx_gain,
                                                     d.wavelength_m, sigma_m2 / per_bin, range_m) *
                                    chamber.two_way_transmittance(range_m, active) *
                                    scene.radome_two_way_transmittance;
        // The phase of a random scatterer is uniform anyway: the complex normal carries it.
        tones.push_back({2.0 * range_m, rng.complex_normal(mean_power_w), 0.0, Origin::fog,
                         static_cast<std::int16_t>(i)});
      }
    }
  }
}

}  // namespace

void Scene::validate() const {
  if (centres.empty() || centres.size() > 10000) {
    throw_invalid("target.centres", static_cast<double>(centres.size()), "a count in [1, 10000]");
  }
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const std::string prefix = "target.centres[" + std::to_string(i) + "].";
    const ScatteringCentre& c = centres[i];
    require_in_range(prefix + "range_offset_m", c.range_offset_m, -100.0, 100.0);
    require_in_range(prefix + "lateral_m", c.lateral_m, -100.0, 100.0);
    require_in_range(prefix + "height_m", c.height_m, 0.0, 100.0);
    require_in_range(prefix + "rcs_m2", c.rcs_m2, 0.0, 1e6);
    require_in_range(prefix + "radial_velocity_m_per_s", c.radial_velocity_m_per_s, -300.0, 300.0);
  }
  require_in_range("radar.height_m", sensor_height_m, 0.0, 100.0);
  if (surfaces.size() > 5) {
    throw_invalid("chamber.room", static_cast<double>(surfaces.size()), "at most 5 surfaces");
  }
  for (const SceneSurface& surface : surfaces) {
    if (!surface.permittivity) {
      require_in_range(surface.key + ".reflection_coefficient", surface.reflection_coefficient,
                       -1.0, 1.0);
    }
  }
  require_in_range("target.micro_motion_std_m", micro_motion_std_m, 0.0, 0.1);
  require_in_range("radar.clutter_scatterers_per_bin", clutter_scatterers_per_bin, 1.0, 64.0);
  require_in_range("radome_two_way_transmittance", radome_two_way_transmittance, 0.0, 1.0);
  require_in_range("target_film_reflectance", target_film_reflectance, 0.0, 1.0);
}

SceneSurface coefficient_floor(double reflection_coefficient) {
  return {.plane = {propagation::Surface::floor, 0.0},
          .reflection_coefficient = reflection_coefficient,
          .permittivity = std::nullopt,
          .key = "chamber.room.floor"};
}

std::vector<propagation::RoomPlane> Scene::planes() const {
  std::vector<propagation::RoomPlane> out;
  for (const SceneSurface& surface : surfaces) out.push_back(surface.plane);
  return out;
}

void Scene::check_room(double target_range_m) const {
  const std::vector<propagation::RoomPlane> room = planes();
  // The first plane with `point` on its far side.
  const auto outside = [&](const Eigen::Vector3d& point) -> const SceneSurface* {
    for (const SceneSurface& surface : surfaces) {
      const propagation::RoomPlane plane[] = {surface.plane};
      if (!propagation::inside_room(plane, point)) return &surface;
    }
    return nullptr;
  };
  const auto refuse = [](const SceneSurface& surface, const std::string& what) {
    const bool ceiling = surface.plane.surface == propagation::Surface::ceiling;
    const std::string key = surface.key + (ceiling ? ".height_m" : ".distance_m");
    throw_invalid(key, std::abs(surface.plane.position_m),
                  "a room that holds " + what + " (the radar's frame: docs/radar.md, the room)");
  };
  if (const SceneSurface* s = outside(Eigen::Vector3d(0.0, 0.0, sensor_height_m))) {
    if (s->plane.surface == propagation::Surface::floor) {
      throw_invalid("radar.height_m", sensor_height_m, ">= 0 above the floor");
    }
    refuse(*s, "the radar at radar.height_m = " + message_number(sensor_height_m));
  }
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const ScatteringCentre& c = centres[i];
    const Eigen::Vector3d point(target_range_m + c.range_offset_m, c.lateral_m, c.height_m);
    if (const SceneSurface* s = outside(point)) {
      refuse(*s, "the target's scattering centre " + std::to_string(i) + " at (" +
                     message_number(point.x()) + ", " + message_number(point.y()) + ", " +
                     message_number(point.z()) + ") m");
    }
  }
  for (const SceneObject& object : objects) {
    const propagation::RoomObject& o = object.object;
    const Eigen::Vector3d middle(o.x_m, o.y_m, o.base_height_m + 0.5 * o.height_m);
    if (const SceneSurface* s = outside(middle)) {
      refuse(*s,
             object.key + " at (" + message_number(o.x_m) + ", " + message_number(o.y_m) + ") m");
    }
    // The radar equation needs the object in front of the radar, the radar outside a cylinder.
    const double near_m = std::hypot(o.x_m, o.y_m) -
                          (o.shape == propagation::ObjectShape::cylinder ? o.radius_m : 0.0);
    if (!(o.x_m > 0.0) || !(near_m > 0.0)) {
      throw_invalid(object.key + ".x_m", o.x_m,
                    "> 0, with the radar outside the object (its nearest side ahead of the "
                    "radar)");
    }
  }
}

FarthestEcho farthest_echo(const Scene& scene, double target_range_m) {
  FarthestEcho farthest{.range_m = 0.0, .key = "chamber.target_gap_m", .value = 0.0};
  RadarParams pattern_free;  // only the ranges matter here
  const Eigen::Vector3d radar(0.0, 0.0, scene.sensor_height_m);
  // The centres along the boresight: the 1 m margin covers their lateral and vertical offsets.
  farthest.range_m = target_range_m;
  for (const ScatteringCentre& c : scene.centres) {
    farthest.range_m = std::max(farthest.range_m, target_range_m + c.range_offset_m);
  }
  for (const SceneSurface& surface : scene.surfaces) {
    if (surface.plane.surface != propagation::Surface::back_wall) continue;
    if (surface.plane.position_m > farthest.range_m) {
      farthest = {.range_m = surface.plane.position_m,
                  .key = surface.key + ".distance_m",
                  .value = surface.plane.position_m};
    }
  }
  for (const SceneObject& object : scene.objects) {
    const ObjectEcho echo = object_echo(object, radar, pattern_free, 1.0);
    if (echo.range_m > farthest.range_m) {
      farthest = {.range_m = echo.range_m, .key = object.key + ".x_m", .value = object.object.x_m};
    }
  }
  return farthest;
}

Scene point_target_scene(double rcs_dbsm) {
  Scene scene;
  scene.centres = {ScatteringCentre{.range_offset_m = 0.0,
                                    .lateral_m = 0.0,
                                    .height_m = scene.sensor_height_m,
                                    .rcs_m2 = db_to_power_ratio(rcs_dbsm),
                                    .swerling = Swerling::zero,
                                    .radial_velocity_m_per_s = 0.0}};
  scene.micro_motion_std_m = 0.0;
  return scene;
}

Scene evt_rear_scene(double rcs_dbsm) {
  // Shares of the mean RCS: rear centre (licence plate / boot lid) 40 %, bumper corners 2 x 15 %,
  // rear light clusters 2 x 15 %. Offsets: corners 5 cm behind the rear face, lights 30 cm.
  struct Share {
    double range_offset_m, lateral_m, height_m, fraction;
  };
  constexpr Share shares[] = {{0.00, 0.0, 0.55, 0.40},
                              {0.05, -0.75, 0.45, 0.15},
                              {0.05, 0.75, 0.45, 0.15},
                              {0.30, -0.65, 0.85, 0.15},
                              {0.30, 0.65, 0.85, 0.15}};
  Scene scene;
  scene.centres.clear();
  const double total_m2 = db_to_power_ratio(rcs_dbsm);
  for (const Share& s : shares) {
    scene.centres.push_back({.range_offset_m = s.range_offset_m,
                             .lateral_m = s.lateral_m,
                             .height_m = s.height_m,
                             .rcs_m2 = s.fraction * total_m2,
                             .swerling = Swerling::zero,
                             .radial_velocity_m_per_s = 0.0});
  }
  return scene;
}

void scene_tones(const Scene& scene, const propagation::Chamber& chamber,
                 const propagation::ActiveLayers& active, const RadarParams& params,
                 const RadarDerived& derived, RandomStream& rng, std::vector<Tone>& tones) {
  tones.clear();
  for (const ScatteringCentre& centre : scene.centres) {
    add_centre_paths(scene, centre, chamber.target_range_m(), chamber, active, params, derived, rng,
                     tones);
  }
  add_room_echoes(scene, chamber, active, params, derived, tones);
  add_fog_clutter(scene, chamber, active, derived, rng, tones);
}

}  // namespace fogradar::radar
