// The paper scenario's lidar part alone, at one thread: 5 steps (0-4 active layers) x 40 scans of
// the default LidarParams in the default chamber (propagation::ChamberSpec defaults = the study's
// chamber and fog, examples/paper.toml), seed 1, streams as experiment/ keys them
// (sensor_stream(seed, lidar::stream_key, step, index)). Prints the lidar's table, the wall time of
// the measurement and of the result files, and writes the lidar's result files into the directory
// given as the first argument (if any). Run:
//   ./build/release/bench/lidar_paper [out-dir]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "fogradar/core/random.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/lidar/summary.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"

int main(int argc, char** argv) {
  using namespace fogradar;
  using Clock = std::chrono::steady_clock;
  const std::uint64_t seed = 1;
  const propagation::SegelsteinTable table;
  const propagation::ChamberSpec chamber;
  const lidar::LidarParams params;
  const auto t0 = Clock::now();
  const lidar::Lidar sensor(params, chamber, table);
  const auto t1 = Clock::now();
  std::vector<lidar::LidarStepResult> steps;
  std::vector<propagation::ActiveLayers> actives;
  for (std::size_t step = 0; step <= chamber.layers.size(); ++step) {
    const propagation::ActiveLayers& active =
        actives.emplace_back(propagation::first_layers_active(step, chamber.layers.size()));
    const lidar::FogFluctuationSeries fog = sensor.fog_fluctuation(
        sensor_stream(seed, lidar::stream_key, step, sensor.fog_series_index()));
    lidar::LidarStepResult result{.active_layers = step, .scans = {}};
    for (std::size_t s = 0; s < params.scans_per_step; ++s) {
      RandomStream stream = sensor_stream(seed, lidar::stream_key, step, s);
      result.scans.push_back(sensor.measure(active, fog.scan(s), stream));
    }
    steps.push_back(std::move(result));
  }
  const auto t2 = Clock::now();
  const lidar::LidarSummary summary = lidar::summarize(sensor, steps, actives);
  const std::vector<std::pair<std::string, std::string>> files = {
      {"lidar_echoes.csv", lidar::lidar_echoes_csv(sensor, steps)},
      {"lidar_summary.csv", lidar::lidar_step_table(summary).csv()},
      {"lidar_summary.json", lidar::lidar_summary_json(sensor, summary).dump(2) + "\n"},
      {"lidar_intensity_boxplot.svg", lidar::lidar_intensity_boxplot_svg(sensor, summary)},
      {"lidar_scans.svg", lidar::lidar_scans_svg(sensor, steps)}};
  const auto t3 = Clock::now();
  std::cout << lidar::lidar_summary_table(summary);
  const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  std::printf(
      "alpha %.4g /m, beta_pi %.4g /m/sr, lidar ratio %.4g sr, threshold %.4g, noise std %.4g\n",
      sensor.layer_extinction_per_m(0), sensor.layer_backscatter_per_m_sr(0),
      sensor.layer_extinction_per_m(0) / sensor.layer_backscatter_per_m_sr(0), sensor.threshold(),
      sensor.noise_std());
  std::printf("construction %.3f s, measurement %.3f s (%zu beams), result files %.3f s\n",
              seconds(t0, t1), seconds(t1, t2),
              sensor.beam_count() * params.scans_per_step * steps.size(), seconds(t2, t3));
  std::size_t bytes = 0;
  for (const auto& [name, content] : files) bytes += content.size();
  std::printf("result files: %zu bytes\n", bytes);
  if (argc > 1) {
    const std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    for (const auto& [name, content] : files) std::ofstream(dir / name) << content;
  }
  return 0;
}
