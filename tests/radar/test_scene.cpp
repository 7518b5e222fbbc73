// Scene -> propagation paths ("tones"): every tone's length, power and phase against the radar
// equation and the two-ray geometry written out here; the random parts (Swerling fluctuation,
// micro-motion, fog clutter) against their distributions with fixed seeds and statistically
// sized bounds. References:
//   [Sk]   M. I. Skolnik, Introduction to Radar Systems, 3rd ed.: eq. 2.1, Swerling models sec. 2.8
//          (case 1: exponential; case 3: chi-square with 4 degrees of freedom).
//   [PJ62] Probert-Jones 1962: two-way beam solid angle (fog clutter volume Omega R^2 dR).
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/gamma.hpp>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "chain_test_support.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/radar/scene.hpp"
#include "validation.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;
using test::make_chamber;
using test::paper_chamber_spec;
using test::reference_received_power_w;

constexpr double kC = 299'792'458.0;

double wrap_phase(double x) { return std::remainder(x, 2.0 * std::numbers::pi); }

// Phase of the dechirped echo of two-way path L at the first sample of a chirp, written out from
// the transmit phase 2 pi (f_0 t + s t^2 / 2), s = eps B / T, f_0 = f_c - eps B / 2: the receiver
// forms rx conj(tx) for a down-chirp and its conjugate for an up-chirp (the product whose beat
// frequency is +|s| tau), so the phase at t = 0 is eps 2 pi (f_0 tau - s tau^2 / 2) (docs/radar.md
// §3.2).
double reference_echo_phase_rad(const RadarParams& p, double path_length_m) {
  const double eps = p.sweep_direction == SweepDirection::up ? 1.0 : -1.0;
  const double f0 = p.centre_frequency_hz - eps * 0.5 * p.sweep_bandwidth_hz;
  const double s = eps * p.sweep_bandwidth_hz / p.chirp_duration_s;
  const double tau = path_length_m / kC;
  return eps * 2.0 * std::numbers::pi * (f0 * tau - 0.5 * s * tau * tau);
}

struct Fixture {
  RadarParams params;
  RadarDerived derived = derive(params);
  propagation::Chamber chamber = make_chamber(paper_chamber_spec(), params.centre_frequency_hz);
  propagation::ActiveLayers no_fog = propagation::first_layers_active(0, 4);
  std::vector<Tone> tones;
};

TEST(SceneFactories, PointTargetAndEvt) {
  const Scene point = point_target_scene(13.0);
  ASSERT_EQ(point.centres.size(), 1u);
  fogradar::testing::validate({.id = "radar.scene.point_target.rcs_13dbsm",
                               .group = "radar: RCS",
                               .quantity = "point target RCS",
                               .unit = "m^2",
                               .conditions = "point_target_scene(13 dBsm)",
                               .reference = std::pow(10.0, 1.3),
                               .source = "dBsm definition: 10^(13/10) m^2",
                               .value = point.centres[0].rcs_m2,
                               .tolerance = 1e-12,
                               .kind = Tolerance::absolute});
  EXPECT_EQ(point.centres[0].height_m, point.sensor_height_m);
  EXPECT_EQ(point.centres[0].swerling, Swerling::zero);
  EXPECT_EQ(point.micro_motion_std_m, 0.0);
  EXPECT_TRUE(point.surfaces.empty());

  // EVT rear: five centres whose mean RCS adds up to the set 10 dBsm, shares 40/15/15/15/15 %,
  // within the 1.8 m x 1.4 m rear; default micro-motion 0.2 mm.
  const Scene evt = evt_rear_scene(10.0);
  ASSERT_EQ(evt.centres.size(), 5u);
  double total = 0.0;
  for (const ScatteringCentre& c : evt.centres) {
    total += c.rcs_m2;
    EXPECT_LE(std::abs(c.lateral_m), 0.9);
    EXPECT_LE(c.height_m, 1.4);
    EXPECT_EQ(c.swerling, Swerling::zero);
  }
  fogradar::testing::validate({.id = "radar.scene.evt.total_rcs",
                               .group = "radar: RCS",
                               .quantity = "sum of the EVT rear centres' mean RCS",
                               .unit = "m^2",
                               .conditions = "evt_rear_scene(10 dBsm), five centres",
                               .reference = 10.0,
                               .source = "the set 10 dBsm = 10 m^2",
                               .value = total,
                               .tolerance = 1e-12,
                               .kind = Tolerance::absolute});
  for (std::size_t i = 0; i < 5; ++i) {
    fogradar::testing::validate(
        {.id = "radar.scene.evt.centre" + std::to_string(i) + ".rcs",
         .group = "radar: RCS",
         .quantity = "EVT rear centre mean RCS",
         .unit = "m^2",
         .conditions = "evt_rear_scene(10 dBsm), centre " + std::to_string(i),
         .reference = i == 0 ? 4.0 : 1.5,
         .source = "the EVT rear's shares 40/15/15/15/15 % of the set 10 m^2 (this test)",
         .value = evt.centres[i].rcs_m2,
         .tolerance = 1e-12,
         .kind = Tolerance::absolute});
  }
  EXPECT_EQ(evt.micro_motion_std_m, 0.2e-3);
}

