// The radar in the room: image paths against specular_paths, the one-wall interference check of
// issue 36, Fresnel coefficients by polarisation, objects' closed-form RCS read back, the back
// wall's own return, and the origins of ghosts and the room (radar/room_paths.hpp, scene.hpp).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "../support/validation.hpp"
#include "chain_test_support.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/propagation/room.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/results.hpp"
#include "fogradar/radar/room_paths.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/radar/target.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;
using test::make_chamber;
using test::paper_chamber_spec;

constexpr double kC = 299'792'458.0;
constexpr double kPi = std::numbers::pi;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

RadarParams noise_free(RadarParams p) {
  p.thermal_noise = false;
  return p;
}

SceneSurface wall(propagation::Surface surface, double position_m, double coefficient) {
  return {.plane = {surface, position_m},
          .reflection_coefficient = coefficient,
          .permittivity = std::nullopt,
          .key = "chamber.room.wall"};
}

// A detection within `tolerance_m` of `range_m`, or nullptr.
const Detection* detection_near(const std::vector<Detection>& detections, double range_m,
                                double tolerance_m) {
  const Detection* best = nullptr;
  for (const Detection& d : detections) {
    if (std::abs(d.range_m - range_m) > tolerance_m) continue;
    if (best == nullptr || d.received_power_w > best->received_power_w) best = &d;
  }
  return best;
}

// The one-way legs agree with propagation::specular_paths (a second method: its reflection points
// and validity test) in count and length, for a room of every plane and points in and near its
// corners. Tolerance 1e-12 m (rounding).
TEST(RoomPaths, OneWayLegsMatchSpecularPaths) {
  Scene scene = point_target_scene(0.0);
  scene.sensor_height_m = 0.6;
  scene.surfaces = {coefficient_floor(-0.7), wall(propagation::Surface::left_wall, -2.0, -0.5),
                    wall(propagation::Surface::right_wall, 3.0, -0.5),
                    wall(propagation::Surface::ceiling, 4.0, -0.5),
                    wall(propagation::Surface::back_wall, 20.0, -0.5)};
  const std::vector<propagation::RoomPlane> planes = scene.planes();
  const Eigen::Vector3d radar(0.0, 0.0, scene.sensor_height_m);
  RadarParams p;
  std::size_t compared = 0;
  for (const Eigen::Vector3d& point :
       {Eigen::Vector3d(10.0, 0.0, 0.5), Eigen::Vector3d(19.5, -1.9, 0.1),
        Eigen::Vector3d(5.0, 2.9, 3.9), Eigen::Vector3d(1.0, 0.0, 0.6)}) {
    OneWayLegs legs;
    const std::size_t count = one_way_legs(scene, radar, point, p, legs);
    const std::vector<propagation::SpecularPath> paths =
        propagation::specular_paths(planes, radar, point, 2);
    ASSERT_EQ(count, paths.size());
    for (std::size_t i = 0; i < count; ++i) {
      EXPECT_NEAR(legs[i].length_m, paths[i].length_m, 1e-12);
      EXPECT_EQ(legs[i].order, paths[i].planes.size());
      ++compared;
    }
  }
  std::printf("[ measured ] %zu one-way legs agree with specular_paths\n", compared);
}

