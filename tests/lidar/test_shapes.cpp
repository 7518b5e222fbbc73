// The lidar's static scene as shapes: the beam's first hit on a line, a segment and a circle
// against closed forms written out here (plane geometry: a wall at lateral distance D is met at
// D / sin|a| at incidence cos = sin|a|; a circle of radius r whose centre lies at distance L and
// angle delta from the beam is met at L cos(delta) - sqrt(r^2 - L^2 sin^2(delta)), where the
// radial normal makes cos(incidence) = sqrt(r^2 - L^2 sin^2(delta)) / r), shadowing, the room's
// shapes at a scan height, the same ranges through the whole lidar chain (waveform, noise,
// leading-edge detection, calibration), and a scenario's room turned into the scan plane's hall
// with its materials' published reflectances, or refused by key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/lidar/shapes.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/diffuse_reflectance.hpp"
#include "fogradar/propagation/room_spec.hpp"
#include "fogradar/propagation/water.hpp"
#include "rejected_field.hpp"
#include "svg_check.hpp"
#include "validation.hpp"

namespace fogradar::lidar {
namespace {

using fogradar::test_support::rejected_field;
using fogradar::testing::Tolerance;
using fogradar::testing::validate;

constexpr double deg = pi / 180.0;

const propagation::SegelsteinTable& table() {
  static const propagation::SegelsteinTable instance;
  return instance;
}

// A number as check ids show it ("2.8").
std::string id_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

double ux_of(double angle_deg) { return std::cos(angle_deg * deg); }
double uy_of(double angle_deg) { return std::sin(angle_deg * deg); }

TEST(LidarShapes, WallLineIsMetAtDistanceOverSine) {
  const double d = 3.0;
  const LineShape left{0.0, -d, 1.0, 0.0};
  for (const double a : {-5.0, -20.0, -45.0, -80.0, -120.0}) {
    const ShapeHit hit = intersect(left, ux_of(a), uy_of(a));
    EXPECT_NEAR(hit.range_m, d / std::sin(std::abs(a) * deg), 1e-12) << a;
    EXPECT_NEAR(hit.cos_incidence, std::sin(std::abs(a) * deg), 1e-12) << a;
  }
  // Along the wall, or away from it: no hit.
  EXPECT_TRUE(std::isinf(intersect(left, 1.0, 0.0).range_m));
  EXPECT_TRUE(std::isinf(intersect(left, ux_of(30.0), uy_of(30.0)).range_m));
  // The back wall x = X: X / cos a.
  const LineShape back{12.0, 0.0, 0.0, 1.0};
  const ShapeHit hit = intersect(back, ux_of(25.0), uy_of(25.0));
  EXPECT_NEAR(hit.range_m, 12.0 / std::cos(25.0 * deg), 1e-12);
  EXPECT_NEAR(hit.cos_incidence, std::cos(25.0 * deg), 1e-12);
}

TEST(LidarShapes, SegmentIsMetOnlyBetweenItsEnds) {
  const SegmentShape plate{5.0, -1.0, 5.0, 1.0};
  const double edge_deg = std::atan2(1.0, 5.0) / deg;
  EXPECT_NEAR(intersect(plate, ux_of(edge_deg - 0.01), uy_of(edge_deg - 0.01)).range_m,
              5.0 / std::cos((edge_deg - 0.01) * deg), 1e-12);
  EXPECT_TRUE(std::isinf(intersect(plate, ux_of(edge_deg + 0.01), uy_of(edge_deg + 0.01)).range_m));
  EXPECT_TRUE(std::isinf(intersect(plate, -1.0, 0.0).range_m));
}

TEST(LidarShapes, CircleIsMetAtTheChordsNearEnd) {
  const double length = 6.0;
  const double centre_deg = -20.0;
  const double r = 0.3;
  const CircleShape barrel{length * ux_of(centre_deg), length * uy_of(centre_deg), r};
  for (const double offset : {0.0, 1.0, -2.0, 2.8}) {
    const double a = centre_deg + offset;
    const double across = length * std::sin(std::abs(offset) * deg);
    const double half_chord = std::sqrt(r * r - across * across);
    const ShapeHit hit = intersect(barrel, ux_of(a), uy_of(a));
    const std::string conditions = "r 0.3 m at 6 m, beam " + id_number(offset) + " deg off";
    validate({.id = "lidar.shapes.circle.range.offset" + id_number(offset),
              .group = "lidar",
              .quantity = "first hit on a circle",
              .unit = "m",
              .conditions = conditions,
              .reference = length * std::cos(offset * deg) - half_chord,
              .source = "closed form: the chord's near end L cos(delta) - sqrt(r^2 - L^2 "
                        "sin^2(delta))",
              .value = hit.range_m,
              .tolerance = 1e-12,
              .kind = Tolerance::absolute});
    EXPECT_NEAR(hit.cos_incidence, half_chord / r, 1e-9) << conditions;
    // The hit lies on the circle and its normal there is radial.
    const double hx = hit.range_m * ux_of(a) - barrel.centre_x_m;
    const double hy = hit.range_m * uy_of(a) - barrel.centre_y_m;
    EXPECT_NEAR(std::hypot(hx, hy), r, 1e-12) << conditions;
    EXPECT_NEAR(-(hx * ux_of(a) + hy * uy_of(a)) / r, hit.cos_incidence, 1e-9) << conditions;
  }
  // Past its edge (6 m sin 3 deg = 0.314 m > r) and behind the sensor: no hit.
  EXPECT_TRUE(
      std::isinf(intersect(barrel, ux_of(centre_deg + 3.0), uy_of(centre_deg + 3.0)).range_m));
  EXPECT_TRUE(std::isinf(intersect(barrel, -ux_of(centre_deg), -uy_of(centre_deg)).range_m));
}

// A plate 2 m wide at 4 m in front of a back wall at 10 m, and a barrel on the left between them:
// the nearer shape wins, the farther is met only where the nearer is not.
TEST(LidarShapes, TheNearerShapeShadowsTheFarther) {
  const std::vector<Shape> shapes = {
      {.geometry = LineShape{10.0, 0.0, 0.0, 1.0}, .reflectivity = 0.3},
      {.geometry = SegmentShape{4.0, -1.0, 4.0, 1.0}, .reflectivity = 0.5},
      {.geometry = CircleShape{7.0, -2.0, 0.5}, .reflectivity = 0.7},
  };
  const FirstHit centre = first_hit(shapes, 1.0, 0.0);
  ASSERT_TRUE(centre.shape);
  EXPECT_EQ(*centre.shape, 1u);
  EXPECT_NEAR(centre.hit.range_m, 4.0, 1e-12);
  const double to_barrel = std::atan2(-2.0, 7.0) / deg;
  const FirstHit barrel = first_hit(shapes, ux_of(to_barrel), uy_of(to_barrel));
  ASSERT_TRUE(barrel.shape);
  EXPECT_EQ(*barrel.shape, 2u);
  EXPECT_NEAR(barrel.hit.range_m, std::hypot(7.0, 2.0) - 0.5, 1e-12);
  const FirstHit wall = first_hit(shapes, ux_of(20.0), uy_of(20.0));
  ASSERT_TRUE(wall.shape);
  EXPECT_EQ(*wall.shape, 0u);
  EXPECT_NEAR(wall.hit.range_m, 10.0 / std::cos(20.0 * deg), 1e-12);
  EXPECT_FALSE(first_hit(shapes, -1.0, 0.0).shape);
  // On a tie the earlier shape: the same plate twice.
  const std::vector<Shape> twice = {shapes[1], shapes[1]};
  EXPECT_EQ(*first_hit(twice, 1.0, 0.0).shape, 0u);
}

ScanPlaneRoom hall() {
  ScanPlaneRoom room;
  room.left_wall = RoomWall{.distance_m = 3.0, .reflectivity = 0.31};
  room.right_wall = RoomWall{.distance_m = 5.0, .reflectivity = 0.23};
  room.back_wall = RoomWall{.distance_m = 15.0, .reflectivity = 0.29};
  room.cylinders = {{.centre_x_m = 3.5,
                     .centre_y_m = -2.0,
                     .radius_m = 0.3,
                     .z_min_m = 0.0,
                     .z_max_m = 0.9,
                     .reflectivity = 0.73}};
  room.plates = {{.x0_m = 8.0,
                  .y0_m = 1.0,
                  .x1_m = 8.0,
                  .y1_m = 2.0,
                  .z_min_m = 0.5,
                  .z_max_m = 2.0,
                  .reflectivity = 0.05}};
  return room;
}

TEST(LidarRoomShapes, ObjectsAreInTheScanPlaneOnlyWhereItCrossesThem) {
  const ScanPlaneRoom room = hall();
  const std::vector<Shape> low = room_shapes(room, 0.3);  // below the plate
  ASSERT_EQ(low.size(), 4u);
  ASSERT_TRUE(std::holds_alternative<CircleShape>(low[3].geometry));
  EXPECT_EQ(low[3].reflectivity, 0.73);
  const std::vector<Shape> middle = room_shapes(room, 0.7);  // both
  ASSERT_EQ(middle.size(), 5u);
  EXPECT_TRUE(std::holds_alternative<SegmentShape>(middle[4].geometry));
  const std::vector<Shape> high = room_shapes(room, 1.5);  // above the barrel
  ASSERT_EQ(high.size(), 4u);
  EXPECT_TRUE(std::holds_alternative<SegmentShape>(high[3].geometry));
  EXPECT_EQ(room_shapes(room, 2.5).size(), 3u);  // the walls only
  // Left wall at y = -3, right at y = +5, back at x = 15.
  EXPECT_NEAR(intersect(high[0], 0.0, -1.0).range_m, 3.0, 1e-12);
  EXPECT_NEAR(intersect(high[1], 0.0, 1.0).range_m, 5.0, 1e-12);
  EXPECT_NEAR(intersect(high[2], 1.0, 0.0).range_m, 15.0, 1e-12);
  EXPECT_EQ(high[2].reflectivity, 0.29);
  EXPECT_TRUE(room_shapes(ScanPlaneRoom{}, 1.0).empty());
}

TEST(LidarRoomShapes, AnInvalidRoomIsRefusedByField) {
  const auto refused = [](auto change) {
    ScanPlaneRoom room = hall();
    change(room);
    return rejected_field([&room] { room.validate("chamber.room."); });
  };
  EXPECT_EQ(refused([](ScanPlaneRoom&) {}), "accepted");
  EXPECT_EQ(refused([](ScanPlaneRoom& r) { r.left_wall->distance_m = 0.0; }),
            "chamber.room.left_wall.distance_m");
  EXPECT_EQ(refused([](ScanPlaneRoom& r) { r.back_wall->reflectivity = 1.2; }),
            "chamber.room.back_wall.reflectivity");
  EXPECT_EQ(refused([](ScanPlaneRoom& r) { r.cylinders[0].radius_m = 5.0; }),
            "chamber.room.cylinders[0].radius_m");
  EXPECT_EQ(refused([](ScanPlaneRoom& r) { r.cylinders[0].z_max_m = -1.0; }),
            "chamber.room.cylinders[0].z_max_m");
  EXPECT_EQ(refused([](ScanPlaneRoom& r) { r.plates[0].y1_m = 1.0; }),
            "chamber.room.plates[0].x1_m");
  EXPECT_EQ(refused([](ScanPlaneRoom& r) { r.plates[0].x0_m = std::nan(""); }),
            "chamber.room.plates[0].x0_m");
  EXPECT_EQ(rejected_field([] { room_shapes(hall(), std::nan("")); }), "scan_height_m");
}

// A lidar with no target and no background segment: only the room's shapes. Noise per sample
// p = 1e-100 (threshold 21 sigma): a single echo's range scatters by ~1 cm, the mean of 40 scans
// by ~0.2 cm, so the +-2 cm check tests the geometry and the receiver, not the luck of the draw.
LidarParams room_lidar() {
  LidarParams params;
  params.target_width_m = 0.0;
  params.background.clear();
  params.field_of_view_deg = 150.0;
  params.false_alarm_probability = 1e-100;
  params.fog_fluctuation.log_std = 0.0;
  return params;
}

// The threshold as the datasheet defines it (params.hpp): a Lambertian target of
// threshold_reflectivity at threshold_range_m, normal incidence, peaks at it.
double datasheet_threshold(const LidarParams& p) {
  return p.threshold_reflectivity / pi / (p.threshold_range_m * p.threshold_range_m);
}

// The reflectivity that makes a surface at `range_m`, met at `cos_incidence`, peak at exactly twice
// the threshold: rho cos / (pi R^2) = 2 thr. There the calibrated leading edge reads the true range
// (the receiver's calibration, docs/lidar.md section 3: no range walk).
double twice_threshold_reflectivity(const LidarParams& p, double range_m, double cos_incidence) {
  return 2.0 * datasheet_threshold(p) * pi * range_m * range_m / cos_incidence;
}

// The mean over 40 scans of the background echoes' range in the beam at `angle_deg`; every scan
// must give that beam exactly one echo, the background's.
double mean_echo_range(const Lidar& lidar, double angle_deg) {
  const double beam_real =
      (angle_deg + 0.5 * lidar.params().field_of_view_deg) / lidar.params().angular_step_deg;
  const auto beam = static_cast<std::uint32_t>(std::lround(beam_real));
  EXPECT_NEAR(lidar.beam_angle_deg(beam), angle_deg, 1e-9);
  double sum = 0.0;
  std::size_t count = 0;
  const std::size_t scans = 40;
  for (std::size_t s = 0; s < scans; ++s) {
    RandomStream stream = sensor_stream(5, stream_key, 0, s);
    const LidarScan scan =
        lidar.measure(propagation::first_layers_active(0, 4), std::vector<double>(4, 1.0), stream);
    for (const LidarEcho& e : scan.echoes) {
      if (e.beam != beam) continue;
      EXPECT_EQ(e.origin, Origin::background) << angle_deg;
      sum += e.range_m;
      ++count;
    }
  }
  EXPECT_EQ(count, scans) << angle_deg;
  return count == 0 ? 0.0 : sum / static_cast<double>(count);
}

// The check: a wall at lateral distance D, seen by the beam at azimuth a, has range
// D / sin|a|, +-2 cm on the echo's estimated range through the whole chain.
TEST(LidarRoom, WallEchoReadsDistanceOverSine) {
  const LidarParams params = room_lidar();
  const double d = 3.0;
  for (const double a : {-20.0, -30.0, -45.0, -60.0}) {
    const double range_m = d / std::sin(std::abs(a) * deg);
    ScanPlaneRoom room;
    room.left_wall = RoomWall{
        .distance_m = d,
        .reflectivity = twice_threshold_reflectivity(params, range_m, std::sin(std::abs(a) * deg))};
    const Lidar lidar(params, propagation::ChamberSpec{}, table(), room_shapes(room, 0.5));
    const std::string tag = std::to_string(static_cast<int>(a));
    validate({.id = "lidar.room.wall_range.azimuth" + tag,
              .group = "lidar",
              .quantity = "wall echo's range",
              .unit = "m",
              .conditions = "left wall at 3 m, beam at " + tag +
                            " deg, reflectivity for a peak of 2 thresholds, mean of 40 scans",
              .reference = range_m,
              .source = "closed form: D / sin|a|",
              .value = mean_echo_range(lidar, a),
              .tolerance = 0.02,
              .kind = Tolerance::absolute});
  }
}

// A barrel of radius 0.3 m, its axis at 6 m on the -20 deg beam: the beams at -20 and -18 deg meet
// it at the chord's near end (closed form as above), through the whole chain, +-2 cm.
TEST(LidarRoom, BarrelEchoReadsTheChordsNearEnd) {
  const LidarParams params = room_lidar();
  const double length = 6.0;
  const double r = 0.3;
  for (const double offset : {0.0, 2.0}) {
    const double across = length * std::sin(offset * deg);
    const double half_chord = std::sqrt(r * r - across * across);
    const double range_m = length * std::cos(offset * deg) - half_chord;
    ScanPlaneRoom room;
    room.cylinders = {
        {.centre_x_m = length * ux_of(-20.0),
         .centre_y_m = length * uy_of(-20.0),
         .radius_m = r,
         .z_min_m = 0.0,
         .z_max_m = 0.9,
         .reflectivity = twice_threshold_reflectivity(params, range_m, half_chord / r)}};
    const Lidar lidar(params, propagation::ChamberSpec{}, table(), room_shapes(room, 0.5));
    const std::string tag = std::to_string(static_cast<int>(offset));
    validate({.id = "lidar.room.barrel_range.offset" + tag,
              .group = "lidar",
              .quantity = "barrel echo's range",
              .unit = "m",
              .conditions = "barrel r 0.3 m at 6 m, beam " + tag +
                            " deg off its axis, a peak of 2 thresholds, mean of 40 scans",
              .reference = range_m,
              .source = "closed form: L cos(delta) - sqrt(r^2 - L^2 sin^2(delta))",
              .value = mean_echo_range(lidar, -20.0 + offset),
              .tolerance = 0.02,
              .kind = Tolerance::absolute});
  }
}

// The Lambertian return: two walls alike but for their reflectivity return in its ratio, and each
// peaks at rho cos(incidence) / (pi R^2) (clear air, full overlap), less the sampling's loss: the
// sampled pulse's largest sample is at most dt/2 = 0.25 ns from its centre, exp(-4 ln2 (0.25/5)^2)
// = 0.9931 of the peak.
TEST(LidarRoom, ReturnScalesWithReflectivityAndIncidence) {
  LidarParams params = room_lidar();
  params.field_of_view_deg = 120.0;
  const double d = 3.0;
  const auto lidar_with = [&params, d](double reflectivity) {
    ScanPlaneRoom room;
    room.left_wall = RoomWall{.distance_m = d, .reflectivity = reflectivity};
    return Lidar(params, propagation::ChamberSpec{}, table(), room_shapes(room, 0.5));
  };
  const Lidar dark = lidar_with(0.2);
  const Lidar bright = lidar_with(0.6);
  const propagation::ActiveLayers none = propagation::first_layers_active(0, 4);
  const std::vector<double> factors(4, 1.0);
  for (const double a : {-15.0, -30.0, -50.0}) {
    const auto beam = static_cast<std::size_t>(std::lround((a + 60.0) / 0.25));
    const std::vector<double> w_dark = dark.waveform(beam, none, factors).background;
    const std::vector<double> w_bright = bright.waveform(beam, none, factors).background;
    const double peak_dark = *std::max_element(w_dark.begin(), w_dark.end());
    const double peak_bright = *std::max_element(w_bright.begin(), w_bright.end());
    EXPECT_NEAR(peak_bright / peak_dark, 3.0, 1e-12) << a;
    const double range_m = d / std::sin(std::abs(a) * deg);
    const double closed = 0.6 * std::sin(std::abs(a) * deg) / (pi * range_m * range_m);
    EXPECT_LE(peak_bright, closed * (1.0 + 1e-12)) << a;
    EXPECT_GE(peak_bright, closed * 0.9931) << a;
  }
}

// [[lidar.background]] segments are segment shapes: the same segments given as the room's shapes
// instead give the same scan, echo for echo. The segments: a wall 3 m to the left and one 0.6 m
// chord at 2.5 m, the paper scenario's background before it had a room.
TEST(LidarRoom, BackgroundSegmentsAreSegmentShapes) {
  LidarParams with_background;
  with_background.background = {
      {.x0_m = 0.5, .y0_m = -3.0, .x1_m = 12.0, .y1_m = -3.0, .reflectivity = 0.5},
      {.x0_m = 2.5, .y0_m = -2.3, .x1_m = 2.5, .y1_m = -1.7, .reflectivity = 0.3}};
  LidarParams without = with_background;
  without.background.clear();
  const Lidar a(with_background, propagation::ChamberSpec{}, table());
  const Lidar b(without, propagation::ChamberSpec{}, table(),
                background_shapes(with_background.background));
  ASSERT_EQ(a.shapes().size(), with_background.background.size());
  for (const std::size_t layers : {0u, 2u}) {
    RandomStream sa = sensor_stream(9, stream_key, layers, 0);
    RandomStream sb = sensor_stream(9, stream_key, layers, 0);
    const propagation::ActiveLayers active = propagation::first_layers_active(layers, 4);
    const LidarScan ea = a.measure(active, std::vector<double>(4, 1.0), sa);
    const LidarScan eb = b.measure(active, std::vector<double>(4, 1.0), sb);
    ASSERT_EQ(ea.echoes.size(), eb.echoes.size());
    std::size_t background = 0;
    for (std::size_t i = 0; i < ea.echoes.size(); ++i) {
      EXPECT_EQ(ea.echoes[i].beam, eb.echoes[i].beam);
      EXPECT_EQ(ea.echoes[i].origin, eb.echoes[i].origin);
      EXPECT_EQ(ea.echoes[i].range_m, eb.echoes[i].range_m);
      EXPECT_EQ(ea.echoes[i].intensity, eb.echoes[i].intensity);
      if (ea.echoes[i].origin == Origin::background) ++background;
    }
    if (layers == 0) {
      EXPECT_GT(background, 0u);
    }
  }
}

// Fig. 5's top view draws the room: its walls clipped to the panel, its barrels as circles, each
// with its title; a scene of segments only draws segments.
TEST(LidarRoom, ScanViewDrawsTheRoomsShapes) {
  const LidarParams params;
  const std::vector<Shape> room = room_shapes(hall(), 0.5);
  const Lidar with_room(params, propagation::ChamberSpec{}, table(), room);
  const Lidar without(params, propagation::ChamberSpec{}, table());
  std::vector<LidarStepResult> steps(1);
  steps[0].scans.resize(1);
  const std::string svg = lidar_scans_svg(with_room, steps);
  EXPECT_EQ(test_support::xml_error(svg), "");
  // Left and right walls in the panel; the back wall at 15 m lies beyond its 12 m depth.
  EXPECT_EQ(test_support::count(svg, "<title>wall</title>"), 2u);
  EXPECT_EQ(test_support::count(svg, "<title>cylinder</title>"), 1u);
  EXPECT_EQ(test_support::count(svg, "<title>background segment</title>"),
            params.background.size() + 1);
  const std::string plain = lidar_scans_svg(without, steps);
  EXPECT_EQ(test_support::count(plain, "<title>wall</title>"), 0u);
  EXPECT_EQ(test_support::count(plain, "<title>background segment</title>"),
            params.background.size());
}

// The scenario's room as the lidar meets it. The materials' 905 and 1550 nm values are the USGS
// splib07a records' (Kokaly et al. 2017; tests/propagation/test_diffuse_reflectance.cpp copies them
// from the records): concrete 0.31044638 and 0.33177111 (18568), brick 0.23423219 (18359), wood
// 0.65911061 (20779), white HDPE 0.73082012 (19604), galvanized sheet metal 0.058301263 (18773);
// fogradar keeps four figures, hence 5e-5.
propagation::RoomSpec material_hall() {
  propagation::RoomSpec room;  // the default floor, a real coefficient: never met, never refused
  room.left_wall = {
      .present = true, .reflection = propagation::Material::concrete, .distance_m = 3.0};
  room.right_wall = {
      .present = true, .reflection = propagation::Material::brick, .distance_m = 4.0};
  room.ceiling = {
      .present = true, .reflection = propagation::ReflectionCoefficient{-0.5}, .distance_m = 4.5};
  room.back_wall = {.present = true, .reflection = propagation::Material::wood, .distance_m = 20.0};
  room.objects = {
      {.shape = propagation::ObjectShape::cylinder, .x_m = 3.5, .y_m = -2.0, .height_m = 0.9},
      {.shape = propagation::ObjectShape::plate,
       .x_m = 8.0,
       .y_m = 1.0,
       .base_height_m = 0.2,
       .height_m = 1.0,
       .width_m = 2.0,
       .yaw_deg = 30.0,
       .material = propagation::Material::metal},
      // Above the scan at 0.5 m: not in its plane.
      {.shape = propagation::ObjectShape::cylinder, .x_m = 6.0, .y_m = 2.0, .base_height_m = 1.0},
  };
  return room;
}

TEST(LidarRoomSpec, WallsAndObjectsTakeTheirMaterialsDiffuseReflectance) {
  const LidarParams params;  // 905 nm, 0.5 m high
  const ScanPlaneRoom plane = scan_plane_room(material_hall(), params);
  ASSERT_TRUE(plane.left_wall && plane.right_wall && plane.back_wall);
  EXPECT_EQ(plane.left_wall->distance_m, 3.0);
  EXPECT_NEAR(plane.left_wall->reflectivity, 0.31044638, 5e-5);
  EXPECT_EQ(plane.right_wall->distance_m, 4.0);
  EXPECT_NEAR(plane.right_wall->reflectivity, 0.23423219, 5e-5);
  EXPECT_EQ(plane.back_wall->distance_m, 20.0);
  EXPECT_NEAR(plane.back_wall->reflectivity, 0.65911061, 5e-5);
  ASSERT_EQ(plane.cylinders.size(), 1u);  // the one above the scan left out
  const RoomCylinder& barrel = plane.cylinders[0];
  EXPECT_EQ(barrel.centre_x_m, 3.5);
  EXPECT_EQ(barrel.centre_y_m, -2.0);
  EXPECT_EQ(barrel.radius_m, 0.3);
  EXPECT_EQ(barrel.z_min_m, 0.0);
  EXPECT_EQ(barrel.z_max_m, 0.9);
  EXPECT_NEAR(barrel.reflectivity, 0.73082012, 5e-5);
  // The plate's normal turned 30 deg from -x toward +y, (-cos 30, sin 30): its 2 m width runs along
  // (sin 30, cos 30) = (0.5, 0.866) about its centre (8, 1).
  ASSERT_EQ(plane.plates.size(), 1u);
  const RoomPlate& plate = plane.plates[0];
  EXPECT_NEAR(plate.x0_m, 7.5, 1e-12);
  EXPECT_NEAR(plate.y0_m, 1.0 - std::sqrt(3.0) / 2.0, 1e-12);
  EXPECT_NEAR(plate.x1_m, 8.5, 1e-12);
  EXPECT_NEAR(plate.y1_m, 1.0 + std::sqrt(3.0) / 2.0, 1e-12);
  const double normal_x = -std::cos(30.0 * deg), normal_y = std::sin(30.0 * deg);
  EXPECT_NEAR((plate.x1_m - plate.x0_m) * normal_x + (plate.y1_m - plate.y0_m) * normal_y, 0.0,
              1e-12);
  EXPECT_EQ(plate.z_min_m, 0.2);
  EXPECT_EQ(plate.z_max_m, 1.2);
  EXPECT_NEAR(plate.reflectivity, 0.058301263, 5e-5);
  // At 1550 nm the same wall reads its 1550 nm value; scanning at 0.95 m, between the barrel's top
  // and the other cylinder's base, only the plate is cut.
  LidarParams other = params;
  other.wavelength_m = 1550e-9;
  other.height_m = 0.95;
  const ScanPlaneRoom high = scan_plane_room(material_hall(), other);
  EXPECT_NEAR(high.left_wall->reflectivity, 0.33177111, 5e-5);
  EXPECT_TRUE(high.cylinders.empty());
  EXPECT_EQ(high.plates.size(), 1u);
  // The empty hall: nothing.
  const ScanPlaneRoom none = scan_plane_room(propagation::RoomSpec{}, params);
  EXPECT_FALSE(none.left_wall || none.right_wall || none.back_wall);
  EXPECT_TRUE(none.cylinders.empty() && none.plates.empty());
}

// One refusal per message, each naming the scenario's key; the floor and the ceiling given by a
// real coefficient are never refused (material_hall's are).
TEST(LidarRoomSpec, WhatTheLidarCannotSeeIsRefusedByKey) {
  const auto refused = [](auto change) {
    propagation::RoomSpec room = material_hall();
    LidarParams params;
    change(room, params);
    return rejected_field([&] { scan_plane_room(room, params); });
  };
  EXPECT_EQ(refused([](propagation::RoomSpec&, LidarParams&) {}), "accepted");
  EXPECT_EQ(refused([](propagation::RoomSpec& r, LidarParams&) {
              r.left_wall.reflection = propagation::ReflectionCoefficient{-0.6};
            }),
            "chamber.room.left_wall.reflection_coefficient");
  EXPECT_EQ(refused([](propagation::RoomSpec& r, LidarParams&) {
              r.back_wall.reflection = propagation::Material::plasterboard;
            }),
            "chamber.room.back_wall.material");
  EXPECT_EQ(refused([](propagation::RoomSpec& r, LidarParams&) {
              r.objects[2].material = propagation::Material::glass;  // above the scan: refused too
            }),
            "chamber.objects[2].material");
  EXPECT_EQ(refused([](propagation::RoomSpec&, LidarParams& p) { p.wavelength_m = 940e-9; }),
            "lidar.wavelength_m");
  EXPECT_EQ(refused([](propagation::RoomSpec&, LidarParams& p) { p.height_m = 4.5; }),
            "lidar.height_m");
  EXPECT_EQ(refused([](propagation::RoomSpec& r, LidarParams&) {
              r.objects[0].x_m = 0.2;
              r.objects[0].y_m = 0.1;
            }),
            "chamber.objects[0].radius_m");
  // A barrel below the scan may stand under the lidar.
  EXPECT_EQ(refused([](propagation::RoomSpec& r, LidarParams& p) {
              r.objects[0].x_m = 0.2;
              r.objects[0].y_m = 0.1;
              p.height_m = 1.0;
            }),
            "accepted");
  // Without walls or objects no wavelength is refused.
  LidarParams far;
  far.wavelength_m = 1064e-9;
  EXPECT_EQ(rejected_field([&far] { scan_plane_room(propagation::RoomSpec{}, far); }), "accepted");
}

TEST(LidarRoomSpec, TheRefusalsSayWhatToGive) {
  propagation::RoomSpec room;
  room.right_wall = {
      .present = true, .reflection = propagation::ReflectionCoefficient{-0.6}, .distance_m = 3.0};
  try {
    scan_plane_room(room, LidarParams{});
    FAIL() << "accepted";
  } catch (const InvalidParameter& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("chamber.room.right_wall.reflection_coefficient = -0.6"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("chamber.room.right_wall.material"), std::string::npos) << message;
    EXPECT_NE(message.find(propagation::diffuse_material_names()), std::string::npos) << message;
  }
  room.right_wall.reflection = propagation::Material::glass;
  try {
    scan_plane_room(room, LidarParams{});
    FAIL() << "accepted";
  } catch (const InvalidParameter& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("chamber.room.right_wall.material = 'glass'"), std::string::npos)
        << message;
    EXPECT_NE(message.find(propagation::diffuse_material_names()), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace fogradar::lidar
