// Random valid scenarios for the property checker (docs/validation.md, "Property checker"): each
// drawn by its own std::mt19937_64 from a seed, with every value inside the range its key declares
// (`fogradar scenario --keys`; parse_scenario refuses anything else, so a draw outside fails the
// test that reads it), and small enough to run in well under a second: few measurements per step,
// short radar frames, a few lidar beams and scans, small camera frames.
//
// The space is narrower than the key table in these places, each for the reason given:
// - target.radial_velocity_m_per_s stays inside the radar's unambiguous ±λ/(4 T_i): beyond it the
//   velocity folds and the range-Doppler coupling correction moves the range (the run warns,
//   `velocity_fold`), which the target-origin check's range window does not model.
// - The chamber is at most 2/3 of the radar's unambiguous range long and shorter than the lidar's
//   max_range_m, so the target is inside both sensors' view.
// - The room (each of the left wall, right wall, ceiling and back wall present with some
//   probability, 0-4 cylinders and plates) holds the radar, the lidar, the target's centres and
//   every object; a surface whose second-order image paths would reach past the radar's
//   unambiguous range (less 1 m and the window tolerance) is left out, and an object whose echo
//   would is not placed, so that no ghost or room echo folds into the range axis (the origin
//   check's reference does not fold). With the lidar running, its walls and objects are of
//   materials with optical data, no wall is given by a reflection_coefficient and its wavelength
//   is 905 or 1550 nm (docs/lidar.md: what the lidar refuses); every material has radio data at the
//   radar's carrier.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fogradar::property {

// One layer as the generator laid it out (the chamber the checks compare origins with).
struct LayerGeometry {
  double start_m = 0.0;
  double end_m = 0.0;
};

// A point in the room's frame (room_spec.hpp): x along the sensors' boresight, y to the right, z up
// from the floor; the radar and the lidar stand at x = y = 0.
struct Point3 {
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.0;
};

// The room as the generator laid it out: each plane present or not, at its distance.
struct RoomGeometry {
  bool floor = false;         // the plane z = 0
  double left_wall_m = 0.0;   // the plane y = -left_wall_m; 0: none
  double right_wall_m = 0.0;  // the plane y = +right_wall_m; 0: none
  double ceiling_m = 0.0;     // the plane z = ceiling_m; 0: none
  double back_wall_m = 0.0;   // the plane x = back_wall_m; 0: none
  struct Object {
    bool cylinder = true;  // a vertical cylinder, else a vertical plate
    double x_m = 0.0, y_m = 0.0, base_height_m = 0.0, height_m = 0.0;
    double radius_m = 0.0;                // cylinder
    double width_m = 0.0, yaw_deg = 0.0;  // plate: its normal (-cos yaw, sin yaw, 0)
  };
  std::vector<Object> objects;

  // Walls, ceiling or objects: more than the floor the checker drew before it walked rooms.
  bool drawn() const {
    return left_wall_m > 0.0 || right_wall_m > 0.0 || ceiling_m > 0.0 || back_wall_m > 0.0 ||
           !objects.empty();
  }
};

// A drawn scenario: its TOML (over the paper scenario, as `fogradar run --scenario` reads it) and
// the geometry and settings the checks need, known from the draw itself rather than from the run.
struct DrawnScenario {
  std::uint64_t seed = 0;
  std::string toml;
  std::vector<LayerGeometry> layers;   // from the sensor
  std::vector<std::size_t> switching;  // layer indices in the order they come on
  std::size_t max_active_layers = 0;
  double target_range_m = 0.0;
  std::vector<std::string> sensors;
  // radar
  bool ideal_adc = true;     // radar.adc_bits = 0
  bool phase_noise = false;  // radar.phase_noise_rms_rad > 0
  double range_bin_m = 0.0;  // c / (2 B) with the samples filling the chirp
  std::string window;
  double window_mainlobe_half_width_bins = 0.0;
  double target_depth_m = 0.0;  // the target's centres behind its rear face
  double radar_height_m = 0.0;
  // The radar's scattering centres in the room's frame: the point target's, or the EVT rear's five
  // (docs/radar.md: the rear centre, the bumper corners, the light clusters).
  std::vector<Point3> target_centres;
  double target_velocity_m_per_s = 0.0;  // each centre's radial velocity on its direct path
  double range_resolution_m = 0.0;       // c / (2 B): scene.hpp's test of a path the radar resolves
  double max_unambiguous_m_per_s = 0.0;  // lambda / (4 T_i)
  // The range the range-Doppler coupling correction moves per m/s of velocity misread, f_c T_c / B
  // (f_D = 2 v / lambda in the beat frequency, c / (2 S) per Hz).
  double coupling_s = 0.0;
  RoomGeometry room;
  // lidar
  double lidar_pulse_width_s = 0.0;
  double lidar_sample_interval_s = 0.0;
  double lidar_min_echo_separation_m = 0.0;
  double lidar_fog_width_m = 0.0;
  double lidar_target_width_m = 0.0;
  double lidar_target_offset_m = 0.0;
  double lidar_height_m = 0.0;  // its scan plane above the floor
  struct Segment {
    double x0_m, y0_m, x1_m, y1_m;
  };
  std::vector<Segment> lidar_background;
};

DrawnScenario draw_scenario(std::uint64_t seed);

}  // namespace fogradar::property
