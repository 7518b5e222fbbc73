#include <sys/stat.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "engine.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/experiment/files.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/run_time.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/heat_map.hpp"
#include "fogradar/stats/line_plot.hpp"
#include "fogradar/stats/svg_plot.hpp"
#include "fogradar/sweep/sweep.hpp"

namespace fogradar::sweep {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::set<std::string, std::less<>> table_names = {
    "sweep.toml", "points.csv",   "results.csv",         "limits.csv",  "comparison.svg",
    "limits.svg", "envelope.csv", "envelope_limits.csv", "envelope.svg"};
constexpr std::string_view state_dir = ".sweep";
constexpr std::string_view points_dir = "points";
constexpr std::string_view origin_file = "origin";  // in .sweep/: the sweep file's directory
// The quantiles of envelope.csv, as its columns name them.
constexpr double envelope_levels[] = {0.05, 0.25, 0.5, 0.75, 0.95};
constexpr const char* envelope_columns = "p05,p25,p50,p75,p95";

std::string shortest(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

// RFC 4180: a field with a comma, a quote or a line break is quoted, its quotes doubled.
std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string fnv_hex(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(hash));
  return out;
}

std::optional<double> number_of(const std::string& text) {
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// A sensor's summary CSV (no quoted fields: the sensors write none).
struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t comma = line.find(','); comma != std::string::npos;
       comma = line.find(',', start)) {
    fields.push_back(line.substr(start, comma - start));
    start = comma + 1;
  }
  fields.push_back(line.substr(start));
  return fields;
}

Table parse_csv(const std::string& text) {
  Table table;
  std::istringstream in(text);
  std::string line;
  if (std::getline(in, line)) table.columns = split(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    table.rows.push_back(split(line));
    FOGRADAR_CHECK(table.rows.back().size() == table.columns.size());
  }
  return table;
}

// One run of a scenario, every sensor's summary table, verdict and curve, as a piece keeps it.
json run_once(const experiment::Scenario& scenario, const propagation::SegelsteinTable& water,
              experiment::SensorCache& cache, const SweepOptions& options, bool with_curves,
              std::vector<sensor::ResultFile>* keep) {
  const experiment::Simulation simulation(scenario, water, &cache);
  const experiment::ExperimentResult result = simulation.run(
      {.threads = options.threads, .progress = {}, .stop = options.stop, .raw = nullptr});
  const experiment::ExperimentSummary summary = experiment::summarize(result);
  if (keep != nullptr) *keep = experiment::result_files(scenario, summary);
  json sensors = json::array();
  for (const experiment::SensorOutcome& outcome : summary.sensors) {
    const Table table = parse_csv(outcome.summary->summary_csv());
    const sensor::Verdict verdict = outcome.summary->verdict();
    json s = {
        {"sensor", std::string(outcome.type->name())},
        {"columns", table.columns},
        {"rows", table.rows},
        {"limit", verdict.layers_to_failure ? json(*verdict.layers_to_failure) : json(nullptr)},
        {"criterion", verdict.criterion},
        {"margin", verdict.margin}};
    if (with_curves) {
      const sensor::Curve curve = outcome.summary->curve();
      s["curve"] = {
          {"metric", curve.metric}, {"x", curve.active_layers}, {"y", curve.relative_value}};
    }
    sensors.push_back(std::move(s));
  }
  return sensors;
}

experiment::Scenario with_seed(experiment::Scenario scenario, std::uint64_t seed) {
  scenario.experiment.seed = seed & 0x7fffffffffffffffULL;  // TOML integers are signed 64-bit
  return scenario;
}

std::vector<std::string> sensor_order(const std::vector<json>& pieces) {
  std::vector<std::string> order;
  for (const json& piece : pieces) {
    for (const json& run : piece["runs"]) {
      for (const json& s : run["sensors"]) {
        const std::string name = s["sensor"];
        if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
      }
    }
  }
  return order;
}

bool is_step_column(const std::string& column) {
  return column == "active_layers" || column == "step";
}

