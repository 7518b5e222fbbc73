// The methodology end to end on small scenarios: determinism across thread counts, the calibrated
// point target read back through the whole experiment, fog that is invisible to the radar leaving
// the RCS unchanged, and a fog dense enough to reach the sensor limit.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>

#include "fogradar/core/units.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/radar/sensor.hpp"
#include "sensors.hpp"
#include "validation.hpp"

namespace fogradar::experiment {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;
using radar::MeasurementRecord;
using radar::StepResult;
using radar::StepSummary;

constexpr const char* kGroup = "experiment: statistics";

Scenario small_scenario() {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"radar"};  // the radar's subject; test_multisensor.cpp runs all
  radar_of(s).radar.chirps_per_frame = 16;
  s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 12;
  return s;
}

TEST(Runner, SameSeedSameResultsForAnyThreadCount) {
  const Scenario s = small_scenario();
  const ExperimentResult one_run = run_experiment(s, {.threads = 1, .progress = {}});
  const ExperimentResult three_run = run_experiment(s, {.threads = 3, .progress = {}});
  const auto one_report = radar_run(one_run), three_report = radar_run(three_run);
  const std::vector<StepResult>& one = one_report->steps();
  const std::vector<StepResult>& three = three_report->steps();
  ASSERT_EQ(one.size(), 5u);
  for (std::size_t k = 0; k < one.size(); ++k) {
    for (std::size_t i = 0; i < one[k].records.size(); ++i) {
      const MeasurementRecord& a = one[k].records[i];
      const MeasurementRecord& b = three[k].records[i];
      EXPECT_EQ(a.detected, b.detected);
      EXPECT_EQ(a.associated, b.associated);
      EXPECT_EQ(a.associated_origin, b.associated_origin);
      EXPECT_EQ(a.fog_detections, b.fog_detections);
      EXPECT_EQ(a.false_alarms, b.false_alarms);
      EXPECT_EQ(a.rcs_dbsm, b.rcs_dbsm);  // bit-identical, not merely close
      EXPECT_EQ(a.range_m, b.range_m);
      EXPECT_EQ(a.snr_db, b.snr_db);
    }
  }
  Scenario other_seed = s;
  other_seed.experiment.seed = 2;
  const ExperimentResult other = run_experiment(other_seed, {.threads = 2, .progress = {}});
  EXPECT_NE(radar_run(other)->steps()[0].records[0].rcs_dbsm, one[0].records[0].rcs_dbsm);
}

// A non-fluctuating 10 dBsm point target at the chamber's 10 m, no multipath, no micro-motion:
// every measurement detects it and reads 10 dBsm back within 0.2 dB (the chain's calibration, issue
// criterion), the paper fog's two-way loss (< 0.01 dB) included.
TEST(Runner, PointTargetReadsBackItsRcsThroughTheExperiment) {
  Scenario s = small_scenario();
  radar::TargetSpec& target = radar_of(s).target;
  target.model = radar::TargetModel::point;
  s.chamber.room.floor.present = false;
  s.target.micro_motion_std_m = 0.0;
  const radar::RadarSummary summary = radar_report(summarize(run_experiment(s))).summary();
  ASSERT_EQ(summary.steps.size(), 5u);
  const std::string point = "10 dBsm point target at 10 m, 10 dBm, paper fog, 12 measurements";
  for (const StepSummary& step : summary.steps) {
    const std::string layers = std::to_string(step.active_layers);
    validate({.id = "experiment.runner.point_target.detection_rate.layers" + layers,
              .group = kGroup,
              .quantity = "detection rate",
              .unit = "1",
              .conditions = point + ", " + layers + " active layers",
              .reference = 1.0,
              .source = "limiting case: about 75 dB SNR per cell, every measurement detects",
              .value = step.detection_rate,
              .tolerance = 0.0,
              .kind = Tolerance::absolute});
    validate({.id = "experiment.runner.point_target.median_rcs.layers" + layers,
              .group = kGroup,
              .quantity = "median RCS read back",
              .unit = "dBsm",
              .conditions = point + ", " + layers + " active layers",
              .reference = 10.0 - step.two_way_attenuation_db,
              .source = "the target's set 10 dBsm less the fog's two-way loss (calibration, "
                        "issue criterion)",
              .value = step.rcs.median,
              .tolerance = 0.2,
              .kind = Tolerance::absolute});
    validate({.id = "experiment.runner.point_target.two_way_attenuation.layers" + layers,
              .group = kGroup,
              .quantity = "two-way attenuation of the paper fog",
              .unit = "dB",
              .conditions = point + ", " + layers + " active layers",
              .reference = 0.05,
              .source = "limiting case: the paper fog's two-way loss is < 0.01 dB at 77 GHz",
              .value = step.two_way_attenuation_db,
              .tolerance = 0.0,
              .kind = Tolerance::at_most});
  }
  EXPECT_FALSE(summary.sensor_limit_layers.has_value());
  ASSERT_TRUE(summary.attenuation_margin_db.has_value());
  validate({.id = "experiment.runner.point_target.attenuation_margin",
            .group = kGroup,
            .quantity = "attenuation margin",
            .unit = "dB",
            .conditions = point,
            .reference = 40.0,
            .source = "limiting case: about 75 dB SNR per cell against the CA threshold",
            .value = *summary.attenuation_margin_db,
            .tolerance = 0.0,
            .kind = Tolerance::at_least});
  EXPECT_TRUE(std::isnan(summary.steps[0].p_value));
  EXPECT_EQ(summary.steps[0].median_shift_db, 0.0);
}

