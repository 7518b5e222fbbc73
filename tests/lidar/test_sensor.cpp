// The lidar as a sensor: the threshold's false-alarm rate, the fog fluctuation series, determinism,
// every invalid key refused by name, result files, the memory estimate, and the paper scenario's
// Fig. 5 / Fig. 6 pattern.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numeric>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/lidar/summary.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "rejected_field.hpp"
#include "svg_check.hpp"
#include "validation.hpp"

namespace fogradar::lidar {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

constexpr double degree_rad = 3.14159265358979323846 / 180.0;

const propagation::SegelsteinTable& table() {
  static const propagation::SegelsteinTable instance;
  return instance;
}

// An empty scene: no target, no background; with no active layer every beam is noise only.
LidarParams empty_scene() {
  LidarParams params;
  params.target_width_m = 0.0;
  params.background.clear();
  return params;
}

// Noise alone: every sample is N(0, sigma^2) with sigma = threshold / z_(1 - p), so a sample
// exceeds the threshold with probability p and starts an echo (an upward crossing) with probability
// p (1 - p) (p at the first sample). With no merging (separation 0), no minimum range and 8 echoes
// allowed, the expected echo count per beam is p + (N - 1) p (1 - p). p = 1e-3, N = 401 samples,
// 20 scans x 361 beams: ~2900 expected echoes; the count is a sum of nearly independent rare events
// (variance ~ mean), tolerance 5 standard deviations.
TEST(LidarSensor, FalseAlarmRateOnNoiseAloneMatchesTheDesign) {
  LidarParams params = empty_scene();
  params.false_alarm_probability = 1e-3;
  params.min_echo_separation_m = 0.0;
  params.min_range_m = 0.0;
  params.max_echoes = 8;
  const Lidar lidar(params, propagation::ChamberSpec{}, table());
  const std::size_t scans = 20;
  std::size_t echoes = 0;
  for (std::size_t s = 0; s < scans; ++s) {
    RandomStream stream = sensor_stream(3, stream_key, 0, s);
    const LidarScan scan =
        lidar.measure(propagation::first_layers_active(0, 4), std::vector<double>(4, 1.0), stream);
    for (const LidarEcho& e : scan.echoes) EXPECT_EQ(e.origin, Origin::noise);
    echoes += scan.echoes.size();
  }
  const double p = params.false_alarm_probability;
  const double n = static_cast<double>(lidar.samples_per_beam());
  const double expected =
      static_cast<double>(scans * lidar.beam_count()) * (p + (n - 1.0) * p * (1.0 - p));
  validate({.id = "lidar.noise.false_alarm_echoes.pfa1e-3",
            .group = "lidar",
            .quantity = "false-alarm echoes on noise alone",
            .unit = "echoes",
            .conditions = "p = 1e-3 per sample, " + std::to_string(scans) + " scans x " +
                          std::to_string(lidar.beam_count()) + " beams x " +
                          std::to_string(lidar.samples_per_beam()) + " samples",
            .reference = expected,
            .source = "closed form: upward crossings of Gaussian noise, p + (N - 1) p (1 - p) "
                      "per beam",
            .value = static_cast<double>(echoes),
            .tolerance = 5.0 * std::sqrt(expected),
            .kind = Tolerance::statistical,
            .samples = scans * lidar.beam_count() * lidar.samples_per_beam(),
            .interval_low = expected - 5.0 * std::sqrt(expected),
            .interval_high = expected + 5.0 * std::sqrt(expected),
            .confidence = "5 standard deviations of the count (variance ~ mean)"});
}

// The series: unit mean of the factor, lag-one correlation of its log rho = exp(-T / tau), std of
// the log = log_std. 4000 scans x 4 layers: the sample mean of f (std ~0.2 / sqrt(n_eff), n_eff =
// n (1 - rho) / (1 + rho) ~ 16000 x 0.05 / 1.95 = 400) within 0.05; log std within 0.03;
// correlation within 0.02 of the design (its sampling std ~ (1 - rho^2) / sqrt(n) ~ 0.001 for rho =
// 0.95).
TEST(LidarSensor, FogFluctuationSeriesHasTheStatedDistributionAndCorrelation) {
  LidarParams params;
  params.scans_per_step = 4000;
  params.fog_fluctuation = {.log_std = 0.2, .correlation_time_s = 0.5};
  const Lidar lidar(params, propagation::ChamberSpec{}, table());
  const FogFluctuationSeries series = lidar.fog_fluctuation(RandomStream(11, 2, 40));
  ASSERT_EQ(series.factors.size(), 16000u);
  double mean = 0.0, log_sum = 0.0, log_sq = 0.0, lag = 0.0;
  std::size_t pairs = 0;
  for (std::size_t s = 0; s < 4000; ++s) {
    for (std::size_t l = 0; l < 4; ++l) {
      const double f = series.scan(s)[l];
      mean += f;
      log_sum += std::log(f);
      log_sq += std::log(f) * std::log(f);
      if (s > 0) {
        lag += (std::log(f) + 0.02) * (std::log(series.scan(s - 1)[l]) + 0.02);
        ++pairs;
      }
    }
  }
  mean /= 16000.0;
  const double log_mean = log_sum / 16000.0;
  const double log_var = log_sq / 16000.0 - log_mean * log_mean;
  const std::string conditions =
      "log std 0.2, correlation time 0.5 s, 40 Hz scans, 4000 scans x 4 layers";
  validate({.id = "lidar.fog_fluctuation.mean",
            .group = "lidar",
            .quantity = "mean optical-depth factor",
            .unit = "1",
            .conditions = conditions,
            .reference = 1.0,
            .source = "design: unit-mean lognormal factor",
            .value = mean,
            .tolerance = 0.05,
            .kind = Tolerance::statistical,
            .samples = 16000,
            .interval_low = 1.0 - 0.05,
            .interval_high = 1.0 + 0.05,
            .confidence = "about 5 standard errors (std ~0.2 / sqrt(n_eff), n_eff ~ 400)"});
  validate({.id = "lidar.fog_fluctuation.log_std",
            .group = "lidar",
            .quantity = "standard deviation of the factor's log",
            .unit = "1",
            .conditions = conditions,
            .reference = 0.2,
            .source = "design: log_std",
            .value = std::sqrt(log_var),
            .tolerance = 0.03,
            .kind = Tolerance::statistical,
            .samples = 16000,
            .interval_low = 0.2 - 0.03,
            .interval_high = 0.2 + 0.03,
            .confidence = "0.03 about the design (sampling of n_eff ~ 400 correlated values)"});
  const double rho = std::exp(-1.0 / (40.0 * 0.5));
  validate({.id = "lidar.fog_fluctuation.lag1_correlation",
            .group = "lidar",
            .quantity = "lag-one correlation of the factor's log",
            .unit = "1",
            .conditions = conditions,
            .reference = rho,
            .source = "closed form: AR(1) correlation exp(-T / tau)",
            .value = lag / static_cast<double>(pairs) / log_var,
            .tolerance = 0.02,
            .kind = Tolerance::statistical,
            .samples = pairs,
            .interval_low = rho - 0.02,
            .interval_high = rho + 0.02,
            .confidence = "0.02 about the design (sampling std ~ (1 - rho^2) / sqrt(n) ~ 0.001)"});
  params.fog_fluctuation.log_std = 0.0;
  const Lidar steady(params, propagation::ChamberSpec{}, table());
  for (const double f : steady.fog_fluctuation(RandomStream(1)).factors) EXPECT_EQ(f, 1.0);
}

std::vector<LidarScan> scans_of_step(const Lidar& lidar, std::size_t step, unsigned threads,
                                     std::uint64_t seed = 5) {
  const auto active = propagation::first_layers_active(step, 4);
  const FogFluctuationSeries fog =
      lidar.fog_fluctuation(sensor_stream(seed, stream_key, step, lidar.fog_series_index()));
  std::vector<LidarScan> scans(lidar.params().scans_per_step);
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (std::size_t s = t; s < scans.size(); s += threads) {
        RandomStream stream = sensor_stream(seed, stream_key, step, s);
        scans[s] = lidar.measure(active, fog.scan(s), stream);
      }
    });
  }
  for (std::thread& thread : pool) thread.join();
  return scans;
}

