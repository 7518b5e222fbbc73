#include "fogradar/experiment/runner.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "fogradar/core/random.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/radar/measurement.hpp"

namespace fogradar::experiment {
namespace {

MeasurementRecord record_of(const radar::Measurement& m) {
  MeasurementRecord record;
  double strongest_fog_w = 0.0;
  for (const radar::Detection& d : m.detections) {
    if (d.origin == radar::Origin::noise) ++record.false_alarms;
    if (d.origin != radar::Origin::fog) continue;
    ++record.fog_detections;
    strongest_fog_w = std::max(strongest_fog_w, d.received_power_w);
  }
  if (m.target) {
    record.associated = true;
    record.associated_origin = m.target->origin;
    record.detected = m.target->origin == radar::Origin::target;
    record.range_m = m.target->range_m;
    record.rcs_dbsm = m.target->rcs_dbsm;
    record.snr_db = m.target->snr_db;
  }
  record.fog_rivals_target = record.fog_detections > 0 &&
                             (!record.detected || strongest_fog_w >= m.target->received_power_w);
  return record;
}

// One sensor's part of a run: `items_per_step` items (radar measurements, lidar scans, camera
// frames) at each step. Each worker thread makes its own measuring function with make_worker, which
// holds that thread's workspace; the function stores item (step, index)'s result at its index.
struct SensorWork {
  std::size_t items_per_step = 0;
  std::function<std::function<void(std::size_t step, std::size_t index)>()> make_worker;
};

// Runs every item of every sensor on one pool of threads taking items from a shared counter.
void run_items(const std::vector<SensorWork>& sensors, std::size_t steps,
               const RunOptions& options) {
  std::vector<std::size_t> first_item;  // of each sensor, in the order of `sensors`
  std::size_t total = 0;
  for (const SensorWork& sensor : sensors) {
    first_item.push_back(total);
    total += steps * sensor.items_per_step;
  }
  // The same count estimate_peak_memory (memory.hpp) sized the run for.
  const unsigned threads = worker_threads(options.threads, total);
  std::atomic<std::size_t> next{0}, done{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;

  const auto worker = [&] {
    try {
      std::vector<std::function<void(std::size_t, std::size_t)>> measure(sensors.size());
      for (std::size_t item = next++; item < total; item = next++) {
        if (options.stop != nullptr && options.stop->load()) {
          next = total;
          break;
        }
        const std::size_t s = static_cast<std::size_t>(
            std::upper_bound(first_item.begin(), first_item.end(), item) - first_item.begin() - 1);
        const std::size_t local = item - first_item[s], per_step = sensors[s].items_per_step;
        if (!measure[s]) measure[s] = sensors[s].make_worker();
        measure[s](local / per_step, local % per_step);
        const std::size_t finished = ++done;
        if (options.progress) options.progress(finished, total);
      }
    } catch (...) {
      const std::lock_guard lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next = total;
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
  if (done != total) throw Interrupted();
}

}  // namespace

ExperimentResult run_experiment(const Scenario& scenario, const RunOptions& options) {
  scenario.validate();
  const propagation::SegelsteinTable table;
  const propagation::ChamberSpec chamber_spec = scenario.chamber_spec();
  const propagation::Chamber chamber(chamber_spec, scenario.radar.centre_frequency_hz, table);
  const std::size_t steps = scenario.experiment.max_active_layers + 1;
  std::vector<propagation::ActiveLayers> active(steps);
  for (std::size_t k = 0; k < steps; ++k)
    active[k] = propagation::first_layers_active(k, chamber.layer_count());

  ExperimentResult result;
  result.sensors = scenario.experiment.sensors;
  std::vector<SensorWork> work;

  std::optional<radar::Scene> scene;
  std::optional<radar::RadarChain> chain;
  if (scenario.runs(SensorId::radar)) {
    scene.emplace(scenario.scene());
    chain.emplace(scenario.radar);
    chain->check_compatible(*scene, chamber);
    const std::size_t per_step = scenario.experiment.measurements_per_step;
    result.cfar_threshold_db = power_ratio_to_db(chain->cfar().threshold_factor());
    result.expected_false_alarm_cells_per_frame =
        chain->cfar().config().false_alarm_probability *
        static_cast<double>(scenario.radar.chirps_per_frame * scenario.radar.samples_per_chirp);
    result.steps.resize(steps);
    for (std::size_t k = 0; k < steps; ++k) {
      result.steps[k].active_layers = k;
      result.steps[k].two_way_attenuation_db =
          chamber.two_way_attenuation_db(chamber.target_range_m(), active[k]);
      result.steps[k].records.resize(per_step);
    }
    work.push_back({per_step, [&] {
                      // Each thread's frame buffers, made on its first radar measurement.
                      auto workspace =
                          std::make_shared<radar::MeasurementWorkspace>(chain->make_workspace());
                      auto measurement = std::make_shared<radar::Measurement>();
                      return [&, workspace, measurement](std::size_t k, std::size_t i) {
                        RandomStream rng =
                            sensor_stream(scenario.experiment.seed, SensorId::radar, k, i);
                        chain->measure(*scene, chamber, active[k], rng, *workspace, *measurement);
                        result.steps[k].records[i] = record_of(*measurement);
                      };
                    }});
  }

  std::vector<lidar::FogFluctuationSeries> lidar_fog;
  if (scenario.runs(SensorId::lidar)) {
    result.lidar = std::make_shared<const lidar::Lidar>(scenario.lidar, chamber_spec, table);
    const lidar::Lidar& sensor = *result.lidar;
    const std::size_t per_step = scenario.lidar.scans_per_step;
    result.lidar_steps.resize(steps);
    for (std::size_t k = 0; k < steps; ++k) {
      result.lidar_steps[k].active_layers = k;
      result.lidar_steps[k].scans.resize(per_step);
      // The step's scan-to-scan fog series, from the stream index the lidar reserves for it.
      lidar_fog.push_back(sensor.fog_fluctuation(
          sensor_stream(scenario.experiment.seed, SensorId::lidar, k, sensor.fog_series_index())));
    }
    work.push_back({per_step, [&] {
                      return [&](std::size_t k, std::size_t i) {
                        RandomStream rng =
                            sensor_stream(scenario.experiment.seed, SensorId::lidar, k, i);
                        result.lidar_steps[k].scans[i] =
                            result.lidar->measure(active[k], lidar_fog[k].scan(i), rng);
                      };
                    }});
  }

  if (scenario.runs(SensorId::camera)) {
    result.camera = std::make_shared<const camera::Camera>(scenario.camera, chamber_spec, table);
    const camera::Camera& sensor = *result.camera;
    const std::size_t per_step = scenario.camera.frames_per_step;
    result.camera_steps.resize(steps);
    for (std::size_t k = 0; k < steps; ++k) {
      result.camera_steps[k].active_layers = k;
      // The band's optics and the exposure: once per step, shared by its frames.
      result.camera_steps[k].optics = sensor.step_optics(active[k]);
      result.camera_steps[k].frames.resize(per_step);
    }
    work.push_back({per_step, [&] {
                      return [&](std::size_t k, std::size_t i) {
                        RandomStream rng =
                            sensor_stream(scenario.experiment.seed, SensorId::camera, k, i);
                        result.camera_steps[k].frames[i] =
                            result.camera->frame(result.camera_steps[k].optics, rng);
                      };
                    }});
  }

  run_items(work, steps, options);
  return result;
}

}  // namespace fogradar::experiment
