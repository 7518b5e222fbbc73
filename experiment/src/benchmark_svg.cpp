// benchmark.svg: the study's three-sensor comparison in one figure (DESIGN §10).
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fogradar/experiment/outputs.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/line_plot.hpp"

namespace fogradar::experiment {
namespace {

struct Curve {
  std::string name;
  std::string metric;  // legend text: which metric (the caption says how it is normalised)
  std::vector<double> layers;
  std::vector<double> value;  // relative to clear weather (step 0)
  std::optional<std::size_t> limit;
};

// The radar's median target RCS as a linear power ratio to clear weather: 10^((m_k - m_0) / 10);
// 0 at a step without target detections.
Curve radar_curve(const ExperimentSummary& summary) {
  Curve c{"radar", "RCS", {}, {}, summary.sensor_limit_layers};
  const double clear = summary.steps.empty() ? std::numeric_limits<double>::quiet_NaN()
                                             : summary.steps.front().rcs.median;
  for (const StepSummary& s : summary.steps) {
    c.layers.push_back(static_cast<double>(s.active_layers));
    const bool known = s.rcs.n > 0 && std::isfinite(clear);
    c.value.push_back(known ? std::pow(10.0, (s.rcs.median - clear) / 10.0) : 0.0);
  }
  return c;
}

// The lidar's median target intensity (a missing target counted as 0, as Fig. 6) over clear
// weather.
Curve lidar_curve(const lidar::LidarSummary& summary) {
  Curve c{"lidar", "intensity", {}, {}, summary.sensor_limit_layers};
  const double clear = summary.steps.empty() ? 0.0 : summary.steps.front().target_intensity.median;
  for (const lidar::LidarStepSummary& s : summary.steps) {
    c.layers.push_back(static_cast<double>(s.active_layers));
    c.value.push_back(clear > 0.0 && s.target_intensity.n > 0 ? s.target_intensity.median / clear
                                                              : 0.0);
  }
  return c;
}

// The camera's target contrast over its noise-free clear-weather contrast.
Curve camera_curve(const camera::CameraSummary& summary) {
  Curve c{"camera", "contrast", {}, {}, summary.sensor_limit_layers};
  for (const camera::CameraStepSummary& s : summary.steps) {
    c.layers.push_back(static_cast<double>(s.active_layers));
    c.value.push_back(s.relative_contrast);
  }
  return c;
}

}  // namespace

std::string benchmark_svg(const Scenario& scenario, const ExperimentSummary& summary) {
  std::vector<stats::LineSeries> series;
  for (SensorId sensor : summary.sensors) {
    Curve c;
    if (sensor == SensorId::radar)
      c = radar_curve(summary);
    else if (sensor == SensorId::lidar && summary.lidar)
      c = lidar_curve(*summary.lidar);
    else if (sensor == SensorId::camera && summary.camera)
      c = camera_curve(*summary.camera);
    else
      continue;
    stats::LineSeries line{.label = c.name + " " + c.metric,
                           .x = c.layers,
                           .y = c.value,
                           .marker_x = {},
                           .marker_label = {}};
    if (c.limit) {
      line.marker_x = static_cast<double>(*c.limit);
      line.marker_label = c.name + " limit " + std::to_string(*c.limit);
    } else {
      line.label += " (no limit)";
    }
    series.push_back(std::move(line));
  }
  stats::LinePlotOptions options;
  options.title =
      "The study's benchmark: each sensor's metric relative to clear weather against active fog "
      "layers";
  options.x_label = "active fog layers";
  options.x_integer_ticks = true;
  options.y_label = "metric / clear-weather value";
  options.caption = {
      "Dashed line: the sensor's limit (layers to failure by its own criterion, summary.json "
      "'sensors'); none: not "
      "reached.",
      "Radar: median target RCS as a power ratio; lidar: median target intensity (a missing target "
      "counted as 0); "
      "camera: target contrast.",
      "Chamber: " + std::to_string(scenario.chamber.layer_count) + " fog layers of " +
          stats::format_number(scenario.chamber.layer_length_m, 3) + " m each; seed " +
          std::to_string(scenario.experiment.seed) + "."};
  return stats::line_plot_svg(series, options);
}

}  // namespace fogradar::experiment