// The one-wall check. A point target of 10 dBsm on boresight at X = 10 m and the radar's
// height, the floor off, one wall on the left with Gamma = -1 at distance w, a 60 deg azimuth beam:
// the one-way legs are the direct r_d = X at azimuth 0 and the wall's r_w = hypot(X, 2 w) at
// azimuth atan(2 w / X) (the target's image 2 w beyond the wall), and the four two-way paths sum to
//   sigma_read = sigma g_d^4 |1 + Gamma (g_w / g_d)(r_d / r_w) e^{-jk (r_w - r_d)}|^4 (R / r_d)^4,
// g the Gaussian amplitude pattern exp(-2 ln 2 (theta / theta_3dB)^2), k = 2 pi f_c / c (the
// processed peak holds the phase at the sweep centre), R the estimated range. A 20 MHz sweep
// (7.5 m resolution) puts every path within 0.002 bin of the others, where the window's response
// is flat to 1e-5. Wall distances 0.30-0.40 m in 2.5 mm steps: the path difference 2 w^2 / X runs
// through about 1.5 interference cycles; noise off. Tolerance 0.3 dB (the issue's).
TEST(RoomPaths, OneWallInterferenceFollowsClosedForm) {
  RadarParams p = noise_free(RadarParams{});
  p.sweep_bandwidth_hz = 20e6;
  p.chirps_per_frame = 4;
  p.azimuth_beamwidth_deg = 60.0;
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const double x_m = chamber.target_range_m();
  const double k = 2.0 * kPi * p.centre_frequency_hz / kC;
  const double beam_rad = p.azimuth_beamwidth_deg * kPi / 180.0;
  const auto g = [&](double angle_rad) {
    return std::exp(-2.0 * std::log(2.0) * std::pow(angle_rad / beam_rad, 2));
  };
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement m;
  int compared = 0, skipped = 0;
  double worst_db = 0.0, lowest_db = 1e9, highest_db = -1e9;
  for (int i = 0; i <= 40; ++i) {
    const double w_m = 0.30 + 0.0025 * i;
    Scene scene = point_target_scene(10.0);
    scene.surfaces = {wall(propagation::Surface::left_wall, -w_m, -1.0)};
    RandomStream rng(static_cast<std::uint64_t>(i));
    chain.measure(scene, chamber, no_fog, rng, ws, m);
    const double r_d = x_m;
    const double r_w = std::hypot(x_m, 2.0 * w_m);
    const double ratio = g(std::atan(2.0 * w_m / x_m)) / g(0.0) * (r_d / r_w);
    const double factor = std::pow(std::abs(1.0 - ratio * std::polar(1.0, -k * (r_w - r_d))), 4);
    const Detection* det = detection_near(m.detections, x_m, 1.0);
    if (det == nullptr) {
      ++skipped;
      continue;
    }
    ++compared;
    const double expected_dbsm = 10.0 + 10.0 * std::log10(factor * std::pow(det->range_m / r_d, 4));
    worst_db = std::max(worst_db, std::abs(det->rcs_dbsm - expected_dbsm));
    lowest_db = std::min(lowest_db, expected_dbsm);
    highest_db = std::max(highest_db, expected_dbsm);
    EXPECT_EQ(det->origin, Origin::target) << "w = " << w_m;
    fogradar::testing::validate(
        {.id = "radar.room.one_wall.w" + number(w_m),
         .group = "radar: room",
         .quantity = "RCS read back beside one wall",
         .unit = "dBsm",
         .conditions = "10 dBsm point at 10 m, wall Gamma -1 at " + number(w_m) +
                       " m, floor off, 60 deg beam, 20 MHz sweep, noise off",
         .reference = expected_dbsm,
         .source = "coherent sum of the four two-way paths from the geometry (this test)",
         .value = det->rcs_dbsm,
         .tolerance = 0.3,
         .kind = Tolerance::absolute,
         .plot = "radar.room.one_wall",
         .x = w_m,
         .x_label = "wall distance (m)"});
  }
  std::printf(
      "[ measured ] one wall: %d distances, expected %.1f..%.1f dBsm, worst error %.4f dB, %d "
      "skipped (no detection)\n",
      compared, lowest_db, highest_db, worst_db, skipped);
  EXPECT_GT(highest_db - lowest_db, 20.0);  // the sweep spans constructive and destructive
  EXPECT_LE(skipped, 2);
}

