// Typed access to the radar of a scenario and of a run's summary, for the tests.
#pragma once

#include <memory>

#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/radar/sensor.hpp"

namespace fogradar::experiment {

inline radar::SensorParams& radar_of(Scenario& s) { return s.params<radar::SensorParams>("radar"); }
inline const radar::SensorParams& radar_of(const Scenario& s) {
  return s.params<radar::SensorParams>("radar");
}

// The radar's report of a run (its run's summary): its records, step by step, and the radar as
// made, its chain and scene.
inline std::shared_ptr<const radar::RadarReport> radar_run(const ExperimentResult& r) {
  return std::dynamic_pointer_cast<const radar::RadarReport>(
      std::shared_ptr<const sensor::SensorSummary>(r.run("radar").summarize()));
}

inline const radar::RadarReport& radar_report(const ExperimentSummary& s) {
  return s.of<radar::RadarReport>("radar");
}

}  // namespace fogradar::experiment