// A centre on boresight: one tone, path 2R, power by the radar equation [Sk eq. 2.1] (1e-12
// relative), phase reference_echo_phase_rad for both sweep directions (1e-6 rad: the phase is
// ~3e4 rad, so 1e-6 allows ~1e4 eps of argument reduction). Off boresight (lateral 1 m at 10 m)
// the power falls by the two-way Gaussian pattern g(az)^2 (g one-way power, 3 dB at half the
// beamwidth).
TEST(SceneTones, DirectPathPowerPhaseAndPattern) {
  Fixture f;
  Scene scene = point_target_scene(10.0);
  RandomStream rng(1);
  for (const SweepDirection direction : {SweepDirection::up, SweepDirection::down}) {
    RadarParams p = f.params;
    p.sweep_direction = direction;
    scene_tones(scene, f.chamber, f.no_fog, p, derive(p), rng, f.tones);
    ASSERT_EQ(f.tones.size(), 1u);
    const std::string dir(to_string(direction));
    const std::string conditions = "point target 10 m^2 on boresight at 10 m, " + dir + "-chirp";
    fogradar::testing::validate({.id = "radar.scene.direct.path_length." + dir,
                                 .group = "radar: signal processing",
                                 .quantity = "two-way path length",
                                 .unit = "m",
                                 .conditions = conditions,
                                 .reference = 20.0,
                                 .source = "geometry: 2 R",
                                 .value = f.tones[0].path_length_m,
                                 .tolerance = 1e-12,
                                 .kind = Tolerance::absolute});
    fogradar::testing::validate({.id = "radar.scene.direct.power." + dir,
                                 .group = "radar: SNR",
                                 .quantity = "tone power",
                                 .unit = "W",
                                 .conditions = conditions,
                                 .reference = reference_received_power_w(p, 10.0, 10.0),
                                 .source = "radar equation, Skolnik eq. 2.1",
                                 .value = std::norm(f.tones[0].amplitude),
                                 .tolerance = 1e-12,
                                 .kind = Tolerance::relative});
    fogradar::testing::validate(
        {.id = "radar.scene.direct.phase." + dir,
         .group = "radar: signal processing",
         .quantity = "echo phase error (wrapped to [-pi, pi])",
         .unit = "rad",
         .conditions = conditions,
         .reference = 0.0,
         .source = "dechirped echo phase eps 2 pi (f_0 tau - s tau^2 / 2) (docs/radar.md §3.2)",
         .value = wrap_phase(std::arg(f.tones[0].amplitude) - reference_echo_phase_rad(p, 20.0)),
         .tolerance = 1e-6,
         .kind = Tolerance::absolute});
    EXPECT_EQ(f.tones[0].radial_velocity_m_per_s, 0.0);
  }

  scene.centres[0].lateral_m = 1.0;
  scene_tones(scene, f.chamber, f.no_fog, f.params, f.derived, rng, f.tones);
  ASSERT_EQ(f.tones.size(), 1u);
  const double r = std::hypot(10.0, 1.0);
  const double az = std::atan2(1.0, 10.0);
  const double beam = 10.0 * std::numbers::pi / 180.0;
  const double g = std::exp(-4.0 * std::log(2.0) * (az / beam) * (az / beam));
  const std::string off_axis = "point target 10 m^2 at 10 m, 1 m lateral, up-chirp";
  fogradar::testing::validate({.id = "radar.scene.off_boresight.path_length",
                               .group = "radar: signal processing",
                               .quantity = "two-way path length",
                               .unit = "m",
                               .conditions = off_axis,
                               .reference = 2.0 * r,
                               .source = "geometry: 2 hypot(10 m, 1 m)",
                               .value = f.tones[0].path_length_m,
                               .tolerance = 1e-12,
                               .kind = Tolerance::absolute});
  fogradar::testing::validate(
      {.id = "radar.scene.off_boresight.power",
       .group = "radar: SNR",
       .quantity = "tone power",
       .unit = "W",
       .conditions = off_axis,
       .reference = reference_received_power_w(f.params, 10.0, r) * g * g,
       .source = "radar equation (Skolnik eq. 2.1) times the two-way Gaussian pattern g(az)^2",
       .value = std::norm(f.tones[0].amplitude),
       .tolerance = 1e-12,
       .kind = Tolerance::relative});
}

