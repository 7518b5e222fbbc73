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
using detail::with_seed;
using nlohmann::json;

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
    const sensor::StepTable& table = outcome.summary->step_table();
    const sensor::Verdict verdict = outcome.summary->verdict();
    json s = {
        {"sensor", outcome.name},
        {"columns", table.csv_headers()},
        {"rows", table.csv_cells()},
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

experiment::Scenario with_seed(experiment::Scenario scenario, std::uint64_t seed) {
  scenario.experiment.seed = seed & 0x7fffffffffffffffULL;  // TOML integers are signed 64-bit
  return scenario;
}

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

std::vector<std::size_t> cost_order(const SweepSpec& spec, const std::vector<Point>& points) {
  std::vector<std::pair<std::size_t, std::size_t>> cost;  // items, index
  for (const Point& p : points) {
    std::size_t items = 0;
    for (std::size_t s = 0; s <= p.setups.size(); ++s) {
      const experiment::Scenario& scenario = s == 0 ? p.scenario : p.setups[s - 1];
      for (const std::string& name : scenario.experiment.sensors) {
        items += scenario.steps() * scenario.configure(name)->items_per_step() *
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
    for (std::size_t r = 0; r < spec.replications; ++r)
      runs.push_back(with_seed(p.scenario, p.seed + r));
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
    for (const std::string& name : scenario.experiment.sensors) {
      e.items += scenario.steps() * scenario.configure(name)->items_per_step();
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
      if (options.keep_points) out.keep(index, computed.kept);
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
