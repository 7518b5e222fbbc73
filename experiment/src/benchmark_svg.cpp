// benchmark.svg: the study's sensor comparison in one figure (DESIGN §10).
#include <cctype>
#include <string>
#include <vector>

#include "fogradar/experiment/outputs.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/line_plot.hpp"

namespace fogradar::experiment {
namespace {

// "Radar: median target RCS as a power ratio; lidar: ...; camera: target contrast." over every
// registered sensor.
std::string metrics_caption(const Scenario& scenario) {
  std::string text;
  for (const SensorSetting& setting : scenario.sensors) {
    text += (text.empty() ? "" : "; ") + std::string(setting.type->name()) + ": " +
            std::string(setting.type->curve_caption());
  }
  if (!text.empty()) text.front() = static_cast<char>(std::toupper(text.front()));
  return text + ".";
}

}  // namespace

std::string benchmark_svg(const Scenario& scenario, const ExperimentSummary& summary) {
  std::vector<stats::LineSeries> series;
  for (const SensorOutcome& sensor : summary.sensors) {
    const sensor::Curve c = sensor.summary->curve();
    const std::string name(sensor.type->name());
    stats::LineSeries line{.label = name + " " + c.metric,
                           .x = c.active_layers,
                           .y = c.relative_value,
                           .marker_x = {},
                           .marker_label = {}};
    if (c.limit) {
      line.marker_x = static_cast<double>(*c.limit);
      line.marker_label = name + " limit " + std::to_string(*c.limit);
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
      metrics_caption(scenario),
      "Chamber: " + std::to_string(scenario.chamber.layer_count) + " fog layers of " +
          stats::format_number(scenario.chamber.layer_length_m, 3) + " m each; seed " +
          std::to_string(scenario.experiment.seed) + "."};
  return stats::line_plot_svg(series, options);
}

}  // namespace fogradar::experiment