// Floor on: three tones, lengths 2 r_d, r_d + r_f, 2 r_f; relative amplitudes of the expansion
// of (g_d / r_d + Gamma g_f / r_f)^2 into its three delays, each with the echo phase of its path
// length (reference_echo_phase_rad), for both sweep directions (1e-9 relative).
TEST(SceneTones, FloorPathsAreTheTwoRayExpansion) {
  Fixture f;
  Scene scene = point_target_scene(10.0);
  scene.sensor_height_m = 0.5;
  scene.centres[0].height_m = 0.8;
  scene.surfaces = {coefficient_floor(-0.6)};
  const double beam = 10.0 * std::numbers::pi / 180.0;
  const auto amp = [&](double angle) {
    return std::exp(-2.0 * std::log(2.0) * (angle / beam) * (angle / beam));
  };
  const double r_d = std::hypot(10.0, 0.3), r_f = std::hypot(10.0, 1.3);
  const double g_d = amp(std::atan2(0.3, 10.0)), g_f = amp(std::atan2(1.3, 10.0));
  const double e_d = g_d / r_d, e_f = -0.6 * g_f / r_f;
  const double magnitudes[] = {e_d * e_d, 2.0 * e_d * e_f, e_f * e_f};
  const double lengths[] = {2.0 * r_d, r_d + r_f, 2.0 * r_f};
  for (const SweepDirection direction : {SweepDirection::up, SweepDirection::down}) {
    RadarParams p = f.params;
    p.sweep_direction = direction;
    RandomStream rng(1);
    scene_tones(scene, f.chamber, f.no_fog, p, derive(p), rng, f.tones);
    ASSERT_EQ(f.tones.size(), 3u);
    const auto expected = [&](int i) {
      return magnitudes[i] * std::polar(1.0, reference_echo_phase_rad(p, lengths[i]));
    };
    const std::string dir(to_string(direction));
    const std::string conditions =
        "sensor 0.5 m, target 0.8 m high at 10 m, floor Gamma -0.6, " + dir + "-chirp";
    const char* paths[] = {"direct", "mixed", "floor"};
    for (int i = 0; i < 3; ++i) {
      fogradar::testing::validate(
          {.id = "radar.scene.floor." + std::string(paths[i]) + ".path_length." + dir,
           .group = "radar: signal processing",
           .quantity = "two-way path length",
           .unit = "m",
           .conditions = conditions + ", " + paths[i] + " path",
           .reference = lengths[i],
           .source = "two-ray geometry (image below the floor)",
           .value = f.tones[i].path_length_m,
           .tolerance = 1e-12,
           .kind = Tolerance::absolute});
      const std::complex<double> ratio =
          (f.tones[i].amplitude / f.tones[0].amplitude) / (expected(i) / expected(0));
      fogradar::testing::validate(
          {.id = "radar.scene.floor." + std::string(paths[i]) + ".relative_amplitude." + dir,
           .group = "radar: SNR",
           .quantity = "|amplitude ratio to the direct path / expected ratio - 1|",
           .unit = "1",
           .conditions = conditions + ", " + paths[i] + " path",
           .reference = 0.0,
           .source = "expansion of (g_d / r_d + Gamma g_f / r_f)^2 with each path's echo phase",
           .value = std::abs(ratio - 1.0),
           .tolerance = 1e-9,
           .kind = Tolerance::absolute});
    }
    fogradar::testing::validate(
        {.id = "radar.scene.floor.direct.power." + dir,
         .group = "radar: SNR",
         .quantity = "direct-path tone power",
         .unit = "W",
         .conditions = conditions,
         .reference = reference_received_power_w(p, 10.0, r_d) * std::pow(g_d, 4),
         .source = "radar equation (Skolnik eq. 2.1) times the two-way pattern g_d^4",
         .value = std::norm(f.tones[0].amplitude),
         .tolerance = 1e-12,
         .kind = Tolerance::relative});
  }
}

