// What the radar looks at: scattering centres placed around the chamber's target position, the
// room around them (its planes, whose image paths carry every centre's echo to second order, the
// back wall's own return, and the objects standing in the hall), and the fog volume clutter of the
// active layers. A scene is turned, per measurement, into the list of propagation paths ("tones")
// the receiver sums.
#pragma once

#include <complex>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/room_spec.hpp"
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

// A plane of the room as the radar's paths meet it: a real amplitude reflection coefficient for
// every ray, or a material's permittivity at the radar's carrier, whose Fresnel coefficients each
// ray takes at its own grazing angle for the radar's polarisation (room_paths.hpp).
struct SceneSurface {
  propagation::RoomPlane plane;
  double reflection_coefficient = -0.7;              // in [-1, 1]; without a permittivity
  std::optional<std::complex<double>> permittivity;  // a material's, eps' + i eps''
  std::string key;  // its scenario table, "chamber.room.floor", for messages
};

// The floor at z = 0 reflecting with a real coefficient: the two-ray floor (Skolnik, Radar
// Handbook 3rd ed., ch. 26).
SceneSurface coefficient_floor(double reflection_coefficient);

// A static object of the room with what its closed-form RCS needs besides its shape: the normal-
// incidence Fresnel power reflectance of its material at the carrier (1 for a perfect conductor).
struct SceneObject {
  propagation::RoomObject object;
  double reflectance = 1.0;
  std::string key;  // "chamber.objects[2]"
};

struct Scene {
  std::vector<ScatteringCentre> centres{ScatteringCentre{}};
  double sensor_height_m = 0.5;  // radar above the floor; boresight horizontal
  // The room's present planes (none: free space), in room_planes' order, and its objects. The radar
  // stands at (0, 0, sensor_height_m) in the room's frame (room_spec.hpp), a centre at (target
  // range + range_offset_m, lateral_m, height_m).
  std::vector<SceneSurface> surfaces;
  std::vector<SceneObject> objects;
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
  // The room's planes (surfaces' planes, in order).
  std::vector<propagation::RoomPlane> planes() const;
  // Throws InvalidParameter unless the radar and every centre (at a target range of
  // `target_range_m`) stand inside the room, off its planes, and every object inside it, naming the
  // surface's or object's key.
  void check_room(double target_range_m) const;
};

// The farthest echo of a scene that a scenario places: the target's direct paths (key
// "chamber.target_gap_m", its value left 0 for the caller), the back wall's own return
// ("chamber.room.back_wall.distance_m"), an object's ("chamber.objects[0].x_m"); its range and the
// key with its value. The target's paths via the room are not bounded: one longer than the
// unambiguous range folds into it, as an aliased ghost (docs/radar.md §3.3).
struct FarthestEcho {
  double range_m = 0.0;
  std::string key;
  double value = 0.0;  // the key's value
};
FarthestEcho farthest_echo(const Scene& scene, double target_range_m);

// One non-fluctuating centre on boresight at the sensor height, no micro-motion, no room.
Scene point_target_scene(double rcs_dbsm);

// Rear of the Euro NCAP Vehicle Target as a cluster of scattering centres whose mean RCS adds up to
// `rcs_dbsm` (about 10 dBsm, vehicle rears 7-12 dBsm per the study's ref. [25]): a dominant centre
// at the rear centre and four weaker ones at the bumper corners and light clusters. Geometry after
// the EVT's 1.8 m x 1.4 m rear (ADAC, the study's ref. [19]); the split of RCS among centres is an
// assumption stated in docs/radar.md.
Scene evt_rear_scene(double rcs_dbsm = 10.0);

// A propagation path as the receiver sees it: two-way path length, complex amplitude (sqrt(W)) at
// the start of the frame, radial velocity (half the rate of change of the path's length), what it
// comes from (never noise: target, multipath, room or fog) and, for fog, the chamber layer it lies
// in (the index in chamber.layers, 0-based from the sensor). A target path via the room is
// `target` when the radar cannot resolve it from its centre's direct path (its range within the
// range resolution c / (2 B) and its velocity within the velocity resolution of the direct
// path's), `multipath` (a ghost) otherwise.
struct Tone {
  double path_length_m;
  std::complex<double> amplitude;
  double radial_velocity_m_per_s;
  Origin origin;
  std::int16_t layer = -1;  // fog only; -1 otherwise
};

// The paths of one measurement: every scattering centre's two-way paths through the room
// (room_paths .hpp: the direct path, and every pair of one-way image paths of at most second order
// in all), each weighted by the bistatic radar equation, its reflection coefficients, the antenna
// pattern at its departure and arrival, the chamber's two-way transmittance at half its length and
// the water films; the room's own echoes (the back wall's specular return, each object by its
// closed-form RCS); plus the fog clutter of the active layers, through the radome. Random draws
// (RCS fluctuation, micro-motion, clutter) come from `rng`. `tones` is cleared and refilled (no
// allocation once it has the capacity).
void scene_tones(const Scene& scene, const propagation::Chamber& chamber,
                 const propagation::ActiveLayers& active, const RadarParams& params,
                 const RadarDerived& derived, RandomStream& rng, std::vector<Tone>& tones);

}  // namespace fogradar::radar