// A fog of 100 g/m^3 in 0.5 mm drops in 3 m layers: each layer costs 3.87 dB two-way at 77 GHz
// (644.7 dB/km, `fogradar fog --lwc 100 --diameter-um 500`), and the point target, seen with
// -19 dBm, has a median SNR of about 19 dB at 0 layers against the CA threshold factor of 14.8 dB:
// detected in every measurement without fog, lost after one or two layers (200 measurements per
// step: 100 %, 66.5 %, 6.5 %, 0 %, 0 %). So the sensor limit is reached inside the chamber,
// whatever the 12 measurements of this test draw.
TEST(Runner, DenseLargeDropFogReachesTheSensorLimit) {
  Scenario s = small_scenario();
  radar_of(s).radar.tx_power_dbm = -19.0;
  radar::TargetSpec& target = radar_of(s).target;
  target.model = radar::TargetModel::point;
  s.chamber.room.floor.present = false;
  target.rcs_dbsm = -8.0;  // a pedestrian
  s.chamber.layer_length_m = 3.0;
  s.fog.density = propagation::LiquidWaterContent{100.0};
  s.fog.droplets = propagation::Monodisperse{0.5e-3};
  const radar::RadarSummary summary = radar_report(summarize(run_experiment(s))).summary();
  const std::string dense =
      "-8 dBsm point target, -19 dBm, 100 g/m^3 of 0.5 mm drops in 3 m layers, 12 measurements";
  validate({.id = "experiment.runner.dense_fog.detection_rate.layers0",
            .group = kGroup,
            .quantity = "detection rate",
            .unit = "1",
            .conditions = dense + ", 0 active layers",
            .reference = 1.0,
            .source = "radar equation: median SNR about 19 dB against the CA threshold factor "
                      "of 14.8 dB",
            .value = summary.steps[0].detection_rate,
            .tolerance = 0.0,
            .kind = Tolerance::absolute});
  ASSERT_TRUE(summary.sensor_limit_layers.has_value());
  const auto limit = static_cast<double>(*summary.sensor_limit_layers);
  validate({.id = "experiment.runner.dense_fog.sensor_limit.low",
            .group = kGroup,
            .quantity = "sensor limit",
            .unit = "active layers",
            .conditions = dense,
            .reference = 1.0,
            .source = "radar equation: 3.87 dB two-way per layer (644.7 dB/km) against 19 dB "
                      "median SNR and a 14.8 dB threshold",
            .value = limit,
            .tolerance = 0.0,
            .kind = Tolerance::at_least});
  validate({.id = "experiment.runner.dense_fog.sensor_limit.high",
            .group = kGroup,
            .quantity = "sensor limit",
            .unit = "active layers",
            .conditions = dense,
            .reference = 3.0,
            .source = "radar equation: 3.87 dB two-way per layer (644.7 dB/km) against 19 dB "
                      "median SNR and a 14.8 dB threshold",
            .value = limit,
            .tolerance = 0.0,
            .kind = Tolerance::at_most});
  // Monotone physics: more layers, more loss.
  for (std::size_t k = 1; k < summary.steps.size(); ++k) {
    EXPECT_GT(summary.steps[k].two_way_attenuation_db, summary.steps[k - 1].two_way_attenuation_db);
  }
}