std::string points_csv(const SweepSpec& spec, const std::vector<Point>& points) {
  std::string out = "point";
  for (const Axis& axis : spec.axes) {
    for (const std::string& key : axis.keys) out += "," + csv_field(key);
  }
  out += ",seed\n";
  for (const Point& p : points) {
    out += std::to_string(p.index);
    for (const auto& [key, value] : p.values) out += "," + csv_field(value.text);
    out += "," + std::to_string(p.seed & 0x7fffffffffffffffULL) + "\n";
  }
  return out;
}

std::string results_csv(const std::vector<json>& pieces) {
  // Every statistic column of every sensor, in the order the sensors and their tables give them.
  std::vector<std::string> columns;
  for (const json& piece : pieces) {
    for (const json& run : piece["runs"]) {
      for (const json& s : run["sensors"]) {
        for (const std::string c : s["columns"]) {
          if (!is_step_column(c) && std::find(columns.begin(), columns.end(), c) == columns.end())
            columns.push_back(c);
        }
      }
    }
  }
  std::string out = "point,replication,sensor,active_layers";
  for (const std::string& c : columns) out += "," + csv_field(c);
  out += "\n";
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    for (const json& run : pieces[p]["runs"]) {
      for (const json& s : run["sensors"]) {
        const std::vector<std::string> own = s["columns"];
        const auto at = [&](const std::string& c) {
          return std::find(own.begin(), own.end(), c) - own.begin();
        };
        const std::size_t layers = static_cast<std::size_t>(at("active_layers"));
        for (const json& row : s["rows"]) {
          out += std::to_string(p) + "," + std::to_string(run["replication"].get<std::size_t>()) +
                 "," + csv_field(s["sensor"].get<std::string>()) + "," +
                 row[layers].get<std::string>();
          for (const std::string& c : columns) {
            const std::size_t i = static_cast<std::size_t>(at(c));
            out += ',';
            if (i < own.size()) out += csv_field(row[i].get<std::string>());
          }
          out += "\n";
        }
      }
    }
  }
  return out;
}

std::string limits_csv(const std::vector<json>& pieces) {
  std::string out = "point,replication,sensor,layers_to_failure,criterion,margin\n";
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    for (const json& run : pieces[p]["runs"]) {
      for (const json& s : run["sensors"]) {
        out +=
            std::to_string(p) + "," + std::to_string(run["replication"].get<std::size_t>()) + "," +
            csv_field(s["sensor"].get<std::string>()) + "," +
            (s["limit"].is_null() ? std::string() : std::to_string(s["limit"].get<std::size_t>())) +
            "," + csv_field(s["criterion"].get<std::string>()) + "," +
            csv_field(s["margin"].get<std::string>()) + "\n";
      }
    }
  }
  return out;
}

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

const json* sensor_of(const json& sensors, const std::string& name) {
  for (const json& s : sensors) {
    if (s["sensor"] == name) return &s;
  }
  return nullptr;
}

// A point's values alone ("300.0, hann"), its keys named in the caption.
std::string values_label(const Point& point) {
  std::string text;
  for (const auto& [key, value] : point.values) text += (text.empty() ? "" : ", ") + value.text;
  return text.empty() ? "the base scenario" : text;
}

std::string keys_caption(const Point& point) {
  std::string text;
  for (const auto& [key, value] : point.values) text += (text.empty() ? "" : ", ") + key;
  return text.empty() ? "" : "lines: " + text;
}

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
    stats::LinePlotOptions options;
    options.title = sensor + ": " + metric + " relative to clear weather, one line per point";
    options.caption = {
        keys_caption(points.front()),
        "replication 0 of each point; the metric of the sensor's benchmark curve (benchmark.svg)"};
    options.x_label = "active fog layers";
    options.y_label = metric + " / clear weather";
    options.x_integer_ticks = true;
    options.height_px = std::max(640.0, 420.0 + 22.0 * static_cast<double>(series.size()));
    panels.push_back(stats::line_plot_svg(series, options));
  }
  return stacked(panels);
}

