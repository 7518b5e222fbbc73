// What a run found, sensor by sensor: each sensor's own summary (per-step statistics, limit
// verdict, table, JSON, files, benchmark curve; sensor/sensor.hpp), in experiment.sensors' order.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

struct SensorOutcome {
  std::string name;  // the instance's
  std::shared_ptr<const sensor::SensorKind> kind;
  std::shared_ptr<const sensor::SensorSummary> summary;
};

struct ExperimentSummary {
  std::vector<SensorOutcome> sensors;  // that ran

  // The summary of the sensor named `name` as its own type (e.g. radar::RadarReport); throws
  // InvalidParameter when it did not run.
  template <class Report>
  const Report& of(std::string_view name) const {
    for (const SensorOutcome& outcome : sensors) {
      if (outcome.name == name) return dynamic_cast<const Report&>(*outcome.summary);
    }
    throw_invalid("experiment.sensors", name, "a sensor that ran");
  }
};

ExperimentSummary summarize(const ExperimentResult& result);

}  // namespace fogradar::experiment
