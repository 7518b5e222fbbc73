#include "fogradar/camera/calibration.hpp"

#include <cmath>

#include "fogradar/core/error.hpp"

namespace fogradar::camera {
namespace {

constexpr int bisection_steps = 60;

double mean_grey(const Camera& camera, const CameraParams& params,
                 const propagation::ActiveLayers& active) {
  const Camera scene = camera.with_scene(params);
  return scene.expected_mean_grey(scene.step_optics(active));
}

}  // namespace

CalibrationResult calibrate_to_means(const Camera& camera, double clear_mean_grey,
                                     std::size_t fog_layers, double fog_mean_grey) {
  require_in_range("clear_mean_grey", clear_mean_grey, 1.0, 254.0);
  require_in_range("fog_mean_grey", fog_mean_grey, 1.0, 254.0);
  require_in_range("fog_layers", static_cast<double>(fog_layers), 1.0,
                   static_cast<double>(camera.layer_count()));
  const propagation::ActiveLayers clear(camera.layer_count(), false);
  const propagation::ActiveLayers fog =
      propagation::first_layers_active(fog_layers, camera.layer_count());

  // The validated ranges of the two keys (params.cpp), in logarithms.
  const double log_level_min = std::log(1e-4);
  const double log_level_max = std::log(1.0);
  const double log_median_min = std::log(1e-4);
  const double log_median_max = std::log(1.5);
  CameraParams params = camera.params();
  params.exposure.mode = ExposureMode::fixed;
  // The target median holding the clear mean at a given ambient level (the mean rises with it).
  const auto fit_clear = [&](double log_level) {
    params.exposure.ambient_level = std::exp(log_level);
    double low = log_median_min;
    double high = log_median_max;
    for (int i = 0; i < bisection_steps; ++i) {
      const double mid = 0.5 * (low + high);
      params.roi.target.median_reflectance = std::exp(mid);
      (mean_grey(camera, params, clear) < clear_mean_grey ? low : high) = mid;
    }
    params.roi.target.median_reflectance = std::exp(0.5 * (low + high));
  };
  // With the clear mean held, the fogged mean rises with the ambient level (more airlight).
  double low = log_level_min;
  double high = log_level_max;
  for (int i = 0; i < bisection_steps; ++i) {
    const double mid = 0.5 * (low + high);
    fit_clear(mid);
    (mean_grey(camera, params, fog) < fog_mean_grey ? low : high) = mid;
  }
  fit_clear(0.5 * (low + high));

  CalibrationResult result{params, mean_grey(camera, params, clear),
                           mean_grey(camera, params, fog)};
  if (std::abs(result.clear_mean_grey - clear_mean_grey) > 0.01) {
    throw_invalid("clear_mean_grey", clear_mean_grey,
                  "reachable with camera.roi.target.median_reflectance in [1e-4, 1.5]");
  }
  if (std::abs(result.fog_mean_grey - fog_mean_grey) > 0.01) {
    throw_invalid("fog_mean_grey", fog_mean_grey,
                  "reachable with camera.exposure.ambient_level in [1e-4, 1]");
  }
  return result;
}

}  // namespace fogradar::camera