// Layers to failure against the first swept key (a line per sensor), or over the first two keys (a
// heat map per sensor); a limit not reached is drawn one step beyond the last.
std::string limits_svg(const SweepSpec& spec, const std::vector<Point>& points,
                       const std::vector<json>& pieces) {
  const std::vector<std::string> sensors = sensor_order(pieces);
  const std::size_t steps = points.front().scenario.experiment.max_active_layers + 1;
  const auto limit_of = [&](std::size_t p, const std::string& sensor) -> std::optional<double> {
    const json* s = sensor_of(pieces[p]["runs"][0]["sensors"], sensor);
    if (s == nullptr || (*s)["limit"].is_null()) return std::nullopt;
    return (*s)["limit"].get<double>();
  };
  const Axis& first = spec.axes.front();
  // Positions in the grid's order (expand's): read back from the points.
  const auto positions_of = [&](std::size_t a) {
    std::vector<std::string> labels;
    for (const Point& p : points) {
      std::string text;
      std::size_t offset = 0;
      for (std::size_t b = 0; b < a; ++b) offset += spec.axes[b].keys.size();
      for (std::size_t k = 0; k < spec.axes[a].keys.size(); ++k)
        text += (k ? " / " : "") + p.values[offset + k].second.text;
      if (std::find(labels.begin(), labels.end(), text) == labels.end()) labels.push_back(text);
    }
    return labels;
  };
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
        s.x.push_back(numeric ? *points[p].values.front().second.number : static_cast<double>(p));
        s.y.push_back(limit_of(p, sensor).value_or(static_cast<double>(steps)));
      }
      series.push_back(std::move(s));
    }
    stats::LinePlotOptions options;
    options.title = "Layers to failure against " + first.keys.front();
    options.caption = {"a limit not reached is drawn at " + std::to_string(steps) +
                       " (one step beyond the last)"};
    if (!numeric) {
      std::string legend;
      for (std::size_t i = 0; i < labels.size(); ++i)
        legend += (i ? ", " : "") + std::to_string(i) + " = " + labels[i];
      options.caption.push_back(first.keys.front() + ": " + legend);
    }
    options.x_label = first.keys.front();
    options.y_label = "layers to failure";
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
    const std::size_t second = spec.axes[0].keys.size();
    for (std::size_t p = 0; p < points.size(); ++p) {
      std::string c, r;
      for (std::size_t k = 0; k < spec.axes[0].keys.size(); ++k)
        c += (k ? " / " : "") + points[p].values[k].second.text;
      for (std::size_t k = 0; k < spec.axes[1].keys.size(); ++k)
        r += (k ? " / " : "") + points[p].values[second + k].second.text;
      const std::size_t ci =
          static_cast<std::size_t>(std::find(columns.begin(), columns.end(), c) - columns.begin());
      const std::size_t ri =
          static_cast<std::size_t>(std::find(rows.begin(), rows.end(), r) - rows.begin());
      if (seen[ri][ci]) continue;  // the other axes at their first position
      seen[ri][ci] = true;
      map.values[ri][ci] = limit_of(p, sensor);
    }
    map.title = sensor + ": layers to failure";
    map.x_label = spec.axes[0].keys.front();
    map.y_label = spec.axes[1].keys.front();
    map.value_label = "layers";
    map.missing_text = "not reached";
    if (spec.axes.size() > 2) map.caption = {"the other swept keys at their first value"};
    panels.push_back(stats::heat_map_svg(map));
  }
  return stacked(panels);
}

double quantile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return stats::quantile_type7(values, p);
}

// Per point x sensor x step x statistic: how many setups gave a value and its quantiles.
std::string envelope_csv(const std::vector<json>& pieces) {
  std::string out =
      std::string("point,sensor,active_layers,statistic,setups,") + envelope_columns + "\n";
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const json& setups = pieces[p]["setups"];
    if (setups.empty()) continue;
    for (const json& s0 : setups[0]["sensors"]) {
      const std::string sensor = s0["sensor"];
      const std::vector<std::string> columns = s0["columns"];
      const std::size_t layers = static_cast<std::size_t>(
          std::find(columns.begin(), columns.end(), "active_layers") - columns.begin());
      for (std::size_t row = 0; row < s0["rows"].size(); ++row) {
        for (std::size_t c = 0; c < columns.size(); ++c) {
          if (is_step_column(columns[c])) continue;
          std::vector<double> values;
          bool numeric = true;
          for (const json& setup : setups) {
            const json* s = sensor_of(setup["sensors"], sensor);
            const std::string text = (*s)["rows"][row][c];
            const std::optional<double> v = number_of(text);
            if (!text.empty() && !v) numeric = false;
            if (v && std::isfinite(*v)) values.push_back(*v);
          }
          if (!numeric) continue;  // a list (the outliers): not a statistic
          out += std::to_string(p) + "," + csv_field(sensor) + "," +
                 s0["rows"][row][layers].get<std::string>() + "," + csv_field(columns[c]) + "," +
                 std::to_string(values.size());
          for (const double level : envelope_levels)
            out += "," + (values.empty() ? std::string() : shortest(quantile(values, level)));
          out += "\n";
        }
      }
    }
  }
  return out;
}

