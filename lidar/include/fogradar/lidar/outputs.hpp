// The lidar's result files as strings (experiment/ writes them into the run's result set) and its
// terminal table and memory estimate.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fogradar/lidar/lidar.hpp"
#include "fogradar/lidar/summary.hpp"
#include "fogradar/sensor/step_table.hpp"

namespace fogradar::lidar {

// lidar_echoes.csv: header "active_layers,item,angle_deg,echo,range_m,intensity,origin,layer", one
// row per echo, item = the scan's index in its step, layer a fog echo's chamber layer (0 nearest
// the sensor), -1 for the others.
std::string lidar_echoes_csv(const Lidar& lidar, const std::vector<LidarStepResult>& steps);
// The per-step statistics as typed columns: lidar_summary.csv (lidar_step_table(s).csv()), the
// steps of lidar_summary_json, and the columns of lidar_summary_table.
sensor::StepTable lidar_step_table(const LidarSummary& summary);
// The object summary.json embeds (and lidar_summary.json holds): per step statistics, the sensor
// limit and its criterion, and the derived sensor figures (alpha, beta_pi per layer, threshold,
// clear-weather margin at the target).
nlohmann::json lidar_summary_json(const Lidar& lidar, const LidarSummary& summary);
// lidar_intensity_boxplot.svg (the study's Fig. 6): target intensity per active-layer count with
// the detection rate strip and the sensor limit marked.
std::string lidar_intensity_boxplot_svg(const Lidar& lidar, const LidarSummary& summary);
// lidar_scans.svg (the study's Fig. 5): the first scan of every step as a top view, sensor at the
// bottom, fog layers and the target region marked, echoes coloured by origin.
std::string lidar_scans_svg(const Lidar& lidar, const std::vector<LidarStepResult>& steps);
// The per-step table `fogradar run` prints for the lidar.
std::string lidar_summary_table(const LidarSummary& summary);

// Upper estimate of the bytes a run holds for the lidar: the step results (max_echoes per beam per
// scan at most, plus the per-scan vectors), per-thread waveform workspaces and the result files'
// strings. `steps` = number of steps, `threads` = worker threads.
std::size_t lidar_memory_bytes(const LidarParams& params, std::size_t steps, unsigned threads);

}  // namespace fogradar::lidar
