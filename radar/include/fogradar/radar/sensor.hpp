// The radar as a sensor of the experiment (DESIGN §10, sensor/sensor.hpp): its parameters and
// scenario keys ([radar], [processing], [processing.cfar], [target] and the fog clutter's
// fog.clutter_scatterers_per_bin), one run on the chamber (the chain made once, one frame per
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
};

// The keys of SensorParams: radar_param_keys(), target_keys() and fog.clutter_scatterers_per_bin.
KeyTable<SensorParams> sensor_keys();

// The radar's entry in the registry.
std::shared_ptr<const sensor::SensorType> sensor_type();

// The radar's raw data per measurement (DESIGN §11), by index: the beat signal, the range-Doppler
// map |X|^2 and the detections, with their axes.
enum RawKindIndex : std::size_t { raw_beat = 0, raw_range_doppler = 1, raw_detections = 2 };
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

// What a run of the radar found (RadarRun::summarize): its records and their summary.
class RadarReport : public sensor::SensorSummary {
 public:
  virtual const RadarSummary& summary() const = 0;
  virtual const std::vector<StepResult>& steps() const = 0;
};

// One run of the radar: the chamber resolved at its sweep centre, the scene, the chain (FFT plans,
// windows, CFAR design) made once and shared by the workers, one record per measurement.
class RadarRun : public sensor::SensorRun {
 public:
  RadarRun(const SensorParams& params, const sensor::Context& context,
           const propagation::SegelsteinTable& water);

  std::size_t items_per_step() const override { return context_.measurements_per_step; }
  void prepare_step(std::size_t) override {}
  std::unique_ptr<sensor::Worker> make_worker() const override;
  std::unique_ptr<const sensor::SensorSummary> summarize() const override;

  const SensorParams& params() const { return params_; }
  const RadarChain& chain() const { return chain_; }
  const Scene& scene() const { return scene_; }
  const propagation::Chamber& chamber() const { return chamber_; }
  // The records, one step per active-layer count, measurements by index.
  const std::vector<StepResult>& steps() const { return *steps_; }
  // 10 log10(alpha): a detection needs about this SNR.
  double cfar_threshold_db() const;
  double expected_false_alarm_cells_per_frame() const;

 private:
  friend class RadarWorker;
  SensorParams params_;
  sensor::Context context_;
  Scene scene_;
  propagation::Chamber chamber_;
  RadarChain chain_;
  std::vector<propagation::ActiveLayers> active_;
  std::shared_ptr<std::vector<StepResult>> steps_;
};

}  // namespace fogradar::radar
