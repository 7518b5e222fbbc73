#include "fogradar/lidar/params.hpp"

#include <cmath>
#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::lidar {
namespace {

void require_count(const char* field, std::size_t value, std::size_t low, std::size_t high) {
  require_in_range(field, static_cast<double>(value), static_cast<double>(low),
                   static_cast<double>(high));
}

// Scene coordinates are bounded by the largest chamber a scenario describes (propagation's 1e4 m).
constexpr double max_coordinate_m = 1e4;

}  // namespace

std::vector<BackgroundSegment> default_background() {
  std::vector<BackgroundSegment> segments{
      {.x0_m = 0.5, .y0_m = -3.0, .x1_m = 12.0, .y1_m = -3.0, .reflectivity = 0.5}};
  for (const double x_m : {2.5, 3.5, 4.5, 5.5}) {
    segments.push_back({.x0_m = x_m, .y0_m = -2.3, .x1_m = x_m, .y1_m = -1.7, .reflectivity = 0.3});
  }
  return segments;
}

void LidarParams::validate() const {
  // 400 nm - 2 um: the optical window of the Segelstein water index the fog is resolved with.
  require_in_range("lidar.wavelength_m", wavelength_m, 400e-9, 2e-6);
  require_in_range("lidar.field_of_view_deg", field_of_view_deg, 0.0, 360.0);
  require_in_range("lidar.angular_step_deg", angular_step_deg, 0.01, 10.0);
  require_in_range("lidar.scan_rate_hz", scan_rate_hz, 0.1, 1000.0);
  require_count("lidar.scans_per_step", scans_per_step, 1, 100000);
  require_in_range("lidar.min_range_m", min_range_m, 0.0, 100.0);
  if (!(max_range_m > min_range_m && max_range_m <= 1000.0)) {
    throw_invalid("lidar.max_range_m", max_range_m,
                  "in (lidar.min_range_m = " + stats::format_number(min_range_m) + ", 1000]");
  }
  require_in_range("lidar.pulse_width_ns", pulse_width_ns, 0.1, 1000.0);
  if (!(sample_interval_ns >= 0.01 && sample_interval_ns <= 0.5 * pulse_width_ns)) {
    throw_invalid(
        "lidar.sample_interval_ns", sample_interval_ns,
        "in [0.01, lidar.pulse_width_ns / 2 = " + stats::format_number(0.5 * pulse_width_ns) +
            "] (at least two samples per pulse width)");
  }
  // A record of more than 1e6 samples per beam is a typo, not a receiver.
  if (2.0 * max_range_m / 299792458.0 / (sample_interval_ns * 1e-9) > 1e6) {
    throw_invalid("lidar.sample_interval_ns", sample_interval_ns,
                  "such that 2 lidar.max_range_m / c / interval <= 1e6 samples per beam");
  }
  require_in_range("lidar.overlap_range_m", overlap_range_m, 0.0, 100.0);
  require_in_range("lidar.threshold_range_m", threshold_range_m, 0.1, 1000.0);
  if (!(threshold_reflectivity > 0.0 && threshold_reflectivity <= 1.0)) {
    throw_invalid("lidar.threshold_reflectivity", threshold_reflectivity, "in (0, 1]");
  }
  if (!(false_alarm_probability > 0.0 && false_alarm_probability <= 0.1)) {
    throw_invalid("lidar.false_alarm_probability", false_alarm_probability, "in (0, 0.1]");
  }
  require_count("lidar.max_echoes", max_echoes, 1, 8);
  require_in_range("lidar.min_echo_separation_m", min_echo_separation_m, 0.0, 100.0);
  require_positive("lidar.intensity_scale", intensity_scale);
  require_positive("lidar.intensity_saturation", intensity_saturation);
  require_in_range("lidar.target_width_m", target_width_m, 0.0, 100.0);
  require_in_range("lidar.target_offset_m", target_offset_m, -100.0, 100.0);
  require_in_range("lidar.target_reflectivity", target_reflectivity, 0.0, 1.0);
  require_in_range("lidar.fog_width_m", fog_width_m, 0.0, max_coordinate_m);
  if (background.size() > 1000) {
    throw_invalid("lidar.background", static_cast<double>(background.size()),
                  "a segment count in [0, 1000]");
  }
  for (std::size_t i = 0; i < background.size(); ++i) {
    const std::string key = "lidar.background[" + std::to_string(i) + "].";
    const BackgroundSegment& s = background[i];
    require_in_range(key + "x0_m", s.x0_m, -max_coordinate_m, max_coordinate_m);
    require_in_range(key + "y0_m", s.y0_m, -max_coordinate_m, max_coordinate_m);
    require_in_range(key + "x1_m", s.x1_m, -max_coordinate_m, max_coordinate_m);
    require_in_range(key + "y1_m", s.y1_m, -max_coordinate_m, max_coordinate_m);
    if (s.x0_m == s.x1_m && s.y0_m == s.y1_m) {
      throw_invalid(key + "x1_m", s.x1_m,
                    "a point distinct from (x0_m, y0_m): a segment of length > 0");
    }
    require_in_range(key + "reflectivity", s.reflectivity, 0.0, 1.0);
  }
  require_in_range("lidar.fog_fluctuation.log_std", fog_fluctuation.log_std, 0.0, 2.0);
  require_positive("lidar.fog_fluctuation.correlation_time_s", fog_fluctuation.correlation_time_s);
  if (!std::isfinite(fog_fluctuation.correlation_time_s)) {
    throw_invalid("lidar.fog_fluctuation.correlation_time_s", fog_fluctuation.correlation_time_s,
                  "finite and > 0");
  }
  if (beam_count() > 100000) {
    throw_invalid("lidar.angular_step_deg", angular_step_deg,
                  "such that lidar.field_of_view_deg / step + 1 <= 100000 beams");
  }
}

std::size_t LidarParams::beam_count() const {
  return static_cast<std::size_t>(std::floor(field_of_view_deg / angular_step_deg + 1e-9)) + 1;
}

}  // namespace fogradar::lidar