// A lidar that sees a 1 m layer of the study's fog (alpha = 0.88 /m at 905 nm) and, 0.3 m behind
// it, the target (reflectivity 0.3 at 3.3 m): 9 beams within 1 deg of boresight, no fog
// fluctuation, noise sigma = threshold / 7 (p = 1e-12), and leading edges within 3 m merging. The
// fog's return (1-2 thresholds, docs/lidar.md §8) rises at 2 m; the target's echo through the
// layer, rho / pi exp(-2 alpha L) / R^2 = 4.7 thresholds, is the stronger.
LidarParams merging_lidar() {
  LidarParams params;
  params.background.clear();
  params.field_of_view_deg = 2.0;
  params.fog_fluctuation.log_std = 0.0;
  params.false_alarm_probability = 1e-12;
  params.min_echo_separation_m = 3.0;
  return params;
}

propagation::ChamberSpec one_layer_before_the_target() {
  propagation::ChamberSpec chamber;
  chamber.layers.resize(1);
  chamber.target_gap_m = 0.3;
  return chamber;
}

// With the layer on, fog and target merge into one echo per beam: its range is read at the fog's
// leading edge, so it is the fog's (layer 0), attributed inside the layer, while its intensity
// stays its strongest sample's, the target's: scale (peak / threshold) within 5 sigma of the
// closed-form peak. With the layer off the lone target echo is the target's, attributed at its
// peak: the sample nearest the target's range along the beam R / cos(angle), within half a sample.
TEST(LidarSensor, MergedFogAndTargetEchoIsTheFogsAtItsRange) {
  const LidarParams params = merging_lidar();
  const propagation::ChamberSpec chamber = one_layer_before_the_target();
  const Lidar lidar(params, chamber, table());
  ASSERT_EQ(lidar.beam_count(), 9u);
  const double dr = speed_of_light_m_per_s * params.sample_interval_ns * 1e-9 / 2.0;
  const double sigma = lidar.noise_std() * params.intensity_scale / lidar.threshold();
  const double loss = std::exp(-2.0 * lidar.layer_extinction_per_m(0));
  RandomStream stream = sensor_stream(11, stream_key, 1, 0);
  const LidarScan fogged = lidar.measure({true}, std::vector<double>{1.0}, stream);
  ASSERT_EQ(fogged.echoes.size(), lidar.beam_count());
  for (const LidarEcho& e : fogged.echoes) {
    const double cos_a = std::cos(lidar.beam_angle_deg(e.beam) * degree_rad);
    const std::string conditions = "one 1 m layer at 2 m, target 0.3 m behind it, beam " +
                                   std::to_string(lidar.beam_angle_deg(e.beam)) + " deg";
    EXPECT_EQ(e.origin, Origin::fog) << conditions;
    EXPECT_EQ(e.layer, 0) << conditions;
    EXPECT_GE(e.range_m, 2.0 / cos_a) << conditions;
    EXPECT_LE(e.range_m, 3.0 / cos_a) << conditions;
    EXPECT_GE(e.attributed_range_m, 2.0 / cos_a) << conditions;
    EXPECT_LE(e.attributed_range_m, 3.0 / cos_a) << conditions;
    const double range_m = 3.3 / cos_a;
    const double peak = hard_target_peak(0.3, cos_a, loss, range_m);
    validate({.id = "lidar.merged_echo.intensity.beam" + std::to_string(e.beam),
              .group = "lidar",
              .quantity = "merged fog and target echo's intensity",
              .unit = "intensity",
              .conditions = conditions,
              .reference = params.intensity_scale * peak / lidar.threshold(),
              .source = "closed form: the target's peak rho cos(i) / pi exp(-2 alpha L) / R^2 "
                        "(off-grid: the sample may sit 4 % below it), 5 noise sigma",
              .value = e.intensity,
              .tolerance = 5.0 * sigma + 0.04 * params.intensity_scale * peak / lidar.threshold(),
              .kind = Tolerance::absolute});
  }
  EXPECT_FALSE(fogged.target_detected);
  RandomStream clear_stream = sensor_stream(11, stream_key, 0, 0);
  const LidarScan clear = lidar.measure({false}, std::vector<double>{1.0}, clear_stream);
  ASSERT_EQ(clear.echoes.size(), lidar.beam_count());
  for (const LidarEcho& e : clear.echoes) {
    const double angle_deg = lidar.beam_angle_deg(e.beam);
    EXPECT_EQ(e.origin, Origin::target) << angle_deg;
    EXPECT_EQ(e.layer, no_layer) << angle_deg;
    validate(
        {.id = "lidar.lone_target.attributed_range.beam" + std::to_string(e.beam),
         .group = "lidar",
         .quantity = "lone target echo's attribution range",
         .unit = "m",
         .conditions = "target at 3.3 m, clear air, beam " + std::to_string(angle_deg) + " deg",
         .reference = 3.3 / std::cos(angle_deg * degree_rad),
         .source = "closed form: the target's range along the beam R / cos(angle); the "
                   "sampled pulse peaks at the nearest sample",
         .value = e.attributed_range_m,
         .tolerance = dr / 2.0,
         .kind = Tolerance::absolute});
  }
  EXPECT_TRUE(clear.target_detected);
}