// Micro-motion: each centre's line-of-sight displacement ~ N(0, s^2), s = 0.2 mm, so the
// two-way path length has standard deviation 2 s and the echo phase 4 pi s / lambda =
// 0.65 rad at 77 GHz. 4000 draws: sample std of the path within 5 % of 2 s (1-sigma 1.1 %), mean
// within 4 sigma of 2R.
TEST(SceneTones, MicroMotionMovesThePathByTwiceTheJitter) {
  Fixture f;
  Scene scene = point_target_scene(10.0);
  scene.micro_motion_std_m = 0.2e-3;
  constexpr int kDraws = 4000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    RandomStream rng(3, i);
    scene_tones(scene, f.chamber, f.no_fog, f.params, f.derived, rng, f.tones);
    const double dl = f.tones[0].path_length_m - 20.0;
    sum += dl;
    sum2 += dl * dl;
  }
  const double mean = sum / kDraws;
  const double std = std::sqrt(sum2 / kDraws - mean * mean);
  const double lambda = kC / f.params.centre_frequency_hz;
  std::printf(
      "[ measured ] micro-motion 0.2 mm: path std %.4f mm (expected 0.4), phase std %.3f rad (4 pi "
      "s / lambda = %.3f)\n",
      std * 1e3, 2.0 * std::numbers::pi * std / lambda, 4.0 * std::numbers::pi * 0.2e-3 / lambda);
  const std::string conditions = "micro-motion 0.2 mm rms, point target at 10 m, 4000 draws";
  fogradar::testing::validate({.id = "radar.scene.micro_motion.path_std",
                               .group = "radar: signal processing",
                               .quantity = "standard deviation of the two-way path length",
                               .unit = "m",
                               .conditions = conditions,
                               .reference = 0.4e-3,
                               .source = "2 s for a line-of-sight displacement N(0, s^2)",
                               .value = std,
                               .tolerance = 0.05,
                               .kind = Tolerance::relative});
  const double half_width = 4.0 * 0.4e-3 / std::sqrt(kDraws);
  fogradar::testing::validate({.id = "radar.scene.micro_motion.path_mean",
                               .group = "radar: signal processing",
                               .quantity = "mean two-way path length change",
                               .unit = "m",
                               .conditions = conditions,
                               .reference = 0.0,
                               .source = "zero-mean displacement N(0, s^2)",
                               .value = mean,
                               .tolerance = 0.0,
                               .kind = Tolerance::statistical,
                               .samples = kDraws,
                               .interval_low = -half_width,
                               .interval_high = half_width,
                               .confidence = "+-4 sigma of the sample mean, sigma 2 s / sqrt(n)"});
}

