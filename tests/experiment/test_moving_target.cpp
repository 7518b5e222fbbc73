// A moving target (target.radial_velocity_m_per_s): the whole EVT at 0, +-5 and +-20 m/s through
// the experiment. The associated detection reads the set velocity back within 2 % of a velocity bin
// (the Doppler peak interpolated to the DTFT maximum, docs/radar.md sec. 5), and the range with the
// range-Doppler coupling corrected: the beat frequency of a path moving at v is raised by the
// Doppler shift f_D = 2 v / lambda (up-chirp), which uncorrected would move the range by
// f_D c / (2 S) = 3.9 cm at 20 m/s (0.26 bins); corrected, the range equals that of the same
// measurement of a static target (same random stream: same micro-motion, clutter and noise) within
// 0.1 mm. Beyond the unambiguous velocity lambda / (4 T_i) the estimate folds by 2 v_max.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/radar/sensor.hpp"
#include "sensors.hpp"
#include "validation.hpp"

namespace fogradar::experiment {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

constexpr const char* kGroup = "experiment: geometry and Doppler";

// The paper scenario's radar with 256-sample chirps of 25.6 us (10 MS/s, 1 GHz): unambiguous to
// lambda / (4 T_i) = 38.0 m/s, a velocity bin lambda / (2 N_c T_i) = 1.19 m/s; 20 measurements at
// each of 0-4 active layers. Without the floor: its paths move at their own range rates
// (docs/radar.md §3.3), slower than the direct path's by the cosine of their leg, and their
// interference would move the read-back velocity and range by the floor's share, not the
// coupling these tests check.
Scenario moving(double velocity_m_per_s, double chirp_s) {
  Scenario s = paper_scenario();
  s.chamber.room.floor.present = false;
  s.experiment.sensors = {"radar"};
  s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 20;
  radar::RadarParams& r = radar_of(s).radar;
  r.samples_per_chirp = static_cast<std::size_t>(std::lround(chirp_s * r.sample_rate_hz));
  r.chirp_duration_s = chirp_s;
  r.chirp_interval_s = chirp_s;
  s.target.radial_velocity_m_per_s = velocity_m_per_s;
  return s;
}

std::vector<radar::StepResult> steps_of(const ExperimentResult& r) { return radar_run(r)->steps(); }

TEST(MovingTarget, VelocityAndCoupledRangeReadBack) {
  const double chirp_s = 25.6e-6;
  const ExperimentResult still =
      run_experiment(moving(0.0, chirp_s), {.threads = 2, .progress = {}});
  const radar::RadarDerived d = radar_run(still)->chain().derived();
  const double v_bin = d.velocity_resolution_m_per_s;
  validate({.id = "experiment.moving_target.max_unambiguous_velocity.25.6us",
            .group = kGroup,
            .quantity = "unambiguous velocity",
            .unit = "m/s",
            .conditions = "77 GHz, chirp interval 25.6 us",
            .reference = 38.0,
            .source = "closed form: lambda / (4 T_i)",
            .value = d.max_unambiguous_velocity_m_per_s,
            .tolerance = 0.1,
            .kind = Tolerance::absolute});
  validate({.id = "experiment.moving_target.velocity_bin.25.6us",
            .group = kGroup,
            .quantity = "velocity bin",
            .unit = "m/s",
            .conditions = "77 GHz, chirp interval 25.6 us, 16 chirps per frame",
            .reference = 1.19,
            .source = "closed form: lambda / (2 N_c T_i)",
            .value = v_bin,
            .tolerance = 0.01,
            .kind = Tolerance::absolute});
  double worst_velocity_bins = 0.0, worst_range_m = 0.0;
  for (const double v : {0.0, 5.0, -5.0, 20.0, -20.0}) {
    const ExperimentResult run = run_experiment(moving(v, chirp_s), {.threads = 2, .progress = {}});
    const double coupling_m =
        2.0 * v / d.wavelength_m * speed_of_light_m_per_s / (2.0 * d.chirp_slope_hz_per_s);
    std::size_t compared = 0;
    double farthest_m_per_s = v;  // the measured velocity farthest from v, of every measurement
    const std::vector<radar::StepResult> moved = steps_of(run), rest = steps_of(still);
    for (std::size_t k = 0; k < moved.size(); ++k) {
      for (std::size_t i = 0; i < moved[k].records.size(); ++i) {
        const radar::MeasurementRecord& m = moved[k].records[i];
        const radar::MeasurementRecord& s = rest[k].records[i];
        ASSERT_TRUE(m.detected && s.detected) << v << " m/s, step " << k << ", " << i;
        if (std::abs(m.velocity_m_per_s - v) >= std::abs(farthest_m_per_s - v))
          farthest_m_per_s = m.velocity_m_per_s;
        EXPECT_NEAR(m.range_m, s.range_m, 1e-4) << v << " m/s (uncorrected: " << coupling_m << ")";
        worst_velocity_bins =
            std::max(worst_velocity_bins, std::abs(m.velocity_m_per_s - v) / v_bin);
        worst_range_m = std::max(worst_range_m, std::abs(m.range_m - s.range_m));
        ++compared;
      }
    }
    validate({.id = "experiment.moving_target.velocity." + std::to_string(std::lround(v)) + "mps",
              .group = kGroup,
              .quantity = "velocity of the associated detection, the farthest of 100",
              .unit = "m/s",
              .conditions = "radial velocity " + std::to_string(std::lround(v)) +
                            " m/s, chirp interval 25.6 us, 5 steps x 20 measurements",
              .reference = v,
              .source = "the target's set radial velocity (geometry); 2 % of a velocity bin",
              .value = farthest_m_per_s,
              .tolerance = 0.02 * v_bin,
              .kind = Tolerance::absolute});
    EXPECT_EQ(compared, 5u * 20u);
    if (v == 20.0) {
      EXPECT_GT(std::abs(coupling_m), 0.03);  // what the correction removes
    }
  }
  std::printf("[ measured ] worst |velocity error| %.2e bin, worst |range(v) - range(0)| %.2e m\n",
              worst_velocity_bins, worst_range_m);
}

// The paper radar (51.2 us chirps) is unambiguous to 19.0 m/s: 25 m/s reads as 25 - 2 x 19.0.
TEST(MovingTarget, BeyondTheUnambiguousVelocityTheEstimateFolds) {
  const ExperimentResult run =
      run_experiment(moving(25.0, 51.2e-6), {.threads = 2, .progress = {}});
  const radar::RadarDerived d = radar_run(run)->chain().derived();
  const double folded = 25.0 - 2.0 * d.max_unambiguous_velocity_m_per_s;
  validate({.id = "experiment.moving_target.folded_velocity.25mps.51.2us",
            .group = kGroup,
            .quantity = "folded velocity 25 - 2 v_max",
            .unit = "m/s",
            .conditions = "25 m/s radial, 77 GHz, chirp interval 51.2 us",
            .reference = -13.0,
            .source = "closed form: v - 2 lambda / (4 T_i) = 25 - 2 x 19.0",
            .value = folded,
            .tolerance = 0.1,
            .kind = Tolerance::absolute});
  double farthest_m_per_s = folded;  // the measured velocity farthest from the folded one
  for (const radar::StepResult& step : steps_of(run)) {
    for (const radar::MeasurementRecord& m : step.records) {
      ASSERT_TRUE(m.associated);
      if (std::abs(m.velocity_m_per_s - folded) >= std::abs(farthest_m_per_s - folded))
        farthest_m_per_s = m.velocity_m_per_s;
    }
  }
  validate({.id = "experiment.moving_target.folded_velocity.25mps",
            .group = kGroup,
            .quantity = "velocity of the associated detection, the farthest of every measurement",
            .unit = "m/s",
            .conditions = "25 m/s radial, chirp interval 51.2 us, every step and measurement",
            .reference = folded,
            .source = "closed form: aliasing by 2 v_max, v_max = lambda / (4 T_i); 2 % of a "
                      "velocity bin",
            .value = farthest_m_per_s,
            .tolerance = 0.02 * d.velocity_resolution_m_per_s,
            .kind = Tolerance::absolute});
}

// The mean over every measurement of the associated detection's range.
double mean_range_m(const ExperimentResult& run) {
  double sum = 0.0, count = 0.0;
  for (const radar::StepResult& step : steps_of(run)) {
    for (const radar::MeasurementRecord& m : step.records) {
      if (!m.associated) continue;
      sum += m.range_m;
      count += 1.0;
    }
  }
  return sum / count;
}

// A velocity beyond +-v_max is warned: on stderr (the summary's warnings), in the printed table and
// in radar_summary.json, which give the velocity it reads as against the closed form v - 2 v_max
// round(v / (2 v_max)), v_max = c / (4 f_c T_i) computed here, and the range error of the coupling
// correction made with it, (2 (v - v_folded) / lambda) c / (2 S) (up-chirp), against the measured
// range difference between 25 m/s and a static target (same random streams: same micro-motion,
// clutter and noise) within 1 mm. Inside (+-5 m/s, and 25 m/s with 25.6 us chirps, v_max = 38 m/s)
// none of the three says anything.
TEST(MovingTarget, AVelocityBeyondTheUnambiguousOneIsWarned) {
  const Scenario scenario = moving(25.0, 51.2e-6);
  const radar::RadarParams& p = radar_of(scenario).radar;
  const double lambda_m = speed_of_light_m_per_s / p.centre_frequency_hz;
  const double v_max = lambda_m / (4.0 * p.chirp_interval_s);
  const double folded = 25.0 - 2.0 * v_max * std::round(25.0 / (2.0 * v_max));
  const double slope_hz_per_s = p.sweep_bandwidth_hz / p.chirp_duration_s;
  const double range_error_m =
      2.0 * (25.0 - folded) / lambda_m * speed_of_light_m_per_s / (2.0 * slope_hz_per_s);

  const ExperimentResult run = run_experiment(scenario, {.threads = 2, .progress = {}});
  const auto summary = radar_run(run);
  const std::vector<std::string> warnings = summary->warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("target.radial_velocity_m_per_s"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("reads as -13.02 m/s"), std::string::npos) << warnings[0];
  EXPECT_NE(summary->table().find("velocity folded: the target's radial velocity 25 m/s"),
            std::string::npos)
      << summary->table();
  const nlohmann::json fold = summary->json().at("velocity_fold");
  validate({.id = "experiment.moving_target.folded_velocity.summary_json",
            .group = kGroup,
            .quantity = "velocity_fold.reads_m_per_s of radar_summary.json",
            .unit = "m/s",
            .conditions = "25 m/s radial, 77 GHz, chirp interval 51.2 us",
            .reference = folded,
            .source = "closed form v - 2 v_max round(v / (2 v_max)), v_max = c / (4 f_c T_i)",
            .value = fold.at("reads_m_per_s").get<double>(),
            .tolerance = 1e-9,
            .kind = Tolerance::absolute});
  EXPECT_NEAR(fold.at("range_error_m").get<double>(), range_error_m, 1e-9);

  Scenario still = scenario;
  still.target.radial_velocity_m_per_s = 0.0;
  const double measured_error_m =
      mean_range_m(run) - mean_range_m(run_experiment(still, {.threads = 2, .progress = {}}));
  validate({.id = "experiment.moving_target.folded_velocity.range_error",
            .group = kGroup,
            .quantity = "range of a 25 m/s target minus a static one's, mean of every measurement",
            .unit = "m",
            .conditions = "25 m/s radial, chirp interval 51.2 us (folded to -13.0 m/s)",
            .reference = range_error_m,
            .source = "closed form (2 (v - v_folded) / lambda) c / (2 S): the coupling corrected "
                      "with the folded velocity",
            .value = measured_error_m,
            .tolerance = 1e-3,
            .kind = Tolerance::absolute});

  for (const auto& [velocity, chirp_s] :
       {std::pair{5.0, 51.2e-6}, std::pair{-5.0, 51.2e-6}, std::pair{25.0, 25.6e-6}}) {
    Scenario inside = moving(velocity, chirp_s);
    inside.target.radial_velocity_m_per_s = velocity;
    inside.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 2;
    const auto quiet = radar_run(run_experiment(inside, {.threads = 2, .progress = {}}));
    EXPECT_TRUE(quiet->warnings().empty()) << velocity << " m/s: " << quiet->warnings()[0];
    EXPECT_EQ(quiet->table().find("velocity folded"), std::string::npos) << velocity;
    EXPECT_TRUE(quiet->json().at("velocity_fold").is_null()) << velocity;
  }
}

}  // namespace
}  // namespace fogradar::experiment