// Two layers: a thin fog (visibility 150 m) in layer 0 and the study's fog in layer 1, both on,
// the threshold from 60 m: layer 0's return peaks at 0.3 thresholds (2 sigma), layer 1's at 3.
// The ground truth names, along the centre beam, layer 0 where
// its fog's return is the larger and layer 1 from where layer 1's is: the reference is a second
// computation, each layer's fog waveform alone (Lidar::waveform with that layer on), layer 1's
// times layer 0's two-way transmittance exp(-2 alpha_0 L_0) in front of it; the switch within one
// sample. The beam's first echo, made by layer 1's leading edge (layer 0's return stays below the
// threshold), is the fog's of layer 1, attributed inside it and read at most the pulse's range
// FWHM c fwhm / 2 before it (the leading edge's walk).
TEST(LidarSensor, FogEchoesAndStretchesNameTheirLayer) {
  LidarParams params = merging_lidar();
  params.min_echo_separation_m = 1.0;
  params.threshold_range_m = 60.0;
  propagation::ChamberSpec chamber;
  chamber.layers.resize(2);
  chamber.layers[0].fog.density = propagation::Visibility{.m = 150.0};
  const Lidar lidar(params, chamber, table());
  const std::size_t beam = lidar.beam_count() / 2;
  ASSERT_EQ(lidar.beam_angle_deg(beam), 0.0);
  const std::vector<double> factors(2, 1.0);
  const BeamWaveform near = lidar.waveform(beam, {true, false}, factors);
  const BeamWaveform far = lidar.waveform(beam, {false, true}, factors);
  const double t0 = std::exp(-2.0 * lidar.layer_extinction_per_m(0) * 1.0);
  const double dr = speed_of_light_m_per_s * params.sample_interval_ns * 1e-9 / 2.0;
  std::size_t switch_sample = 0;
  while (!(t0 * far.fog[switch_sample] > near.fog[switch_sample])) ++switch_sample;
  RandomStream stream = sensor_stream(12, stream_key, 2, 0);
  std::vector<OriginRun> origins;
  const LidarScan scan = lidar.measure({true, true}, factors, stream, {}, {}, &origins);
  std::vector<OriginRun> fog_runs;
  for (const OriginRun& run : origins) {
    if (run.beam != beam) continue;
    if (run.origin == Origin::fog) {
      fog_runs.push_back(run);
    } else {
      EXPECT_EQ(run.layer, no_layer) << to_string(run.origin);
    }
  }
  ASSERT_EQ(fog_runs.size(), 2u);
  EXPECT_EQ(fog_runs[0].layer, 0);
  EXPECT_EQ(fog_runs[1].layer, 1);
  EXPECT_EQ(fog_runs[0].end_m, fog_runs[1].start_m);
  EXPECT_LT(fog_runs[0].start_m, 2.0);
  validate({.id = "lidar.origins.layer_switch",
            .group = "lidar",
            .quantity = "range where the ground truth's fog passes from layer 0 to layer 1",
            .unit = "m",
            .conditions = "layers [2, 3] m (visibility 150 m) and [3, 4] m (the study's fog), "
                          "both on, boresight beam",
            .reference = static_cast<double>(switch_sample) * dr,
            .source = "second computation: each layer's fog waveform alone, layer 1's times layer "
                      "0's two-way transmittance; the first sample where layer 1's is larger",
            .value = fog_runs[1].start_m,
            .tolerance = dr,
            .kind = Tolerance::absolute});
  std::size_t echoes = 0;
  for (const LidarEcho& e : scan.echoes) {
    if (e.beam != beam || e.index != 0) continue;
    ++echoes;
    EXPECT_EQ(e.origin, Origin::fog);
    EXPECT_EQ(e.layer, 1);
    EXPECT_GE(e.range_m, 3.0 - speed_of_light_m_per_s * params.pulse_width_ns * 1e-9 / 2.0);
    EXPECT_LE(e.range_m, 4.0);
    EXPECT_GE(e.attributed_range_m, 3.0);
    EXPECT_LE(e.attributed_range_m, 4.0);
  }
  EXPECT_EQ(echoes, 1u);
}

