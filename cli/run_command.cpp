// `fogradar run` and `fogradar scenario` (docs/scenario.md).
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <functional>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"

namespace fogradar::cli {
namespace {

struct RunOptions {
  std::optional<std::string> scenario_path;
  std::string out_dir = "fogradar-out";
  std::optional<std::int64_t> seed;  // signed: CLI11 would wrap "-4" into an unsigned
  int threads = 0;
  std::optional<double> memory_limit_mib;  // default: experiment::default_memory_limit_bytes()
};

// Progress on stderr only when it is a terminal (docs/architecture.md, Contracts); throttled to whole percents.
std::function<void(std::size_t, std::size_t)> terminal_progress() {
  if (!::isatty(STDERR_FILENO)) return {};
  auto last_percent = std::make_shared<std::atomic<int>>(-1);
  return [last_percent](std::size_t done, std::size_t total) {
    const int percent = static_cast<int>(100 * done / total);
    int previous = last_percent->load();
    while (percent > previous) {
      if (last_percent->compare_exchange_weak(previous, percent)) {
        std::fprintf(stderr, "\rfogradar: %3d %% (%zu of %zu measurements)%s", percent, done, total,
                     done == total ? "\n" : "");
        break;
      }
    }
  };
}

void run(const RunOptions& options) {
  experiment::Scenario scenario = options.scenario_path ? experiment::load_scenario_file(*options.scenario_path)
                                                        : experiment::paper_scenario();
  if (options.seed) {
    if (*options.seed < 0) throw_invalid("--seed", static_cast<double>(*options.seed), "an integer >= 0");
    scenario.experiment.seed = static_cast<std::uint64_t>(*options.seed);
  }
  require_in_range("--threads", options.threads, 0.0, 4096.0);
  scenario.validate();
  if (options.memory_limit_mib) require_in_range("--memory-limit-mib", *options.memory_limit_mib, 1.0, 1e9);
  experiment::require_memory_within(
      scenario, static_cast<unsigned>(options.threads),
      options.memory_limit_mib ? static_cast<std::size_t>(*options.memory_limit_mib * 1048576.0)
                               : experiment::default_memory_limit_bytes());

  const std::filesystem::path dir(options.out_dir);
  const bool created = experiment::prepare_output_directory(dir);
  try {
    const experiment::ExperimentResult result =
        experiment::run_experiment(
        scenario, {.threads = static_cast<unsigned>(options.threads), .progress = terminal_progress()});
    const experiment::ExperimentSummary summary = experiment::summarize(result);
    experiment::write_outputs(dir, scenario, result, summary);
    std::cout << experiment::summary_table(summary) << "results in " << dir.string() << "/\n";
  } catch (...) {
    std::error_code ignored;
    if (created) std::filesystem::remove(dir, ignored);  // only removes it if still empty
    throw;
  }
}

}  // namespace

Action add_run_command(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* run_app = app.add_subcommand(
      "run", "Run the fog-layer experiment (default: the study's embedded paper scenario) and write its results");
  run_app->add_option("--scenario", options->scenario_path, "Scenario TOML file (keys override the paper scenario)");
  run_app->add_option("--out", options->out_dir, "Output directory")->capture_default_str();
  run_app->add_option("--seed", options->seed, "Random seed (overrides experiment.seed)");
  run_app->add_option("--threads", options->threads, "Worker threads, 0 = all cores [0, 4096]")
      ->capture_default_str();
  run_app->add_option("--memory-limit-mib", options->memory_limit_mib,
                      "Refuse a run whose estimated peak memory exceeds this many MiB [1, 1e9] (default: half the physical memory)");
  return [options] { run(*options); };
}

Action add_scenario_command(CLI::App& app) {
  app.add_subcommand("scenario", "Print the default (paper) scenario as TOML, every key commented");
  return [] { std::cout << experiment::paper_scenario_toml(); };
}

}  // namespace fogradar::cli