// Swerling 1 and 3 tone power over 4000 draws against the exponential and the chi-square with 4
// degrees of freedom (Gamma(2, mean/2)) [Sk sec. 2.8]: chi-square GoF, 10 equiprobable cells of
// the reference distribution, df 9, significance 1e-3; Swerling 0 is constant.
TEST(SceneTones, SwerlingFluctuationDistributions) {
  Fixture f;
  const double mean_power = reference_received_power_w(f.params, 10.0, 10.0);
  for (const Swerling model : {Swerling::one, Swerling::three}) {
    Scene scene = point_target_scene(10.0);
    scene.centres[0].swerling = model;
    const double shape = model == Swerling::one ? 1.0 : 2.0;
    const boost::math::gamma_distribution<double> reference(shape, 1.0 / shape);
    constexpr int kDraws = 4000, kCells = 10;
    std::vector<double> counts(kCells, 0.0);
    for (int i = 0; i < kDraws; ++i) {
      RandomStream rng(4, static_cast<int>(model), i);
      scene_tones(scene, f.chamber, f.no_fog, f.params, f.derived, rng, f.tones);
      const double u = boost::math::cdf(reference, std::norm(f.tones[0].amplitude) / mean_power);
      counts[std::min(kCells - 1, static_cast<int>(u * kCells))] += 1.0;
    }
    double statistic = 0.0;
    for (const double c : counts)
      statistic += (c - kDraws / kCells) * (c - kDraws / kCells) / (kDraws / kCells);
    const double p = boost::math::cdf(boost::math::complement(
        boost::math::chi_squared_distribution<double>(kCells - 1), statistic));
    std::printf("[ measured ] Swerling %s tone power GoF p = %.3f\n",
                std::string(to_string(model)).c_str(), p);
    fogradar::testing::validate(
        {.id = "radar.scene.swerling" + std::string(to_string(model)) + ".gof_p_value",
         .group = "radar: RCS",
         .quantity = "chi-square goodness-of-fit p-value of the tone power",
         .unit = "1",
         .conditions = "Swerling " + std::string(to_string(model)) +
                       ", 4000 draws, 10 equiprobable cells, df 9",
         .reference = 1e-3,
         .source = model == Swerling::one ? "exponential distribution [Sk sec. 2.8]"
                                          : "chi-square with 4 degrees of freedom [Sk sec. 2.8]",
         .value = p,
         .tolerance = 0.0,
         .kind = Tolerance::at_least});
  }
  Scene steady = point_target_scene(10.0);
  RandomStream a(1), b(2);
  scene_tones(steady, f.chamber, f.no_fog, f.params, f.derived, a, f.tones);
  const double first = std::norm(f.tones[0].amplitude);
  scene_tones(steady, f.chamber, f.no_fog, f.params, f.derived, b, f.tones);
  EXPECT_EQ(std::norm(f.tones[0].amplitude), first);
}

// Fog clutter tones: with all four layers on, clutter_scatterers_per_bin static tones per range
// bin, inside the fog, whose mean total power equals the volume integral
//   integral eta Omega r^2 * P_t G^2 lambda^2 / ((4 pi)^3 r^4) * T(r) dr  over [2 m, 6 m]
// (Simpson, 2000 panels). 400 draws: within 3 % (1-sigma ~0.6 %), for 1 and 16 scatterers per bin.
// A target at the chamber's far end gets the chamber's two-way transmittance.
TEST(SceneTones, FogClutterPowerIsTheVolumeIntegral) {
  Fixture f;
  propagation::FogSpec fog;
  fog.density = propagation::LiquidWaterContent{20.0};
  fog.droplets = propagation::Monodisperse{50e-6};
  const propagation::Chamber chamber =
      make_chamber(paper_chamber_spec(fog), f.params.centre_frequency_hz);
  const auto all_on = propagation::first_layers_active(4, 4);
  const double eta = chamber.layer(0).optics.volume_backscatter_m2_per_m3;
  const double a_db_per_m = chamber.layer(0).optics.specific_attenuation_db_per_km * 1e-3;
  const double omega = f.derived.beam_solid_angle_sr;
  const auto integrand = [&](double r) {
    return reference_received_power_w(f.params, eta * omega * r * r, r) *
           std::pow(10.0, -2.0 * a_db_per_m * (r - 2.0) / 10.0);
  };
  const int panels = 2000;
  const double h = 4.0 / panels;
  double expected = integrand(2.0) + integrand(6.0);
  for (int i = 1; i < panels; ++i) expected += (i % 2 ? 4.0 : 2.0) * integrand(2.0 + i * h);
  expected *= h / 3.0;

  for (const unsigned per_bin : {1u, 16u}) {
    Scene scene = point_target_scene(10.0);
    scene.clutter_scatterers_per_bin = per_bin;
    constexpr int kDraws = 400;
    double total = 0.0;
    for (int i = 0; i < kDraws; ++i) {
      RandomStream rng(6, per_bin, i);
      scene_tones(scene, chamber, all_on, f.params, f.derived, rng, f.tones);
      ASSERT_EQ(f.tones.size(),
                1 + 4 * static_cast<std::size_t>(std::ceil(1.0 / f.derived.range_bin_m)) * per_bin);
      for (std::size_t t = 1; t < f.tones.size(); ++t) {
        const Tone& tone = f.tones[t];
        ASSERT_GE(tone.path_length_m, 4.0);
        ASSERT_LE(tone.path_length_m, 12.0);
        ASSERT_EQ(tone.radial_velocity_m_per_s, 0.0);
        total += std::norm(tone.amplitude);
      }
    }
    const double mean = total / kDraws;
    std::printf(
        "[ measured ] fog clutter tones (%u per bin): mean total power / volume integral = %.4f\n",
        per_bin, mean / expected);
    fogradar::testing::validate(
        {.id = "radar.scene.fog_clutter.mean_power." + std::to_string(per_bin) + "_per_bin",
         .group = "radar: SNR",
         .quantity = "mean total power of the fog clutter tones",
         .unit = "W",
         .conditions = "LWC 20 g/m^3, 50 um droplets, four layers, " + std::to_string(per_bin) +
                       " scatterers per bin, 400 draws",
         .reference = expected,
         .source = "volume radar equation integral eta Omega r^2 x Skolnik eq. 2.1 x T(r) "
                   "(Simpson, this test; Omega [PJ62])",
         .value = mean,
         .tolerance = 0.03,
         .kind = Tolerance::relative});
  }
  // The target tone carries the chamber's two-way transmittance 10^(-2 a 4 m / 10).
  RandomStream rng(1);
  scene_tones(point_target_scene(10.0), chamber, all_on, f.params, f.derived, rng, f.tones);
  fogradar::testing::validate(
      {.id = "radar.scene.fog_clutter.target_power",
       .group = "radar: SNR",
       .quantity = "target tone power behind four fog layers",
       .unit = "W",
       .conditions = "LWC 20 g/m^3, 50 um droplets, four 1 m layers, target 10 m^2 at 10 m",
       .reference = reference_received_power_w(f.params, 10.0, 10.0) *
                    std::pow(10.0, -2.0 * a_db_per_m * 4.0 / 10.0),
       .source = "radar equation (Skolnik eq. 2.1) times the two-way transmittance "
                 "10^(-2 a 4 m / 10)",
       .value = std::norm(f.tones[0].amplitude),
       .tolerance = 1e-12,
       .kind = Tolerance::relative});
}