// At a larger wall distance the paths separate: with the wall 5 m to the left, a 120 deg azimuth
// beam and a 1 GHz sweep (0.15 m resolution) the direct path reads at X = 10 m, the direct-wall
// pair (both ways) at (r_d + r_w) / 2 = 12.07 m and the wall-wall path at r_w = hypot(X, 10 m) =
// 14.14 m, each a detection of its own (a -10 dBsm target: its window sidelobes sink into the noise
// before the next echo); the two ghosts are `multipath`. Thermal noise on. Tolerance 0.05 m (a
// third of a bin). The direct-wall ghost is 1.3 dB stronger than the direct path (2 g_w/g_d
// r_d/r_w = 1.16): with a 2.5 m association gate it is what the gate takes, a false association
// and a miss.
TEST(RoomPaths, GhostsStandWherePathLengthsPutThem) {
  RadarParams p;
  p.azimuth_beamwidth_deg = 120.0;
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const double x_m = chamber.target_range_m();
  const double r_w = std::hypot(x_m, 10.0);
  Scene scene = point_target_scene(-10.0);
  scene.surfaces = {wall(propagation::Surface::left_wall, -5.0, -1.0)};
  for (const double gate_m : {0.5, 2.5}) {
    p.association_gate_m = gate_m;
    const RadarChain chain(p);
    MeasurementWorkspace ws = chain.make_workspace();
    Measurement m;
    RandomStream rng(7);
    chain.measure(scene, chamber, no_fog, rng, ws, m);
    for (const Detection& d : m.detections) {
      std::printf("[ measured ] gate %.1f m: detection at %.3f m, %s, %.1f dBsm\n", gate_m,
                  d.range_m, std::string(to_string(d.origin)).c_str(), d.rcs_dbsm);
    }
    const struct {
      double range_m;
      Origin origin;
      const char* name;
    } expected[] = {{x_m, Origin::target, "direct"},
                    {0.5 * (x_m + r_w), Origin::multipath, "direct_wall"},
                    {r_w, Origin::multipath, "wall_wall"}};
    for (const auto& e : expected) {
      const Detection* det = detection_near(m.detections, e.range_m, 0.1);
      ASSERT_NE(det, nullptr) << e.name;
      EXPECT_EQ(det->origin, e.origin) << e.name;
      if (gate_m != 0.5) continue;
      fogradar::testing::validate({.id = std::string("radar.room.ghost.") + e.name + ".range",
                                   .group = "radar: room",
                                   .quantity = "range of a path via a wall",
                                   .unit = "m",
                                   .conditions = "-10 dBsm point at 10 m, wall Gamma -1 5 m to "
                                                 "the left, 120 deg beam, 1 GHz sweep",
                                   .reference = e.range_m,
                                   .source = "half the two-way path length from the geometry",
                                   .value = det->range_m,
                                   .tolerance = 0.05,
                                   .kind = Tolerance::absolute});
    }
    const MeasurementRecord record = record_of(m, x_m, gate_m);
    ASSERT_TRUE(record.associated);
    if (gate_m == 0.5) {
      EXPECT_TRUE(record.detected);
      EXPECT_EQ(record.associated_origin, Origin::target);
    } else {
      EXPECT_FALSE(record.detected);
      EXPECT_EQ(record.associated_origin, Origin::multipath);
    }
  }
}

// Fresnel coefficients of concrete at 77 GHz (ITU-R P.2040-3 Table 3: eps' = 5.24, sigma = 0.0462
// f^0.7822 S/m, eps'' = 17.98 sigma / f, written out here) against the closed forms
//   TE = (sin psi - sqrt(eps - cos^2 psi)) / (sin psi + sqrt(eps - cos^2 psi)),
//   TM = (eps sin psi - sqrt(eps - cos^2 psi)) / (eps sin psi + sqrt(eps - cos^2 psi)):
// horizontal polarisation is TE on the floor and TM on a side wall (a horizontal ray), vertical the
// reverse; at normal incidence on the back wall both read (1 - sqrt(eps)) / (1 + sqrt(eps)).
// Tolerance 1e-12.
TEST(RoomPaths, CoPolarCoefficientPicksTeOrTm) {
  const double f_ghz = 77.0;
  const std::complex<double> eps(5.24, 17.98 * 0.0462 * std::pow(f_ghz, 0.7822) / f_ghz);
  const auto te = [&](double psi) {
    const std::complex<double> root = std::sqrt(eps - std::cos(psi) * std::cos(psi));
    return (std::sin(psi) - root) / (std::sin(psi) + root);
  };
  const auto tm = [&](double psi) {
    const std::complex<double> root = std::sqrt(eps - std::cos(psi) * std::cos(psi));
    return (eps * std::sin(psi) - root) / (eps * std::sin(psi) + root);
  };
  for (const double psi_deg : {2.0, 10.0, 30.0, 60.0}) {
    const double psi = psi_deg * kPi / 180.0;
    const propagation::FresnelCoefficients f = propagation::fresnel_reflection(eps, psi);
    // Down onto the floor (normal +z), in the x-z plane and turned 20 deg in azimuth.
    for (const double azimuth_deg : {0.0, 20.0}) {
      const double a = azimuth_deg * kPi / 180.0;
      const Eigen::Vector3d down(std::cos(psi) * std::cos(a), std::cos(psi) * std::sin(a),
                                 -std::sin(psi));
      EXPECT_LT(std::abs(co_polar_reflection(f, down, Eigen::Vector3d::UnitZ(),
                                             Polarisation::horizontal) -
                         te(psi)),
                1e-12);
      EXPECT_LT(
          std::abs(co_polar_reflection(f, down, Eigen::Vector3d::UnitZ(), Polarisation::vertical) -
                   tm(psi)),
          1e-12);
    }
    // Horizontally onto the left wall (normal +y).
    const Eigen::Vector3d left(std::cos(psi), -std::sin(psi), 0.0);
    const std::complex<double> h =
        co_polar_reflection(f, left, Eigen::Vector3d::UnitY(), Polarisation::horizontal);
    const std::complex<double> v =
        co_polar_reflection(f, left, Eigen::Vector3d::UnitY(), Polarisation::vertical);
    EXPECT_LT(std::abs(h - tm(psi)), 1e-12);
    EXPECT_LT(std::abs(v - te(psi)), 1e-12);
    fogradar::testing::validate(
        {.id = "radar.room.fresnel.side_wall.horizontal.psi" + number(psi_deg),
         .group = "radar: room",
         .quantity = "|co-polar coefficient|, horizontal, side wall",
         .unit = "1",
         .conditions = "concrete, 77 GHz, grazing " + number(psi_deg) + " deg",
         .reference = std::abs(tm(psi)),
         .source = "Fresnel TM closed form, ITU-R P.2040-3 concrete",
         .value = std::abs(h),
         .tolerance = 1e-12,
         .kind = Tolerance::absolute});
  }
  const std::complex<double> normal = (1.0 - std::sqrt(eps)) / (1.0 + std::sqrt(eps));
  const propagation::FresnelCoefficients f = propagation::fresnel_reflection(eps, 0.5 * kPi);
  for (const Polarisation pol : {Polarisation::horizontal, Polarisation::vertical}) {
    EXPECT_LT(
        std::abs(co_polar_reflection(f, Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), pol) -
                 normal),
        1e-12);
    // Off normal by 0.1 deg either way the coefficient stays near the normal value (no sign flip
    // from the TM convention).
    for (const Eigen::Vector3d& d :
         {Eigen::Vector3d(1.0, 0.0017, 0.0), Eigen::Vector3d(1.0, 0.0, 0.0017),
          Eigen::Vector3d(1.0, 0.0012, -0.0012)}) {
      const Eigen::Vector3d u = d.normalized();
      const propagation::FresnelCoefficients near =
          propagation::fresnel_reflection(eps, std::asin(u.x()));
      EXPECT_LT(std::abs(co_polar_reflection(near, u, -Eigen::Vector3d::UnitX(), pol) - normal),
                1e-3);
    }
  }
}