// Same seed, any thread count and order: byte-identical echoes CSV.
TEST(LidarSensor, ScansAreDeterministicForAnyThreadCount) {
  LidarParams params;
  params.scans_per_step = 6;
  params.field_of_view_deg = 20.0;
  const Lidar lidar(params, propagation::ChamberSpec{}, table());
  std::vector<LidarStepResult> one{{1, scans_of_step(lidar, 1, 1)}};
  std::vector<LidarStepResult> three{{1, scans_of_step(lidar, 1, 3)}};
  EXPECT_EQ(lidar_echoes_csv(lidar, one), lidar_echoes_csv(lidar, three));
  EXPECT_FALSE(one[0].scans[0].echoes.empty());
}

// A flat water film on the window (lidar.window_water_film_m): every echo of a beam, the target's,
// the fog's and the background's, is the dry lidar's times the film's two-way transmittance,
// written out here as the incoherent sum of the film on glass n = 1.5 against the dry face
// (Harbecke 1986, Appl. Phys. B 39, 165): T = (1 - R_af)(1 - R_fg) tau / (1 - R_af R_fg tau^2) /
// (1 - R_ag), tau = exp(-4 pi k t / lambda), with Segelstein's water at 905 nm; to rounding.
TEST(LidarSensor, WindowFilmScalesEveryEchoByItsTwoWayTransmittance) {
  LidarParams dry;
  dry.background = {{.x0_m = 0.5, .y0_m = -3.0, .x1_m = 12.0, .y1_m = -3.0, .reflectivity = 0.5}};
  LidarParams wet = dry;
  wet.window_water_film_m = 0.2e-3;
  const Lidar dry_lidar(dry, propagation::ChamberSpec{}, table());
  const Lidar wet_lidar(wet, propagation::ChamberSpec{}, table());
  const std::complex<double> m = table().refractive_index(wet.wavelength_m);
  const auto reflectance = [](std::complex<double> a, std::complex<double> b) {
    return std::norm((a - b) / (a + b));
  };
  const double r_af = reflectance(1.0, m), r_fg = reflectance(m, 1.5), r_ag = reflectance(1.0, 1.5);
  const double tau = std::exp(-4.0 * 3.14159265358979323846 * m.imag() * wet.window_water_film_m /
                              wet.wavelength_m);
  const double one_way =
      (1.0 - r_af) * (1.0 - r_fg) * tau / (1.0 - r_af * r_fg * tau * tau) / (1.0 - r_ag);
  std::printf("[ measured ] lidar window film 0.2 mm at 905 nm: one-way T = %.6f (wet / dry)\n",
              one_way);
  EXPECT_EQ(dry_lidar.window_two_way_transmittance(), 1.0);
  fogradar::testing::validate(
      {.id = "lidar.window_film.two_way_transmittance",
       .group = "lidar: optics",
       .quantity = "two-way transmittance of the window's water film against the dry window",
       .unit = "1",
       .conditions = "0.2 mm flat water film on glass n = 1.5, 905 nm, Segelstein water",
       .reference = one_way * one_way,
       .source = "incoherent film sum (Harbecke 1986), written out in this test",
       .value = wet_lidar.window_two_way_transmittance(),
       .tolerance = 1e-12,
       .kind = Tolerance::relative});
  const propagation::ActiveLayers all_on(4, true);
  const std::vector<double> factors(4, 1.0);
  for (std::size_t beam : {dry_lidar.target_beam(), std::size_t{0}}) {
    const BeamWaveform d = dry_lidar.waveform(beam, all_on, factors);
    const BeamWaveform w = wet_lidar.waveform(beam, all_on, factors);
    double compared = 0.0;
    for (const auto& [dry_part, wet_part] :
         {std::pair{&d.target, &w.target}, {&d.fog, &w.fog}, {&d.background, &w.background}}) {
      for (std::size_t k = 0; k < dry_part->size(); ++k) {
        EXPECT_NEAR((*wet_part)[k], one_way * one_way * (*dry_part)[k],
                    1e-12 * std::abs((*dry_part)[k]));
        compared += (*dry_part)[k];
      }
    }
    EXPECT_GT(compared, 0.0) << "beam " << beam;
  }
}

