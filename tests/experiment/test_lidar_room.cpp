// The lidar sees the scenario's room: walls and objects given by [chamber.room] and
// [[chamber.objects]] keys, read back through the whole experiment (the scenario read, the lidar
// configured and made, its scans measured: waveform, noise, leading-edge detection, calibration).
// References are plane geometry: a wall at lateral distance D is met by the beam at azimuth a at
// D / sin|a| (incidence cos = sin|a|); a vertical cylinder of radius r whose axis lies at L on the
// beam's azimuth + delta at L cos(delta) - sqrt(r^2 - L^2 sin^2(delta)). A room the lidar cannot
// see breaks nothing when the lidar does not run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/summary.hpp"
#include "sensors.hpp"
#include "validation.hpp"

namespace fogradar::experiment {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

constexpr double deg = pi / 180.0;

// The 905 nm diffuse reflectances of USGS splib07a records 18568 (road concrete) and 19604 (white
// HDPE) (Kokaly et al. 2017, doi:10.3133/ds1035), as tests/propagation/test_diffuse_reflectance.cpp
// copies them.
constexpr double concrete_905 = 0.31044638;
constexpr double white_hdpe_905 = 0.73082012;

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// The lidar alone on its room: no target, no background segment, no fog (one step, 0 layers),
// 150 deg in 0.25 deg steps, noise at p = 1e-100 per sample (threshold 21 sigma: a single echo's
// range scatters by ~1 cm, the mean of 40 scans by ~0.2 cm, so +-2 cm tests geometry and
// receiver). The threshold is set so that the surface under test peaks at two thresholds,
// rho cos(incidence) / (pi R^2) = 2 rho_ref / (pi R_ref^2) with rho_ref = 0.9: there the calibrated
// leading edge reads the true range (docs/lidar.md section 3: no range walk), and the reflectance
// the material gives enters only through that peak.
// `more_lidar_keys` go into [lidar].
std::string lidar_alone(double reflectivity, double range_m, double cos_incidence,
                        const std::string& more_lidar_keys = "") {
  const double threshold_range_m =
      std::sqrt(2.0 * 0.9 * range_m * range_m / (reflectivity * cos_incidence));
  return "[experiment]\nsensors = [\"lidar\"]\nmax_active_layers = 0\n"
         "[lidar]\ntarget_width_m = 0\nbackground = []\nfield_of_view_deg = 150\n"
         "false_alarm_probability = 1e-100\nthreshold_reflectivity = 0.9\nthreshold_range_m = " +
         number(threshold_range_m) + "\n" + more_lidar_keys +
         "[lidar.fog_fluctuation]\nlog_std = 0\n";
}

struct BeamEchoes {
  std::size_t scans = 0;
  std::size_t echoes = 0;
  std::size_t background = 0;
  double mean_range_m = 0.0;
};

// Every echo of the beam at `angle_deg` over the step's scans.
BeamEchoes beam_echoes(const Scenario& scenario, double angle_deg) {
  const ExperimentSummary summary =
      summarize(run_experiment(scenario, {.threads = 2, .progress = {}}));
  const lidar::LidarReport& report = lidar_report(summary);
  const lidar::Lidar& lidar = report.lidar();
  const auto beam = static_cast<std::uint32_t>(std::lround(
      (angle_deg + 0.5 * lidar.params().field_of_view_deg) / lidar.params().angular_step_deg));
  EXPECT_NEAR(lidar.beam_angle_deg(beam), angle_deg, 1e-9);
  BeamEchoes out;
  double sum = 0.0;
  for (const lidar::LidarScan& scan : report.steps().at(0).scans) {
    ++out.scans;
    for (const lidar::LidarEcho& e : scan.echoes) {
      if (e.beam != beam) continue;
      ++out.echoes;
      if (e.origin == lidar::Origin::background) ++out.background;
      sum += e.range_m;
    }
  }
  if (out.echoes > 0) out.mean_range_m = sum / static_cast<double>(out.echoes);
  return out;
}

// The check: a concrete left wall at D = 3 m given by keys (the paper's barrels taken out
// of the way), seen at azimuth a, reads D / sin|a|, +-2 cm, one background echo per scan.
TEST(LidarRoomKeys, WallEchoReadsDistanceOverSine) {
  const double d = 3.0;
  for (const double a : {-20.0, -30.0, -45.0, -60.0}) {
    const double range_m = d / std::sin(std::abs(a) * deg);
    const std::string toml = lidar_alone(concrete_905, range_m, std::sin(std::abs(a) * deg)) +
                             "[chamber]\nobjects = []\n"
                             "[chamber.room.left_wall]\ndistance_m = 3\nmaterial = \"concrete\"\n";
    const BeamEchoes echoes = beam_echoes(parse_scenario(toml, "wall.toml"), a);
    const std::string tag = std::to_string(static_cast<int>(a));
    EXPECT_EQ(echoes.echoes, echoes.scans) << a;
    EXPECT_EQ(echoes.background, echoes.echoes) << a;
    validate({.id = "experiment.lidar_room.wall_range.azimuth" + tag,
              .group = "lidar",
              .quantity = "wall echo's range",
              .unit = "m",
              .conditions = "[chamber.room.left_wall] concrete at 3 m, beam at " + tag +
                            " deg, threshold for a peak of 2 thresholds, mean of 40 scans",
              .reference = range_m,
              .source = "closed form: D / sin|a|",
              .value = echoes.mean_range_m,
              .tolerance = 0.02,
              .kind = Tolerance::absolute});
  }
}

// A rain barrel given as a [[chamber.objects]] cylinder (white HDPE, r 0.3 m, 0.9 m high), its axis
// at 6 m on the -20 deg beam: the beams at -20 and -18 deg read the chord's near end, +-2 cm.
// The scan at lidar.height_m = 1.0 m passes above it: no echo.
TEST(LidarRoomKeys, BarrelEchoReadsItsNearSurface) {
  const double length = 6.0, r = 0.3;
  const std::string barrel =
      "[[chamber.objects]]\nshape = \"cylinder\"\nx_m = " + number(length * std::cos(20.0 * deg)) +
      "\ny_m = " + number(-length * std::sin(20.0 * deg)) +
      "\nradius_m = 0.3\nheight_m = 0.9\nmaterial = \"plastic\"\n";
  for (const double offset : {0.0, 2.0}) {
    const double across = length * std::sin(offset * deg);
    const double half_chord = std::sqrt(r * r - across * across);
    const double range_m = length * std::cos(offset * deg) - half_chord;
    const std::string toml = lidar_alone(white_hdpe_905, range_m, half_chord / r) + barrel;
    const BeamEchoes echoes = beam_echoes(parse_scenario(toml, "barrel.toml"), -20.0 + offset);
    const std::string tag = std::to_string(static_cast<int>(offset));
    EXPECT_EQ(echoes.echoes, echoes.scans) << offset;
    EXPECT_EQ(echoes.background, echoes.echoes) << offset;
    validate({.id = "experiment.lidar_room.barrel_range.offset" + tag,
              .group = "lidar",
              .quantity = "barrel echo's range",
              .unit = "m",
              .conditions = "[[chamber.objects]] plastic cylinder r 0.3 m at 6 m, beam " + tag +
                            " deg off its axis, scan 0.5 m high, mean of 40 scans",
              .reference = range_m,
              .source = "closed form: L cos(delta) - sqrt(r^2 - L^2 sin^2(delta))",
              .value = echoes.mean_range_m,
              .tolerance = 0.02,
              .kind = Tolerance::absolute});
  }
  const std::string above = lidar_alone(white_hdpe_905, length - r, 1.0, "height_m = 1.0\n");
  EXPECT_EQ(beam_echoes(parse_scenario(above + barrel, "above.toml"), -20.0).echoes, 0u);
}

// A room the lidar cannot see (a wall by a real coefficient, objects of glass, which has no
// optical sample) is the radar's business alone: a radar-only scenario reads and runs; the same
// room with the lidar running is refused by key (test_scenario.cpp's ScenarioRejects has each
// message with its line).
TEST(LidarRoomKeys, ARoomTheLidarCannotSeeBreaksNothingWithoutTheLidar) {
  const std::string room =
      "[chamber.room.left_wall]\ndistance_m = 3\nreflection_coefficient = -0.6\n"
      "[[chamber.objects]]\nshape = \"plate\"\nx_m = 5\ny_m = -2\nmaterial = \"glass\"\n";
  const std::string radar_only =
      "[experiment]\nsensors = [\"radar\"]\nmax_active_layers = 1\n"
      "[radar]\nmeasurements_per_step = 3\nchirps_per_frame = 16\n";
  const Scenario scenario = parse_scenario(radar_only + room, "radar_only.toml");
  const ExperimentSummary summary =
      summarize(run_experiment(scenario, {.threads = 2, .progress = {}}));
  EXPECT_EQ(summary.sensors.size(), 1u);
  const std::string with_lidar =
      "[experiment]\nsensors = [\"radar\", \"lidar\"]\nmax_active_layers = 1\n";
  try {
    parse_scenario(with_lidar + room, "with_lidar.toml");
    FAIL() << "accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "chamber.room.left_wall.reflection_coefficient") << e.what();
  }
}

}  // namespace
}  // namespace fogradar::experiment
