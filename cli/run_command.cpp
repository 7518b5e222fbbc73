// `fogradar run` and `fogradar scenario` (docs/scenario.md).
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "checks.hpp"
#include "commands.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/raw_file.hpp"
#include "fogradar/experiment/run_time.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "signal_watch.hpp"

namespace fogradar::cli {
namespace {

struct RunOptions {
  std::optional<std::string> scenario_path;
  std::string out_dir = "fogradar-out";
  std::optional<std::int64_t> seed;  // signed: CLI11 would wrap "-4" into an unsigned
  int threads = 0;
  std::optional<double> memory_limit_mib;  // default: experiment::default_memory_limit_bytes()
  std::optional<double> time_limit_s;      // --time-limit: none by default
  std::optional<std::string> raw_path;     // --raw: the raw data out (docs/data-out.md)
  // --raw-select, --raw-steps, --raw-items, --raw-limit-mib
  experiment::RawRequest raw;
};

// --raw must not lie inside --out, which is replaced whole.
void require_raw_outside(const std::filesystem::path& raw, const std::filesystem::path& out) {
  std::error_code error;
  const std::filesystem::path file = std::filesystem::absolute(raw, error).lexically_normal();
  const std::filesystem::path dir = std::filesystem::absolute(out, error).lexically_normal();
  const auto [d, f] = std::mismatch(dir.begin(), dir.end(), file.begin(), file.end());
  if (d == dir.end() || (std::next(d) == dir.end() && d->empty())) {
    throw_invalid(
        "--raw", raw.string(),
        "a file outside --out = '" + out.string() + "' (the result set is replaced whole)");
  }
}

// Progress on stderr only when it is a terminal (docs/architecture.md, Contracts); throttled to
// whole percents. `items` says what is counted ("radar measurements and lidar scans").
std::function<void(std::size_t, std::size_t)> terminal_progress(std::string items) {
  if (!::isatty(STDERR_FILENO)) return {};
  auto last_percent = std::make_shared<std::atomic<int>>(-1);
  return [last_percent, items](std::size_t done, std::size_t total) {
    const int percent = static_cast<int>(100 * done / total);
    int previous = last_percent->load();
    while (percent > previous) {
      if (last_percent->compare_exchange_weak(previous, percent)) {
        std::fprintf(stderr, "\rfogradar: %3d %% (%zu of %zu %s)%s", percent, done, total,
                     items.c_str(), done == total ? "\n" : "");
        break;
      }
    }
  };
}

// "40.2 MiB".
std::string mib_text(std::size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / 1048576.0);
  return text;
}

void run(const RunOptions& options) {
  experiment::Scenario scenario = options.scenario_path
                                      ? experiment::load_scenario_file(*options.scenario_path)
                                      : experiment::paper_scenario();
  // --seed and --threads were checked as typed (checks.hpp) before CLI11 converted them.
  if (options.seed) scenario.experiment.seed = static_cast<std::uint64_t>(*options.seed);
  scenario.validate();
  const auto threads = static_cast<unsigned>(options.threads);
  experiment::require_memory_within(
      scenario, threads,
      options.memory_limit_mib ? static_cast<std::size_t>(*options.memory_limit_mib * 1048576.0)
                               : experiment::default_memory_limit_bytes());
  if (options.time_limit_s)
    experiment::require_time_within(scenario, threads, *options.time_limit_s);

  const std::filesystem::path dir(options.out_dir);
  std::optional<experiment::RawPlan> raw_plan;
  if (options.raw_path) {
    require_raw_outside(*options.raw_path, dir);
    experiment::RawRequest request = options.raw;
    request.path = *options.raw_path;
    raw_plan = experiment::resolve_raw(scenario, request);
  }
  // Before the output directory: the directory is released with the signals still held off.
  const SignalWatch signals;
  experiment::OutputDirectory out(dir);
  std::optional<experiment::RawFile> raw;
  if (raw_plan) raw.emplace(*raw_plan, scenario);
  // Once nothing is left to refuse, so that a refused run prints its message alone. Flushed: a
  // caller reads it while the run works.
  std::cout << "estimated time: " << experiment::estimate_run_time(scenario, threads).text()
            << ", peak memory: "
            << mib_text(experiment::estimate_peak_memory(scenario, threads).total_bytes())
            << std::endl;
  experiment::ExperimentResult result;
  try {
    result = experiment::run_experiment(
        scenario, {.threads = threads,
                   .progress = terminal_progress(experiment::item_nouns(scenario)),
                   .stop = &signals.stop(),
                   .raw = raw ? &*raw : nullptr});
  } catch (const experiment::Interrupted&) {
    signals.throw_interrupted("no results written, " + dir.string() + " left as it was");
  }
  const experiment::ExperimentSummary summary = experiment::summarize(result);
  // The raw file complete on disk before the result set is swapped, named only after it.
  if (raw) raw->finish();
  if (!out.replace(experiment::result_files(scenario, summary),
                   [&] { return signals.stop().load(); })) {
    signals.throw_interrupted("no results written, " + dir.string() + " left as it was");
  }
  if (raw) raw->publish();
  std::cout << experiment::sensor_tables(summary) << experiment::benchmark_table(summary)
            << "results in " << dir.string() << "/\n";
  if (raw) std::cout << "raw data in " << options.raw_path->c_str() << "\n";
  // Each sensor's warnings about its numbers (e.g. the radar's ADC clipping), after the tables.
  std::cout.flush();
  for (const experiment::SensorOutcome& outcome : summary.sensors) {
    for (const std::string& warning : outcome.summary->warnings()) {
      std::cerr << "fogradar: warning: " << warning << '\n';
    }
  }
}

}  // namespace