TEST(LidarSensor, EveryInvalidKeyIsRefusedByName) {
  using test_support::rejected_field;
  // Three background segments (there are none by default), so that one element's key is named.
  const auto rejects = [](auto change) {
    LidarParams p;
    p.background.assign(3,
                        {.x0_m = 3.0, .y0_m = 2.0, .x1_m = 6.0, .y1_m = 2.0, .reflectivity = 0.4});
    EXPECT_EQ(rejected_field([&] { p.validate(); }), "accepted");
    change(p);
    return rejected_field([&] { p.validate(); });
  };
  EXPECT_EQ(rejected_field([] { LidarParams{}.validate(); }), "accepted");
  EXPECT_EQ(rejects([](LidarParams& p) { p.wavelength_m = 10e-6; }), "lidar.wavelength_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.field_of_view_deg = -1.0; }), "lidar.field_of_view_deg");
  EXPECT_EQ(rejects([](LidarParams& p) { p.angular_step_deg = 0.0; }), "lidar.angular_step_deg");
  EXPECT_EQ(rejects([](LidarParams& p) { p.scan_rate_hz = std::nan(""); }), "lidar.scan_rate_hz");
  EXPECT_EQ(rejects([](LidarParams& p) { p.scans_per_step = 0; }), "lidar.scans_per_step");
  EXPECT_EQ(rejects([](LidarParams& p) { p.min_range_m = -0.1; }), "lidar.min_range_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.max_range_m = 0.05; }), "lidar.max_range_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.pulse_width_ns = 0.0; }), "lidar.pulse_width_ns");
  EXPECT_EQ(rejects([](LidarParams& p) { p.sample_interval_ns = 3.0; }),
            "lidar.sample_interval_ns");
  EXPECT_EQ(rejects([](LidarParams& p) { p.overlap_range_m = -1.0; }), "lidar.overlap_range_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.threshold_range_m = 0.0; }), "lidar.threshold_range_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.threshold_reflectivity = 0.0; }),
            "lidar.threshold_reflectivity");
  EXPECT_EQ(rejects([](LidarParams& p) { p.false_alarm_probability = 0.5; }),
            "lidar.false_alarm_probability");
  EXPECT_EQ(rejects([](LidarParams& p) { p.max_echoes = 0; }), "lidar.max_echoes");
  EXPECT_EQ(rejects([](LidarParams& p) { p.max_echoes = 9; }), "lidar.max_echoes");
  EXPECT_EQ(rejects([](LidarParams& p) { p.min_echo_separation_m = -1.0; }),
            "lidar.min_echo_separation_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.intensity_scale = 0.0; }), "lidar.intensity_scale");
  EXPECT_EQ(rejects([](LidarParams& p) { p.intensity_saturation = -1.0; }),
            "lidar.intensity_saturation");
  EXPECT_EQ(rejects([](LidarParams& p) { p.target_width_m = -1.0; }), "lidar.target_width_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.target_offset_m = 1e3; }), "lidar.target_offset_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.target_reflectivity = 1.5; }),
            "lidar.target_reflectivity");
  EXPECT_EQ(rejects([](LidarParams& p) { p.fog_width_m = -2.0; }), "lidar.fog_width_m");
  EXPECT_EQ(rejects([](LidarParams& p) { p.background[2].reflectivity = 2.0; }),
            "lidar.background[2].reflectivity");
  EXPECT_EQ(rejects([](LidarParams& p) { p.background[0].y1_m = std::nan(""); }),
            "lidar.background[0].y1_m");
  EXPECT_EQ(rejects([](LidarParams& p) {
              p.background[1] = {1.0, 1.0, 1.0, 1.0, 0.5};
            }),
            "lidar.background[1].x1_m");
  for (const double bad : {-1e-4, 0.5e-6, 0.011, std::nan("")}) {
    EXPECT_EQ(rejects([&](LidarParams& p) { p.window_water_film_m = bad; }),
              "lidar.window_water_film_m")
        << bad;
  }
  EXPECT_EQ(rejects([](LidarParams& p) { p.fog_fluctuation.log_std = -0.1; }),
            "lidar.fog_fluctuation.log_std");
  EXPECT_EQ(rejects([](LidarParams& p) { p.fog_fluctuation.correlation_time_s = 0.0; }),
            "lidar.fog_fluctuation.correlation_time_s");
  // The sensor refuses inputs that do not match the chamber, naming them.
  const Lidar lidar(LidarParams{}, propagation::ChamberSpec{}, table());
  RandomStream stream(1);
  EXPECT_EQ(rejected_field([&] {
              (void)lidar.measure(propagation::ActiveLayers(3, true), std::vector<double>(4, 1.0),
                                  stream);
            }),
            "active_layers");
  EXPECT_EQ(rejected_field([&] {
              (void)lidar.measure(propagation::ActiveLayers(4, true), std::vector<double>(2, 1.0),
                                  stream);
            }),
            "optical_depth_factors");
}

