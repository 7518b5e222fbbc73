// What the radar looks at: scattering centres placed around the chamber's target position, an
// optional floor (two-ray) multipath, and the fog volume clutter of the active layers. A scene is
// turned, per measurement, into the list of propagation paths ("tones") the receiver sums.
#pragma once

#include <complex>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/radar/origin.hpp"
#include "fogradar/radar/params.hpp"

namespace fogradar::radar {

// Swerling fluctuation of a centre's RCS from one measurement (frame) to the next: 0 constant,
// 1 exponential (many equal scatterers), 3 chi-square with 4 degrees of freedom (one dominant
// scatterer plus many small). Swerling 1957; Skolnik, Introduction to Radar Systems, sec. 2.8.
enum class Swerling { zero = 0, one = 1, three = 3 };
inline constexpr auto swerling_names =
    enum_names<Swerling>({{Swerling::zero, "0"}, {Swerling::one, "1"}, {Swerling::three, "3"}});
constexpr std::string_view to_string(Swerling model) noexcept { return swerling_names.name(model); }

// A scattering centre relative to the target reference point, which sits on the radar boresight at
// the chamber's target range (sensor to target plane).
struct ScatteringCentre {
  double range_offset_m = 0.0;  // along boresight, + away from the radar
  double lateral_m = 0.0;       // across boresight, horizontal
  double height_m = 0.5;        // above the floor
  double rcs_m2 = 10.0;         // mean RCS
  Swerling swerling = Swerling::zero;
  double radial_velocity_m_per_s = 0.0;  // + receding
};

// Two-ray floor reflection (Skolnik, Radar Handbook 3rd ed., ch. 26): each path to a centre also
// exists via its image below a flat floor, with a real amplitude reflection coefficient.
struct FloorMultipath {
  bool enabled = false;
  // In [-1, 1]; -0.7: smooth concrete near grazing incidence (docs/scenario.md), negative for the
  // phase reversal of both polarisations there.
  double reflection_coefficient = -0.7;
};

struct Scene {
  std::vector<ScatteringCentre> centres{ScatteringCentre{}};
  double sensor_height_m = 0.5;  // radar above the floor; boresight horizontal
  FloorMultipath floor;
  // Standard deviation of each centre's independent sub-wavelength displacement along the line of
  // sight per measurement: the mechanical jitter of a real target and mount. 0.2 mm (lambda/19 at
  // 77 GHz) moves the two-way phase by 0.65 rad rms; docs/radar.md justifies the default.
  double micro_motion_std_m = 0.2e-3;
  // Random point scatterers per range bin that represent the fog's volume clutter. Fog nearer than
  // one range bin to the radar is left out: the far-field radar equation (R^-4) does not hold there
  // (a 25 dBi antenna's far field starts at about 1 m at 77 GHz) and the radar cannot resolve it.
  unsigned clutter_scatterers_per_bin = 4;
  // The water-covered sensor and target (the made radar sets them from [radar.radome] and
  // [target] water_film_m): the power through the radome and its film, out and back, on every
  // path, fog clutter included; and the reflectance of the target's film on metal, on the target's
  // paths. 1: dry, no radome.
  double radome_two_way_transmittance = 1.0;
  double target_film_reflectance = 1.0;

  // Names the key of a field a scenario sets ("radar.height_m", "target.micro_motion_std_m"), or
  // "target.centres[i].<field>" for a centre.
  void validate() const;
};

// One non-fluctuating centre on boresight at the sensor height, no micro-motion, no floor.
Scene point_target_scene(double rcs_dbsm);

// Rear of the Euro NCAP Vehicle Target as a cluster of scattering centres whose mean RCS adds up to
// `rcs_dbsm` (about 10 dBsm, vehicle rears 7-12 dBsm per the study's ref. [25]): a dominant centre
// at the rear centre and four weaker ones at the bumper corners and light clusters. Geometry after
// the EVT's 1.8 m x 1.4 m rear (ADAC, the study's ref. [19]); the split of RCS among centres is an
// assumption stated in docs/radar.md.
Scene evt_rear_scene(double rcs_dbsm = 10.0);

// A propagation path as the receiver sees it: two-way path length, complex amplitude (sqrt(W)) at
// the start of the frame, radial velocity, what it comes from (target or fog, never noise) and,
// for fog, the chamber layer it lies in (the index in chamber.layers, 0-based from the sensor).
struct Tone {
  double path_length_m;
  std::complex<double> amplitude;
  double radial_velocity_m_per_s;
  Origin origin;
  std::int16_t layer = -1;  // fog only; -1 for a target path
};

// The paths of one measurement: every scattering centre (direct, and with the floor the
// direct-floor, floor-direct and floor-floor paths), each weighted by the radar equation, the
// antenna pattern, the chamber's two-way transmittance and the water films; plus the fog clutter
// of the active layers, through the radome. Random draws (RCS fluctuation, micro-motion, clutter)
// come from `rng`. `tones` is cleared and refilled (no allocation once it has the capacity).
void scene_tones(const Scene& scene, const propagation::Chamber& chamber,
                 const propagation::ActiveLayers& active, const RadarParams& params,
                 const RadarDerived& derived, RandomStream& rng, std::vector<Tone>& tones);

}  // namespace fogradar::radar