std::string envelope_limits_csv(const std::vector<json>& pieces) {
  std::string out = "point,sensor,layers_to_failure,setups,fraction\n";
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const json& setups = pieces[p]["setups"];
    if (setups.empty()) continue;
    for (const json& s0 : setups[0]["sensors"]) {
      const std::string sensor = s0["sensor"];
      std::map<std::size_t, std::size_t> counts;  // limit + 1, 0 = not reached, so it sorts last
      for (const json& setup : setups) {
        const json& limit = (*sensor_of(setup["sensors"], sensor))["limit"];
        ++counts[limit.is_null() ? 0 : limit.get<std::size_t>() + 1];
      }
      const auto row = [&](std::size_t key, std::size_t n) {
        out += std::to_string(p) + "," + csv_field(sensor) + "," +
               (key == 0 ? std::string() : std::to_string(key - 1)) + "," + std::to_string(n) +
               "," + shortest(static_cast<double>(n) / static_cast<double>(setups.size())) + "\n";
      };
      for (const auto& [key, n] : counts) {
        if (key != 0) row(key, n);
      }
      if (counts.contains(0)) row(0, counts.at(0));
    }
  }
  return out;
}

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
      std::vector<stats::BoxPlotSeries> series;
      for (std::size_t row = 0; row < (*nominal)["rows"].size(); ++row) {
        const json& cells = (*nominal)["rows"][row];
        stats::BoxPlotSeries s;
        s.label = cells[layers];
        std::vector<std::optional<double>> box;
        if (plot.box.empty()) {
          box.assign(5, number_of(cells[statistic]));
        } else {
          for (const std::string& name : plot.box) box.push_back(number_of(cells[column(name)]));
        }
        if (std::all_of(box.begin(), box.end(),
                        [](const auto& v) { return v && std::isfinite(*v); })) {
          s.box.n = 1;
          s.box.whisker_low = s.box.min = *box[0];
          s.box.q1 = *box[1];
          s.box.median = s.box.mean = *box[2];
          s.box.q3 = *box[3];
          s.box.whisker_high = s.box.max = *box[4];
        }
        std::vector<double> values;
        for (const json& setup : setups) {
          const std::optional<double> v =
              number_of((*sensor_of(setup["sensors"], plot.sensor))["rows"][row][statistic]);
          if (v && std::isfinite(*v)) values.push_back(*v);
        }
        if (!values.empty()) {
          s.band_low = quantile(values, 0.05);
          s.band_high = quantile(values, 0.95);
          s.inner_band_low = quantile(values, 0.25);
          s.inner_band_high = quantile(values, 0.75);
        }
        const std::size_t k = std::stoul(cells[layers].get<std::string>());
        for (const EnvelopePlot::Reference& ref : plot.references) {
          if (ref.active_layers == k) s.references.push_back(ref.value);
        }
        series.push_back(std::move(s));
      }
      stats::SvgPlotOptions options;
      options.title = plot.sensor + ": " + plot.statistic + " across " +
                      std::to_string(setups.size()) + " setups";
      options.caption = {
          points[p].label() + "; boxes: the nominal run" + (plot.box.empty() ? " (its value)" : ""),
          "bands: " + plot.statistic + " across the setups of [uncertain]"};
      options.x_label = "active fog layers";
      options.y_label = plot.y_label;
      options.show_mean = false;
      options.band_label = "5-95 % of setups";
      options.inner_band_label = "25-75 % of setups";
      options.reference_label = plot.reference_label;
      panels.push_back(stats::box_plot_svg(series, options));
    }
  }
  return stacked(panels);
}

std::string seconds_text(double seconds) {
  std::ostringstream out;
  out.precision(3);
  if (seconds < 120.0) {
    out << seconds << " s";
  } else if (seconds < 7200.0) {
    out << seconds / 60.0 << " min";
  } else {
    out << seconds / 3600.0 << " h";
  }
  return out.str();
}

}  // namespace

