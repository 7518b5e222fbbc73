// `fogradar sweep` (docs/sweep.md).
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "checks.hpp"
#include "commands.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/sweep/spec.hpp"
#include "fogradar/sweep/sweep.hpp"
#include "signal_watch.hpp"

namespace fogradar::cli {
namespace {

struct SweepOptions {
  std::string sweep_path;
  std::string out_dir;
  int threads = 0;
  bool resume = false;
  bool keep_points = false;
  std::optional<double> memory_limit_mib;
};

// Points done, their rate and the time left, on a terminal only.
void print_progress(std::size_t done, std::size_t total, double seconds) {
  if (!::isatty(STDERR_FILENO)) return;
  const double rate = seconds > 0.0 ? static_cast<double>(done) / seconds : 0.0;
  const double left = rate > 0.0 ? static_cast<double>(total - done) / rate : 0.0;
  std::fprintf(stderr, "\rfogradar: point %zu of %zu, %.3g points/s, about %.0f s left%s", done,
               total, rate, left, done == total ? "\n" : "   ");
}

void sweep(const SweepOptions& options) {
  const sweep::SweepSpec spec = sweep::load_sweep_file(options.sweep_path);
  const std::vector<sweep::Point> points = sweep::expand(spec);
  experiment::SensorCache cache;
  sweep::SweepOptions run{
      .threads = static_cast<unsigned>(options.threads),
      .resume = options.resume,
      .keep_points = options.keep_points,
      .memory_limit_bytes = options.memory_limit_mib
                                ? static_cast<std::size_t>(*options.memory_limit_mib * 1048576.0)
                                : 0,
      .stop = nullptr,
      .progress = print_progress,
      .cache = &cache};
  const sweep::SweepEstimate estimate = sweep::estimate(spec, points, run);
  std::cout << "sweep: " << estimate.text() << std::endl;
  const SignalWatch signals;
  run.stop = &signals.stop();
  sweep::SweepOutcome outcome;
  try {
    outcome = sweep::run_sweep(spec, points, options.out_dir, run);
  } catch (const experiment::Interrupted&) {
    signals.throw_interrupted("the points committed so far stay in " + options.out_dir +
                              "; rerun with --resume to compute only the others");
  }
  std::cout << "layers to failure (limits.csv), replication 0:\n"
            << outcome.limits_table << outcome.computed << " point"
            << (outcome.computed == 1 ? "" : "s") << " computed, " << outcome.reused
            << " committed before; results in " << options.out_dir << "/:";
  for (const std::string& file : outcome.files) std::cout << " " << file;
  std::cout << "\n";
}

}  // namespace

Action add_sweep_command(CLI::App& app) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* sweep_app = app.add_subcommand(
      "sweep",
      "Run every point of a sweep file (docs/sweep.md) into one directory of tables and plots");
  sweep_app->add_option("--sweep", options->sweep_path, "Sweep file (TOML)")
      ->required()
      ->check(non_empty_path("--sweep"));
  sweep_app->add_option("--out", options->out_dir, "Output directory (grows point by point)")
      ->required()
      ->check(non_empty_path("--out"));
  sweep_app
      ->add_option("--threads", options->threads,
                   "Worker threads of each point, 0 = all cores [0, 4096]")
      ->capture_default_str()
      ->check(integer_in("--threads", 0, 4096));
  sweep_app->add_flag("--resume", options->resume,
                      "Keep the points --out has committed for this sweep; compute the others");
  sweep_app->add_flag("--keep-points", options->keep_points,
                      "Also write each point's result set (replication 0) into points/<index>/");
  sweep_app
      ->add_option("--memory-limit-mib", options->memory_limit_mib,
                   "Refuse a point estimated to need more memory [1, 1e9] (default: half the "
                   "physical memory)")
      ->check(number_in("--memory-limit-mib", 1.0, 1e9, "in [1, 1e9]"));
  return [options] { sweep(*options); };
}

}  // namespace fogradar::cli
