// `fogradar sweep` (docs/sweep.md): every point of a sweep run into one directory of
// tidy tables and overlay plots, each point committed whole as it finishes, so that a sweep stopped
// at any instant and resumed ends with the same bytes as one never interrupted.
//
// DIR holds sweep.toml (the sweep file), points.csv, results.csv, limits.csv, comparison.svg,
// limits.svg (with an axis), with [uncertain] envelope.csv, envelope_limits.csv and envelope.svg,
// with --keep-points each point's result set in points/<index>/, and the committed points in
// .sweep/<definition>.json, each filed by a hash of its resolved scenarios (never its index, so a
// resumed sweep whose axes gained values reuses every point it has). The tables are written when
// every point is committed.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fogradar/experiment/runner.hpp"
#include "fogradar/sweep/spec.hpp"

namespace fogradar::sweep {

// The i-th of N shares of a sweep's points, for the tasks of a job array: the points at positions
// i, i + N, i + 2N, ... of the cost order (the most costly first), so each share gets as many of
// the costly ones.
struct Shard {
  std::size_t index = 0;
  std::size_t count = 1;
};

struct SweepOptions {
  unsigned threads = 0;  // of each point's run (0: all hardware threads)
  bool resume = false;   // keep the points DIR has committed for this sweep
  bool keep_points = false;
  // Run only this share: its points are committed into DIR beside the other shards' (those it
  // finds committed for this sweep are kept, as with `resume`), and no table is written;
  // merge_sweep() writes them once every shard is in.
  std::optional<Shard> shard;
  std::size_t memory_limit_bytes = 0;  // 0: experiment::default_memory_limit_bytes()
  // Refuse a sweep whose runs' cost-model estimate (experiment::estimate_run_time) exceeds this
  // many seconds; 0: no limit.
  double time_limit_seconds = 0.0;
  // Set by another thread (a signal): the sweep stops at its next item; experiment::Interrupted.
  const std::atomic<bool>* stop = nullptr;
  // Once the output directory is accepted, before any point runs (on rank 0 under MPI): where a
  // caller says what the sweep will do, so that a refused sweep prints its message alone.
  std::function<void()> opened;
  // After each point: (points committed, points in all, seconds so far of this invocation's
  // points).
  std::function<void(std::size_t, std::size_t, double)> progress;
  // Sensors kept from point to point (what does not depend on a swept key is made once);
  // run_sweep() uses this one when given, else keeps its own.
  experiment::SensorCache* cache = nullptr;
};

// What a sweep will do, said before it does it.
struct SweepEstimate {
  std::size_t points = 0;
  std::size_t runs = 0;      // points x (replications + setups)
  std::size_t items = 0;     // of every sensor of every run
  double seconds = 0.0;      // experiment::estimate_runs of every run, in one process: wall time
  double cpu_seconds = 0.0;  // and CPU time
  std::size_t peak_bytes = 0;
  std::string text() const;
};

// Refuses (InvalidParameter naming "--memory-limit-mib") a point whose run would exceed the memory
// limit, and one over the time limit (experiment::require_time_within: filed under the key that
// dominates it) or a sweep whose runs together exceed it ("--time-limit"). Its time is the cost
// models' (experiment::estimate_runs): nothing is run or timed.
SweepEstimate estimate(const SweepSpec& spec, const std::vector<Point>& points,
                       const SweepOptions& options);

struct SweepOutcome {
  std::size_t computed = 0;  // points run by this invocation
  std::size_t reused = 0;    // points found committed (--resume)
  // A line per point: its values and each sensor's layers to failure (replication 0), as the
  // command prints them.
  std::string limits_table;
  std::vector<std::string> files;  // the tables written, in DIR
  // On MPI: the ranks, and rank 0's time spent per message of a worker (receiving, committing,
  // answering).
  std::size_t ranks = 1;
  double bookkeeping_seconds_per_message = 0.0;
};

// Runs every point not yet committed into `dir` and writes the tables. Refuses (InvalidParameter
// naming "--out") a `dir` that holds anything but a sweep's files (so no file of the user's is ever
// deleted) or that another sweep holds. Without `resume` the files of an earlier sweep there are
// replaced; with it, points committed for the same point definition are kept, wherever in the
// grid they were computed. Throws experiment::Interrupted when stopped: the points committed so
// far stay.
SweepOutcome run_sweep(const SweepSpec& spec, const std::vector<Point>& points,
                       const std::filesystem::path& dir, const SweepOptions& options);

// The tables of a sweep whose shards have committed every point into `dir`; the sweep is read from
// dir/sweep.toml (a base path relative to where the sweep file was). Refuses (InvalidParameter
// naming "--merge") a directory that is not a sweep's or misses a point, listing the missing ones.
SweepOutcome merge_sweep(const std::filesystem::path& dir);

}  // namespace fogradar::sweep
