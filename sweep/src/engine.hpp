// The sweep's parts that its serial, sharded, merged and MPI runs share (run.cpp, directory.cpp,
// mpi.cpp), the tables and their CSV (tables.cpp, envelope.cpp, csv.cpp), and the reading of the
// pieces and the plots (pieces.cpp, plots.cpp).
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/experiment/files.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/sensor/sensor.hpp"
#include "fogradar/sweep/spec.hpp"
#include "fogradar/sweep/sweep.hpp"

namespace fogradar::sweep::detail {

// The directory a sweep grows in (the result set's rules, for a directory that grows): holding
// nothing but a sweep's files, locked for one sweep at a time (for a shard, for one run of that
// shard). Fresh: an earlier sweep's files are removed; resume, shard and merge: committed points
// stay. A committed piece is filed under its point's definition (definition_of), not the point's
// index, so that a point keeps its piece when values added to an axis move it in the grid.
class SweepDirectory {
 public:
  enum class Mode { fresh, resume, shard, merge };
  // `definitions`: the sweep's points' (with resume, the pieces of any other are removed).
  SweepDirectory(const std::filesystem::path& dir, Mode mode,
                 const std::vector<std::string>& definitions, std::size_t shard = 0);
  ~SweepDirectory();

  const std::filesystem::path& path() const { return dir_; }
  // The piece committed for `definition`, wherever in the grid it was computed.
  std::optional<nlohmann::json> committed(const std::string& definition) const;
  // Files `piece` under its "definition".
  void commit(const nlohmann::json& piece) const;
  void write_table(std::string_view name, std::string_view content) const;
  // Point `index`'s result set into points/<index>/, as `fogradar run --out` writes it.
  void keep(std::size_t index, const std::vector<sensor::ResultFile>& files) const;
  // Whether points/<index>/ holds the result set of `point` (its scenario.toml is the point's).
  bool holds_kept(const Point& point) const;
  // Removes points/<index>/ of each of `indices` that holds another point's result set (one that
  // moved in the grid since), and with `all` the sweep's indices, every points/<i>/ beyond them.
  void remove_stale_kept(const std::vector<Point>& points, const std::vector<std::size_t>& indices,
                         bool all) const;

 private:
  std::filesystem::path dir_;
  std::unique_ptr<experiment::PathLock> lock_;
};

// A hash of everything point `point`'s numbers depend on: its scenarios, resolved (seed
// included), and its runs; 16 hexadecimal digits, never its index.
std::string definition_of(const Point& point, std::size_t replications);
// Every point's definition, in point order.
std::vector<std::string> definitions_of(const std::vector<Point>& points, std::size_t replications);

struct Computed {
  nlohmann::json piece;                  // what DIR/.sweep/<index>.json holds
  std::vector<sensor::ResultFile> kept;  // --keep-points: replication 0's result set
};
Computed compute_point(const SweepSpec& spec, const Point& point, const std::string& definition,
                       const propagation::SegelsteinTable& water, experiment::SensorCache& cache,
                       const SweepOptions& options);

// The points' indices, the most costly first (runs x items, then by index): the order a queue
// hands them out and shards split them.
std::vector<std::size_t> cost_order(const SweepSpec& spec, const std::vector<Point>& points);

// The tables from every point's piece (in point order), written into `out`.
SweepOutcome write_tables(const SweepSpec& spec, const std::vector<Point>& points,
                          const std::vector<nlohmann::json>& pieces, const SweepDirectory& out);

// A summary cell's number (nullopt: empty or not a number).
std::optional<double> number_of(const std::string& text);
// The sensors of the pieces' runs, in order of first appearance.
std::vector<std::string> sensor_order(const std::vector<nlohmann::json>& pieces);
// The entry of sensor `name` in a run's "sensors" (nullptr: it did not run).
const nlohmann::json* sensor_of(const nlohmann::json& sensors, const std::string& name);
// Type-7 quantile of any finite, non-empty sample.
double quantile(std::vector<double> values, double p);

// The plots (docs/sweep.md), from every point's piece in point order.
std::string comparison_svg(const std::vector<Point>& points,
                           const std::vector<nlohmann::json>& pieces);
std::string limits_svg(const SweepSpec& spec, const std::vector<Point>& points,
                       const std::vector<nlohmann::json>& pieces);
std::string envelope_svg(const SweepSpec& spec, const std::vector<Point>& points,
                         const std::vector<nlohmann::json>& pieces);

// The sweep file's directory, kept in DIR so that `--merge DIR` reads its base as the sweep did.
void write_origin(const SweepDirectory& out, const std::filesystem::path& sweep_directory);
SweepSpec read_spec(const std::filesystem::path& dir);

// The CSV writer (csv.cpp).
// A number in the fewest digits that read back as it (std::to_chars).
std::string shortest(double value);
// RFC 4180: a field with a comma, a quote or a line break is quoted, its quotes doubled.
using sensor::csv_field;

// Whether a summary column is the step (the active layers), not a statistic (tables.cpp).
bool is_step_column(const std::string& column);

// The envelope's tables (envelope.cpp): per point x sensor x step x statistic, how many setups
// gave a value and its quantiles; and the same of the limits.
std::string envelope_csv(const std::vector<nlohmann::json>& pieces);
std::string envelope_limits_csv(const std::vector<nlohmann::json>& pieces);

// `scenario` with experiment.seed = `seed` as TOML holds it (run.cpp).
experiment::Scenario with_seed(experiment::Scenario scenario, std::uint64_t seed);

}  // namespace fogradar::sweep::detail