// The water films: with the same draws, every target path's power is the dry one's times the
// radome's two-way transmittance and the target film's reflectance, every fog clutter path's times
// the radome's alone (the clutter is in front of the target), to rounding.
TEST(SceneTones, WaterFilmsScaleTargetPathsAndClutterThroughTheRadome) {
  Fixture f;
  propagation::FogSpec fog;
  fog.density = propagation::LiquidWaterContent{20.0};
  fog.droplets = propagation::Monodisperse{50e-6};
  const propagation::Chamber chamber =
      make_chamber(paper_chamber_spec(fog), f.params.centre_frequency_hz);
  const auto all_on = propagation::first_layers_active(4, 4);
  Scene dry = evt_rear_scene();
  dry.surfaces = {coefficient_floor(-0.7)};
  Scene wet = dry;
  wet.radome_two_way_transmittance = 0.03;
  wet.target_film_reflectance = 0.7;
  std::vector<Tone> wet_tones;
  RandomStream dry_rng(4), wet_rng(4);
  scene_tones(dry, chamber, all_on, f.params, f.derived, dry_rng, f.tones);
  scene_tones(wet, chamber, all_on, f.params, f.derived, wet_rng, wet_tones);
  ASSERT_EQ(wet_tones.size(), f.tones.size());
  std::size_t target_paths = 0, clutter_paths = 0;
  for (std::size_t t = 0; t < f.tones.size(); ++t) {
    const bool target = f.tones[t].origin == Origin::target;
    (target ? target_paths : clutter_paths) += 1;
    const double expected = target ? 0.03 * 0.7 : 0.03;
    EXPECT_NEAR(std::norm(wet_tones[t].amplitude) / std::norm(f.tones[t].amplitude), expected,
                1e-12 * expected)
        << "tone " << t;
    EXPECT_EQ(wet_tones[t].path_length_m, f.tones[t].path_length_m);
  }
  EXPECT_EQ(target_paths, 15u);  // five centres, three paths each with the floor
  EXPECT_GT(clutter_paths, 0u);
}

// The tone list is cleared and refilled: calling twice does not accumulate.
TEST(SceneTones, RefillsTheList) {
  Fixture f;
  Scene scene = evt_rear_scene();
  scene.surfaces = {coefficient_floor(-0.7)};
  RandomStream rng(1);
  scene_tones(scene, f.chamber, f.no_fog, f.params, f.derived, rng, f.tones);
  EXPECT_EQ(f.tones.size(), 15u);
  scene_tones(scene, f.chamber, f.no_fog, f.params, f.derived, rng, f.tones);
  EXPECT_EQ(f.tones.size(), 15u);
}

}  // namespace
}  // namespace fogradar::radar