// ---- The paper scenario: 5 steps x 40 scans of the defaults in the study's chamber. ----

struct PaperRun {
  LidarParams params;
  std::unique_ptr<Lidar> lidar;
  std::vector<LidarStepResult> steps;
  LidarSummary summary;
};

const PaperRun& paper_run() {
  static const PaperRun run = [] {
    PaperRun r;
#ifdef FOGRADAR_SANITIZE_BUILD
    // The sanitizer build measures the beams around the target only (the pattern is per beam).
    r.params.field_of_view_deg = 30.0;
#endif
    r.lidar = std::make_unique<Lidar>(r.params, propagation::ChamberSpec{}, table());
    for (std::size_t step = 0; step <= 4; ++step) {
      // experiment.seed of examples/paper.toml: the run `fogradar run` makes, scan for scan.
      r.steps.push_back({step, scans_of_step(*r.lidar, step, 2, 1)});
    }
    std::vector<propagation::ActiveLayers> active;
    for (std::size_t step = 0; step <= 4; ++step) {
      active.push_back(propagation::first_layers_active(step, 4));
    }
    r.summary = summarize(*r.lidar, r.steps, active);
    return r;
  }();
  return run;
}

// The study's Fig. 6 and text: at 0 layers the target is seen in every scan; at 1 layer the median
// intensity drops to 0 with "a few outliers" (here: at most 10 of the 40 scans see it); from 2
// layers on "no signal is received from the EVT" (no target-origin echo in any beam of any scan).
// The sensor limit is 1 layer.
// A [[lidar.background]] segment has no defaults (one with only x0_m ran with the other
// coordinates 0 and reflectivity 0.5). Segments are set as the scenario reader sets them, through
// the key table onto freshly resized elements; each missing key is refused naming it as the user
// writes it, and the message says it is missing and what it must be.
TEST(LidarSensor, BackgroundSegmentMissingAKeyIsRefusedNamingIt) {
  const KeyTable<LidarParams> keys = lidar_keys();
  const auto background = std::find_if(keys.keys().begin(), keys.keys().end(), [](const auto& key) {
    return key.name == "lidar.background";
  });
  ASSERT_NE(background, keys.keys().end());
  const std::vector<std::pair<std::string, double>> segment{
      {"x0_m", 1.0}, {"y0_m", -2.0}, {"x1_m", 6.0}, {"y1_m", -2.0}, {"reflectivity", 0.4}};
  // Two segments from the reader's starting values, each given `segment` but for `missing[i]`.
  const auto read = [&](const std::vector<std::string>& missing) {
    LidarParams p;
    background->array_resize(p, 0);
    background->array_resize(p, missing.size());
    for (std::size_t i = 0; i < missing.size(); ++i) {
      KeyTable<LidarParams> element;
      background->array_element(i, element);
      for (const auto& key : element.keys()) {
        for (const auto& [name, value] : segment) {
          if (name != missing[i] && key.short_name() == name) key.set_number(p, value);
        }
      }
    }
    return p;
  };
  EXPECT_EQ(test_support::rejected_field([&] { read({"", ""}).validate(); }), "accepted");
  for (const auto& [name, value] : segment) {
    for (const std::size_t index : {0u, 1u}) {
      std::vector<std::string> missing{"", ""};
      missing[index] = name;
      const std::string key = "lidar.background[" + std::to_string(index) + "]." + name;
      try {
        read(missing).validate();
        ADD_FAILURE() << key << " missing: accepted";
      } catch (const InvalidParameter& e) {
        EXPECT_EQ(e.field(), key);
        const std::string range = name == "reflectivity" ? "[0, 1]" : "[-10000, 10000]";
        EXPECT_EQ(std::string(e.what()),
                  key +
                      " is missing: every [[lidar.background]] segment must give it, a number "
                      "in " +
                      range);
      }
    }
  }
  // A value given out of range is named before a key not given (the reader points at its line).
  LidarParams bad = read({"y0_m", ""});
  bad.background[0].reflectivity = 1.5;
  EXPECT_EQ(test_support::rejected_field([&] { bad.validate(); }),
            "lidar.background[0].reflectivity");
  // A segment that gives nothing names its first key.
  LidarParams bare;
  bare.background.assign(1, BackgroundSegment{});
  EXPECT_EQ(test_support::rejected_field([&] { bare.validate(); }), "lidar.background[0].x0_m");
}