namespace detail {

Computed compute_point(const SweepSpec& spec, const Point& point, const std::string& definition,
                       const propagation::SegelsteinTable& water, experiment::SensorCache& cache,
                       const SweepOptions& options) {
  Computed computed;
  computed.piece = {{"definition", definition}, {"runs", json::array()}, {"setups", json::array()}};
  for (std::size_t r = 0; r < spec.replications; ++r) {
    const bool keep = options.keep_points && r == 0;
    computed.piece["runs"].push_back(
        {{"replication", r},
         {"sensors", run_once(with_seed(point.scenario, point.seed + r), water, cache, options,
                              r == 0, keep ? &computed.kept : nullptr)}});
  }
  for (const experiment::Scenario& setup : point.setups) {
    computed.piece["setups"].push_back(
        {{"sensors", run_once(setup, water, cache, options, false, nullptr)}});
  }
  return computed;
}

SweepDirectory::SweepDirectory(const fs::path& dir, Mode mode, std::size_t points,
                               std::size_t shard) {
  const std::string given = dir.string();
  const std::string option = mode == Mode::merge ? "--merge" : "--out";
  std::error_code error;
  dir_ = fs::absolute(dir, error).lexically_normal();
  if (!dir_.has_filename()) dir_ = dir_.parent_path();
  if (error || given.empty() || dir_.filename() == "." || dir_.filename() == "..") {
    throw_invalid(option, given, "a directory name");
  }
  if (fs::is_symlink(fs::symlink_status(dir_, error))) {
    throw_invalid(option, given, "a directory, not a symbolic link");
  }
  if (fs::exists(dir_, error) && !fs::is_directory(dir_, error)) {
    throw_invalid(option, given, "a directory");
  }
  if (mode == Mode::merge && !fs::is_directory(dir_ / state_dir)) {
    throw_invalid(option, given, "a sweep's directory (it has no " + std::string(state_dir) + "/)");
  }
  fs::create_directories(dir_, error);
  if (error) {
    throw_invalid(option, given, "a directory that can be created (" + error.message() + ")");
  }
  if (mode != Mode::shard) {
    lock_ =
        std::make_unique<experiment::detail::PathLock>(dir_, option, given, "a sweep directory");
  }
  const auto refuse = [&](const fs::path& path) {
    throw_invalid(option, given,
                  "a new directory or one holding only a sweep's files (it holds " +
                      fs::relative(path, dir_).string() +
                      ", which fogradar would not replace; fogradar never deletes a file of "
                      "yours)");
  };
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    if (table_names.contains(name) && entry.is_regular_file()) continue;
    if (name.starts_with(".") && name.find(".tmp-") != std::string::npos) continue;  // a crash's
    if ((name == state_dir || name == points_dir) && entry.is_directory()) continue;
    refuse(entry.path());
  }
  for (const std::string_view sub : {state_dir, points_dir}) {
    if (!fs::is_directory(dir_ / sub)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_ / sub)) {
      const std::string name = entry.path().filename().string();
      const std::string stem = name.substr(0, name.find('.'));
      const bool numbered = !stem.empty() && std::all_of(stem.begin(), stem.end(), [](char c) {
        return c >= '0' && c <= '9';
      });
      if (numbered || name.starts_with(".") || name == origin_file) continue;
      refuse(entry.path());
    }
  }
  fs::create_directories(dir_ / state_dir, error);
  if (error) {
    throw_invalid(option, given, "a directory that can be written (" + error.message() + ")");
  }
  // Shards of one sweep run side by side: each holds its own lock, the others' points stay.
  if (mode == Mode::shard) {
    lock_ = std::make_unique<experiment::detail::PathLock>(
        dir_ / state_dir / ("shard-" + std::to_string(shard)), option, given, "a sweep directory");
  }
  // A crash's temporary files go; without --resume an earlier sweep's files, with it the points
  // beyond this sweep's. A shard removes nothing (the others write beside it), nor does a merge.
  if (mode == Mode::shard || mode == Mode::merge) return;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    if ((name.starts_with(".") && name.find(".tmp-") != std::string::npos) ||
        (mode == Mode::fresh && table_names.contains(name))) {
      fs::remove_all(entry.path(), error);
    }
  }
  if (mode == Mode::fresh) fs::remove_all(dir_ / points_dir, error);
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_ / state_dir)) {
    const std::string name = entry.path().filename().string();
    std::size_t index = 0;
    const auto [end, parsed] = std::from_chars(name.data(), name.data() + name.size(), index);
    const bool stale = name.starts_with(".") || (parsed == std::errc() && index >= points);
    if (mode == Mode::fresh || stale) fs::remove(entry.path(), error);
  }
}

