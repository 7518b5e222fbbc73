// The lidar as a sensor of the experiment (sensor/sensor.hpp): its keys ([lidar] and
// its sub-tables), one run on the chamber (the Lidar built once, a fog series per step, one scan
// per item), and its result files lidar_echoes.csv, lidar_summary.csv, lidar_summary.json,
// lidar_intensity_boxplot.svg and lidar_scans.svg.
#pragma once

#include <memory>
#include <vector>

#include "fogradar/lidar/lidar.hpp"
#include "fogradar/lidar/summary.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::lidar {

// The lidar's kind, for the registry.
std::shared_ptr<const sensor::SensorKind> sensor_kind();

// The lidar's raw data per scan (docs/data-out.md), by index: the received waveforms, the echoes
// and the ground truth's stretches, in a chamber of `layer_count` layers.
enum RawKindIndex : std::size_t { raw_waveforms = 0, raw_echoes = 1, raw_origins = 2 };
std::vector<sensor::RawKind> lidar_raw_kinds(const LidarParams& params, std::size_t layer_count);

// What a run of the lidar found: the sensor as built (its files need its geometry and derived
// figures), one result per step with the scans by index, and their summary.
class LidarReport : public sensor::SensorSummary {
 public:
  virtual const Lidar& lidar() const = 0;
  virtual const std::vector<LidarStepResult>& steps() const = 0;
  virtual const LidarSummary& summary() const = 0;
};

}  // namespace fogradar::lidar
