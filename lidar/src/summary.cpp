#include "fogradar/lidar/summary.hpp"

#include <limits>

#include "fogradar/stats/box_plot.hpp"

namespace fogradar::lidar {

LidarSummary summarize(const LidarParams& params, const std::vector<LidarStepResult>& steps) {
  (void)params;
  LidarSummary summary;
  for (const LidarStepResult& step : steps) {
    LidarStepSummary s;
    s.active_layers = step.active_layers;
    s.scans = step.scans.size();
    std::vector<double> intensities;
    std::vector<double> first_ranges;
    std::size_t told = 0;
    std::size_t with_fog_echo = 0;
    for (const LidarScan& scan : step.scans) {
      intensities.push_back(scan.target_intensity);
      if (scan.target_detected) ++s.target_detections;
      if (scan.target_detected && !scan.fog_outshines_target) ++told;
      s.beams_through_fog += scan.beams_through_fog;
      with_fog_echo += scan.beams_through_fog_with_fog_echo;
      first_ranges.insert(first_ranges.end(), scan.first_echo_range_through_fog_m.begin(),
                          scan.first_echo_range_through_fog_m.end());
    }
    if (s.scans > 0) {
      const double n = static_cast<double>(s.scans);
      s.target_detection_rate = static_cast<double>(s.target_detections) / n;
      s.target_told_rate = static_cast<double>(told) / n;
    }
    s.target_intensity = stats::box_plot(intensities);
    s.fog_echo_rate = s.beams_through_fog == 0 ? std::numeric_limits<double>::quiet_NaN()
                                               : static_cast<double>(with_fog_echo) /
                                                     static_cast<double>(s.beams_through_fog);
    s.median_first_echo_range_m = first_ranges.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                       : stats::median(first_ranges);
    if (!summary.sensor_limit_layers && s.scans > 0 &&
        s.target_told_rate < lidar_sensor_limit_fraction) {
      summary.sensor_limit_layers = s.active_layers;
    }
    summary.steps.push_back(std::move(s));
  }
  return summary;
}

}  // namespace fogradar::lidar
