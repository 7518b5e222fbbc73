// Parameters of the 905 nm scanning lidar (the study's Hokuyo UTM-30LX-EW, sec. IV-B) and of the
// scene it sees (the EVT, static background segments, the fog bank's lateral width). Every field is
// a key of the scenario's [lidar] section with the same name; defaults are the paper scenario's.
// Keys the datasheet or the study do not give are assumptions, each with its reasoning in
// docs/lidar.md ("Scenario keys").
//
// Coordinates (metres): the sensor at the origin, x along its boresight (towards the fog layers and
// the target, the chamber's range axis), y lateral, positive to the sensor's right.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "fogradar/core/keys.hpp"

namespace fogradar::lidar {

// A static reflecting segment from (x0_m, y0_m) to (x1_m, y1_m): a Lambertian surface of
// reflectivity `reflectivity` at the lidar's wavelength, in the scan plane besides the scenario's
// room (shapes.hpp, scan_plane_room), for what the room does not describe (none by default: the
// study's wall and rain barrels of Fig. 5 are the paper scenario's room). Every key of a
// `[[lidar.background]]` segment is required: no position or reflectivity is a sensible default
// for a wall the user describes. A field starts as NaN, "not given", so that the scenario reader,
// which starts each segment from these defaults, leaves a missing key for validate() to refuse.
struct BackgroundSegment {
  double x0_m = std::numeric_limits<double>::quiet_NaN();
  double y0_m = std::numeric_limits<double>::quiet_NaN();
  double x1_m = std::numeric_limits<double>::quiet_NaN();
  double y1_m = std::numeric_limits<double>::quiet_NaN();
  double reflectivity = std::numeric_limits<double>::quiet_NaN();
};

// Scan-to-scan fluctuation of each layer's optical depth (the study's "due to the dynamic of fog
// bank, some regions are denser than others"): the layer's extinction and backscatter are scaled
// per scan by f = exp(log_std z - log_std^2 / 2), unit mean, with z an AR(1) series in the scan
// index, z_k = rho z_(k-1) + sqrt(1 - rho^2) e_k, z_0 and e_k standard normal, independent per
// layer, rho = exp(-(1 / scan_rate_hz) / correlation_time_s). log_std = 0 switches it off.
struct FogFluctuation {
  double log_std = 0.2;
  double correlation_time_s = 0.5;
};

struct LidarParams {
  double wavelength_m = 905e-9;  // datasheet: 905 nm pulsed laser diode
  double field_of_view_deg =
      90.0;  // simulated part of the datasheet's 270 deg, centred on boresight
  double angular_step_deg = 0.25;   // datasheet
  double scan_rate_hz = 40.0;       // datasheet: 25 ms per scan
  std::size_t scans_per_step = 40;  // the study: 40 scans per box of Fig. 6
  double min_range_m = 0.1;         // datasheet: 0.1 - 30 m guaranteed
  double max_range_m = 30.0;        // end of the recorded waveform
  double pulse_width_ns = 5.0;      // FWHM of the Gaussian pulse (assumption)
  double sample_interval_ns = 0.5;  // receiver sampling of the waveform (assumption)
  // Full overlap of the receiver's field of view with the beam from this range on:
  // O(r) = min(1, (r / overlap_range_m)^2) (assumption).
  double overlap_range_m = 0.5;
  // The threshold is the noise-free peak of a Lambertian target of `threshold_reflectivity` at
  // `threshold_range_m` in clear air (datasheet: 30 m on white Kent sheet, reflectivity ~0.9).
  double threshold_range_m = 30.0;
  double threshold_reflectivity = 0.9;
  // Per range sample, noise alone: the receiver noise std is threshold / Phi^-1(1 - p).
  double false_alarm_probability = 1e-6;
  std::size_t max_echoes = 3;          // datasheet: multi-echo, up to 3 per direction
  double min_echo_separation_m = 1.0;  // leading edges closer than this merge into one echo
  // Reported intensity = min(intensity_saturation, intensity_scale * peak / threshold).
  double intensity_scale = 180.0;
  double intensity_saturation = 65535.0;
  double target_width_m = 1.8;       // the EVT's rear, at the chamber's target range
  double target_offset_m = 0.0;      // lateral (y) position of the EVT's centre
  double target_reflectivity = 0.3;  // 905 nm, Lambertian (assumption)
  double fog_width_m = 3.0;          // lateral width of the fog bank, centred on boresight
  // The scan plane's height above the floor (the mounting height; the scan is horizontal): where
  // it cuts the room's objects (assumption, docs/lidar.md).
  double height_m = 0.5;
  // Water film on the window (the study's water-covered sensor): the pulse and its echoes cross
  // it, propagation::window_film_transmittance at the wavelength, out and back.
  double window_water_film_m = 0.0;
  std::vector<BackgroundSegment> background;
  FogFluctuation fog_fluctuation;

  // Throws InvalidParameter naming "lidar.<key>" (e.g. "lidar.pulse_width_ns",
  // "lidar.fog_fluctuation.log_std", "lidar.background[2].reflectivity") and the allowed range
  // (lidar_keys).
  void validate() const;

  std::size_t beam_count() const;  // floor(field_of_view_deg / angular_step_deg + 1e-9) + 1
  // -fov/2 + beam step: 0 on boresight, + to the right.
  double beam_angle_deg(std::size_t beam) const;
  // Samples of a beam's waveform: floor(2 max_range_m / c / sample interval) + 1, sample k at
  // round-trip time k dt.
  std::size_t samples_per_beam() const;
};

// The keys of [lidar], [lidar.fog_fluctuation] and [[lidar.background]], each with its unit,
// range and source (datasheet, the study, or an assumption with its reasoning).
KeyTable<LidarParams> lidar_keys();
// The keys of one background segment under `prefix` ("lidar.background[2].").
KeyTable<BackgroundSegment> background_segment_keys(std::string prefix);

}  // namespace fogradar::lidar
