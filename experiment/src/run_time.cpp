#include "fogradar/experiment/run_time.hpp"

#include <algorithm>
#include <cstdio>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/memory.hpp"

namespace fogradar::experiment {
namespace {

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

double TimeEstimate::Part::cpu_seconds() const {
  return static_cast<double>(items) * time.item_seconds;
}

double TimeEstimate::cpu_seconds() const {
  double total = 0.0;
  for (const Part& part : sensors) total += part.cpu_seconds();
  return total;
}

double TimeEstimate::wall_seconds() const {
  double longest_item = 0.0;
  for (const Part& part : sensors) longest_item = std::max(longest_item, part.time.item_seconds);
  return std::max(cpu_seconds() / std::max(1u, threads), longest_item);
}

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
  text += ')';
  return text;
}

TimeEstimate estimate_run_time(const Scenario& scenario, unsigned requested_threads) {
  const sensor::Context context = scenario.context();
  TimeEstimate e;
  std::size_t items = 0;
  for (const std::string& name : scenario.experiment.sensors) {
    const SensorSetting& s = scenario.setting(name);
    const std::size_t count = context.steps * s.type->items_per_step(s.params, context);
    e.sensors.push_back({name, count, s.type->item_time(s.params, context)});
    items += count;
  }
  // The same count the runner starts (runner.cpp): one pool for every sensor's items.
  e.threads = worker_threads(requested_threads, items);
  return e;
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
    message += "), ";
    if (part.cpu_seconds() > largest->cpu_seconds()) largest = &part;
  }
  const std::string& field =
      largest->time.item_seconds > limit_seconds ? largest->time.key : largest->time.items_key;
  message += "a cost model's estimate (docs/scenario.md, \"Time limit\"); reduce ";
  message += field;
  message += " or raise --time-limit";
  throw InvalidParameter(field, message);
}

}  // namespace fogradar::experiment
