// `fogradar sweep` (docs/sweep.md).
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "checks.hpp"
#include "commands.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/sweep/mpi.hpp"
#include "fogradar/sweep/spec.hpp"
#include "fogradar/sweep/sweep.hpp"
#include "signal_watch.hpp"

namespace fogradar::cli {
namespace {

struct SweepOptions {
  std::string sweep_path;
  std::string out_dir;
  std::string merge_dir;
  std::optional<sweep::Shard> shard;
  int threads = 0;
  bool resume = false;
  bool keep_points = false;
  std::optional<double> memory_limit_mib;
  double time_limit_s = 0.0;  // 0: none
};

// Points done, their rate and the time left, on a terminal only.
void print_progress(std::size_t done, std::size_t total, double seconds) {
  if (!::isatty(STDERR_FILENO)) return;
  const double rate = seconds > 0.0 ? static_cast<double>(done) / seconds : 0.0;
  const double left = rate > 0.0 ? static_cast<double>(total - done) / rate : 0.0;
  std::fprintf(stderr, "\rfogradar: point %zu of %zu, %.3g points/s, about %.0f s left%s", done,
               total, rate, left, done == total ? "\n" : "   ");
}

sweep::SweepOptions run_options(const SweepOptions& options, experiment::SensorCache& cache) {
  return {
      .threads = static_cast<unsigned>(options.threads),
      .resume = options.resume,
      .keep_points = options.keep_points,
      .shard = options.shard,
      .memory_limit_bytes = options.memory_limit_mib
                                ? static_cast<std::size_t>(*options.memory_limit_mib * 1048576.0)
                                : 0,
      .time_limit_seconds = options.time_limit_s,
      .stop = nullptr,
      .opened = {},
      .progress = print_progress,
      .cache = &cache};
}

void print_tables(const sweep::SweepOutcome& outcome, const std::string& dir) {
  std::cout << "layers to failure (limits.csv), replication 0:\n"
            << outcome.limits_table << outcome.computed << " point"
            << (outcome.computed == 1 ? "" : "s") << " computed, " << outcome.reused
            << " committed before; results in " << dir << "/:";
  for (const std::string& file : outcome.files) std::cout << " " << file;
  std::cout << "\n";
}

// Runs `body`; SIGINT or SIGTERM during it ends the command as Interrupted.
template <class Body>
sweep::SweepOutcome interruptible(const SignalWatch& signals, const std::string& dir, Body body) {
  try {
    return body();
  } catch (const experiment::Interrupted&) {
    signals.throw_interrupted("the points committed so far stay in " + dir +
                              "; rerun with --resume to compute only the others");
  }
}

void merge(const SweepOptions& options) {
  const sweep::SweepOutcome outcome = sweep::merge_sweep(options.merge_dir);
  print_tables(outcome, options.merge_dir);
}

// Under mpirun or srun: rank 0 reads, validates and tells; every rank runs points.
void sweep_on_mpi(const SweepOptions& options) {
  const SignalWatch signals;  // before MPI starts its threads, so that they inherit the mask
  sweep::MpiJob job;
  std::optional<sweep::SweepSpec> spec;
  std::vector<sweep::Point> points;
  experiment::SensorCache cache;
  sweep::SweepOptions run = run_options(options, cache);
  // Rank 0 says why it refuses before it meets the others in MPI_Finalize: a rank that exits with
  // status 2 first makes the launcher end the job, and rank 0 with it.
  try {
    job.settle([&] {
      spec = sweep::load_sweep_file(options.sweep_path);
      points = sweep::expand(*spec);
      const std::string said = "sweep: " + sweep::estimate(*spec, points, run).text() +
                               " (on each of " + std::to_string(job.size()) + " rank" +
                               (job.size() == 1 ? "" : "s") + ")";
      run.opened = [said] { std::cout << said << std::endl; };
    });
  } catch (const InvalidParameter& e) {
    std::cerr << "fogradar: " << e.what() << std::endl;
    throw sweep::RefusedOnRankZero();
  }
  const std::string text = job.share(spec ? spec->text : std::string());
  const std::string source = job.share(spec ? spec->source : std::string());
  const std::string directory = job.share(spec ? spec->directory.string() : std::string());
  if (job.rank() != 0) {
    spec = sweep::parse_sweep(text, source, directory);
    points = sweep::expand(*spec);
  }
  run.stop = &signals.stop();
  const sweep::SweepOutcome outcome = interruptible(signals, options.out_dir, [&] {
    return sweep::run_sweep(job, *spec, points, options.out_dir, run);
  });
  if (job.rank() != 0) return;
  print_tables(outcome, options.out_dir);
  std::cout << "on " << outcome.ranks << " MPI rank" << (outcome.ranks == 1 ? "" : "s")
            << "; rank 0 spent " << outcome.bookkeeping_seconds_per_message * 1e3
            << " ms per message of a worker (receiving, committing, answering)\n";
}

void sweep(const SweepOptions& options) {
  if (!options.merge_dir.empty()) {
    if (!options.sweep_path.empty() || !options.out_dir.empty() || options.shard) {
      throw InvalidParameter("--merge",
                             "--merge: builds the tables of the sweep in its directory; "
                             "give it alone, without --sweep, --out or --shard");
    }
    merge(options);
    return;
  }
  if (options.sweep_path.empty() || options.out_dir.empty()) {
    throw InvalidParameter(options.sweep_path.empty() ? "--sweep" : "--out",
                           std::string(options.sweep_path.empty() ? "--sweep" : "--out") +
                               " is required (or --merge DIR, to build a sharded sweep's tables)");
  }
  if (options.shard && sweep::launched_size().value_or(1) > 1) {
    throw InvalidParameter("--shard",
                           "--shard: runs one share of a sweep as a process of its own (a job "
                           "array's task); under mpirun the ranks share the points by themselves: "
                           "drop --shard, or run the shards without mpirun");
  }
  if (sweep::launched_rank() && !options.shard) {
    sweep_on_mpi(options);
    return;
  }
  const sweep::SweepSpec spec = sweep::load_sweep_file(options.sweep_path);
  const std::vector<sweep::Point> points = sweep::expand(spec);
  experiment::SensorCache cache;
  sweep::SweepOptions run = run_options(options, cache);
  const std::string said = "sweep: " + sweep::estimate(spec, points, run).text();
  // Said once --out is accepted too, so that a refused sweep prints its message alone.
  run.opened = [said] { std::cout << said << std::endl; };
  const SignalWatch signals;
  run.stop = &signals.stop();
  const sweep::SweepOutcome outcome = interruptible(signals, options.out_dir, [&] {
    return sweep::run_sweep(spec, points, options.out_dir, run);
  });
  if (options.shard) {
    std::cout << "shard " << options.shard->index << "/" << options.shard->count << ": "
              << outcome.computed << " point" << (outcome.computed == 1 ? "" : "s") << " computed, "
              << outcome.reused << " committed before, in " << options.out_dir
              << "/; once every shard is in: fogradar sweep --merge " << options.out_dir << "\n";
    return;
  }
  print_tables(outcome, options.out_dir);
}

// "i/N" with 0 <= i < N <= 100000.
CLI::Validator shard_check() {
  return CLI::Validator(
      [](const std::string& text) {
        const std::size_t slash = text.find('/');
        const std::optional<std::int64_t> index =
            slash == std::string::npos ? std::nullopt
                                       : parse_whole<std::int64_t>(text.substr(0, slash));
        const std::optional<std::int64_t> count =
            slash == std::string::npos ? std::nullopt
                                       : parse_whole<std::int64_t>(text.substr(slash + 1));
        if (!index || !count || *count < 1 || *count > 100000 || *index < 0 || *index >= *count) {
          throw_invalid("--shard", text, "i/N: integers with 0 <= i < N <= 100000");
        }
        return std::string();
      },
      "i/N");
}

}  // namespace

Action add_sweep_command(CLI::App& app) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* sweep_app = app.add_subcommand(
      "sweep",
      "Run every point of a sweep file (docs/sweep.md) into one directory of tables and plots; "
      "under mpirun or srun on every rank (docs/scale-out.md)");
  sweep_app
      ->add_option("--sweep", options->sweep_path, "Sweep file (TOML); required but with --merge")
      ->check(non_empty_path("--sweep"));
  sweep_app->add_option("--out", options->out_dir, "Output directory (grows point by point)")
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
  sweep_app
      ->add_option("--time-limit", options->time_limit_s,
                   "Refuse a sweep whose estimated wall time (each run's cost model, summed) "
                   "exceeds this many seconds [0.001, 1e9] (default: no limit)")
      ->check(number_in("--time-limit", 1e-3, 1e9, "in [0.001, 1e9] (seconds)"));
  sweep_app
      ->add_option_function<std::string>(
          "--shard",
          [options](const std::string& text) {
            const std::size_t slash = text.find('/');
            options->shard = sweep::Shard{
                static_cast<std::size_t>(*parse_whole<std::int64_t>(text.substr(0, slash))),
                static_cast<std::size_t>(*parse_whole<std::int64_t>(text.substr(slash + 1)))};
          },
          "Run only the i-th of N shares of the points into --out (a job array's task), keeping "
          "the points committed there; no tables (see --merge)")
      ->check(shard_check());
  sweep_app
      ->add_option("--merge", options->merge_dir,
                   "Build the tables of the sweep whose shards are all in DIR (alone)")
      ->check(non_empty_path("--merge"));
  return [options] { sweep(*options); };
}

}  // namespace fogradar::cli