SweepDirectory::~SweepDirectory() = default;

std::optional<json> SweepDirectory::committed(std::size_t index,
                                              const std::string& definition) const {
  std::ifstream in(dir_ / state_dir / (std::to_string(index) + ".json"));
  if (!in) return std::nullopt;
  try {
    json piece = json::parse(in);
    if (piece.value("definition", std::string()) == definition) return piece;
  } catch (const json::exception&) {
  }
  return std::nullopt;
}

void SweepDirectory::commit(std::size_t index, const json& piece) const {
  write_table(std::string(state_dir) + "/" + std::to_string(index) + ".json", piece.dump() + "\n");
}

void SweepDirectory::write_table(std::string_view name, std::string_view content) const {
  const fs::path path = dir_ / name;
  if (!experiment::detail::write_file_atomically(path, content)) {
    throw_invalid("--out", dir_.string(),
                  "a directory that can be written (" + path.filename().string() + ": " +
                      experiment::detail::errno_text() + ")");
  }
}

void SweepDirectory::keep(std::size_t index, const experiment::Scenario& scenario,
                          const std::vector<sensor::ResultFile>& files) const {
  std::error_code error;
  fs::create_directories(dir_ / points_dir, error);
  experiment::OutputDirectory out(dir_ / points_dir / std::to_string(index),
                                  experiment::result_file_names(scenario));
  out.replace(files);
}

std::string definition_of(const Point& point, std::size_t replications) {
  std::string text =
      experiment::to_toml(point.scenario) + "\nreplications " + std::to_string(replications);
  for (const experiment::Scenario& setup : point.setups) {
    text += "\nsetup\n" + experiment::to_toml(setup);
  }
  return fnv_hex(text);
}

std::vector<std::size_t> cost_order(const SweepSpec& spec, const std::vector<Point>& points) {
  std::vector<std::pair<std::size_t, std::size_t>> cost;  // items, index
  for (const Point& p : points) {
    std::size_t items = 0;
    for (std::size_t s = 0; s <= p.setups.size(); ++s) {
      const experiment::Scenario& scenario = s == 0 ? p.scenario : p.setups[s - 1];
      const sensor::Context context = scenario.context();
      for (const std::string& name : scenario.experiment.sensors) {
        const experiment::SensorSetting& setting = scenario.setting(name);
        items += context.steps * setting.type->items_per_step(setting.params, context) *
                 (s == 0 ? spec.replications : 1);
      }
    }
    cost.emplace_back(items, p.index);
  }
  std::stable_sort(cost.begin(), cost.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<std::size_t> order;
  for (const auto& [items, index] : cost) order.push_back(index);
  return order;
}

void write_origin(const SweepDirectory& out, const fs::path& sweep_directory) {
  std::error_code error;
  const fs::path absolute = fs::absolute(sweep_directory, error).lexically_normal();
  out.write_table(std::string(state_dir) + "/" + std::string(origin_file),
                  absolute.string() + "\n");
}

SweepSpec read_spec(const fs::path& dir) {
  std::ifstream text_in(dir / "sweep.toml"), origin_in(dir / state_dir / origin_file);
  if (!text_in || !origin_in) {
    throw_invalid("--merge", dir.string(),
                  "a sweep's directory (sweep.toml and " + std::string(state_dir) + "/" +
                      std::string(origin_file) + " written by its shards)");
  }
  std::ostringstream text;
  text << text_in.rdbuf();
  std::string origin;
  std::getline(origin_in, origin);
  return parse_sweep(text.str(), (dir / "sweep.toml").string(), origin);
}

SweepOutcome write_tables(const SweepSpec& spec, const std::vector<Point>& points,
                          const std::vector<json>& pieces, const SweepDirectory& out) {
  SweepOutcome outcome;
  const auto write = [&](std::string_view name, const std::string& content) {
    out.write_table(name, content);
    outcome.files.emplace_back(name);
  };
  write("points.csv", points_csv(spec, points));
  write("results.csv", results_csv(pieces));
  write("limits.csv", limits_csv(pieces));
  write("comparison.svg", comparison_svg(points, pieces));
  if (!spec.axes.empty()) write("limits.svg", limits_svg(spec, points, pieces));
  if (spec.uncertain) {
    write("envelope.csv", envelope_csv(pieces));
    write("envelope_limits.csv", envelope_limits_csv(pieces));
    if (!spec.uncertain->plots.empty()) write("envelope.svg", envelope_svg(spec, points, pieces));
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    outcome.limits_table += "  " + std::to_string(p) + "  " + points[p].label() + ":";
    for (const json& s : pieces[p]["runs"][0]["sensors"]) {
      outcome.limits_table +=
          " " + s["sensor"].get<std::string>() + " " +
          (s["limit"].is_null() ? std::string("not reached")
                                : std::to_string(s["limit"].get<std::size_t>()));
    }
    outcome.limits_table += "\n";
  }
  return outcome;
}

}  // namespace detail

