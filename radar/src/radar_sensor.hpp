// The radar's sensor and its run (sensor/sensor.hpp), private to radar/: what its kind makes
// (kind.cpp) and what sensor.cpp implements.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "fogradar/propagation/chamber.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/results.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/radar/sensor.hpp"

namespace fogradar::radar {

// Key 0: the radar's streams are RandomStream(seed, step, index), those of every earlier version.
inline constexpr std::uint64_t stream_key = 0;

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
