// benchmark.svg: the study's sensor comparison in one figure (docs/architecture.md).
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "fogradar/experiment/outputs.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/line_plot.hpp"

namespace fogradar::experiment {
namespace {

// "Radar, radar_24: median target RCS as a power ratio; lidar: ...; camera: target contrast." over
// every registered kind's own instance and every other instance that runs, each kind's once.
std::string metrics_caption(const Scenario& scenario) {
  std::string text;
  for (const SensorSetting& own : scenario.sensors) {
    if (!own.is_kinds_own()) continue;
    std::string names = own.name;
    for (const SensorSetting& other : scenario.sensors) {
      if (other.kind == own.kind && !other.is_kinds_own() && scenario.runs(other.name)) {
        names += ", " + other.name;
      }
    }
    text += (text.empty() ? "" : "; ") + names + ": " + own.kind->info().curve_caption;
  }
  if (!text.empty()) text.front() = static_cast<char>(std::toupper(text.front()));
  return text + ".";
}

// "Chamber: 4 fog layers of 1 m each; seed 1.", each length where they differ, and the switching
// order where it is not the study's.
std::string chamber_caption(const Scenario& scenario) {
  const propagation::ChamberSpec chamber = scenario.chamber_spec();
  const std::vector<propagation::FogLayerSpec>& layers = chamber.layers;
  std::string lengths;
  bool one_length = true;
  bool one_fog = true;
  for (const propagation::FogLayerSpec& layer : layers) {
    lengths += (lengths.empty() ? "" : ", ") + stats::format_number(layer.length_m, 3);
    one_length = one_length && layer.length_m == layers.front().length_m;
    one_fog = one_fog && layer.fog == layers.front().fog;
  }
  std::string text = "Chamber: " + std::to_string(layers.size()) + " fog layers of ";
  text +=
      one_length ? stats::format_number(layers.front().length_m, 3) + " m each" : lengths + " m";
  if (!one_fog) text += " whose fogs differ (summary.json 'chamber')";
  const std::vector<std::size_t> order = scenario.context().switching_order;
  if (!std::is_sorted(order.begin(), order.end())) {
    std::string listed;
    for (const std::size_t i : order) listed += (listed.empty() ? "" : ", ") + std::to_string(i);
    text += ", switched on in the order " + listed + " (0 at the sensors)";
  }
  return text + "; seed " + std::to_string(scenario.experiment.seed) + ".";
}

}  // namespace

std::string benchmark_svg(const Scenario& scenario, const ExperimentSummary& summary) {
  std::vector<stats::LineSeries> series;
  for (const SensorOutcome& sensor : summary.sensors) {
    const sensor::Curve c = sensor.summary->curve();
    const std::string& name = sensor.name;
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
      metrics_caption(scenario), chamber_caption(scenario)};
  return stats::line_plot_svg(series, options);
}

}  // namespace fogradar::experiment
