// Sweep files and their grid (sweep/spec.hpp): axes and ranges, ordering by value, seeds, arrays
// and element keys as axes against the scenario reader, every bad sweep file refused with its key
// and line, and the [uncertain] draws against their distributions' known quantiles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <utility>
#include <variant>

#include "fogradar/core/error.hpp"
#include "fogradar/radar/sensor.hpp"
#include "fogradar/sweep/spec.hpp"
#include "validation.hpp"

namespace fogradar::sweep {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

constexpr const char* kGroup = "experiment: statistics";

SweepSpec parse(const std::string& text) { return parse_sweep(text, "s.toml", "."); }

// The key an InvalidParameter names and its message, or "none".
std::pair<std::string, std::string> refusal(const std::string& text) {
  try {
    expand(parse(text));
  } catch (const InvalidParameter& e) {
    return {e.field(), e.what()};
  }
  return {"none", ""};
}

TEST(SweepFile, AxesValuesRangesAndZippedKeys) {
  const SweepSpec spec = parse(R"(
[sweep]
replications = 2
[[axis]]
key = "fog.extinction_per_km"
range = { from = 100.0, to = 1000.0, count = 3, spacing = "log" }
[[axis]]
keys = ["radar.centre_frequency_hz", "radar.sweep_bandwidth_hz"]
values = [[76.5e9, 1e9], [24.125e9, 250e6]]
[[axis]]
key = "radar.processing.cfar.training_cells"
range = { from = 8, to = 16, count = 3 }
)");
  ASSERT_EQ(spec.axes.size(), 3u);
  EXPECT_EQ(spec.replications, 2u);
  // log spacing: the ends as written, the middle the geometric mean.
  EXPECT_EQ(spec.axes[0].positions[0][0].toml, "100.0");
  EXPECT_EQ(spec.axes[0].positions[2][0].toml, "1000.0");
  validate({.id = "sweep.axis.log_spacing.middle",
            .group = kGroup,
            .quantity = "middle value of a 3-point log-spaced axis",
            .unit = "1/km",
            .conditions = "fog.extinction_per_km from 100 to 1000, count 3, spacing log",
            .reference = std::sqrt(100.0 * 1000.0),
            .source = "closed form: geometric mean sqrt(100 x 1000)",
            .value = *spec.axes[0].positions[1][0].number,
            .tolerance = 1e-9,
            .kind = Tolerance::absolute});
  // Integer ends with an even step: integers (an integer key takes them).
  EXPECT_EQ(spec.axes[2].positions[1][0].toml, "12");
  const std::vector<Point> points = expand(spec);
  ASSERT_EQ(points.size(), 3u * 2u * 3u);
  // The first axis outermost, each axis by value: 24 GHz before 76.5 GHz though listed after.
  // Numbers as their shortest exact text (std::to_chars).
  EXPECT_EQ(points[0].label(),
            "fog.extinction_per_km = 100.0, radar.centre_frequency_hz = 2.4125e+10, "
            "radar.sweep_bandwidth_hz = 2.5e+08, radar.processing.cfar.training_cells = 8");
  EXPECT_EQ(points[1].values[3].second.text, "12");
  EXPECT_EQ(points[3].values[1].second.text, "7.65e+10");
  EXPECT_EQ(points[6].values[0].second.toml, points[7].values[0].second.toml);
  // Each point is the base scenario with its values: the zipped pair set together.
  const std::string toml = experiment::to_toml(points[0].scenario);
  EXPECT_NE(toml.find("centre_frequency_hz = 2.4125e+10"), std::string::npos);
  EXPECT_NE(toml.find("sweep_bandwidth_hz = 2.5e+08"), std::string::npos);
  EXPECT_NE(toml.find("extinction_per_km = 100.0"), std::string::npos);
}

TEST(SweepFile, SeedsAreCommonOrFollowTheValuesNeverThePosition) {
  const std::string axis = "[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = ";
  const std::vector<Point> common = expand(parse(axis + "[300.0, 900.0]\n"));
  EXPECT_EQ(common[0].seed, experiment::paper_scenario().experiment.seed);
  EXPECT_EQ(common[1].seed, common[0].seed);
  const std::string by_values = "[sweep]\nseed = \"by_values\"\n" + axis;
  const std::vector<Point> two = expand(parse(by_values + "[300.0, 900.0]\n"));
  const std::vector<Point> three = expand(parse(by_values + "[100.0, 900.0, 300.0]\n"));
  EXPECT_NE(two[0].seed, two[1].seed);
  // Adding a value leaves the other points' seeds (and so their numbers) as they were.
  EXPECT_EQ(two[0].seed, three[1].seed);
  EXPECT_EQ(two[1].seed, three[2].seed);
  EXPECT_LT(two[0].seed, std::uint64_t{1} << 63);  // a TOML integer
  EXPECT_EQ(two[1].scenario.experiment.seed, two[1].seed);
}

TEST(SweepFile, EveryBadSweepFileIsRefusedNamingItsKeyAndLine) {
  const auto expect = [](const std::string& text, const std::string& key, const std::string& part) {
    const auto [field, message] = refusal(text);
    EXPECT_EQ(field, key) << text;
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_EQ(message.rfind("s.toml:", 0), 0u) << message;
  };
  expect("[sweep]\nfrobnicate = 1\n", "sweep.frobnicate", "unknown key 'sweep.frobnicate'");
  expect("[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = []\n", "axis[0].values",
         "must be a non-empty array");
  expect(
      "[[axis]]\nkeys = [\"radar.centre_frequency_hz\", \"radar.sweep_bandwidth_hz\"]\n"
      "values = [[76.5e9, 1e9], [24e9]]\n",
      "axis[0].values", "zipped axes of one length");
  // A value out of the key's range: the axis, the value and the scenario's own range.
  expect("[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = [900.0, 2e6]\n",
         "fog.extinction_per_km", "s.toml:1: axis[0] value 2e+06 of fog.extinction_per_km: ");
  const auto [field, message] =
      refusal("[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = [900.0, 2e6]\n");
  EXPECT_NE(message.find("must be in [0, 1000000]"), std::string::npos) << message;
  // An unknown key is refused when the file is read, at the axis's key, with the section's keys.
  expect("[[axis]]\nkey = \"radar.no_such_key\"\nvalues = [1.0]\n", "axis[0].key",
         "s.toml:2: axis[0]: 'radar.no_such_key' is no scenario key (keys of [radar]: ");
  expect(
      "[uncertain]\nsetups = 8\n[uncertain.keys.\"target.no_such_key\"]\n"
      "distribution = \"uniform\"\nlow = 0.4\nhigh = 0.6\n",
      "uncertain.keys.target.no_such_key", "'target.no_such_key' is no scenario key");
  // A key of an element the base does not have (the paper chamber lists no layers).
  expect("[[axis]]\nkey = \"chamber.layers[2].fog.lwc_g_per_m3\"\nvalues = [0.1, 0.2]\n",
         "axis[0].key", "the base scenario's chamber.layers has no elements");
  expect("[[axis]]\nkey = \"experiment.seed\"\nvalues = [1, 2]\n", "axis[0].key",
         "set by the sweep");
  expect(
      "[[axis]]\nkey = \"fog.extinction_per_km\"\nrange = { from = 0.0, to = 10.0, count = 3, "
      "spacing = \"log\" }\n",
      "axis[0].range.from", "must be > 0 for spacing = \"log\"");
  expect(
      "[uncertain]\nsetups = 8\n[uncertain.keys.\"radar.height_m\"]\n"
      "distribution = \"normal\"\nmean = 0.5\nstd = -0.1\n",
      "uncertain.keys.radar.height_m.std", "must be > 0");
  expect(
      "[uncertain]\nsetups = 8\n[uncertain.keys.\"radar.height_m\"]\n"
      "distribution = \"uniform\"\nlow = 0.6\nhigh = 0.4\n",
      "uncertain.keys.radar.height_m.high", "must be > low");
  expect(
      "[uncertain]\nsetups = 8\n[uncertain.keys.\"radar.height_m\"]\n"
      "distribution = \"beta\"\n",
      "uncertain.keys.radar.height_m.distribution", "must be one of");
  // A draw outside the key's range: named as the uncertain key that drew it.
  expect(
      "[uncertain]\nsetups = 8\n[uncertain.keys.\"radar.height_m\"]\n"
      "distribution = \"uniform\"\nlow = -5.0\nhigh = -4.0\n",
      "uncertain.keys.radar.height_m", "drew -");
  expect("[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = [900.0\n", "toml", "malformed TOML");
}

// The layered example's chamber as a base, with the third layer's fog written as `lwc`.
std::string layered_chamber(const std::string& lwc) {
  return "[chamber]\nsensor_gap_m = 2.0\ntarget_gap_m = 4.0\n"
         "[[chamber.layers]]\nlength_m = 1.0\n"
         "[[chamber.layers]]\nlength_m = 1.0\nfog = { lwc_g_per_m3 = 0.0 }\n"
         "[[chamber.layers]]\nlength_m = 1.0\nfog = { lwc_g_per_m3 = " +
         lwc +
         ", droplets = { median_diameter_m = 4e-6 } }\n"
         "[[chamber.layers]]\nlength_m = 1.0\n"
         "[experiment]\nswitching_order = \"target_first\"\n";
}

// Any key a scenario file takes is an axis: an array (a listed switching order) and a key of one
// element of an array of tables (a layer's fog), each point the scenario a file giving that value
// reads to (the scenario reader as the reference).
TEST(SweepFile, ArraysAndElementKeysAreAxesAsAScenarioFileGivesThem) {
  const std::vector<Point> orders =
      expand(parse("[[axis]]\nkey = \"experiment.switching_order\"\nvalues = [[3, 1, 2, 0], "
                   "\"target_first\"]\n"));
  ASSERT_EQ(orders.size(), 2u);
  EXPECT_EQ(orders[0].values[0].second.text, "[3, 1, 2, 0]");  // text after '[' sorts first
  const auto over_paper = [](const std::string& text) {
    return experiment::to_toml(
        experiment::parse_scenario_over(experiment::paper_scenario(), text, "reference.toml"));
  };
  EXPECT_EQ(experiment::to_toml(orders[0].scenario),
            over_paper("[experiment]\nswitching_order = [3, 1, 2, 0]\n"));
  EXPECT_EQ(experiment::to_toml(orders[1].scenario),
            over_paper("[experiment]\nswitching_order = \"target_first\"\n"));

  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "fogradar_sweep_element_keys";
  std::filesystem::create_directories(dir);
  { std::ofstream(dir / "layered.toml") << layered_chamber("1.2"); }
  const SweepSpec spec = parse_sweep(
      "[sweep]\nbase = \"layered.toml\"\n[[axis]]\nkey = \"chamber.layers[2].fog.lwc_g_per_m3\"\n"
      "values = [0.5, 0.1]\n[[axis]]\nkey = \"chamber.layers[0].length_m\"\nvalues = [0.5]\n",
      "s.toml", dir);
  const std::vector<Point> layers = expand(spec);
  ASSERT_EQ(layers.size(), 2u);
  for (const auto& [point, lwc] : {std::pair{0, "0.1"}, std::pair{1, "0.5"}}) {
    std::string file = layered_chamber(lwc);
    file.replace(file.find("length_m = 1.0"), 14, "length_m = 0.5");
    EXPECT_EQ(experiment::to_toml(layers[point].scenario),
              experiment::to_toml(experiment::parse_scenario(file, "reference.toml")))
        << "point " << point;
  }

  // Refusals name the axis, the value and the element's key with its range or what it takes.
  const auto refused = [&](const std::string& axis) -> std::pair<std::string, std::string> {
    try {
      expand(parse_sweep("[sweep]\nbase = \"layered.toml\"\n[[axis]]\n" + axis, "s.toml", dir));
    } catch (const InvalidParameter& e) {
      return {e.field(), e.what()};
    }
    return {"none", ""};
  };
  auto [field, message] =
      refused("key = \"chamber.layers[2].fog.lwc_g_per_m3\"\nvalues = [0.5, 200.0]\n");
  EXPECT_EQ(field, "chamber.layers[2].fog.lwc_g_per_m3");
  EXPECT_NE(message.find("s.toml:3: axis[0] value 200.0 of chamber.layers[2].fog.lwc_g_per_m3: "
                         "chamber.layers[2].fog.lwc_g_per_m3 = 200.0: must be in [0, 100]"),
            std::string::npos)
      << message;
  std::tie(field, message) =
      refused("key = \"chamber.layers[2].fog.lwc_g_per_m3\"\nvalues = [\"wet\"]\n");
  // As a scenario file's reader states it: the value as TOML writes it, the key's range.
  EXPECT_NE(
      message.find("chamber.layers[2].fog.lwc_g_per_m3 = 'wet': must be a number in [0, 100]"),
      std::string::npos)
      << message;
  std::tie(field, message) = refused("key = \"chamber.layers[4].length_m\"\nvalues = [1.0]\n");
  EXPECT_EQ(field, "axis[0].key");
  EXPECT_NE(message.find("s.toml:4: axis[0]: 'chamber.layers[4].length_m': the base scenario's "
                         "chamber.layers has elements 0 … 3"),
            std::string::npos)
      << message;
  std::tie(field, message) = refused("key = \"chamber.layers[1].fog.wetness\"\nvalues = [1.0]\n");
  EXPECT_NE(message.find("'chamber.layers[1].fog.wetness' is no scenario key"), std::string::npos)
      << message;
  std::tie(field, message) = refused(
      "key = \"chamber.layers[1].length_m\"\nvalues = [1.0]\n[[axis]]\nkey = \"chamber.layers\"\n"
      "values = [[{ length_m = 2.0 }]]\n");
  EXPECT_NE(message.find("which is swept whole too"), std::string::npos) << message;
  std::filesystem::remove_all(dir);
}

// Latin hypercube: each key's N draws fall one in each of its N equiprobable strata, exactly; a
// collapsed (one-value) distribution draws that value every time.
TEST(Uncertain, LatinHypercubeDrawsFillEveryStratumOnce) {
  const SweepSpec spec = parse(R"(
[uncertain]
setups = 50
[uncertain.keys."radar.height_m"]
distribution = "normal"
mean = 0.5
std = 0.01
[uncertain.keys."chamber.room.floor.reflection_coefficient"]
distribution = "uniform"
low = -0.9
high = -0.5
[uncertain.keys."target.micro_motion_std_m"]
distribution = "discrete"
values = [0.0002]
)");
  const std::vector<Point> points = expand(spec);
  ASSERT_EQ(points.size(), 1u);
  ASSERT_EQ(points[0].setups.size(), 50u);
  // The strata through each distribution's own CDF (the normal's by erfc, not the code's Boost).
  const auto normal_cdf = [](double x) {
    return 0.5 * std::erfc(-(x - 0.5) / (0.01 * std::sqrt(2.0)));
  };
  std::vector<int> normal_strata, uniform_strata;
  for (const auto& setup : points[0].setup_values) {
    ASSERT_EQ(setup.size(), 3u);
    const auto drawn = [&](const std::string& key) {
      return *std::find_if(setup.begin(), setup.end(),
                           [&](const auto& v) { return v.first == key; });
    };
    normal_strata.push_back(
        static_cast<int>(std::floor(normal_cdf(*drawn("radar.height_m").second.number) * 50.0)));
    uniform_strata.push_back(static_cast<int>(std::floor(
        (*drawn("chamber.room.floor.reflection_coefficient").second.number + 0.9) / 0.4 * 50.0)));
    EXPECT_EQ(*drawn("target.micro_motion_std_m").second.number, 0.0002);
  }
  std::sort(normal_strata.begin(), normal_strata.end());
  std::sort(uniform_strata.begin(), uniform_strata.end());
  // Sorted, the strata must be 0 .. 49: the largest |stratum - k| over k is 0.
  int normal_offset = 0, uniform_offset = 0;
  for (int k = 0; k < 50; ++k) {
    normal_offset = std::max(normal_offset, std::abs(normal_strata[k] - k));
    uniform_offset = std::max(uniform_offset, std::abs(uniform_strata[k] - k));
  }
  validate({.id = "sweep.uncertain.latin_hypercube.normal.strata",
            .group = kGroup,
            .quantity = "largest |k-th sorted stratum - k| of 50 Latin hypercube draws",
            .unit = "strata",
            .conditions = "radar.height_m normal, mean 0.5, std 0.01, 50 setups",
            .reference = 0.0,
            .source = "definition of Latin hypercube sampling; strata by the normal CDF (erfc)",
            .value = static_cast<double>(normal_offset),
            .tolerance = 0.0,
            .kind = Tolerance::absolute});
  validate(
      {.id = "sweep.uncertain.latin_hypercube.uniform.strata",
       .group = kGroup,
       .quantity = "largest |k-th sorted stratum - k| of 50 Latin hypercube draws",
       .unit = "strata",
       .conditions = "chamber.room.floor.reflection_coefficient uniform on [-0.9, -0.5], 50 setups",
       .reference = 0.0,
       .source = "definition of Latin hypercube sampling; strata by the uniform CDF",
       .value = static_cast<double>(uniform_offset),
       .tolerance = 0.0,
       .kind = Tolerance::absolute});
  // Each setup is the point's scenario with its draws, and its seed.
  EXPECT_EQ(points[0].setups[7].experiment.seed, points[0].seed);
  for (const auto& [key, value] : points[0].setup_values[7]) {
    EXPECT_NE(experiment::to_toml(points[0].setups[7])
                  .find(key.substr(key.rfind('.') + 1) + " = " + value.toml),
              std::string::npos)
        << key;
  }
}

// Discrete numbers draw the values they drew before discrete keys took strings and booleans: the
// draws of this file pinned from the build before that change (same seed, same uniforms).
TEST(Uncertain, DiscreteNumberDrawsAreUnchanged) {
  const auto drawn = [](const std::string& sampling, const std::string& key) {
    const std::vector<Point> points = expand(parse(R"(
[uncertain]
setups = 12
sampling = ")" + sampling + R"("
[uncertain.keys."target.micro_motion_std_m"]
distribution = "discrete"
values = [0.0001, 0.0002, 0.0004]
weights = [1, 2, 1]
[uncertain.keys."radar.height_m"]
distribution = "discrete"
values = [0.45, 0.5, 0.55, 0.6]
)"));
    std::vector<std::string> texts;
    for (const auto& setup : points[0].setup_values) {
      for (const auto& [k, value] : setup) {
        if (k == key) texts.push_back(value.toml);
      }
    }
    return texts;
  };
  using Texts = std::vector<std::string>;
  EXPECT_EQ(drawn("latin_hypercube", "radar.height_m"),
            (Texts{"0.6", "0.55", "0.45", "0.55", "0.55", "0.5", "0.6", "0.5", "0.45", "0.6", "0.5",
                   "0.45"}));
  EXPECT_EQ(drawn("latin_hypercube", "target.micro_motion_std_m"),
            (Texts{"4e-04", "4e-04", "2e-04", "2e-04", "2e-04", "2e-04", "2e-04", "2e-04", "4e-04",
                   "1e-04", "1e-04", "1e-04"}));
  EXPECT_EQ(drawn("monte_carlo", "radar.height_m"),
            (Texts{"0.45", "0.45", "0.55", "0.45", "0.6", "0.5", "0.45", "0.5", "0.6", "0.45",
                   "0.5", "0.45"}));
  EXPECT_EQ(drawn("monte_carlo", "target.micro_motion_std_m"),
            (Texts{"1e-04", "4e-04", "2e-04", "2e-04", "2e-04", "4e-04", "2e-04", "2e-04", "2e-04",
                   "1e-04", "2e-04", "2e-04"}));
}

// Strings drawn by weight: 400 Monte Carlo draws of "vertical" at weight 3 of 4. The count of
// "vertical" is binomial(400, 0.75), sd sqrt(400 * 0.75 * 0.25) = 8.66: its share within 5 sd,
// 0.75 +- 0.108; and each setup's scenario holds the polarisation its setup drew.
TEST(Uncertain, DiscreteStringsDrawByWeightIntoTheScenario) {
  const std::vector<Point> points = expand(parse(R"(
[uncertain]
setups = 400
sampling = "monte_carlo"
[uncertain.keys."radar.polarisation"]
distribution = "discrete"
values = ["horizontal", "vertical"]
weights = [1, 3]
)"));
  ASSERT_EQ(points[0].setups.size(), 400u);
  int vertical = 0;
  for (std::size_t s = 0; s < 400; ++s) {
    const Value& value = points[0].setup_values[s][0].second;
    ASSERT_TRUE(value.text == "horizontal" || value.text == "vertical") << value.text;
    EXPECT_EQ(value.toml, "\"" + value.text + "\"");
    EXPECT_FALSE(value.number.has_value());
    EXPECT_EQ(radar::to_string(
                  points[0].setups[s].params<radar::SensorParams>("radar").radar.polarisation),
              value.text)
        << "setup " << s;
    vertical += value.text == "vertical" ? 1 : 0;
  }
  const double half_width = 5.0 * std::sqrt(0.75 * 0.25 / 400.0);
  validate({.id = "sweep.uncertain.monte_carlo.discrete_strings.share",
            .group = kGroup,
            .quantity = "share of \"vertical\" among 400 Monte Carlo draws",
            .unit = "1",
            .conditions = "radar.polarisation discrete, [\"horizontal\", \"vertical\"], weights "
                          "[1, 3], 400 setups",
            .reference = 0.75,
            .source = "binomial(400, 0.75): 5 standard deviations sqrt(p (1 - p) / n)",
            .value = vertical / 400.0,
            .tolerance = 0.0,
            .kind = Tolerance::statistical,
            .samples = 400,
            .interval_low = 0.75 - half_width,
            .interval_high = 0.75 + half_width,
            .confidence = "5 binomial standard deviations"});
}

// Latin hypercube strata of two equal weights: the first half of the strata lie below 0.5, so an
// even number of setups draws each value exactly half the time; booleans drawn as booleans.
TEST(Uncertain, DiscreteStringsAndBooleansFillTheirStrata) {
  const std::vector<Point> points = expand(parse(R"(
[uncertain]
setups = 64
[uncertain.keys."radar.polarisation"]
distribution = "discrete"
values = ["horizontal", "vertical"]
[uncertain.keys."chamber.room.left_wall"]
distribution = "discrete"
values = [false, true]
)"));
  int vertical = 0, walls = 0;
  for (std::size_t s = 0; s < 64; ++s) {
    const auto& setup = points[0].setup_values[s];
    ASSERT_EQ(setup.size(), 2u);
    ASSERT_EQ(setup[0].first, "chamber.room.left_wall");
    EXPECT_EQ(points[0].setups[s].chamber.room.left_wall.present, setup[0].second.toml == "true");
    walls += setup[0].second.toml == "true" ? 1 : 0;
    vertical += setup[1].second.text == "vertical" ? 1 : 0;
  }
  EXPECT_EQ(vertical, 32);
  EXPECT_EQ(walls, 32);
}

// A switch and a key of its table in one setup (chamber.room.ceiling and its height_m): `true` is
// the table the key fills, whichever comes first; `false` contradicts the key and is refused,
// naming the switch.
TEST(Uncertain, ASwitchAndAKeyOfItsTableDrawnTogether) {
  const auto ceiling = [](const std::string& switch_values) {
    return "[uncertain]\nsetups = 4\n[uncertain.keys.\"chamber.room.ceiling\"]\n"
           "distribution = \"discrete\"\nvalues = " +
           switch_values +
           "\n[uncertain.keys.\"chamber.room.ceiling.height_m\"]\n"
           "distribution = \"uniform\"\nlow = 4.0\nhigh = 8.0\n";
  };
  const std::vector<Point> points = expand(parse(ceiling("[true]")));
  for (std::size_t s = 0; s < 4; ++s) {
    const auto& drawn = points[0].setup_values[s];
    ASSERT_EQ(drawn.size(), 2u);
    const auto& room = points[0].setups[s].chamber.room;
    EXPECT_TRUE(room.ceiling.present);
    EXPECT_EQ(room.ceiling.distance_m, *drawn[1].second.number);
  }
  const auto [field, message] = refusal(ceiling("[false]"));
  EXPECT_EQ(field, "uncertain.keys.chamber.room.ceiling");
  EXPECT_NE(message.find("chamber.room.ceiling = false leaves out [chamber.room.ceiling], but keys "
                         "of that table are given too"),
            std::string::npos)
      << message;
}

// A discrete key's values are numbers, strings or booleans of one type; a drawn value the key
// does not take is refused by the scenario's own check, naming the key, the value and the setup.
TEST(Uncertain, DiscreteValuesRefused) {
  const auto discrete = [](const std::string& key, const std::string& values) {
    return refusal("[uncertain]\nsetups = 8\n[uncertain.keys.\"" + key +
                   "\"]\ndistribution = \"discrete\"\nvalues = " + values + "\n");
  };
  auto [field, message] = discrete("radar.polarisation", R"(["horizontal", 1.0])");
  EXPECT_EQ(field, "uncertain.keys.radar.polarisation.values");
  EXPECT_NE(message.find("s.toml:5: uncertain.keys.radar.polarisation.values: must be a non-empty "
                         "array of numbers, strings or booleans, all of one type; values[1] is a "
                         "number, values[0] a string"),
            std::string::npos)
      << message;
  std::tie(field, message) = discrete("radar.polarisation", "[[1.0], [2.0]]");
  EXPECT_NE(message.find("values[0] is an array"), std::string::npos) << message;
  std::tie(field, message) = discrete("radar.polarisation", "[]");
  EXPECT_EQ(field, "uncertain.keys.radar.polarisation.values");
  EXPECT_NE(message.find("uncertain.keys.radar.polarisation.values: must be a non-empty array of "
                         "numbers, strings or booleans"),
            std::string::npos)
      << message;
  std::tie(field, message) = discrete("radar.polarisation", R"(["horizontal", "diagonal"])");
  EXPECT_EQ(field, "uncertain.keys.radar.polarisation");
  EXPECT_NE(message.find("uncertain.keys.radar.polarisation drew diagonal (setup "),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("of [uncertain])"), std::string::npos) << message;
  EXPECT_NE(message.find("horizontal"), std::string::npos) << message;
  EXPECT_NE(message.find("vertical"), std::string::npos) << message;
  // A base with a left wall: a drawn material reaches it, an unknown one is refused.
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "fogradar_sweep_drawn_material";
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "walled.toml")
        << "[chamber.room.left_wall]\ndistance_m = 3.0\nmaterial = \"concrete\"\n";
  }
  const auto walled = [&](const std::string& values) {
    return parse_sweep(
        "[sweep]\nbase = \"walled.toml\"\n[uncertain]\nsetups = 8\n"
        "[uncertain.keys.\"chamber.room.left_wall.material\"]\n"
        "distribution = \"discrete\"\nvalues = " +
            values + "\n",
        "s.toml", dir);
  };
  const std::vector<Point> points = expand(walled(R"(["concrete", "wood", "metal"])"));
  for (std::size_t s = 0; s < 8; ++s) {
    const auto& wall = points[0].setups[s].chamber.room.left_wall;
    ASSERT_TRUE(std::holds_alternative<propagation::Material>(wall.reflection));
    EXPECT_EQ(propagation::to_string(std::get<propagation::Material>(wall.reflection)),
              points[0].setup_values[s][0].second.text);
  }
  try {
    expand(walled(R"(["concrete", "unobtainium"])"));
    field = "none";
  } catch (const InvalidParameter& e) {
    field = e.field();
    message = e.what();
  }
  std::filesystem::remove_all(dir);
  EXPECT_EQ(field, "uncertain.keys.chamber.room.left_wall.material");
  EXPECT_NE(message.find("uncertain.keys.chamber.room.left_wall.material drew unobtainium (setup "),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("concrete"), std::string::npos) << message;
}

// Plain Monte Carlo: 2000 uniform draws; their empirical CDF within the Kolmogorov-Smirnov 99 %
// bound 1.628 / sqrt(n) of the true one (Massey 1951); and the same draws again for the same seed.
TEST(Uncertain, MonteCarloDrawsFollowTheirDistribution) {
  const std::string text = R"(
[uncertain]
setups = 2000
sampling = "monte_carlo"
[uncertain.keys."chamber.room.floor.reflection_coefficient"]
distribution = "truncated_normal"
mean = -0.7
std = 0.1
low = -0.8
high = -0.5
)";
  const std::vector<Point> points = expand(parse(text));
  std::vector<double> v;
  for (const auto& setup : points[0].setup_values) v.push_back(*setup[0].second.number);
  std::sort(v.begin(), v.end());
  const std::string conditions =
      "truncated normal, mean -0.7, std 0.1, on [-0.8, -0.5], 2000 Monte Carlo draws";
  validate({.id = "sweep.uncertain.monte_carlo.truncated_normal.smallest",
            .group = kGroup,
            .quantity = "smallest draw",
            .unit = "1",
            .conditions = conditions,
            .reference = -0.8,
            .source = "support of the truncated normal: low = -0.8",
            .value = v.front(),
            .tolerance = 0.0,
            .kind = Tolerance::at_least});
  validate({.id = "sweep.uncertain.monte_carlo.truncated_normal.largest",
            .group = kGroup,
            .quantity = "largest draw",
            .unit = "1",
            .conditions = conditions,
            .reference = -0.5,
            .source = "support of the truncated normal: high = -0.5",
            .value = v.back(),
            .tolerance = 0.0,
            .kind = Tolerance::at_most});
  // The truncated normal's CDF: (Phi(x) - Phi(a)) / (Phi(b) - Phi(a)).
  const auto phi = [](double x) { return 0.5 * std::erfc(-(x + 0.7) / (0.1 * std::sqrt(2.0))); };
  double worst = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double cdf = (phi(v[i]) - phi(-0.8)) / (phi(-0.5) - phi(-0.8));
    worst = std::max({worst, std::abs(cdf - static_cast<double>(i) / 2000.0),
                      std::abs(cdf - static_cast<double>(i + 1) / 2000.0)});
  }
  validate({.id = "sweep.uncertain.monte_carlo.truncated_normal.ks",
            .group = kGroup,
            .quantity = "Kolmogorov-Smirnov distance of the draws to the truncated normal CDF",
            .unit = "1",
            .conditions = conditions,
            .reference = 0.0,
            .source = "Kolmogorov-Smirnov 99 % bound 1.628 / sqrt(n) (Massey 1951); CDF "
                      "(Phi(x) - Phi(a)) / (Phi(b) - Phi(a))",
            .value = worst,
            .tolerance = 0.0,
            .kind = Tolerance::statistical,
            .samples = 2000,
            .interval_low = 0.0,
            .interval_high = 1.628 / std::sqrt(2000.0),
            .confidence = "99 % Kolmogorov-Smirnov bound (Massey 1951)"});
  const std::vector<Point> again = expand(parse(text));
  EXPECT_EQ(again[0].setup_values[1234][0].second.toml,
            points[0].setup_values[1234][0].second.toml);
}

}  // namespace
}  // namespace fogradar::sweep