TEST(LidarPaperScenario, Fig6TargetIntensityPattern) {
  const PaperRun& run = paper_run();
  ASSERT_EQ(run.summary.steps.size(), 5u);
  const auto check = [](const std::string& id, const std::string& quantity, std::size_t layers,
                        double reference, double value, Tolerance kind, const std::string& source) {
    validate({.id = "lidar.paper.fig6." + id + "." + std::to_string(layers) + "layers",
              .group = "paper comparison",
              .quantity = quantity,
              .unit = quantity == "target detections" ? "scans of 40" : "1",
              .conditions = "paper scenario, " + std::to_string(layers) + " active layers",
              .reference = reference,
              .source = source,
              .value = value,
              .tolerance = 0.0,
              .kind = kind,
              .plot = "paper_comparison",
              .x = static_cast<double>(layers),
              .x_label = "active fog layers"});
  };
  const LidarStepSummary& clear = run.summary.steps[0];
  check("target_detections", "target detections", 0, 40.0,
        static_cast<double>(clear.target_detections), Tolerance::absolute,
        "the study's Fig. 6 and text: the target is seen in every scan in clear weather");
  check("target_intensity_median", "median target intensity", 0, 0.0, clear.target_intensity.median,
        Tolerance::above, "the study's Fig. 6: the target's intensity is above 0 in clear weather");
  const LidarStepSummary& one = run.summary.steps[1];
  check("target_intensity_median", "median target intensity", 1, 0.0, one.target_intensity.median,
        Tolerance::absolute, "the study's Fig. 6: the median intensity drops to 0 at 1 layer");
  check("target_detections", "target detections", 1, 10.0,
        static_cast<double>(one.target_detections), Tolerance::at_most,
        "the study's Fig. 6 and text: \"a few outliers\" at 1 layer (at most 10 of 40 scans)");
  for (std::size_t step = 2; step <= 4; ++step) {
    check("target_detections", "target detections", step, 0.0,
          static_cast<double>(run.summary.steps[step].target_detections), Tolerance::absolute,
          "the study's text: from 2 layers on \"no signal is received from the EVT\"");
    for (const LidarScan& scan : run.steps[step].scans) {
      for (const LidarEcho& e : scan.echoes) EXPECT_NE(e.origin, Origin::target);
    }
  }
  ASSERT_TRUE(run.summary.sensor_limit_layers.has_value());
  validate({.id = "lidar.paper.fig6.sensor_limit",
            .group = "paper comparison",
            .quantity = "lidar sensor limit",
            .unit = "layers",
            .conditions = "paper scenario, 0-4 active layers, 40 scans each",
            .reference = 1.0,
            .source = "the study's Fig. 6 and text: the lidar loses the target after one fog layer",
            .value = static_cast<double>(*run.summary.sensor_limit_layers),
            .tolerance = 0.0,
            .kind = Tolerance::absolute,
            .plot = "paper_comparison",
            .x = 1.0,
            .x_label = "active fog layers"});
}

