// The study's radar baseline against the model's band (docs/paper-comparison.md, "The envelope"):
// the setups of examples/sweeps/paper_uncertainty.toml, each the paper scenario with the keys the
// study does not report drawn from their ranges, run as the sweep runs them; the band is the 5-95 %
// of their mean RCS at 0 layers, as envelope.csv gives it. The study's 14.97 dBsm lies above it, a
// disagreement docs/paper-comparison.md explains; the validation page shows it as one, not as a
// pass. The check holds while the disagreement is as documented: were the study's value to fall
// inside the band, it fails, and the page and the document must be revised.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/sweep/spec.hpp"
#include "validation.hpp"

namespace fogradar::sweep {
namespace {

// The study's Fig. 4 and text: the EVT's mean RCS in clear weather (Hasirlioglu et al., sec. IV-A).
constexpr double study_mean_rcs_dbsm = 14.97;

TEST(PaperEnvelope, StudysRadarBaselineLiesAboveTheModelsBand) {
#ifdef FOGRADAR_SANITIZE_BUILD
  GTEST_SKIP() << "sanitizer build (several times slower): the Release run records the band";
#endif
  const SweepSpec spec =
      load_sweep_file(std::string(FOGRADAR_EXAMPLES_DIR) + "/sweeps/paper_uncertainty.toml");
  const std::vector<Point> points = expand(spec);
  ASSERT_EQ(points.size(), 1u);
  ASSERT_EQ(points[0].setups.size(), 64u);
  // The radar alone at 0 layers: its streams are the same as in the sweep's full runs (a sensor's
  // items and steps draw from streams of their own, experiment/runner.hpp).
  std::vector<double> means_dbsm;
  for (const experiment::Scenario& setup : points[0].setups) {
    const experiment::Scenario radar_only = experiment::parse_scenario_over(
        setup, "[experiment]\nsensors = [\"radar\"]\nmax_active_layers = 0\n", "test");
    const experiment::ExperimentSummary summary =
        experiment::summarize(experiment::run_experiment(radar_only));
    ASSERT_EQ(summary.sensors.size(), 1u);
    const nlohmann::json steps = summary.sensors[0].summary->json()["steps"];
    ASSERT_EQ(steps.size(), 1u);
    means_dbsm.push_back(steps[0]["mean_dbsm"].get<double>());
  }
  std::sort(means_dbsm.begin(), means_dbsm.end());
  std::printf("[ measured ] the setups' mean RCS at 0 layers: %.2f ... %.2f dBsm\n",
              means_dbsm.front(), means_dbsm.back());
  const double low = stats::quantile_type7(means_dbsm, 0.05);
  const double high = stats::quantile_type7(means_dbsm, 0.95);
  fogradar::testing::validate(
      {.id = "paper.radar.fig4.clear_weather_mean_rcs",
       .group = "paper comparison",
       .quantity = "EVT's mean RCS at 0 layers",
       .unit = "dBsm",
       .conditions = "paper scenario, 200 measurements, over the 64 setups of "
                     "examples/sweeps/paper_uncertainty.toml (radar height, polarisation and "
                     "range resolution, the wall, ceiling and barrels, micro-motion); fogradar: "
                     "their median",
       .reference = study_mean_rcs_dbsm,
       .source = "the study's Fig. 4 and text (sec. IV-A): mean 14.97 dBsm, \"higher than the "
                 "expected value\"; docs/paper-comparison.md",
       .value = stats::quantile_type7(means_dbsm, 0.5),
       .kind = fogradar::testing::Tolerance::disagreement,
       .samples = means_dbsm.size(),
       .interval_low = low,
       .interval_high = high,
       .confidence = "the setups' 5-95 % band",
       .plot = "paper_comparison",
       .x = 0.0,
       .x_label = "active fog layers"});
  // The extremes docs/paper-comparison.md quotes: the study's value is above every setup.
  EXPECT_LT(means_dbsm.back(), study_mean_rcs_dbsm);
}

}  // namespace
}  // namespace fogradar::sweep
