#include "fogradar/experiment/summary.hpp"

namespace fogradar::experiment {

ExperimentSummary summarize(const ExperimentResult& result) {
  ExperimentSummary summary;
  for (const SensorRunEntry& entry : result.sensors) {
    summary.sensors.push_back({entry.name, entry.kind, entry.run->summarize()});
  }
  return summary;
}

}  // namespace fogradar::experiment
