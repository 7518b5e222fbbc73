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
#include "fogradar/sweep/sweep.hpp"

namespace fogradar::sweep {
namespace {

namespace fs = std::filesystem;
using detail::number_of;
using detail::quantile;
using detail::sensor_of;
using detail::sensor_order;
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
  const experiment::Simulation simulation(scenario, water, &cache, options.stop);
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

bool is_step_column(const std::string& column) { return column == "active_layers"; }

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
          for (const double level : envelope_levels) {
            out += ',';
            if (!values.empty()) out += shortest(quantile(values, level));
          }
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

SweepDirectory::SweepDirectory(const fs::path& dir, Mode mode,
                               const std::vector<std::string>& definitions, std::size_t shard) {
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
      // points/<index>/, and .sweep/<definition>.json (an earlier version's .sweep/<index>.json).
      const std::string stem = name.substr(0, name.find('.'));
      const bool hex = sub == state_dir;
      const bool ours = !stem.empty() && std::all_of(stem.begin(), stem.end(), [hex](char c) {
        return (c >= '0' && c <= '9') || (hex && c >= 'a' && c <= 'f');
      });
      if (ours || name.starts_with(".") || name == origin_file) continue;
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
  // A crash's temporary files go; without --resume an earlier sweep's files, with it the pieces of
  // points this sweep does not have. A shard removes nothing (the others write beside it), nor
  // does a merge.
  if (mode == Mode::shard || mode == Mode::merge) return;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    if ((name.starts_with(".") && name.find(".tmp-") != std::string::npos) ||
        (mode == Mode::fresh && table_names.contains(name))) {
      fs::remove_all(entry.path(), error);
    }
  }
  if (mode == Mode::fresh) fs::remove_all(dir_ / points_dir, error);
  const std::set<std::string, std::less<>> own(definitions.begin(), definitions.end());
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_ / state_dir)) {
    const std::string name = entry.path().filename().string();
    const bool piece = name.ends_with(".json") && !name.starts_with(".");
    const bool stale =
        name.starts_with(".") || (piece && !own.contains(name.substr(0, name.size() - 5)));
    if (mode == Mode::fresh || stale) fs::remove(entry.path(), error);
  }
}

SweepDirectory::~SweepDirectory() = default;

std::optional<json> SweepDirectory::committed(const std::string& definition) const {
  std::ifstream in(dir_ / state_dir / (definition + ".json"));
  if (!in) return std::nullopt;
  try {
    json piece = json::parse(in);
    if (piece.value("definition", std::string()) == definition) return piece;
  } catch (const json::exception&) {
  }
  return std::nullopt;
}

void SweepDirectory::commit(const json& piece) const {
  write_table(std::string(state_dir) + "/" + piece.at("definition").get<std::string>() + ".json",
              piece.dump() + "\n");
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

bool SweepDirectory::holds_kept(const Point& point) const {
  std::ifstream in(dir_ / points_dir / std::to_string(point.index) / "scenario.toml",
                   std::ios::binary);
  if (!in) return false;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str() == experiment::to_toml(with_seed(point.scenario, point.seed));
}

std::string definition_of(const Point& point, std::size_t replications) {
  std::string text =
      experiment::to_toml(point.scenario) + "\nreplications " + std::to_string(replications);
  for (const experiment::Scenario& setup : point.setups) {
    text += "\nsetup\n" + experiment::to_toml(setup);
  }
  return fnv_hex(text);
}

void SweepDirectory::remove_stale_kept(const std::vector<Point>& points,
                                       const std::vector<std::size_t>& indices, bool all) const {
  std::error_code error;
  if (!fs::is_directory(dir_ / points_dir, error)) return;
  for (const std::size_t index : indices) {
    const fs::path kept = dir_ / points_dir / std::to_string(index);
    if (fs::exists(kept, error) && !holds_kept(points[index])) fs::remove_all(kept, error);
  }
  if (!all) return;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_ / points_dir, error)) {
    const std::string name = entry.path().filename().string();
    std::size_t index = 0;
    const auto [end, parsed] = std::from_chars(name.data(), name.data() + name.size(), index);
    if (parsed == std::errc() && end == name.data() + name.size() && index >= points.size())
      fs::remove_all(entry.path(), error);
  }
}

std::vector<std::string> definitions_of(const std::vector<Point>& points,
                                        std::size_t replications) {
  std::vector<std::string> definitions;
  for (const Point& point : points) definitions.push_back(definition_of(point, replications));
  return definitions;
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
  const std::vector<std::string> definitions = detail::definitions_of(points, spec.replications);
  const detail::SweepDirectory out(dir, mode, definitions, shard ? shard->index : 0);
  out.write_table("sweep.toml", spec.text);
  detail::write_origin(out, spec.directory);
  if (options.opened) options.opened();
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
  if (mode != Mode::fresh) out.remove_stale_kept(points, mine, mode == Mode::resume);
  SweepOutcome outcome;
  std::vector<json> pieces;
  const auto start = std::chrono::steady_clock::now();
  for (const std::size_t index : mine) {
    const Point& point = points[index];
    const std::string& definition = definitions[index];
    std::optional<json> piece = mode != Mode::fresh ? out.committed(definition) : std::nullopt;
    // --keep-points wants point `index`'s result set in points/<index>/: one made for another
    // point there (before values were added to an axis) was removed, and the point is made again.
    if (piece && options.keep_points && !out.holds_kept(point)) piece.reset();
    if (piece) {
      ++outcome.reused;
    } else {
      detail::Computed computed =
          detail::compute_point(spec, point, definition, water, cache, options);
      if (options.keep_points) out.keep(index, point.scenario, computed.kept);
      out.commit(computed.piece);
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
  const detail::SweepDirectory out(dir, detail::SweepDirectory::Mode::merge, {});
  const SweepSpec spec = detail::read_spec(out.path());
  const std::vector<Point> points = expand(spec);
  std::vector<json> pieces;
  std::vector<std::size_t> missing;
  for (const Point& point : points) {
    std::optional<json> piece = out.committed(detail::definition_of(point, spec.replications));
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
