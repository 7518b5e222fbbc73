// The radar as a sensor of the experiment (sensor/sensor.hpp): its parameters and
// scenario keys ([radar] with [radar.processing], [radar.processing.cfar] and [radar.target]), its
// kind, its raw data kinds and the report of a run (one frame per item on the chamber, the chain
// made once), from which experiment/ writes radar_samples.csv, radar_detections.csv,
// radar_summary.csv, radar_summary.json and radar_rcs_boxplot.svg. The sensor and its run are
// private to radar/src.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "fogradar/core/keys.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/results.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/radar/target.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::radar {

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

// What a run of the radar found (its run's summarize): its records and their summary, and the
// radar as made for the scenario (made once and shared by every run): the chamber resolved at its
// sweep centre, the scene, the chain (FFT plans, windows, CFAR design) and the water films' losses.
class RadarReport : public sensor::SensorSummary {
 public:
  virtual const RadarSummary& summary() const = 0;
  virtual const std::vector<StepResult>& steps() const = 0;
  virtual const RadarChain& chain() const = 0;
  virtual const Scene& scene() const = 0;
  virtual const propagation::Chamber& chamber() const = 0;
  // The water-covered sensor and target at the sweep centre (propagation/water_film.hpp): the
  // radome with its film out and back, and the target's film on metal, each in dB.
  virtual double radome_two_way_loss_db() const = 0;
  virtual double target_film_loss_db() const = 0;
};

}  // namespace fogradar::radar
