#include "fogradar/experiment/summary.hpp"

#include <cmath>
#include <limits>

#include "fogradar/stats/shift_test.hpp"

namespace fogradar::experiment {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::vector<double> detected_rcs_dbsm(const StepResult& step) {
  std::vector<double> values;
  for (const MeasurementRecord& r : step.records) {
    if (r.detected) values.push_back(r.rcs_dbsm);
  }
  return values;
}

double median_of(const std::vector<double>& values) { return values.empty() ? nan : stats::median(values); }

}  // namespace

ExperimentSummary summarize(const ExperimentResult& result) {
  ExperimentSummary summary;
  const std::vector<double> baseline = result.steps.empty() ? std::vector<double>{} : detected_rcs_dbsm(result.steps[0]);
  for (const StepResult& step : result.steps) {
    StepSummary s;
    s.active_layers = step.active_layers;
    s.n = step.records.size();
    const std::vector<double> rcs = detected_rcs_dbsm(step);
    s.detections = rcs.size();
    s.detection_rate = s.n == 0 ? 0.0 : static_cast<double>(s.detections) / static_cast<double>(s.n);
    s.rcs = stats::box_plot(rcs);
    s.two_way_attenuation_db = step.two_way_attenuation_db;
    std::vector<double> snr;
    std::size_t confused = 0;
    for (const MeasurementRecord& r : step.records) {
      if (r.detected) snr.push_back(r.snr_db);
      if (!r.detected || r.fog_rivals_target) ++confused;
    }
    s.median_snr_db = median_of(snr);
    s.confusion_rate = s.n == 0 ? 0.0 : static_cast<double>(confused) / static_cast<double>(s.n);
    if (step.active_layers == 0 || rcs.empty() || baseline.empty()) {
      s.median_shift_db = s.active_layers == 0 && !rcs.empty() ? 0.0 : nan;
      s.p_value = nan;
      s.median_shift_ci95 = {nan, nan};
    } else {
      const stats::ShiftTestResult test = stats::mann_whitney_u(rcs, baseline);
      s.median_shift_db = test.median_shift;
      s.p_value = test.p_value;
      s.median_shift_ci95 = stats::median_shift_interval(rcs, baseline, 0.95);
    }
    summary.steps.push_back(std::move(s));
  }
  for (const StepSummary& s : summary.steps) {
    if (1.0 - s.confusion_rate < sensor_limit_success_fraction) {
      summary.sensor_limit_layers = s.active_layers;
      break;
    }
  }
  if (!summary.steps.empty() && !std::isnan(summary.steps.back().median_snr_db)) {
    summary.attenuation_margin_db = summary.steps.back().median_snr_db - result.cfar_threshold_db;
  }
  return summary;
}

}  // namespace fogradar::experiment
