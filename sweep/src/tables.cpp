// The sweep's tables (docs/sweep.md): points.csv, results.csv, limits.csv and the plots and
// envelope tables beside them, written from every point's piece.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine.hpp"
#include "fogradar/sweep/sweep.hpp"

namespace fogradar::sweep::detail {

using nlohmann::json;

namespace {

std::string points_csv(const SweepSpec& spec, const std::vector<Point>& points) {
  std::string out = "point";
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on `"," + std::string&&` here.
  for (const Axis& axis : spec.axes) {
    for (const std::string& key : axis.keys) out.append(",").append(csv_field(key));
  }
  out += ",seed\n";
  for (const Point& p : points) {
    out += std::to_string(p.index);
    for (const auto& [key, value] : p.values) out.append(",").append(csv_field(value.text));
    out.append(",").append(std::to_string(p.seed & 0x7fffffffffffffffULL)).append("\n");
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

}  // namespace

bool is_step_column(const std::string& column) { return column == "active_layers"; }

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
    std::string& table = outcome.limits_table;
    table.append("  ").append(std::to_string(p)).append("  ").append(points[p].label()).append(":");
    for (const json& s : pieces[p]["runs"][0]["sensors"]) {
      table.append(" ").append(s["sensor"].get<std::string>()).append(" ");
      table.append(s["limit"].is_null() ? std::string("not reached")
                                        : std::to_string(s["limit"].get<std::size_t>()));
    }
    outcome.limits_table += "\n";
  }
  return outcome;
}

}  // namespace fogradar::sweep::detail
