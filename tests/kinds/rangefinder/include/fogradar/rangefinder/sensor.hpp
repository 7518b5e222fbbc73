// An ideal optical range finder, the test tree's sensor kind: a pulse at the fog's 550 nm
// extinction, its echo from the target detected when the two-way Beer-Lambert transmittance through
// the active layers, exp(-2 sum beta_i f_i), is at least min_transmittance; each detection reads
// the target range with Gaussian noise. Its keys are [rangefinder]; its files rangefinder_shots.csv
// and rangefinder_summary.json.
#pragma once

#include <cstddef>
#include <memory>

#include "fogradar/sensor/sensor.hpp"

namespace fogradar::rangefinder {

struct RangeFinderParams {
  std::size_t shots_per_step = 5;
  double range_noise_m = 0.02;
  double min_transmittance = 0.1;
};

// The range finder's kind, for the registry: name "rangefinder", stream key 3, its keys over
// RangeFinderParams.
std::shared_ptr<const sensor::SensorKind> sensor_kind();

}  // namespace fogradar::rangefinder
