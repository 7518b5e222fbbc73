// The sweep's plots (docs/sweep.md): comparison.svg, limits.svg and envelope.svg, from the points'
// committed pieces.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/heat_map.hpp"
#include "fogradar/stats/line_plot.hpp"
#include "fogradar/stats/svg_plot.hpp"

namespace fogradar::sweep::detail {
namespace {

using nlohmann::json;

// Several SVG documents one under the other in one document (nested <svg> elements).
std::string stacked(const std::vector<std::string>& documents) {
  double width = 0.0, height = 0.0;
  std::string body;
  for (const std::string& doc : documents) {
    const auto attribute = [&](std::string_view name) {
      const std::size_t at = doc.find(std::string(name) + "=\"", doc.find("<svg"));
      return std::stod(doc.substr(at + name.size() + 2));
    };
    const double w = attribute("width"), h = attribute("height");
    std::string inner = doc.substr(doc.find("<svg"));
    inner.insert(4, " x=\"0\" y=\"" + stats::format_fixed(height, 2) + "\"");
    body += inner;
    width = std::max(width, w);
    height += h;
  }
  return "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n"
         "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" +
         stats::format_fixed(width, 2) + "\" height=\"" + stats::format_fixed(height, 2) +
         "\" viewBox=\"0 0 " + stats::format_fixed(width, 2) + " " +
         stats::format_fixed(height, 2) + "\">\n" + body + "</svg>\n";
}

// A point's values alone ("300.0, hann"); the legend's title names their keys.
std::string values_label(const Point& point) {
  std::string text;
  for (const auto& [key, value] : point.values) text += (text.empty() ? "" : ", ") + value.text;
  return text.empty() ? "the base scenario" : text;
}

std::vector<std::string> swept_keys(const Point& point) {
  std::vector<std::string> keys;
  for (const auto& [key, value] : point.values) keys.push_back(key);
  return keys;
}

std::string joined(const std::vector<std::string>& parts, std::string_view separator) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : std::string(separator)) + part;
  return text;
}

// Ratios to clear weather are drawn in dB (10 log10, as the power quantities the benchmark metrics
// are), so that ratios that span decades and ratios near 1 both fill the axis; a panel with a zero
// ratio (the signal lost) stays linear.
bool all_positive(const std::vector<stats::LineSeries>& series) {
  return std::all_of(series.begin(), series.end(), [](const stats::LineSeries& s) {
    return std::all_of(s.y.begin(), s.y.end(), [](double y) { return y > 0.0; });
  });
}

// Words for a summary column: its name without the unit ("mean_dbsm" -> "mean").
std::string column_words(const std::string& column) {
  static constexpr std::string_view units[] = {"dbsm", "db", "dbm", "m", "hz", "s", "deg"};
  std::vector<std::string> words;
  std::size_t from = 0;
  while (from <= column.size()) {
    const std::size_t to = std::min(column.find('_', from), column.size());
    const std::string word = column.substr(from, to - from);
    if (!word.empty() && std::find(std::begin(units), std::end(units), word) == std::end(units))
      words.push_back(word);
    from = to + 1;
  }
  return words.empty() ? column : joined(words, " ");
}

}  // namespace

