// Per-step statistics of the lidar (Fig. 6's box of the target's intensity per active-layer count,
// a missing target counted as 0 as the study plots it) and its sensor limit (docs/lidar.md).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "fogradar/lidar/lidar.hpp"
#include "fogradar/lidar/params.hpp"
#include "fogradar/stats/box_plot.hpp"

namespace fogradar::lidar {

inline constexpr const char* lidar_sensor_limit_criterion =
    "first active-layer count at which fewer than 50 % of the scans detect the target in the beam "
    "through its centre (a target-origin echo) with no fog-origin echo in that beam at least as "
    "intense";

struct LidarStepSummary {
  std::size_t active_layers = 0;
  std::size_t scans = 0;
  std::size_t target_detections = 0;  // scans whose target-centre beam has a target echo
  double target_detection_rate = 0.0;
  double target_told_rate = 0.0;    // detected and not outshone by a fog echo
  stats::BoxPlot target_intensity;  // one value per scan, 0 where the target is missing
  double fog_echo_rate = 0.0;       // beams through the fog with a fog echo / beams through it
  double median_first_echo_range_m = 0.0;  // of beams through the fog; NaN when none has an echo
  std::size_t beams_through_fog = 0;       // summed over the step's scans
  double eq4_intensity = 0.0;  // the study's eq. 4 for the target echo (eq4_target_intensity)
};

struct LidarSummary {
  std::vector<LidarStepSummary> steps;
  std::optional<std::size_t> sensor_limit_layers;  // lidar_sensor_limit_criterion; empty if never
};

inline constexpr double lidar_sensor_limit_fraction = 0.5;

// The study's eq. 4 for the target echo behind the `active` layers, I = I_0 rho_obj prod_i tau_i^2
// with tau_i = exp(-alpha_i f_i) of each active layer, I_0 rho_obj the clear-weather target echo's
// noise-free intensity in the beam through the target's centre; the sensor's saturation applies
// (a saturated clear echo makes the prediction a lower bound).
double eq4_target_intensity(const Lidar& lidar, const propagation::ActiveLayers& active);

// Step k's statistics; its layers `active[k]`.
LidarSummary summarize(const Lidar& lidar, const std::vector<LidarStepResult>& steps,
                       std::span<const propagation::ActiveLayers> active);

}  // namespace fogradar::lidar
