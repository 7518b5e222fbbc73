// The one shape every sensor has (docs/architecture.md, "The sensor interface"): experiment/, cli/
// and python/ know a sensor only through this interface, and one registry in experiment/ lists the
// kinds that implement it (pbrt-v4's Medium: a small interface, one factory that names the types).
// A sensor folder (radar/, lidar/, camera/) provides:
//
//   SensorKind        its name and stream key (KindInfo), its keys over its own parameter struct
//                     with their defaults, and configure(params, context): its keys checked with
//                     what they cannot check alone, the
//   ConfiguredSensor  the sensor for one scenario, typed: its items per step, cost, memory, raw
//                     data kinds and view of the fog, and make(): the
//   Sensor            what every run shares (chamber, plans, tables, optics), made once,
//                     immutable, safe to share between threads; it begins
//   SensorRun         one run: per-step state, then the items measured by
//   Worker            per-thread workers from their own random streams, then
//   SensorSummary     its per-step statistics (a StepTable of typed columns), limit verdict,
//                     printed table, JSON summary, result files and benchmark curve.
//
// Kind<P> implements SensorKind over a parameter struct P once: experiment/ holds a kind's
// parameters as an opaque Params, which only the kind's keys and configure() read. Items are keyed
// (seed, sensor's stream key, step, index), so a run is byte-identical for any thread count and
// adding a sensor never changes another's numbers.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fogradar/core/keys.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/core/stop.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/room_spec.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/sensor/step_table.hpp"

namespace fogradar::sensor {

// The target and the floor as the world has them ([target]), the same for every sensor: what each
// sensor's own view of the target (its model, RCS or reflectivity) does not decide.
struct TargetWorld {
  double micro_motion_std_m = 0.2e-3;    // rms line-of-sight jitter per measurement
  double radial_velocity_m_per_s = 0.0;  // the whole target's, + receding
  double water_film_m = 0.0;             // water film on the target's metal surfaces
};

// The keys of [target] over the world's target.
KeyTable<TargetWorld> target_world_keys();

// What a scenario gives every sensor besides its own keys: the chamber, the target in it and the
// room around it, the methodology's steps (k = 0 .. steps - 1 active layers, switched on in the
// switching order) and the seed.
struct Context {
  propagation::ChamberSpec chamber;
  TargetWorld target;
  propagation::RoomSpec room;
  std::size_t steps = 5;
  std::uint64_t seed = 1;
  // The layer indices (0 at the sensor) in the order they are switched on; empty: from the sensor,
  // the study's order.
  std::vector<std::size_t> switching_order;
  // Whether the sensor is to run (it is in experiment.sensors): a scenario configures the others
  // too, to check their keys against the chamber, but what only a sensor that runs needs of the
  // room (the lidar's optical data of its walls and objects) is not asked of them.
  bool runs = true;

  // The layers switched on at `step`: the first `step` of the switching order.
  propagation::ActiveLayers active(std::size_t step) const;
};

// The study's benchmark line of one sensor: layers to failure by its own criterion, or how far from
// failure it stayed at the last step.
struct Verdict {
  std::optional<std::size_t> layers_to_failure;
  std::string criterion;  // as the benchmark table and summary.json state it
  std::string margin;     // empty when the limit is reached
};

// The sensor's metric relative to clear weather (step 0) per step, for benchmark.svg.
struct Curve {
  std::string metric;  // the legend's word: "RCS", "intensity", "contrast"
  std::vector<double> active_layers;
  std::vector<double> relative_value;
  std::optional<std::size_t> limit;
};

struct ResultFile {
  // "<kind>_<rest>", the kind's name its prefix: the result set holds it under its instance's
  // name ("radar_24_summary.csv" for the kind's "radar_summary.csv").
  std::string name;
  std::string content;
};

// The bytes a run holds for one sensor with `threads` workers, and what they are made of (the keys
// and values a refusal over the memory limit names).
struct MemoryPart {
  std::size_t bytes = 0;
  std::string detail;  // "radar.samples_per_chirp = 512 x radar.chirps_per_frame = 64: ..."
  std::string key;     // the key the refusal names when this part is the largest
};

// The CPU time of one item on one thread, estimated from the sensor's parameters with a cost model
// whose constants the sensor states with how they were measured, and what it is made of.
struct TimePart {
  double item_seconds = 0.0;
  std::string detail;     // "36001 beams (lidar.field_of_view_deg = ...) x 667129 samples (...)"
  std::string key;        // the key that sizes an item most ("lidar.sample_interval_ns")
  std::string items_key;  // the key that counts its items ("lidar.scans_per_step")
};

// The CPU time of what a run does for a sensor besides its items, from the same kind of cost model
// (the Mie sums of its fog optics, its plans and tables, its CFAR design), in three parts by how
// often they happen.
struct SetupTime {
  double make_seconds = 0.0;    // make(): once per process, or per sensor a sweep cannot reuse
  double run_seconds = 0.0;     // each run: begin_run, every step prepared, summarize
  double report_seconds = 0.0;  // a result set (`fogradar run`): its fog reports and result files
  std::string detail;           // what make_seconds is made of, with its keys and values
  std::string key;  // the key that sizes it most ("radar.processing.cfar.threshold_design")
};

enum class Band { radio, optical };

// The fog of one layer as the sensor sees it (`fogradar fog`): one JSON object and one line of
// text.
struct FogReport {
  nlohmann::json json;
  std::string line;
};

// One kind of raw data a sensor can write per item (docs/data-out.md): an array of `shape` per
// item, or a table of rows per item (element = table). The run's HDF5 file holds it as
// /<sensor>/<name>, indexed [active_layers, item, ...].
enum class RawElement { complex128, float64, uint8, table, int16 };

struct RawAxis {
  std::string name;  // dataset /<sensor>/<name>, attached to its dimension
  std::string units;
  std::vector<double> values;
};

struct RawColumn {
  std::string name;
  std::string units;
  bool integer = false;             // stored as a 64-bit integer
  std::vector<std::string> labels;  // non-empty: an enumeration, the value its label's index
};

struct RawKind {
  std::string name;
  std::string description;
  std::string units;
  RawElement element = RawElement::float64;
  std::vector<std::string> dimensions;  // names of an item's dimensions
  std::vector<std::size_t> shape;       // an item's shape
  std::vector<RawAxis> axes;            // one per dimension; an axis without values has no dataset
  std::vector<RawColumn> columns;       // table kinds
  std::size_t rows_per_item = 0;        // table kinds: the size estimate's rows per item
  // Numbers a reader needs beside the data (e.g. the map's thermal-noise level), as attributes.
  std::vector<std::pair<std::string, double>> attributes;
  // Kept when no kinds are named (--raw without --raw-select); false: only when asked for by name.
  bool by_default = true;
  // uint8 arrays: non-empty, an enumeration, the value its label's index (the origin maps:
  // sensor::origin_labels()). int16 arrays hold small signed indices (the radar's fog layer per
  // cell, -1 where none).
  std::vector<std::string> labels = {};