// A wall of concrete through the whole scene: the direct-wall tone of a point target beside a
// left wall at grazing psi carries 2 TM(psi) g_w/g_d r_d/r_w for horizontal polarisation and
// 2 TE(psi) ... for vertical, relative to the direct tone (amplitudes, the path phase taken out
// with the dechirped phase 2 pi f_0 tau - pi S tau^2 written out here). Tolerance 1e-9 relative.
TEST(RoomPaths, MaterialWallToneCarriesFresnelCoefficient) {
  const double f_ghz = 77.0;
  const std::complex<double> eps(5.24, 17.98 * 0.0462 * std::pow(f_ghz, 0.7822) / f_ghz);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), 77e9);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const double x_m = chamber.target_range_m(), w_m = 1.0;
  const double psi = std::atan(2.0 * w_m / x_m);
  const std::complex<double> root = std::sqrt(eps - std::cos(psi) * std::cos(psi));
  const std::complex<double> te = (std::sin(psi) - root) / (std::sin(psi) + root);
  const std::complex<double> tm = (eps * std::sin(psi) - root) / (eps * std::sin(psi) + root);
  for (const Polarisation pol : {Polarisation::horizontal, Polarisation::vertical}) {
    RadarParams p;
    p.azimuth_beamwidth_deg = 60.0;
    p.polarisation = pol;
    const RadarDerived d = derive(p);
    Scene scene = point_target_scene(10.0);
    scene.surfaces = {{.plane = {propagation::Surface::left_wall, -w_m},
                       .reflection_coefficient = 0.0,
                       .permittivity = eps,
                       .key = "chamber.room.left_wall"}};
    RandomStream rng(1);
    std::vector<Tone> tones;
    scene_tones(scene, chamber, no_fog, p, d, rng, tones);
    ASSERT_EQ(tones.size(), 3u);  // direct, direct-wall (both ways), wall-wall
    const auto phase = [&](double length_m) {
      const double tau = length_m / kC;
      const double f0 = 77e9 - 0.5 * p.sweep_bandwidth_hz;
      return std::polar(1.0, 2.0 * kPi * tau * f0 -
                                 kPi * (p.sweep_bandwidth_hz / p.chirp_duration_s) * tau * tau);
    };
    const double r_w = std::hypot(x_m, 2.0 * w_m);
    const double beam_rad = 60.0 * kPi / 180.0;
    const double g_ratio = std::exp(-2.0 * std::log(2.0) * std::pow(psi / beam_rad, 2));
    const std::complex<double> measured = (tones[1].amplitude / phase(tones[1].path_length_m)) /
                                          (tones[0].amplitude / phase(tones[0].path_length_m));
    const std::complex<double> gamma = pol == Polarisation::horizontal ? tm : te;
    const std::complex<double> expected = 2.0 * gamma * g_ratio * (x_m / r_w);
    EXPECT_NEAR(tones[1].path_length_m, x_m + r_w, 1e-9);
    EXPECT_LT(std::abs(measured - expected), 1e-9 * std::abs(expected))
        << to_string(pol) << ": " << measured << " vs " << expected;
  }
}

