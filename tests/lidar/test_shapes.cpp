// The lidar's static scene as shapes: the beam's first hit on a line, a segment and a circle
// against closed forms written out here (plane geometry: a wall at lateral distance D is met at
// D / sin|a| at incidence cos = sin|a|; a circle of radius r whose centre lies at distance L and
// angle delta from the beam is met at L cos(delta) - sqrt(r^2 - L^2 sin^2(delta)), where the
// radial normal makes cos(incidence) = sqrt(r^2 - L^2 sin^2(delta)) / r), shadowing, the room's
// shapes at a scan height, and the same ranges through the whole lidar chain (waveform, noise,
// leading-edge detection, calibration).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/lidar/shapes.hpp"
#include "fogradar/propagation/chamber.hpp"
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

// Today's [[lidar.background]] segments are segment shapes: the same segments given as the room's
// shapes instead give the same scan, echo for echo.
TEST(LidarRoom, BackgroundSegmentsAreSegmentShapes) {
  LidarParams with_background;
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

}  // namespace
}  // namespace fogradar::lidar