  std::size_t item_values() const;  // product of `shape`
  std::size_t item_bytes() const;   // of one item (tables: rows_per_item rows)
};

// Where a worker puts one item's raw data, as the run was asked for it (null when none is).
class RawSink {
 public:
  virtual ~RawSink() = default;
  // Whether kind `kind` (an index into the sensor's raw_kinds()) is wanted for this item.
  virtual bool wants(std::size_t kind) const = 0;
  virtual void write(std::size_t kind, std::span<const std::complex<double>> values) = 0;
  virtual void write(std::size_t kind, std::span<const double> values) = 0;
  virtual void write(std::size_t kind, std::span<const std::uint8_t> values) = 0;
  virtual void write(std::size_t kind, std::span<const std::int16_t> values) = 0;
  // Table rows, row-major, one value per column (integers and labels by their index).
  virtual void append_rows(std::size_t kind, std::span<const double> rows) = 0;
};

class SensorSummary {
 public:
  virtual ~SensorSummary() = default;
  virtual Verdict verdict() const = 0;
  // Its per-step statistics, a column `active_layers` and the others named with their units: its
  // <name>_summary.csv, the steps of its JSON, its printed table's columns, a sweep's rows.
  virtual const StepTable& step_table() const = 0;
  // The per-step table `fogradar run` prints under the sensor's name: step_table().printed() and
  // its notes.
  virtual std::string table() const = 0;
  // <name>_summary.json, embedded in summary.json as sensors.<name>.summary: step_table().json() as
  // its "steps" and the run's figures besides.
  virtual nlohmann::json json() const = 0;
  // Every result file of the sensor's own.
  virtual std::vector<ResultFile> files() const = 0;
  virtual Curve curve() const = 0;
  // What the user should know about the run's numbers (one sentence each, no prefix): `fogradar
  // run` prints them on stderr after the tables. None by default.
  virtual std::vector<std::string> warnings() const { return {}; }
};

class Worker {
 public:
  virtual ~Worker() = default;
  // Measures item `index` of step `step`, every random draw from `stream`, and stores its record at
  // its index; writes its raw data into `raw` when given. Throws Stopped (core/stop.hpp), its
  // record not stored, when `stop` says stop part way through.
  virtual void measure(std::size_t step, std::size_t index, RandomStream& stream, RawSink* raw,
                       const StopToken& stop) = 0;
};

// One run of a sensor: its steps prepared, its items measured by workers on any thread (each item
// stored at its index), then summarised. A run keeps its Sensor alive.
class SensorRun {
 public:
  virtual ~SensorRun() = default;
  // The step's own state (a fog series, band optics), made once on the calling thread before any of
  // the step's items.
  virtual void prepare_step(std::size_t step) = 0;
  // A worker holding one thread's workspace; made by the thread that uses it.
  virtual std::unique_ptr<Worker> make_worker() const = 0;
  // After every item: what the run found.
  virtual std::unique_ptr<const SensorSummary> summarize() const = 0;
};

// A sensor made for one scenario (ConfiguredSensor::make): what all its runs share, made once.
// Const and safe to use from several threads at once; every run begun from it is its own.
class Sensor {
 public:
  virtual ~Sensor() = default;
  virtual std::unique_ptr<SensorRun> begin_run() const = 0;
};

// What a run costs: one item's CPU time, and the rest of the sensor's work in a run.
struct Cost {
  TimePart item;
  SetupTime setup;
};

// A sensor configured for one scenario (SensorKind::configure): its parameters checked against the
// scenario's chamber, cheap to make; what a run of it needs is made by make().
class ConfiguredSensor {
 public:
  virtual ~ConfiguredSensor() = default;
  virtual std::size_t items_per_step() const = 0;
  // Its CPU time, estimated with a cost model whose constants the sensor states.
  virtual Cost cost() const = 0;
  // Peak memory of its part of a run with `threads` workers.
  virtual MemoryPart memory(unsigned threads) const = 0;
  virtual std::vector<RawKind> raw_kinds() const = 0;
  // A fog layer as the sensor sees it (`fogradar fog`, summary.json's chamber): of the kind's band
  // (KindInfo::band).
  virtual FogReport fog_report(const propagation::FogSpec& fog, double layer_length_m,
                               const propagation::SegelsteinTable& water) const = 0;
  // Makes the sensor for its scenario; `water` is used while it is made, not kept. Throws Stopped
  // when `stop` is asked for inside set-up work that can be long (the radar's CFAR design).
  virtual std::shared_ptr<const Sensor> make(const propagation::SegelsteinTable& water,
                                             const StopToken& stop) const = 0;
};

// What a kind states of itself, the same for every scenario.
struct KindInfo {
  // The scenario's name of the sensor ("radar"): experiment.sensors, its section, its files'
  // prefix.
  std::string name;
  // Its random streams' key (sensor_stream); distinct in one registry.
  std::uint64_t stream_key = 0;
  // Where in the spectrum it works: a radio sensor sees a fog through its liquid water, an optical
  // one through its droplets' extinction (`fogradar fog --lwc-from kunkel` ties the two by an
  // empirical law instead of one droplet distribution, so they are two fogs there).
  Band band = Band::optical;
  // Its items in words, for progress: "radar measurements".
  std::string item_noun;
  // What its benchmark curve shows, for benchmark.svg's caption: "median target RCS as a power
  // ratio".
  std::string curve_caption;
};

// A kind's parameters as experiment/ holds them: its own struct (ParamsOf), read and written by the
// kind's keys; params_of gives the struct to code that knows it (tests, benchmarks).
class Params {
 public:
  virtual ~Params() = default;
  virtual std::unique_ptr<Params> clone() const = 0;
};

template <class P>
class ParamsOf final : public Params {
 public:
  ParamsOf() = default;
  explicit ParamsOf(P v) : value(std::move(v)) {}
  std::unique_ptr<Params> clone() const override { return std::make_unique<ParamsOf>(value); }
  P value;
};

// Throws std::bad_cast when `params` holds another struct.
template <class P>
P& params_of(Params& params) {
  return dynamic_cast<ParamsOf<P>&>(params).value;
}
template <class P>
const P& params_of(const Params& params) {
  return dynamic_cast<const ParamsOf<P>&>(params).value;
}

class SensorKind {
 public:
  virtual ~SensorKind() = default;
  virtual const KindInfo& info() const = 0;
  // Its keys over its parameters (one table, made with the kind and shared by every scenario).
  virtual const KeyTable<Params>& keys() const = 0;
  // Its parameters with every key at its default.
  virtual std::unique_ptr<Params> defaults() const = 0;
  // Checks its keys (keys().check) and what they cannot check alone, the bounds that involve the
  // chamber, and configures the sensor for the scenario; throws InvalidParameter naming the
  // scenario key (its own or the chamber's).
  virtual std::shared_ptr<const ConfiguredSensor> configure(const Params& params,
                                                            const Context& context) const = 0;
  std::string_view name() const { return info().name; }
  std::uint64_t stream_key() const { return info().stream_key; }
};

// A kind over its own parameter struct P: it gives its info and keys to the constructor and
// implements configured() (its keys already checked).
template <class P>
class Kind : public SensorKind {
 public:
  Kind(KindInfo info, KeyTable<P> keys) : info_(std::move(info)), typed_keys_(std::move(keys)) {
    keys_.include(
        typed_keys_, [](auto& params) -> auto& { return params_of<P>(params); });
  }

  const KindInfo& info() const final { return info_; }
  const KeyTable<Params>& keys() const final { return keys_; }
  std::unique_ptr<Params> defaults() const final { return std::make_unique<ParamsOf<P>>(); }
  std::shared_ptr<const ConfiguredSensor> configure(const Params& params,
                                                    const Context& context) const final {
    const P& p = params_of<P>(params);
    typed_keys_.check(p);
    return configured(p, context);
  }

 protected:
  // The sensor configured for `context` from `params`, whose keys hold allowed values; throws
  // InvalidParameter for a bound across its keys and the chamber's.
  virtual std::shared_ptr<const ConfiguredSensor> configured(const P& params,
                                                             const Context& context) const = 0;

 private:
  KindInfo info_;
  KeyTable<P> typed_keys_;
  KeyTable<Params> keys_;
};

}  // namespace fogradar::sensor
