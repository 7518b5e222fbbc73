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
  double target_depth_m = 0.0;        // the target's centres behind its rear face
  double target_height_span_m = 0.0;  // largest sensor height + centre height (multipath)
  // lidar
  double lidar_pulse_width_s = 0.0;
  double lidar_sample_interval_s = 0.0;
  double lidar_min_echo_separation_m = 0.0;
  double lidar_fog_width_m = 0.0;
  double lidar_target_width_m = 0.0;
  double lidar_target_offset_m = 0.0;
  struct Segment {
    double x0_m, y0_m, x1_m, y1_m;
  };
  std::vector<Segment> lidar_background;
};

DrawnScenario draw_scenario(std::uint64_t seed);

}  // namespace fogradar::property
