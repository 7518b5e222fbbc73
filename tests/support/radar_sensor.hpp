// Typed access to the radar of a scenario and of a run's summary, for the tests.
#pragma once

#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/radar/sensor.hpp"

namespace fogradar::experiment {

inline radar::SensorParams& radar_of(Scenario& s) { return s.params<radar::SensorParams>("radar"); }
inline const radar::SensorParams& radar_of(const Scenario& s) {
  return s.params<radar::SensorParams>("radar");
}

// The radar's run: its chain and its records, step by step.
inline const radar::RadarRun& radar_run(const ExperimentResult& r) {
  return dynamic_cast<const radar::RadarRun&>(r.run("radar"));
}

inline const radar::RadarReport& radar_report(const ExperimentSummary& s) {
  return s.of<radar::RadarReport>("radar");
}

}  // namespace fogradar::experiment