Action add_run_command(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* run_app = app.add_subcommand("run",
                                         "Run the fog-layer experiment (default: the study's "
                                         "embedded paper scenario) and write its results");
  run_app
      ->add_option("--scenario", options->scenario_path,
                   "Scenario TOML file, a regular file of at most 1 MiB (keys override the paper "
                   "scenario)")
      ->check(non_empty_path("--scenario"));
  run_app->add_option("--out", options->out_dir, "Output directory")
      ->capture_default_str()
      ->check(non_empty_path("--out"));
  run_app
      ->add_option("--seed", options->seed,
                   "Random seed [0, 9223372036854775807] (overrides experiment.seed)")
      ->check(integer_in("--seed", 0, std::numeric_limits<std::int64_t>::max()));
  run_app->add_option("--threads", options->threads, "Worker threads, 0 = all cores [0, 4096]")
      ->capture_default_str()
      ->check(integer_in("--threads", 0, 4096));
  run_app
      ->add_option("--memory-limit-mib", options->memory_limit_mib,
                   "Refuse a run whose estimated peak memory exceeds this many MiB [1, 1e9] "
                   "(default: half the physical memory)")
      ->check(number_in("--memory-limit-mib", 1.0, 1e9, "in [1, 1e9]"));
  run_app
      ->add_option("--time-limit", options->time_limit_s,
                   "Refuse a run whose estimated wall time exceeds this many seconds [0.001, 1e9] "
                   "(the estimate is printed before every run; default: no limit)")
      ->check(number_in("--time-limit", 1e-3, 1e9, "in [0.001, 1e9] (seconds)"));
  CLI::Option* raw =
      run_app
          ->add_option("--raw", options->raw_path,
                       "Write every measurement's raw data asked for into this HDF5 file "
                       "(docs/data-out.md); a new file or one fogradar wrote, outside --out")
          ->check(non_empty_path("--raw"));
  run_app
      ->add_option("--raw-select", options->raw.kinds,
                   "With --raw: the kinds, sensor.kind separated by commas (docs/data-out.md; a "
                   "wrong one is refused with the running sensors' kinds) (default: every kind "
                   "of the sensors that run)")
      ->needs(raw);
  run_app
      ->add_option("--raw-steps", options->raw.steps,
                   "With --raw: the steps (active layers), e.g. 0,4 or 0-2 (default: every step)")
      ->needs(raw);
  run_app
      ->add_option("--raw-items", options->raw.items,
                   "With --raw: the items of each step (measurements, scans, frames), e.g. 0-9 "
                   "(default: the first ten)")
      ->needs(raw);
  run_app
      ->add_option("--raw-limit-mib", options->raw.limit_mib,
                   "With --raw: refuse a raw file estimated larger than this many MiB [1, 1e9]")
      ->capture_default_str()
      ->check(number_in("--raw-limit-mib", 1.0, 1e9, "in [1, 1e9]"))
      ->needs(raw);
  return [options] { run(*options); };
}

Action add_scenario_command(CLI::App& app) {
  auto sections = std::make_shared<std::vector<std::string>>();
  auto keys = std::make_shared<bool>(false);
  CLI::App* scenario = app.add_subcommand(
      "scenario", "Print the default (paper) scenario as TOML, every key commented");
  scenario->add_flag("--keys", *keys,
                     "Print the key tables of docs/scenario.md instead: key, default, allowed "
                     "values, meaning, one table per top-level section");
  scenario->add_option("sections", *sections, "With --keys: only these top-level sections");
  return [sections, keys] {
    if (!*keys && sections->empty()) {
      std::cout << experiment::paper_scenario_toml();
      return;
    }
    if (!*keys) throw_invalid("sections", sections->front(), "given with --keys only");
    // Every section is checked before anything is printed.
    const experiment::Scenario paper = experiment::paper_scenario();
    std::vector<std::string> tables;
    for (const std::string& section : *sections) {
      tables.push_back(experiment::key_table_markdown(paper, section));
    }
    if (sections->empty()) {
      for (const std::string& section : experiment::top_level_sections(paper)) {
        std::cout << (section == experiment::top_level_sections(paper).front() ? "" : "\n")
                  << "### [" << section << "]\n\n"
                  << experiment::key_table_markdown(paper, section);
      }
      return;
    }
    for (const std::string& table : tables) std::cout << table;
  };
}

}  // namespace fogradar::cli
