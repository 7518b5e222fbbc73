// The radar as a sensor of the experiment (sensor/sensor.hpp): its parameters and
// scenario keys ([radar] with [radar.processing], [radar.processing.cfar] and [radar.target]), one
// run on the chamber (the chain made once, one frame per
// item), and what experiment/ writes of it: radar_samples.csv, radar_summary.csv,
// radar_summary.json, radar_rcs_boxplot.svg.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "fogradar/core/keys.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/results.hpp"
#include "fogradar/radar/target.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::radar {

// Key 0: the radar's streams are RandomStream(seed, step, index), those of every earlier version.
inline constexpr std::uint64_t stream_key = 0;

struct SensorParams {
  RadarParams radar;
  TargetSpec target;
  // Random point scatterers per range bin that make up the fog clutter (Scene).
  unsigned clutter_scatterers_per_bin = 4;
  std::size_t measurements_per_step = 200;  // the study's series: frames per step
};

// The keys of SensorParams: radar_param_keys(), target_keys() and radar.clutter_scatterers_per_bin.
KeyTable<SensorParams> sensor_keys();

// The radar's kind, for the registry.
std::shared_ptr<const sensor::SensorKind> sensor_kind();

// The radar's raw data per measurement (docs/data-out.md), by index: the beat signal, the
// range-Doppler map |X|^2 and the detections, with their axes; the beat's two parts (synthesis.hpp,
// FrameParts) and the frame's ground truth per cell (OriginClassifier::origin_map: the origins and
// the fog layers) only when asked for by name.
enum RawKindIndex : std::size_t {
  raw_beat = 0,
  raw_range_doppler = 1,
  raw_detections = 2,
  raw_signal = 3,
  raw_noise = 4,
  raw_origins = 5,
  raw_origin_layers = 6
};
std::vector<sensor::RawKind> radar_raw_kinds(const SensorParams& params);

// Peak memory of the radar's part of a run, by part: an upper estimate from the sizes of the
// buffers the chain keeps (measurement.hpp, estimation.hpp, cfar.hpp, attribution.hpp), not a
// measurement; docs/scenario.md gives its ratio to measured peak RSS.
struct MemoryEstimate {
  std::size_t per_thread_bytes = 0;  // frame, detection mask, CFAR and estimation workspaces, tones
  std::size_t shared_bytes = 0;      // windows, window spectra, FFT plans
  std::size_t records_bytes = 0;     // per measurement: its record, detections and CSV rows
};
MemoryEstimate memory_estimate(const SensorParams& params, std::size_t measurements);

// The CPU time of the radar's work in a run besides its frames (sensor::SetupTime), from a cost
// model in parts whose constants bench/estimate_calibration measures (docs/scenario.md, "Time
// limit").
struct SetupCost {
  double fog_seconds = 0.0;          // the chamber: each distinct fog resolved and its Mie sum at
                                     // the sweep centre (propagation::bulk_optics_seconds)
  double chain_seconds = 0.0;        // the RadarChain's plans, windows and noise correlation
  double cfar_design_seconds = 0.0;  // its CFAR threshold factors (cfar_design.hpp)
  double summary_seconds = 0.0;      // each run's summary (box plots, Hodges-Lehmann pairs)
  double report_seconds = 0.0;       // the fog reports of summary.json and the result files
};
SetupCost setup_cost(const SensorParams& params, const sensor::Context& context);

// What a run of the radar found (RadarRun::summarize): its records and their summary.
class RadarReport : public sensor::SensorSummary {
 public:
  virtual const RadarSummary& summary() const = 0;
  virtual const std::vector<StepResult>& steps() const = 0;
};

// The radar made for one scenario (its configured sensor's make): the chamber resolved at its sweep
// centre, the scene, the chain (FFT plans, windows, CFAR design), made once and shared by every run
// and worker.
class RadarSensor : public sensor::Sensor, public std::enable_shared_from_this<RadarSensor> {
 public:
  // Throws Stopped when `stop` is asked for while the chain's CFAR threshold is designed.
  RadarSensor(const SensorParams& params, const sensor::Context& context,
              const propagation::SegelsteinTable& water, const StopToken& stop = StopToken());

  std::unique_ptr<sensor::SensorRun> begin_run() const override;

  const SensorParams& params() const { return params_; }
  const sensor::Context& context() const { return context_; }
  const RadarChain& chain() const { return chain_; }
  const Scene& scene() const { return scene_; }
  const propagation::Chamber& chamber() const { return chamber_; }
  const propagation::ActiveLayers& active(std::size_t step) const { return active_.at(step); }
  // 10 log10(alpha): a detection needs about this SNR.
  double cfar_threshold_db() const;
  double expected_false_alarm_cells_per_frame() const;
  // The water-covered sensor and target at the sweep centre (propagation/water_film.hpp): the
  // radome with its film out and back, and the target's film on metal, each in dB.
  double radome_two_way_loss_db() const { return radome_two_way_loss_db_; }
  double target_film_loss_db() const { return target_film_loss_db_; }

 private:
  SensorParams params_;
  sensor::Context context_;
  Scene scene_;
  propagation::Chamber chamber_;
  RadarChain chain_;
  std::vector<propagation::ActiveLayers> active_;
  double radome_two_way_loss_db_ = 0.0;
  double target_film_loss_db_ = 0.0;
};

// One run of the radar: one record per measurement.
class RadarRun : public sensor::SensorRun {
 public:
  explicit RadarRun(std::shared_ptr<const RadarSensor> sensor);

  void prepare_step(std::size_t) override {}
  std::unique_ptr<sensor::Worker> make_worker() const override;
  std::unique_ptr<const sensor::SensorSummary> summarize() const override;

  const RadarSensor& sensor() const { return *sensor_; }
  // The records, one step per active-layer count, measurements by index.
  const std::vector<StepResult>& steps() const { return *steps_; }

 private:
  friend class RadarWorker;
  std::shared_ptr<const RadarSensor> sensor_;
  std::shared_ptr<std::vector<StepResult>> steps_;
};

}  // namespace fogradar::radar