// Objects alone in an empty room (no floor), on boresight at the radar's height, read back their
// closed-form RCS (Knott, Radar Cross Section, Table 5.1, written out here) times the normal-
// incidence power reflectance of their material: a metal plate 0.2 m x 0.2 m facing the radar,
// 4 pi A^2 / lambda^2 |r|^2 with eps of metal from P.2040 (1 + i 17.98e7 / f_GHz); an HDPE barrel
// (r 0.3 m, 0.9 m tall) with its mid-height at the radar, broadside, k a L^2 |r|^2 with eps =
// 1.526^2 (1 + 3e-4 i). The point target stays out of the way (-100 dBsm). Noise off; tolerance
// 0.3 dB; both detections are `room`.
TEST(RoomPaths, ObjectsReadBackClosedFormRcs) {
  const RadarParams p = noise_free(RadarParams{});
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const double lambda_m = kC / p.centre_frequency_hz;
  const double k = 2.0 * kPi / lambda_m;
  const auto reflectance = [](std::complex<double> eps) {
    return std::norm((1.0 - std::sqrt(eps)) / (1.0 + std::sqrt(eps)));
  };
  struct Case {
    const char* name;
    propagation::RoomObject object;
    double sensor_height_m;
    double expected_m2;
    double range_m;
  };
  const double n = 1.526;
  const Case cases[] = {
      {"metal_plate",
       {.shape = propagation::ObjectShape::plate,
        .x_m = 7.0,
        .y_m = 0.0,
        .base_height_m = 0.4,
        .height_m = 0.2,
        .width_m = 0.2,
        .yaw_deg = 0.0,
        .material = propagation::Material::metal},
       0.5,
       4.0 * kPi * 0.04 * 0.04 / (lambda_m * lambda_m) * reflectance({1.0, 17.98e7 / 77.0}),
       7.0},
      {"plastic_barrel",
       {.shape = propagation::ObjectShape::cylinder,
        .x_m = 7.3,
        .y_m = 0.0,
        .base_height_m = 0.0,
        .height_m = 0.9,
        .radius_m = 0.3,
        .material = propagation::Material::plastic},
       0.45,
       k * 0.3 * 0.81 * reflectance({n * n, n * n * 3e-4}),
       7.0}};
  for (const Case& c : cases) {
    propagation::RoomSpec room;
    room.floor.present = false;
    room.objects = {c.object};
    // The scene as make_scene builds it from the room: the material's reflectance at 77 GHz.
    const TargetSpec target{.model = TargetModel::point,
                            .rcs_dbsm = -100.0,
                            .height_m = c.sensor_height_m,
                            .sensor_height_m = c.sensor_height_m};
    sensor::TargetWorld world;
    world.micro_motion_std_m = 0.0;
    const Scene scene = make_scene(target, world, room, 4, 77e9);
    MeasurementWorkspace ws = chain.make_workspace();
    Measurement m;
    RandomStream rng(3);
    chain.measure(scene, chamber, no_fog, rng, ws, m);
    const Detection* det = detection_near(m.detections, c.range_m, 0.2);
    ASSERT_NE(det, nullptr) << c.name;
    EXPECT_EQ(det->origin, Origin::room) << c.name;
    const double expected_dbsm =
        10.0 * std::log10(c.expected_m2 * std::pow(det->range_m / c.range_m, 4));
    fogradar::testing::validate(
        {.id = std::string("radar.room.object.") + c.name + ".rcs",
         .group = "radar: room",
         .quantity = "RCS of an object read back",
         .unit = "dBsm",
         .conditions = std::string(c.name) + " on boresight at 7 m, no floor, noise off",
         .reference = expected_dbsm,
         .source = "PO closed form [Knott Table 5.1] x normal-incidence "
                   "Fresnel reflectance (this test)",
         .value = det->rcs_dbsm,
         .tolerance = 0.3,
         .kind = Tolerance::absolute});
  }
}

