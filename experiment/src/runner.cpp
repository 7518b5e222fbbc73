#include "fogradar/experiment/runner.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/experiment/memory.hpp"

namespace fogradar::experiment {
namespace {

// Runs every item of every sensor on one pool of threads taking items from a shared counter. Each
// worker thread makes its own sensor::Worker (its workspace) on its first item of that sensor.
void run_items(const std::vector<SensorRunEntry>& sensors, std::size_t steps, std::uint64_t seed,
               const RunOptions& options) {
  std::vector<std::size_t> first_item;  // of each sensor, in the order of `sensors`
  std::size_t total = 0;
  for (const SensorRunEntry& sensor : sensors) {
    first_item.push_back(total);
    total += steps * sensor.configured->items_per_step();
  }
  // The same count estimate_peak_memory (memory.hpp) sized the run for.
  const unsigned threads = worker_threads(options.threads, total);
  std::atomic<std::size_t> next{0}, done{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const StopToken stop(options.stop);

  const auto worker = [&] {
    try {
      std::vector<std::unique_ptr<sensor::Worker>> measure(sensors.size());
      for (std::size_t item = next++; item < total; item = next++) {
        if (stop.requested()) {
          next = total;
          break;
        }
        const std::size_t s = static_cast<std::size_t>(
            std::upper_bound(first_item.begin(), first_item.end(), item) - first_item.begin() - 1);
        const std::size_t local = item - first_item[s],
                          per_step = sensors[s].configured->items_per_step();
        if (!measure[s]) measure[s] = sensors[s].run->make_worker();
        const std::size_t step = local / per_step, index = local % per_step;
        RandomStream stream = sensor_stream(seed, sensors[s].stream_key, step, index);
        const std::unique_ptr<sensor::RawSink> raw =
            options.raw != nullptr ? options.raw->sink(s, step, index) : nullptr;
        try {
          measure[s]->measure(step, index, stream, raw.get(), stop);
        } catch (const Stopped&) {
          next = total;
          break;
        }
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

const sensor::SensorRun& ExperimentResult::run(std::string_view name) const {
  for (const SensorRunEntry& entry : sensors) {
    if (entry.name == name) return *entry.run;
  }
  throw_invalid("experiment.sensors", name, "a sensor that ran");
}

std::string sensor_identity(const Scenario& scenario, const SensorSetting& setting) {
  Scenario alone = scenario;
  for (SensorSetting& other : alone.sensors) {
    if (other.name != setting.name) other.params = other.kind->defaults();
  }
  alone.experiment.sensors = {setting.name};
  return to_toml(alone);
}

std::shared_ptr<const sensor::Sensor> SensorCache::sensor(
    const Scenario& scenario, const SensorSetting& setting,
    const sensor::ConfiguredSensor& configured, const propagation::SegelsteinTable& water,
    const StopToken& stop) {
  std::string identity = sensor_identity(scenario, setting);
  {
    const std::lock_guard lock(mutex_);
    for (auto it = made_.begin(); it != made_.end(); ++it) {
      if (it->first != identity) continue;
      auto found = std::move(*it);
      made_.erase(it);
      made_.push_back(std::move(found));
      return made_.back().second;
    }
  }
  std::shared_ptr<const sensor::Sensor> made = configured.make(water, stop);
  const std::lock_guard lock(mutex_);
  if (made_.size() == capacity) made_.erase(made_.begin());
  made_.emplace_back(std::move(identity), made);
  return made;
}

Simulation::Simulation(Scenario scenario)
    : Simulation(std::move(scenario), propagation::SegelsteinTable(), nullptr) {}

Simulation::Simulation(Scenario scenario, const propagation::SegelsteinTable& water,
                       SensorCache* cache, const std::atomic<bool>* stop)
    : scenario_(std::move(scenario)) {
  scenario_.validate();
  context_ = scenario_.context();
  const StopToken token(stop);
  for (const std::string& name : scenario_.experiment.sensors) {
    const SensorSetting& setting = scenario_.setting(name);
    std::shared_ptr<const sensor::ConfiguredSensor> configured =
        configure_instance(setting, context_);
    try {
      std::shared_ptr<const sensor::Sensor> made =
          cache ? cache->sensor(scenario_, setting, *configured, water, token)
                : configured->make(water, token);
      sensors_.push_back({setting.name, setting.stream_key(), setting.kind, std::move(configured),
                          std::move(made), nullptr});
    } catch (const Stopped&) {
      throw Interrupted();
    }
  }
}

ExperimentResult Simulation::run(const RunOptions& options) const {
  ExperimentResult result;
  for (const SensorRunEntry& m : sensors_) {
    result.sensors.push_back(
        {m.name, m.stream_key, m.kind, m.configured, m.sensor, m.sensor->begin_run()});
  }
  // Per-step state first, on this thread.
  for (const SensorRunEntry& entry : result.sensors) {
    for (std::size_t k = 0; k < context_.steps; ++k) entry.run->prepare_step(k);
  }
  run_items(result.sensors, context_.steps, context_.seed, options);
  return result;
}

SensorRunEntry Simulation::begin_run(std::string_view sensor) const {
  std::string running;
  for (const SensorRunEntry& m : sensors_) {
    if (m.name == sensor) {
      return {m.name, m.stream_key, m.kind, m.configured, m.sensor, m.sensor->begin_run()};
    }
    running += (running.empty() ? "" : ", ") + m.name;
  }
  throw_invalid("sensor", sensor, "a sensor of experiment.sensors: " + running);
}

ItemRun::ItemRun(const Simulation& simulation, std::string_view sensor)
    : entry_(simulation.begin_run(sensor)),
      seed_(simulation.context().seed),
      steps_(simulation.context().steps) {
  items_per_step_ = entry_.configured->items_per_step();
  kinds_ = entry_.configured->raw_kinds();
  prepared_.assign(steps_, false);
}

void ItemRun::measure(std::size_t step, std::size_t index, sensor::RawSink* raw) {
  if (step >= steps_) {
    throw_invalid(
        "step", static_cast<double>(step),
        "an integer in [0, experiment.max_active_layers = " + std::to_string(steps_ - 1) + "]");
  }
  if (index >= items_per_step_) {
    throw_invalid("index", static_cast<double>(index),
                  "an integer in [0, " + std::to_string(items_per_step_ - 1) + "] (" +
                      entry_.kind->info().item_noun + " per step)");
  }
  if (!prepared_[step]) {
    entry_.run->prepare_step(step);
    prepared_[step] = true;
  }
  if (!worker_) worker_ = entry_.run->make_worker();
  RandomStream stream = sensor_stream(seed_, entry_.stream_key, step, index);
  worker_->measure(step, index, stream, raw, StopToken());
}

ExperimentResult run_experiment(const Scenario& scenario, const RunOptions& options) {
  return Simulation(scenario, propagation::SegelsteinTable(), nullptr, options.stop).run(options);
}

std::string item_nouns(const Scenario& scenario) {
  std::string text;
  const std::vector<std::string>& names = scenario.experiment.sensors;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " and " : ", ";
    text += scenario.setting(names[i]).kind->info().item_noun;
  }
  return text;
}

}  // namespace fogradar::experiment
