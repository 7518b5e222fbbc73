#include "fogradar/lidar/summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fogradar/stats/box_plot.hpp"

namespace fogradar::lidar {

// Eq. 4: I = I_0 rho_obj tau^(2 layers) (paper sec. II-B), one tau per layer.
double eq4_target_intensity(const Lidar& lidar, const propagation::ActiveLayers& active) {
  const std::vector<double> no_fluctuation(lidar.layer_count(), 1.0);
  const std::vector<double> clear =
      lidar
          .waveform(lidar.target_beam(), propagation::ActiveLayers(lidar.layer_count(), false),
                    no_fluctuation)
          .target;
  const double clear_peak = clear.empty() ? 0.0 : *std::max_element(clear.begin(), clear.end());
  double two_way_optical_depth = 0.0;
  for (std::size_t i = 0; i < lidar.layer_count(); ++i) {
    if (!active.at(i)) continue;
    two_way_optical_depth +=
        2.0 * lidar.layer_extinction_per_m(i) * (lidar.layer_end_m(i) - lidar.layer_start_m(i));
  }
  const LidarParams& params = lidar.params();
  const double clear_intensity = params.intensity_scale * clear_peak / lidar.threshold();
  return std::min(params.intensity_saturation, clear_intensity * std::exp(-two_way_optical_depth));
}

LidarSummary summarize(const Lidar& lidar, const std::vector<LidarStepResult>& steps,
                       std::span<const propagation::ActiveLayers> active) {
  LidarSummary summary;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const LidarStepResult& step = steps[k];
    LidarStepSummary s;
    s.eq4_intensity = eq4_target_intensity(lidar, active[k]);
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