// The back wall's own return, the radar's image 2 D away: P = P_t G_t G_r lambda^2 |Gamma|^2 /
// ((4 pi)^2 (2 D)^2), read by eq. 7 at range D as sigma = pi D^2 |Gamma|^2. Wall at 15 m with
// Gamma = -0.5, the target out of the way (-100 dBsm), no floor, noise off: a `room` detection at
// 15 m within 0.05 m, its RCS within 0.3 dB.
TEST(RoomPaths, BackWallReturnsAtItsRange) {
  const RadarParams p = noise_free(RadarParams{});
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const double d_m = 15.0, gamma = -0.5;
  Scene scene = point_target_scene(-100.0);
  scene.surfaces = {wall(propagation::Surface::back_wall, d_m, gamma)};
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement m;
  RandomStream rng(5);
  chain.measure(scene, chamber, no_fog, rng, ws, m);
  const Detection* det = detection_near(m.detections, d_m, 0.2);
  ASSERT_NE(det, nullptr);
  EXPECT_EQ(det->origin, Origin::room);
  EXPECT_NEAR(det->range_m, d_m, 0.05);
  const double expected_dbsm =
      10.0 * std::log10(kPi * d_m * d_m * gamma * gamma * std::pow(det->range_m / d_m, 4));
  fogradar::testing::validate({.id = "radar.room.back_wall.rcs",
                               .group = "radar: room",
                               .quantity = "back wall's specular return as RCS",
                               .unit = "dBsm",
                               .conditions = "wall at 15 m, Gamma -0.5, noise off",
                               .reference = expected_dbsm,
                               .source = "image of the radar 2 D away (Friis): sigma = pi D^2 "
                                         "|Gamma|^2",
                               .value = det->rcs_dbsm,
                               .tolerance = 0.3,
                               .kind = Tolerance::absolute});
}

// The default room (the floor alone, by a real coefficient) makes the same tones as the two-ray
// model written out here: direct, 2 Gamma direct-floor, Gamma^2 floor-floor, in that order, their
// lengths from the floor image (a second method for the byte-for-byte claim: lengths to 1e-12 m,
// amplitude ratios to 1e-12), and a moving target's floor paths change by their own Doppler, the
// direct path's range rate scaled by the floor leg's direction cosine along the boresight.
TEST(RoomPaths, FloorOnlyRoomIsTheTwoRayModel) {
  RadarParams p;
  const RadarDerived d = derive(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), 77e9);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  Scene scene = point_target_scene(10.0);
  scene.centres[0].height_m = 0.8;
  scene.centres[0].radial_velocity_m_per_s = 2.0;
  scene.surfaces = {coefficient_floor(-0.6)};
  RandomStream rng(1);
  std::vector<Tone> tones;
  scene_tones(scene, chamber, no_fog, p, d, rng, tones);
  ASSERT_EQ(tones.size(), 3u);
  const double x_m = chamber.target_range_m();
  const double r_d = std::hypot(x_m, 0.3), r_f = std::hypot(x_m, 1.3);
  EXPECT_NEAR(tones[0].path_length_m, 2.0 * r_d, 1e-12);
  EXPECT_NEAR(tones[1].path_length_m, r_d + r_f, 1e-12);
  EXPECT_NEAR(tones[2].path_length_m, 2.0 * r_f, 1e-12);
  EXPECT_EQ(tones[0].radial_velocity_m_per_s, 2.0);
  const double floor_rate = 2.0 * (x_m / r_f) / (x_m / r_d);
  EXPECT_NEAR(tones[1].radial_velocity_m_per_s, 0.5 * (2.0 + floor_rate), 1e-12);
  EXPECT_NEAR(tones[2].radial_velocity_m_per_s, floor_rate, 1e-12);
  std::printf("[ measured ] floor-floor path of a 2 m/s target at 10 m: %.6f m/s (%.3f %%)\n",
              tones[2].radial_velocity_m_per_s,
              100.0 * (tones[2].radial_velocity_m_per_s / 2.0 - 1.0));
  for (const Tone& t : tones) EXPECT_EQ(t.origin, Origin::target);  // unresolved: one echo
}

}  // namespace
}  // namespace fogradar::radar
