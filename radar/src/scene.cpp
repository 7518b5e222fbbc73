#include "fogradar/radar/scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::radar {
namespace {

constexpr double degree_rad = pi / 180.0;

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

// One leg (sensor to centre or centre to sensor) of a path: its length and one-way amplitude
// pattern factor sqrt(g_az g_el), for the direct ray or the ray via the floor image.
struct Leg {
  double length_m;
  double pattern_amplitude;
};

Leg leg(double along_m, double lateral_m, double vertical_m, const RadarParams& p) {
  const double horizontal_m = std::hypot(along_m, lateral_m);
  const double azimuth = std::atan2(lateral_m, along_m);
  const double elevation = std::atan2(vertical_m, horizontal_m);
  const double gain = gaussian_beam_power(azimuth, p.azimuth_beamwidth_deg * degree_rad) *
                      gaussian_beam_power(elevation, p.elevation_beamwidth_deg * degree_rad);
  return {std::hypot(horizontal_m, vertical_m), std::sqrt(gain)};
}

void add_centre_paths(const Scene& scene, const ScatteringCentre& centre, double target_range_m,
                      const propagation::Chamber& chamber, const propagation::ActiveLayers& active,
                      const RadarParams& p, const RadarDerived& d, RandomStream& rng,
                      std::vector<Tone>& tones) {
  const double rcs_m2 = fluctuated_rcs_m2(centre, rng);
  const double jitter_m = scene.micro_motion_std_m * rng.normal();
  const double along_m = target_range_m + centre.range_offset_m + jitter_m;
  const Leg direct = leg(along_m, centre.lateral_m, centre.height_m - scene.sensor_height_m, p);
  // The floor image of the centre lies as far below the floor as the centre is above it.
  const Leg via_floor =
      leg(along_m, centre.lateral_m, -(centre.height_m + scene.sensor_height_m), p);
  const double gamma = scene.floor.reflection_coefficient;

  // Monostatic two-ray field: (direct + Gamma floor)^2 expands into three delays; the mixed path
  // occurs twice (out direct, back via floor, and the reverse).
  struct Path {
    const Leg& out;
    const Leg& back;
    double coefficient;
  };
  const Path paths[] = {{direct, direct, 1.0},
                        {direct, via_floor, 2.0 * gamma},
                        {via_floor, via_floor, gamma * gamma}};
  const std::size_t path_count = scene.floor.enabled ? 3 : 1;
  for (std::size_t i = 0; i < path_count; ++i) {
    const Path& path = paths[i];
    // Bistatic radar equation per leg pair: P = Pt Gt Gr lambda^2 sigma / ((4 pi)^3 r1^2 r2^2).
    const double geometric_mean_range_m = std::sqrt(path.out.length_m * path.back.length_m);
    const double power_w = received_power_w(d.tx_power_w, d.tx_gain, d.rx_gain, d.wavelength_m,
                                            rcs_m2, geometric_mean_range_m);
    const double pattern = path.out.pattern_amplitude * path.back.pattern_amplitude;
    const double length_m = path.out.length_m + path.back.length_m;
    const double transmittance = chamber.two_way_transmittance(0.5 * length_m, active) *
                                 scene.radome_two_way_transmittance * scene.target_film_reflectance;
    tones.push_back(
        {length_m,
         path.coefficient * pattern * path_amplitude(power_w * transmittance, length_m, d),
         centre.radial_velocity_m_per_s, Origin::target, -1});
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
  require_in_range("target.floor_reflection_coefficient", floor.reflection_coefficient, -1.0, 1.0);
  require_in_range("target.micro_motion_std_m", micro_motion_std_m, 0.0, 0.1);
  require_in_range("radar.clutter_scatterers_per_bin", clutter_scatterers_per_bin, 1.0, 64.0);
  require_in_range("radome_two_way_transmittance", radome_two_way_transmittance, 0.0, 1.0);
  require_in_range("target_film_reflectance", target_film_reflectance, 0.0, 1.0);
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
  add_fog_clutter(scene, chamber, active, derived, rng, tones);
}

}  // namespace fogradar::radar
