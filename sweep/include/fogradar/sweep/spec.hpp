// A sweep file (docs/sweep.md): a base scenario, the keys to vary (axes: value lists or
// lin/log ranges, several keys zipped on one axis, the grid their product), replications, a seed
// mode, and an optional [uncertain] section that gives unmeasured keys distributions. Expanded into
// points, each a full scenario validated before anything runs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fogradar/experiment/scenario.hpp"

namespace fogradar::sweep {

// A value of a swept or drawn key, as TOML writes it ("900.0", "\"os\"", "true", "[3, 1, 2, 0]")
// and as a table writes it ("900.0", "os", "true", "[3, 1, 2, 0]").
namespace detail {
struct ValueNode;  // the value as the sweep file gives it, or as drawn (TOML)
}  // namespace detail

struct Value {
  std::string toml;
  std::string text;
  std::optional<double> number;  // numbers (and integers): for ordering and plotting
  std::shared_ptr<const detail::ValueNode> node;  // set through the scenario's keys
};

struct Axis {
  std::vector<std::string> keys;              // one key, or several zipped
  std::vector<std::vector<Value>> positions;  // per position, one value per key
  std::size_t line = 0;                       // of its [[axis]] table in the sweep file
};

enum class SeedMode {
  common,     // every point the base scenario's seed: common random numbers across points
  by_values,  // a seed from the point's values (never its position)
};

enum class Sampling { latin_hypercube, monte_carlo };

struct Distribution {
  enum class Kind { uniform, normal, truncated_normal, discrete } kind = Kind::uniform;
  double low = 0.0, high = 0.0;  // uniform, truncated_normal
  double mean = 0.0, std = 0.0;  // normal, truncated_normal
  std::vector<Value> values;     // discrete: numbers, strings or booleans, all of one type
  std::vector<double> weights;   // discrete, summing to 1

  // The value drawn at cumulative probability u in (0, 1): the inverse CDF; of a discrete
  // distribution the first value whose cumulative weight exceeds u.
  Value drawn_at(double u) const;
};

struct UncertainKey {
  std::string key;
  Distribution distribution;
};

// A panel of envelope.svg: a sensor's per-step statistic drawn as a band across the setups, the
// nominal run's box plots under it where `box` names their columns, and reference values marked.
struct EnvelopePlot {
  std::string sensor;
  std::string statistic;         // a column of <sensor>_summary.csv
  std::vector<std::string> box;  // whisker_low, q1, median, q3, whisker_high columns; or empty
  std::string y_label;
  struct Reference {
    std::size_t active_layers = 0;
    double value = 0.0;
  };
  std::vector<Reference> references;
  std::string reference_label;
};

struct Uncertain {
  std::size_t setups = 0;
  Sampling sampling = Sampling::latin_hypercube;
  std::vector<UncertainKey> keys;
  std::vector<EnvelopePlot> plots;
};

struct SweepSpec {
  std::string source;               // the sweep file's path as given (messages)
  std::string text;                 // the file, verbatim (written into DIR as sweep.toml)
  std::filesystem::path directory;  // a relative base path's directory (the sweep file's)
  experiment::Scenario base;
  std::string base_name;  // "paper" or the path as the file gives it
  std::size_t replications = 1;
  SeedMode seed_mode = SeedMode::common;
  std::vector<Axis> axes;
  std::optional<Uncertain> uncertain;
};

// Reads a sweep file. Throws InvalidParameter naming the sweep key ("axis[1].values",
// "uncertain.keys.target.sensor_height_m.std") with "<source>:<line>: " as the scenario reader
// does; a base path is relative to the sweep file's directory. Every axis and [uncertain] key must
// be one of the base scenario's keys, or a key of an element the base's array of tables has
// ("chamber.layers[2].fog.lwc_g_per_m3").
SweepSpec load_sweep_file(const std::string& path);
SweepSpec parse_sweep(std::string_view text, std::string_view source,
                      const std::filesystem::path& directory);

// One point of the grid: its values (one per swept key, axis by axis), its seed and its scenario.
struct Point {
  std::size_t index = 0;
  std::vector<std::pair<std::string, Value>> values;
  std::uint64_t seed = 0;
  experiment::Scenario scenario;
  // A setup of [uncertain] (the point with the drawn values), one per setup.
  std::vector<experiment::Scenario> setups;
  std::vector<std::vector<std::pair<std::string, Value>>> setup_values;

  // "fog.extinction_per_km = 300.0, radar.window = hann": the point's label in plots.
  std::string label() const;
};

// The grid: the product of the axes, each axis's positions ordered by value (numbers by size, then
// text), the first axis outermost; every point's scenario (and every setup's) read over the base
// and validated: its keys as a scenario file giving them, an element key set through its
// element's key table. A bad point throws InvalidParameter naming the axis, the value and the key
// with the scenario's own message (its allowed range).
std::vector<Point> expand(const SweepSpec& spec);

}  // namespace fogradar::sweep