std::string comparison_svg(const std::vector<Point>& points, const std::vector<json>& pieces) {
  std::vector<std::string> panels;
  for (const std::string& sensor : sensor_order(pieces)) {
    std::vector<stats::LineSeries> series;
    std::string metric;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      const json* s = sensor_of(pieces[p]["runs"][0]["sensors"], sensor);
      if (s == nullptr) continue;
      metric = (*s)["curve"]["metric"];
      series.push_back({.label = values_label(points[p]),
                        .x = (*s)["curve"]["x"],
                        .y = (*s)["curve"]["y"],
                        .marker_x = {},
                        .marker_label = {}});
    }
    const bool decibels = all_positive(series);
    if (decibels) {
      for (stats::LineSeries& s : series) {
        for (double& y : s.y) y = 10.0 * std::log10(y);
      }
    }
    stats::LinePlotOptions options;
    options.title = sensor + ": " + metric + " relative to clear weather, one line per point";
    options.caption = {
        "replication 0 of each point; the metric of the sensor's benchmark curve (benchmark.svg)",
        "each point has its own mark and dash: lines drawn over each other are equal"};
    if (decibels) options.caption.push_back("in dB: 10 log10 of the ratio to clear weather");
    options.x_label = "active fog layers";
    options.y_label = metric + (decibels ? " relative to clear weather (dB)" : " / clear weather");
    options.x_integer_ticks = true;
    options.point_markers = true;
    options.legend_title = swept_keys(points.front());
    options.height_px = std::max(640.0, 420.0 + 22.0 * static_cast<double>(series.size()));
    panels.push_back(stats::line_plot_svg(series, options));
  }
  return stacked(panels);
}

// Layers to failure against the first swept key (a line per sensor), or over the first two keys (a
// heat map per sensor, all on one colour scale).
std::string limits_svg(const SweepSpec& spec, const std::vector<Point>& points,
                       const std::vector<json>& pieces) {
  const std::vector<std::string> sensors = sensor_order(pieces);
  std::size_t last_step = 1;
  for (const Point& p : points) last_step = std::max(last_step, p.scenario.steps() - 1);
  const auto limit_of = [&](std::size_t p, const std::string& sensor) -> std::optional<double> {
    const json* s = sensor_of(pieces[p]["runs"][0]["sensors"], sensor);
    if (s == nullptr || (*s)["limit"].is_null()) return std::nullopt;
    return (*s)["limit"].get<double>();
  };
  const auto offset_of = [&](std::size_t a) {
    std::size_t offset = 0;
    for (std::size_t b = 0; b < a; ++b) offset += spec.axes[b].keys.size();
    return offset;
  };
  const auto position_text = [&](const Point& p, std::size_t a) {
    std::string text;
    for (std::size_t k = 0; k < spec.axes[a].keys.size(); ++k)
      text += (k ? " / " : "") + p.values[offset_of(a) + k].second.text;
    return text;
  };
  // Positions in the grid's order (expand's): read back from the points.
  const auto positions_of = [&](std::size_t a) {
    std::vector<std::string> labels;
    for (const Point& p : points) {
      const std::string text = position_text(p, a);
      if (std::find(labels.begin(), labels.end(), text) == labels.end()) labels.push_back(text);
    }
    return labels;
  };
  const auto axis_name = [&](std::size_t a) { return joined(spec.axes[a].keys, " / "); };
  std::vector<std::string> panels;
  if (spec.axes.size() == 1) {
    const std::vector<std::string> labels = positions_of(0);
    const bool numeric = std::all_of(points.begin(), points.end(), [](const Point& p) {
      return p.values.front().second.number.has_value();
    });
    std::vector<stats::LineSeries> series;
    for (const std::string& sensor : sensors) {
      stats::LineSeries s;
      s.label = sensor;
      for (std::size_t p = 0; p < points.size(); ++p) {
        const double x = numeric ? *points[p].values.front().second.number : static_cast<double>(p);
        const std::optional<double> limit = limit_of(p, sensor);
        if (limit) {
          s.x.push_back(x);
          s.y.push_back(*limit);
        } else {
          s.beyond_x.push_back(x);
        }
      }
      series.push_back(std::move(s));
    }
    stats::LinePlotOptions options;
    const std::string& first_key = spec.axes[0].keys.front();
    options.title = "Layers to failure against " + first_key;
    options.caption = {
        "a mark per point; a step holds its limit halfway to the neighbouring points",
        "marks in the top row: not reached by the last step (" + std::to_string(last_step) +
            " layers)"};
    if (!numeric) {
      std::string legend;
      for (std::size_t i = 0; i < labels.size(); ++i)
        legend += (i ? ", " : "") + std::to_string(i) + " = " + labels[i];
      options.caption.push_back(axis_name(0) + ": " + legend);
    }
    // The x axis is the first key's; zipped keys move with it.
    options.x_label = first_key;
    if (spec.axes[0].keys.size() > 1) {
      options.x_label += " (" +
                         joined({spec.axes[0].keys.begin() + 1, spec.axes[0].keys.end()}, ", ") +
                         " with it)";
    }
    options.y_label = "layers to failure";
    options.y_integer_ticks = true;
    options.y_reach = static_cast<double>(last_step);
    options.point_markers = true;
    options.steps = true;
    options.legend_title = {"sensor"};
    options.beyond_label = "not reached";
    panels.push_back(stats::line_plot_svg(series, options));
    return stacked(panels);
  }
  const std::vector<std::string> columns = positions_of(0), rows = positions_of(1);
  for (const std::string& sensor : sensors) {
    stats::HeatMap map;
    map.column_labels = columns;
    map.row_labels = rows;
    map.values.assign(rows.size(), std::vector<std::optional<double>>(columns.size()));
    std::vector<std::vector<bool>> seen(rows.size(), std::vector<bool>(columns.size(), false));
    for (std::size_t p = 0; p < points.size(); ++p) {
      const std::string c = position_text(points[p], 0), r = position_text(points[p], 1);
      const std::size_t ci =
          static_cast<std::size_t>(std::find(columns.begin(), columns.end(), c) - columns.begin());
      const std::size_t ri =
          static_cast<std::size_t>(std::find(rows.begin(), rows.end(), r) - rows.begin());
      if (seen[ri][ci]) continue;  // the other axes at their first position
      seen[ri][ci] = true;
      map.values[ri][ci] = limit_of(p, sensor);
    }
    map.title = sensor + ": layers to failure";
    map.x_label = axis_name(0);
    map.y_label = axis_name(1);
    map.value_label = "layers to failure";
    map.missing_text = "not reached";
    // Every panel on the same scale, from no layer to the last step.
    map.value_range = {{0.0, static_cast<double>(last_step)}};
    map.integer_values = true;
    map.caption = {"one colour scale for every sensor: 0 to " + std::to_string(last_step) +
                   " layers (the last step)"};
    if (spec.axes.size() > 2) map.caption.push_back("the other swept keys at their first value");
    panels.push_back(stats::heat_map_svg(map));
  }
  return stacked(panels);
}