// A lost target: a -60 dBsm point target seen with 1 uW (-30 dBm) transmit power, about 35 dB under
// the noise per cell (the 10 dBsm, 10 dBm target of PointTargetReadsBack... has about 75 dB: minus
// 70 dB RCS and 40 dB power), and P_fa = 1e-2, so that about one noise cell in a hundred crosses
// the threshold and the association gate (+-0.5 m, ~7 range bins x 16 Doppler bins) often holds
// one. Every gate association is noise; none is a target detection: detection rate 0, the
// associations counted as false associations, no statistics of a target, the sensor limit at 0
// layers.
TEST(Runner, LostTargetGateAssociationsAreNoiseAndCountAsMisses) {
  Scenario s = small_scenario();
  radar::TargetSpec& target = radar_of(s).target;
  target.model = radar::TargetModel::point;
  s.chamber.room.floor.present = false;
  target.rcs_dbsm = -60.0;
  radar_of(s).radar.tx_power_dbm = -30.0;
  radar_of(s).radar.cfar.false_alarm_probability = 1e-2;
  const ExperimentResult run = run_experiment(s, {.threads = 2, .progress = {}});
  const auto report = radar_run(run);
  EXPECT_DOUBLE_EQ(report->summary().expected_false_alarm_cells_per_frame, 1e-2 * 16 * 512);
  const std::vector<StepResult>& steps = report->steps();
  std::size_t associations = 0, false_alarms = 0;
  for (const StepResult& step : steps) {
    for (const MeasurementRecord& r : step.records) {
      EXPECT_FALSE(r.detected);
      if (r.associated) {
        EXPECT_EQ(r.associated_origin, radar::Origin::noise);
      }
      associations += r.associated ? 1 : 0;
      false_alarms += r.false_alarms;
    }
  }
  EXPECT_GT(associations, 0u);
  EXPECT_GE(false_alarms, associations);  // every association is one of the frame's false alarms
  const radar::RadarSummary summary = radar_report(summarize(run)).summary();
  double false_association_sum = 0.0;
  for (std::size_t k = 0; k < summary.steps.size(); ++k) {
    const StepSummary& step = summary.steps[k];
    std::size_t associated = 0;
    for (const MeasurementRecord& r : steps[k].records) associated += r.associated ? 1 : 0;
    EXPECT_EQ(step.detections, 0u);
    validate({.id = "experiment.runner.lost_target.detection_rate.layers" +
                    std::to_string(step.active_layers),
              .group = kGroup,
              .quantity = "detection rate",
              .unit = "1",
              .conditions = "-60 dBsm point target, -30 dBm, P_fa = 1e-2, " +
                            std::to_string(step.active_layers) + " active layers",
              .reference = 0.0,
              .source = "limiting case: the target about 35 dB under the noise per cell",
              .value = step.detection_rate,
              .tolerance = 0.0,
              .kind = Tolerance::absolute});
    EXPECT_EQ(step.false_association_rate,
              static_cast<double>(associated) / static_cast<double>(step.n));
    EXPECT_GT(step.false_alarms_per_frame, 0.0);
    EXPECT_EQ(step.confusion_rate, 1.0);
    EXPECT_TRUE(std::isnan(step.rcs.median));
    EXPECT_TRUE(std::isnan(step.median_snr_db));
    EXPECT_TRUE(std::isnan(step.median_shift_db));
    false_association_sum += step.false_association_rate;
  }
  EXPECT_GT(false_association_sum, 0.0);
  ASSERT_TRUE(summary.sensor_limit_layers.has_value());
  validate({.id = "experiment.runner.lost_target.sensor_limit",
            .group = kGroup,
            .quantity = "sensor limit",
            .unit = "active layers",
            .conditions = "-60 dBsm point target, -30 dBm, P_fa = 1e-2",
            .reference = 0.0,
            .source = "limiting case: the target about 35 dB under the noise per cell",
            .value = static_cast<double>(*summary.sensor_limit_layers),
            .tolerance = 0.0,
            .kind = Tolerance::absolute});
  EXPECT_FALSE(summary.attenuation_margin_db.has_value());
}

// The stop flag: set before the run, no measurement is made; set part-way (here by the progress
// callback after the 3rd of 60 measurements, one thread), the run ends with Interrupted, never with
// a partial result; a flag never set changes nothing.
TEST(Runner, StopFlagEndsTheRunWithoutAResult) {
  const Scenario s = small_scenario();
  std::atomic<bool> stop{true};
  std::size_t calls = 0;
  EXPECT_THROW(
      run_experiment(
          s, {.threads = 1, .progress = [&](std::size_t, std::size_t) { ++calls; }, .stop = &stop}),
      Interrupted);
  EXPECT_EQ(calls, 0u);

  stop = false;
  std::size_t last_done = 0;
  const auto stop_after_three = [&](std::size_t done, std::size_t) {
    last_done = done;
    if (done == 3) stop = true;
  };
  EXPECT_THROW(run_experiment(s, {.threads = 1, .progress = stop_after_three, .stop = &stop}),
               Interrupted);
  EXPECT_EQ(last_done, 3u);

  stop = false;
  const ExperimentResult full = run_experiment(s, {.threads = 2, .progress = {}, .stop = &stop});
  const auto report = radar_run(full);
  const std::vector<StepResult>& steps = report->steps();
  EXPECT_EQ(steps.size() * steps.front().records.size(),
            s.steps() * s.params<fogradar::radar::SensorParams>("radar").measurements_per_step);
}

}  // namespace
}  // namespace fogradar::experiment