// The study's Fig. 5: with one or more layers the beams through the fog (here those within 20 deg
// of boresight, inside the fog's 3 m width for the whole first layer) return their first echo from
// the fog's near edge: origin fog, range within [-0.5, +0.75] m of the edge's range along the beam
// (sensor_gap / cos(angle)); the window is the pulse's range length c fwhm / 2 = 0.75 m, within
// which the leading edge of the fog's rising return crosses the threshold. At least 95 % of those
// beams qualify in every step; and "more than one layer has almost no further effect": the median
// first-echo range at 2-4 layers is within 0.15 m of that at 1 layer.
TEST(LidarPaperScenario, Fig5FirstEchoesAtTheFogsNearEdge) {
  const PaperRun& run = paper_run();
  for (std::size_t step = 1; step <= 4; ++step) {
    std::size_t beams = 0, at_edge = 0;
    for (const LidarScan& scan : run.steps[step].scans) {
      std::vector<bool> seen(run.lidar->beam_count(), false);
      for (const LidarEcho& e : scan.echoes) {
        const double angle_deg = run.lidar->beam_angle_deg(e.beam);
        if (e.index != 0 || std::abs(angle_deg) > 20.0) continue;
        const double edge_m = 2.0 / std::cos(angle_deg * degree_rad);
        if (e.origin == Origin::fog && e.range_m > edge_m - 0.5 && e.range_m < edge_m + 0.75) {
          ++at_edge;
        }
        seen[e.beam] = true;
      }
      for (std::size_t b = 0; b < seen.size(); ++b) {
        if (std::abs(run.lidar->beam_angle_deg(b)) <= 20.0) ++beams;
      }
    }
    validate({.id = "lidar.paper.fig5.first_echo_at_fog_edge." + std::to_string(step) + "layers",
              .group = "paper comparison",
              .quantity = "beams within 20 deg whose first echo is the fog's near edge",
              .unit = "beams",
              .conditions = "paper scenario, " + std::to_string(step) + " active layers, " +
                            std::to_string(beams) + " beams within 20 deg over 40 scans",
              .reference = 0.95 * static_cast<double>(beams),
              .source = "the study's Fig. 5: first echoes from the fog's near edge (at least 95 "
                        "% of the beams, within [-0.5, +0.75] m of the edge)",
              .value = static_cast<double>(at_edge),
              .tolerance = 0.0,
              .kind = Tolerance::at_least});
    EXPECT_NEAR(run.summary.steps[step].median_first_echo_range_m,
                run.summary.steps[1].median_first_echo_range_m, 0.15)
        << step;
  }
  EXPECT_TRUE(std::isnan(run.summary.steps[0].fog_echo_rate));  // no beam crosses fog at 0 layers
}

// Result files: one CSV row per echo, the JSON's limit, well-formed SVGs, the memory estimate an
// upper bound of what the step results hold.
TEST(LidarPaperScenario, ResultFilesAndMemoryEstimate) {
  const PaperRun& run = paper_run();
  std::size_t echoes = 0, held = 0;
  for (const LidarStepResult& step : run.steps) {
    for (const LidarScan& scan : step.scans) {
      echoes += scan.echoes.size();
      held += sizeof(LidarScan) + scan.echoes.capacity() * sizeof(LidarEcho) +
              scan.first_echo_range_through_fog_m.capacity() * sizeof(double);
    }
  }
  const std::string csv = lidar_echoes_csv(*run.lidar, run.steps);
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), echoes + 1);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "active_layers,item,angle_deg,echo,range_m,intensity,origin,layer");
  const nlohmann::json json = lidar_summary_json(*run.lidar, run.summary);
  EXPECT_EQ(json.at("sensor_limit_layers"), 1);
  EXPECT_EQ(json.at("steps").size(), 5u);
  const std::string summary_csv = lidar_step_table(run.summary).csv();
  EXPECT_EQ(std::count(summary_csv.begin(), summary_csv.end(), '\n'), 6);
  EXPECT_EQ(test_support::xml_error(lidar_intensity_boxplot_svg(*run.lidar, run.summary)), "");
  EXPECT_EQ(test_support::xml_error(lidar_scans_svg(*run.lidar, run.steps)), "");
  EXPECT_NE(lidar_summary_table(run.summary).find("lidar sensor limit: 1 layer"),
            std::string::npos);
  const std::size_t estimate = lidar_memory_bytes(run.params, 5, 2);
  EXPECT_GE(estimate, held + csv.size());
  EXPECT_LT(csv.size(), 10u << 20);  // the paper run's lidar files stay well under 10 MB
}

}  // namespace
}  // namespace fogradar::lidar