// Per point and [[uncertain.plot]]: the statistic of each run, the nominal run's as a bar and the
// setups' as bands, with the references; and, with `box`, the nominal run's measurements as box
// plots in a panel of their own (a statistic of other values, so on another axis).
std::string envelope_svg(const SweepSpec& spec, const std::vector<Point>& points,
                         const std::vector<json>& pieces) {
  std::vector<std::string> panels;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const json& setups = pieces[p]["setups"];
    for (const EnvelopePlot& plot : spec.uncertain->plots) {
      const json* nominal = sensor_of(pieces[p]["runs"][0]["sensors"], plot.sensor);
      if (nominal == nullptr) {
        throw_invalid("uncertain.plot.sensor", plot.sensor, "a sensor that runs in the sweep");
      }
      const std::vector<std::string> columns = (*nominal)["columns"];
      const auto column = [&](const std::string& name) {
        const auto it = std::find(columns.begin(), columns.end(), name);
        if (it == columns.end()) {
          throw_invalid("uncertain.plot.statistic", name,
                        "a column of " + plot.sensor + "_summary.csv");
        }
        return static_cast<std::size_t>(it - columns.begin());
      };
      const std::size_t layers = column("active_layers"), statistic = column(plot.statistic);
      const std::string words = column_words(plot.statistic);
      const std::string n_setups = std::to_string(setups.size());
      std::vector<stats::BoxPlotSeries> values, boxes;
      bool all_alike = true;
      for (std::size_t row = 0; row < (*nominal)["rows"].size(); ++row) {
        const json& cells = (*nominal)["rows"][row];
        stats::BoxPlotSeries s;
        s.label = cells[layers];
        stats::BoxPlotSeries b = s;
        if (const std::optional<double> v = number_of(cells[statistic]); v && std::isfinite(*v)) {
          s.box.n = 1;
          s.box.min = s.box.q1 = s.box.median = s.box.mean = s.box.q3 = s.box.max = *v;
          s.box.whisker_low = s.box.whisker_high = *v;
        }
        std::vector<double> setup_values;
        for (const json& setup : setups) {
          const std::optional<double> v =
              number_of((*sensor_of(setup["sensors"], plot.sensor))["rows"][row][statistic]);
          if (v && std::isfinite(*v)) setup_values.push_back(*v);
        }
        if (!setup_values.empty()) {
          s.band_low = quantile(setup_values, 0.05);
          s.band_high = quantile(setup_values, 0.95);
          s.inner_band_low = quantile(setup_values, 0.25);
          s.inner_band_high = quantile(setup_values, 0.75);
          all_alike = all_alike && s.band_low == s.band_high;
        }
        const std::size_t k = std::stoul(cells[layers].get<std::string>());
        for (const EnvelopePlot::Reference& ref : plot.references) {
          if (ref.active_layers == k) s.references.push_back(ref.value);
        }
        values.push_back(std::move(s));
        if (plot.box.empty()) continue;
        std::vector<std::optional<double>> box;
        for (const std::string& name : plot.box) box.push_back(number_of(cells[column(name)]));
        if (std::all_of(box.begin(), box.end(),
                        [](const auto& v) { return v && std::isfinite(*v); })) {
          b.box.n = 1;
          b.box.whisker_low = b.box.min = *box[0];
          b.box.q1 = *box[1];
          b.box.median = b.box.mean = *box[2];
          b.box.q3 = *box[3];
          b.box.whisker_high = b.box.max = *box[4];
        }
        boxes.push_back(std::move(b));
      }
      if (all_alike) {
        for (stats::BoxPlotSeries& s : values) {
          s.band_low = s.band_high = s.inner_band_low = s.inner_band_high = stats::BoxPlot::nan;
        }
      }
      stats::SvgPlotOptions options;
      options.title =
          plot.sensor + ": " + words + " of each run, the nominal run and " + n_setups + " setups";
      options.caption = {points[p].label() + "; a value per run: the " + words + " (" +
                             plot.statistic + ") of its measurements at each step",
                         "bar: the nominal run (the sweep's scenario); shaded: the middle 90 % and "
                         "50 % of the " +
                             n_setups + " setups of [uncertain]"};
      if (all_alike) {
        options.caption.back() = "bar: the nominal run; every one of the " + n_setups +
                                 " setups gives its value: no key of [uncertain] changes it";
      }
      options.x_label = "active fog layers";
      options.y_label = plot.y_label;
      options.show_mean = false;
      options.value_label = "the nominal run";
      options.band_label = "5-95 % of the setups";
      options.inner_band_label = "25-75 % of the setups";
      options.reference_label = plot.reference_label;
      options.axis_padding = 0.06;
      panels.push_back(stats::box_plot_svg(values, options));
      if (plot.box.empty()) continue;
      stats::SvgPlotOptions box_options;
      box_options.title = plot.sensor + ": each measurement of the nominal run";
      box_options.caption = {
          points[p].label() + "; the run's box plot from its summary columns " +
              joined(plot.box, ", "),
          "a spread of single measurements, not of run values: not comparable with the bands "
          "above"};
      box_options.x_label = "active fog layers";
      box_options.y_label = plot.y_label;
      box_options.show_mean = false;
      box_options.axis_padding = 0.06;
      panels.push_back(stats::box_plot_svg(boxes, box_options));
    }
  }
  return stacked(panels);
}

}  // namespace fogradar::sweep::detail
