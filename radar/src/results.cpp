#include "fogradar/radar/results.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fogradar/stats/shift_test.hpp"

namespace fogradar::radar {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::vector<double> detected_rcs_dbsm(const StepResult& step) {
  std::vector<double> values;
  for (const MeasurementRecord& r : step.records) {
    if (r.detected) values.push_back(r.rcs_dbsm);
  }
  return values;
}

double median_of(const std::vector<double>& values) {
  return values.empty() ? nan : stats::median(values);
}

double fraction(std::size_t count, std::size_t n) {
  return n == 0 ? 0.0 : static_cast<double>(count) / static_cast<double>(n);
}

}  // namespace

MeasurementRecord record_of(const Measurement& m, double target_range_m, double gate_m) {
  MeasurementRecord record;
  record.samples = m.synthesis.samples;
  record.clipped_samples = m.synthesis.clipped_samples;
  double strongest_fog_w = 0.0;
  record.detections.reserve(m.detections.size());
  for (const Detection& d : m.detections) {
    record.detections.push_back({.range_m = d.range_m,
                                 .velocity_m_per_s = d.radial_velocity_m_per_s,
                                 .received_power_w = d.received_power_w,
                                 .snr_db = d.snr_db,
                                 .rcs_dbsm = d.rcs_dbsm,
                                 .origin = d.origin,
                                 .in_gate = std::abs(d.range_m - target_range_m) <= gate_m,
                                 .associated = m.target && d.range_cell == m.target->range_cell &&
                                               d.doppler_cell == m.target->doppler_cell,
                                 .range_cell = d.range_cell,
                                 .doppler_cell = d.doppler_cell,
                                 .layer = d.layer});
    if (d.origin == Origin::noise) ++record.false_alarms;
    if (d.origin == Origin::clipping) ++record.clipping_detections;
    if (d.origin == Origin::sidelobe) ++record.sidelobe_detections;
    if (d.origin == Origin::multipath) ++record.multipath_detections;
    if (d.origin == Origin::room) ++record.room_detections;
    if (d.origin != Origin::fog) continue;
    ++record.fog_detections;
    strongest_fog_w = std::max(strongest_fog_w, d.received_power_w);
  }
  if (m.target) {
    record.associated = true;
    record.associated_origin = m.target->origin;
    record.detected = m.target->origin == Origin::target;
    record.range_m = m.target->range_m;
    record.velocity_m_per_s = m.target->radial_velocity_m_per_s;
    record.rcs_dbsm = m.target->rcs_dbsm;
    record.snr_db = m.target->snr_db;
  }
  record.fog_rivals_target = record.fog_detections > 0 &&
                             (!record.detected || strongest_fog_w >= m.target->received_power_w);
  return record;
}

std::optional<VelocityFold> velocity_fold(double radial_velocity_m_per_s,
                                          const RadarDerived& derived) {
  const double v_max = derived.max_unambiguous_velocity_m_per_s;
  if (!(std::abs(radial_velocity_m_per_s) > v_max)) return std::nullopt;
  const double reads = folded_velocity_m_per_s(radial_velocity_m_per_s, v_max);
  const double doppler_error_hz =
      doppler_shift_hz(radial_velocity_m_per_s, derived) - doppler_shift_hz(reads, derived);
  return VelocityFold{.set_m_per_s = radial_velocity_m_per_s,
                      .unambiguous_m_per_s = v_max,
                      .reads_m_per_s = reads,
                      .range_error_m = doppler_error_hz * speed_of_light_m_per_s /
                                       (2.0 * derived.chirp_slope_hz_per_s)};
}

RadarSummary summarize(const std::vector<StepResult>& steps, double cfar_threshold_db,
                       double expected_false_alarm_cells_per_frame) {
  RadarSummary summary;
  summary.expected_false_alarm_cells_per_frame = expected_false_alarm_cells_per_frame;
  const std::vector<double> baseline =
      steps.empty() ? std::vector<double>{} : detected_rcs_dbsm(steps[0]);
  for (const StepResult& step : steps) {
    StepSummary s;
    s.active_layers = step.active_layers;
    s.n = step.records.size();
    const std::vector<double> rcs = detected_rcs_dbsm(step);
    s.detections = rcs.size();
    s.rcs = stats::box_plot(rcs);
    s.two_way_attenuation_db = step.two_way_attenuation_db;
    s.radome_two_way_loss_db = step.radome_two_way_loss_db;
    s.target_film_loss_db = step.target_film_loss_db;
    std::vector<double> snr;
    std::size_t confused = 0, false_associations = 0, false_alarms = 0, fog_detections = 0,
                clipping_detections = 0, sidelobe_detections = 0, multipath_detections = 0,
                room_detections = 0;
    std::size_t samples = 0, clipped_samples = 0;
    for (const MeasurementRecord& r : step.records) {
      if (r.detected) snr.push_back(r.snr_db);
      if (!r.detected || r.fog_rivals_target) ++confused;
      if (r.associated && !r.detected) ++false_associations;
      false_alarms += r.false_alarms;
      fog_detections += r.fog_detections;
      clipping_detections += r.clipping_detections;
      sidelobe_detections += r.sidelobe_detections;
      multipath_detections += r.multipath_detections;
      room_detections += r.room_detections;
      samples += r.samples;
      clipped_samples += r.clipped_samples;
    }
    s.detection_rate = fraction(s.detections, s.n);
    s.false_association_rate = fraction(false_associations, s.n);
    s.false_alarms_per_frame = fraction(false_alarms, s.n);
    s.fog_detections_per_frame = fraction(fog_detections, s.n);
    s.clipping_detections_per_frame = fraction(clipping_detections, s.n);
    s.sidelobe_detections_per_frame = fraction(sidelobe_detections, s.n);
    s.multipath_detections_per_frame = fraction(multipath_detections, s.n);
    s.room_detections_per_frame = fraction(room_detections, s.n);
    s.median_snr_db = median_of(snr);
    s.confusion_rate = fraction(confused, s.n);
    s.adc_clipped_fraction = fraction(clipped_samples, samples);
    if (step.active_layers == 0 || rcs.empty() || baseline.empty()) {
      s.median_shift_db = s.active_layers == 0 && !rcs.empty() ? 0.0 : nan;
      s.p_value = nan;
      s.median_shift_ci95 = {nan, nan};
    } else {
      s.median_shift_db = stats::hodges_lehmann_shift(rcs, baseline);
      s.median_shift_ci95 = stats::median_shift_interval(rcs, baseline, 0.95);
      s.p_value = stats::mann_whitney_u(rcs, baseline).p_value;
    }
    summary.steps.push_back(std::move(s));
  }
  for (const StepSummary& s : summary.steps) {
    if (1.0 - s.confusion_rate < sensor_limit_success_fraction) {
      summary.sensor_limit_layers = s.active_layers;
      break;
    }
  }
  if (!summary.steps.empty() && !std::isnan(summary.steps.back().median_snr_db) &&
      summary.steps.back().adc_clipped_fraction == 0.0) {
    summary.attenuation_margin_db = summary.steps.back().median_snr_db - cfar_threshold_db;
  }
  return summary;
}

}  // namespace fogradar::radar