std::string SweepEstimate::text() const {
  std::ostringstream out;
  out.precision(4);
  out << points << " point" << (points == 1 ? "" : "s") << ", " << runs << " run"
      << (runs == 1 ? "" : "s") << ", " << items << " items; about " << seconds_text(seconds)
      << " (cost models; " << seconds_text(cpu_seconds) << " of CPU), peak memory about "
      << static_cast<double>(peak_bytes) / 1048576.0 << " MiB";
  return out.str();
}

namespace {

// Every run of the sweep in the order compute_point runs them: each point's replications, then
// its setups.
std::vector<experiment::Scenario> sweep_runs(const SweepSpec& spec,
                                             const std::vector<Point>& points) {
  std::vector<experiment::Scenario> runs;
  for (const Point& p : points) {
    for (std::size_t r = 0; r < spec.replications; ++r) runs.push_back(with_seed(p.scenario, p.seed + r));
    for (const experiment::Scenario& setup : p.setups) runs.push_back(setup);
  }
  return runs;
}

// The runs' cost-model estimate in one process (experiment::estimate_runs).
experiment::RunsEstimate sweep_estimate(const std::vector<experiment::Scenario>& runs,
                                        unsigned threads) {
  std::vector<const experiment::Scenario*> order;
  for (const experiment::Scenario& run : runs) order.push_back(&run);
  return experiment::estimate_runs(order, threads);
}

// The run that alone exceeds the limit is refused as `run` refuses it, else the sweep's estimate
// against the limit.
void require_sweep_time_within(const std::vector<experiment::Scenario>& runs, double total_seconds,
                               std::size_t points, const SweepOptions& options) {
  for (const experiment::Scenario& run : runs)
    experiment::require_time_within(run, options.threads, options.time_limit_seconds);
  if (total_seconds <= options.time_limit_seconds) return;
  std::string message = "the sweep needs an estimated ";
  message += seconds_text(total_seconds);
  message += " for its ";
  message += std::to_string(runs.size());
  message += " runs (";
  message += std::to_string(points);
  message += " points) with --threads ";
  message += std::to_string(options.threads);
  message += ", each within --time-limit = ";
  message += seconds_text(options.time_limit_seconds);
  message += " but not all together; shard it (--shard i/N) or raise --time-limit";
  throw InvalidParameter("--time-limit", message);
}

}  // namespace

