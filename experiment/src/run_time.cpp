#include "fogradar/experiment/run_time.hpp"

#include <algorithm>
#include <cstdio>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/propagation/fog.hpp"

namespace fogradar::experiment {
namespace {

// bench/estimate_calibration: the CPU time of `fogradar run` of one item per sensor, less its
// modelled work.
constexpr double process_constant_seconds = 0.015;

// Three significant digits in the unit that keeps them readable: "31.7 s", "0.27 ms".
std::string seconds_text(double seconds) {
  char text[32];
  if (seconds >= 1.0 || seconds == 0.0) {
    std::snprintf(text, sizeof text, "%.3g s", seconds);
  } else if (seconds >= 1e-3) {
    std::snprintf(text, sizeof text, "%.3g ms", seconds * 1e3);
  } else {
    std::snprintf(text, sizeof text, "%.3g us", seconds * 1e6);
  }
  return text;
}

std::string counted_threads(unsigned threads) {
  return std::to_string(threads) + (threads == 1 ? " thread" : " threads");
}

}  // namespace

double process_seconds() { return process_constant_seconds; }

double TimeEstimate::Part::cpu_seconds() const {
  return static_cast<double>(items) * time.item_seconds;
}

double TimeEstimate::Part::setup_seconds() const {
  return setup.make_seconds + setup.run_seconds + setup.report_seconds;
}

double TimeEstimate::cpu_seconds() const {
  double total = 0.0;
  for (const Part& part : sensors) total += part.cpu_seconds();
  return total;
}

double TimeEstimate::items_wall_seconds() const {
  double longest_item = 0.0;
  for (const Part& part : sensors) longest_item = std::max(longest_item, part.time.item_seconds);
  return std::max(cpu_seconds() / std::max(1u, threads), longest_item);
}

double TimeEstimate::setup_seconds() const {
  double total = process_seconds + chamber_seconds;
  for (const Part& part : sensors) total += part.setup_seconds();
  return total;
}

double TimeEstimate::wall_seconds() const { return setup_seconds() + items_wall_seconds(); }

std::string TimeEstimate::text() const {
  std::string text = seconds_text(wall_seconds());
  text += " on ";
  text += counted_threads(threads);
  text += " (";
  for (const Part& part : sensors) {
    if (&part != &sensors.front()) text += ", ";
    text += part.sensor;
    text += ' ';
    text += std::to_string(part.items);
    text += " x ";
    text += seconds_text(part.time.item_seconds);
  }
  text += "; set-up and files ";
  text += seconds_text(setup_seconds());
  text += ')';
  return text;
}

namespace {

// summary.json's chamber (outputs.cpp): each distinct fog resolved, then its 550 nm extinction and
// visibility, each a bulk evaluation at 550 nm.
double chamber_report_seconds(const sensor::Context& context) {
  const std::vector<propagation::FogLayerSpec>& layers = context.chamber.layers;
  double seconds = 0.0;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    std::size_t same = 0;
    while (same < i && layers[same] != layers[i]) ++same;
    if (same < i) continue;
    seconds += propagation::fog_resolution_seconds(layers[i].fog) +
               2.0 * propagation::bulk_optics_seconds(layers[i].fog.droplets,
                                                      propagation::visibility_wavelength_m);
  }
  return seconds;
}

}  // namespace

TimeEstimate estimate_run_time(const Scenario& scenario, unsigned requested_threads) {
  const sensor::Context context = scenario.context();
  TimeEstimate e;
  std::size_t items = 0;
  for (const std::string& name : scenario.experiment.sensors) {
    const std::shared_ptr<const sensor::ConfiguredSensor> configured = scenario.configure(name);
    const std::size_t count = context.steps * configured->items_per_step();
    const sensor::Cost cost = configured->cost();
    e.sensors.push_back({name, count, cost.item, cost.setup});
    items += count;
  }
  // The same count the runner starts (runner.cpp): one pool for every sensor's items.
  e.threads = worker_threads(requested_threads, items);
  e.process_seconds = process_constant_seconds;
  e.chamber_seconds = chamber_report_seconds(context);
  return e;
}

RunsEstimate estimate_runs(const std::vector<const Scenario*>& runs, unsigned requested_threads) {
  RunsEstimate total{.wall_seconds = process_constant_seconds,
                     .cpu_seconds = process_constant_seconds};
  // The identities SensorCache holds, newest last, as it evicts them.
  std::vector<std::string> cached;
  for (const Scenario* scenario : runs) {
    const TimeEstimate e = estimate_run_time(*scenario, requested_threads);
    double setup = 0.0;
    for (const TimeEstimate::Part& part : e.sensors) {
      setup += part.setup.run_seconds;
      std::string identity = sensor_identity(*scenario, scenario->setting(part.sensor));
      const auto found = std::find(cached.begin(), cached.end(), identity);
      if (found != cached.end()) {
        cached.erase(found);
      } else {
        setup += part.setup.make_seconds;
        if (cached.size() == SensorCache::capacity) cached.erase(cached.begin());
      }
      cached.push_back(std::move(identity));
    }
    total.wall_seconds += setup + e.items_wall_seconds();
    total.cpu_seconds += setup + e.cpu_seconds();
  }
  return total;
}

void require_time_within(const Scenario& scenario, unsigned requested_threads,
                         double limit_seconds) {
  const TimeEstimate estimate = estimate_run_time(scenario, requested_threads);
  if (estimate.wall_seconds() <= limit_seconds) return;
  const sensor::Context context = scenario.context();
  std::string message = "the run needs an estimated ";
  message += seconds_text(estimate.wall_seconds());
  message += " with --threads ";
  message += std::to_string(requested_threads);
  message += " (";
  message += counted_threads(estimate.threads);
  message += "), more than --time-limit = ";
  message += seconds_text(limit_seconds);
  message += ": ";
  const TimeEstimate::Part* largest = &estimate.sensors.front();
  const TimeEstimate::Part* largest_setup = &estimate.sensors.front();
  for (const TimeEstimate::Part& part : estimate.sensors) {
    message += part.sensor;
    message += ' ';
    message += std::to_string(part.items);
    message += " x ";
    message += seconds_text(part.time.item_seconds);
    message += " (";
    message += part.time.items_key;
    message += " x ";
    message += std::to_string(context.steps);
    message += context.steps == 1 ? " step; " : " steps; ";
    message += part.time.detail;
    message += "; set-up ";
    message += seconds_text(part.setup_seconds());
    message += ": ";
    message += part.setup.detail;
    message += "), ";
    if (part.cpu_seconds() > largest->cpu_seconds()) largest = &part;
    if (part.setup_seconds() > largest_setup->setup_seconds()) largest_setup = &part;
  }
  const double items_seconds = largest->cpu_seconds() / estimate.threads;
  const std::string& field = largest_setup->setup_seconds() > items_seconds
                                 ? largest_setup->setup.key
                             : largest->time.item_seconds > limit_seconds ? largest->time.key
                                                                          : largest->time.items_key;
  message += "the process ";
  message += seconds_text(estimate.process_seconds);
  message += "; a cost model's estimate (docs/scenario.md, \"Time limit\"); reduce ";
  message += field;
  message += " or raise --time-limit";
  throw InvalidParameter(field, message);
}

}  // namespace fogradar::experiment
