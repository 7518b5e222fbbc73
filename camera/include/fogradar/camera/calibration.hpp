// Calibration of the two scene parameters the study's Fig. 7 means pin down (docs/camera.md §6):
// exposure.ambient_level and roi.target.median_reflectance, so that the noise-free mean grey of the
// ROI is `clear_mean_grey` with no layer active and `fog_mean_grey` with the first `fog_layers`
// layers active (the study: 46 at 0 layers, 64 at 2). Every other key keeps its value.
#pragma once

#include <cstddef>

#include "fogradar/camera/camera.hpp"

namespace fogradar::camera {

struct CalibrationResult {
  CameraParams params;           // the input with the two calibrated keys replaced
  double clear_mean_grey = 0.0;  // noise-free means the calibrated params give
  double fog_mean_grey = 0.0;
};

// Nested bisection: for each ambient level the target median that gives clear_mean_grey, and the
// ambient level at which fog_mean_grey follows. Throws InvalidParameter naming "clear_mean_grey" or
// "fog_mean_grey" when no pair within the keys' ranges reproduces the means.
CalibrationResult calibrate_to_means(const Camera& camera, double clear_mean_grey,
                                     std::size_t fog_layers, double fog_mean_grey);

}  // namespace fogradar::camera