SweepEstimate estimate(const SweepSpec& spec, const std::vector<Point>& points,
                       const SweepOptions& options) {
  const std::size_t limit = options.memory_limit_bytes ? options.memory_limit_bytes
                                                       : experiment::default_memory_limit_bytes();
  SweepEstimate e;
  e.points = points.size();
  const std::vector<experiment::Scenario> runs = sweep_runs(spec, points);
  e.runs = runs.size();
  const experiment::Scenario* largest = nullptr;
  for (const experiment::Scenario& scenario : runs) {
    const std::size_t bytes =
        experiment::estimate_peak_memory(scenario, options.threads).total_bytes();
    if (bytes > e.peak_bytes || largest == nullptr) {
      e.peak_bytes = std::max(e.peak_bytes, bytes);
      largest = &scenario;
    }
    const sensor::Context context = scenario.context();
    for (const std::string& name : scenario.experiment.sensors) {
      const experiment::SensorSetting& setting = scenario.setting(name);
      e.items += context.steps * setting.type->items_per_step(setting.params, context);
    }
  }
  if (largest != nullptr) experiment::require_memory_within(*largest, options.threads, limit);
  const experiment::RunsEstimate time = sweep_estimate(runs, options.threads);
  e.seconds = time.wall_seconds;
  e.cpu_seconds = time.cpu_seconds;
  if (options.time_limit_seconds > 0.0)
    require_sweep_time_within(runs, e.seconds, points.size(), options);
  return e;
}

SweepOutcome run_sweep(const SweepSpec& spec, const std::vector<Point>& points, const fs::path& dir,
                       const SweepOptions& options) {
  using Mode = detail::SweepDirectory::Mode;
  const std::optional<Shard>& shard = options.shard;
  const Mode mode = shard ? Mode::shard : options.resume ? Mode::resume : Mode::fresh;
  const detail::SweepDirectory out(dir, mode, points.size(), shard ? shard->index : 0);
  out.write_table("sweep.toml", spec.text);
  detail::write_origin(out, spec.directory);
  // A shard's points: every count-th of the cost order, so that each share has as many costly ones.
  std::vector<std::size_t> mine;
  if (shard) {
    const std::vector<std::size_t> order = detail::cost_order(spec, points);
    for (std::size_t position = shard->index; position < order.size(); position += shard->count)
      mine.push_back(order[position]);
    std::sort(mine.begin(), mine.end());
  } else {
    for (const Point& point : points) mine.push_back(point.index);
  }
  const propagation::SegelsteinTable water;
  experiment::SensorCache own_cache;
  experiment::SensorCache& cache = options.cache ? *options.cache : own_cache;
  SweepOutcome outcome;
  std::vector<json> pieces;
  const auto start = std::chrono::steady_clock::now();
  for (const std::size_t index : mine) {
    const Point& point = points[index];
    const std::string definition = detail::definition_of(point, spec.replications);
    std::optional<json> piece =
        mode != Mode::fresh ? out.committed(index, definition) : std::nullopt;
    if (piece) {
      ++outcome.reused;
    } else {
      detail::Computed computed =
          detail::compute_point(spec, point, definition, water, cache, options);
      if (options.keep_points) out.keep(index, point.scenario, computed.kept);
      out.commit(index, computed.piece);
      piece = std::move(computed.piece);
      ++outcome.computed;
    }
    pieces.push_back(std::move(*piece));
    if (options.progress) {
      options.progress(
          pieces.size(), mine.size(),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  }
  if (shard) return outcome;
  SweepOutcome tables = detail::write_tables(spec, points, pieces, out);
  tables.computed = outcome.computed;
  tables.reused = outcome.reused;
  return tables;
}

SweepOutcome merge_sweep(const fs::path& dir) {
  const detail::SweepDirectory out(dir, detail::SweepDirectory::Mode::merge, 0);
  const SweepSpec spec = detail::read_spec(out.path());
  const std::vector<Point> points = expand(spec);
  std::vector<json> pieces;
  std::vector<std::size_t> missing;
  for (const Point& point : points) {
    std::optional<json> piece =
        out.committed(point.index, detail::definition_of(point, spec.replications));
    if (piece) {
      pieces.push_back(std::move(*piece));
    } else {
      missing.push_back(point.index);
    }
  }
  if (!missing.empty()) {
    std::string list;
    for (std::size_t i = 0; i < missing.size() && i < 20; ++i)
      list += (i ? ", " : "") + std::to_string(missing[i]);
    if (missing.size() > 20) list += ", ...";
    throw_invalid("--merge", dir.string(),
                  "a sweep's directory with every point committed (" +
                      std::to_string(missing.size()) + " of " + std::to_string(points.size()) +
                      " points are not: " + list + "; run the shards that hold them)");
  }
  SweepOutcome outcome = detail::write_tables(spec, points, pieces, out);
  outcome.reused = points.size();
  return outcome;
}

}  // namespace fogradar::sweep
