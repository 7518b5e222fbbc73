// Key declarations (core/keys.hpp): the allowed intervals as messages and docs state them, and a
// table's keys named in full, reached through projections into nested structs and arrays, checked
// in declaration order with the bad-input messages core/error.hpp's checks give.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/keys.hpp"

namespace fogradar {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

TEST(Keys, DocNumbersAreShortestWithPlainExponents) {
  EXPECT_EQ(doc_number(77e9), "7.7e10");
  EXPECT_EQ(doc_number(1e-6), "1e-6");
  EXPECT_EQ(doc_number(2.5e-7), "2.5e-7");
  EXPECT_EQ(doc_number(0.5), "0.5");
  EXPECT_EQ(doc_number(-20.0), "-20");
  EXPECT_EQ(doc_number(1e10), "1e10");
  EXPECT_EQ(doc_number(10000.0), "10000");
}

TEST(Keys, IntervalsAsMessagesAndDocsStateThem) {
  const Interval c = closed(0.0, 40.0);
  EXPECT_EQ(c.constraint(), "in [0, 40]");
  EXPECT_EQ(c.doc(), "[0, 40]");
  EXPECT_TRUE(c.contains(0.0) && c.contains(40.0));
  EXPECT_FALSE(c.contains(-1e-300) || c.contains(nan) || c.contains(inf));
  const Interval oc = open_closed(0.0, 1e4);
  EXPECT_EQ(oc.constraint(), "in (0, 10000]");
  EXPECT_FALSE(oc.contains(0.0));
  EXPECT_TRUE(oc.contains(1e4));
  EXPECT_EQ(open(0.0, 1.0).constraint(), "in (0, 1)");
  EXPECT_FALSE(open(0.0, 1.0).contains(1.0));
  // The wording of require_positive; infinity is no positive number of a scenario.
  EXPECT_EQ(positive().constraint(), "finite and > 0");
  EXPECT_EQ(positive().doc(), "> 0");
  EXPECT_FALSE(positive().contains(inf));
  EXPECT_TRUE(positive().contains(1e-300));
  // Ten significant digits, as require_in_range writes them.
  EXPECT_EQ(closed(1e9, 300e9).constraint(), "in [1000000000, 3e+11]");
}

struct Point {
  double x_m = 1.0;
  unsigned count = 2;
};

struct Plan {
  Point origin;
  std::vector<Point> points = std::vector<Point>(3);
  bool fine = false;
};

KeyTable<Point> point_keys(std::string prefix) {
  KeyTable<Point> keys(std::move(prefix));
  keys.number("x_m", FOGRADAR_KEY_FIELD(x_m), closed(0.0, 10.0), "distance");
  keys.integer("count", FOGRADAR_KEY_FIELD(count), 1, 9, "how many");
  return keys;
}

KeyTable<Plan> plan_keys() {
  KeyTable<Plan> keys("plan.");
  keys.include(point_keys("plan.origin."), FOGRADAR_KEY_FIELD(origin));
  keys.table_array("points", FOGRADAR_KEY_FIELD(points), &point_keys, 4, "≤ 4", "the points");
  keys.boolean("fine", FOGRADAR_KEY_FIELD(fine), "fine grid").with_check([](const Plan& p) {
    if (p.fine && p.origin.count < 2) throw_invalid("plan.fine", "true", "false with count 1");
  });
  return keys;
}

std::string rejected(const Plan& plan) {
  try {
    plan_keys().check(plan);
  } catch (const InvalidParameter& e) {
    return e.field() + " | " + e.what();
  }
  return "accepted";
}

TEST(Keys, IncludedKeysAreNamedInFullAndReachTheirField) {
  const KeyTable<Plan> keys = plan_keys();
  std::vector<std::string> names;
  for (const Key<Plan>& key : keys.keys()) names.push_back(key.name);
  EXPECT_EQ(names, (std::vector<std::string>{"plan.origin.x_m", "plan.origin.count", "plan.points",
                                             "plan.fine"}));
  EXPECT_EQ(keys.keys()[0].section(), "plan.origin");
  EXPECT_EQ(keys.keys()[0].short_name(), "x_m");
  Plan plan;
  keys.keys()[0].set_number(plan, 7.5);
  keys.keys()[1].set_integer(plan, 4);
  EXPECT_EQ(plan.origin.x_m, 7.5);
  EXPECT_EQ(plan.origin.count, 4u);
  const Plan& read_only = plan;
  EXPECT_EQ(keys.keys()[0].get_number(read_only), 7.5);
  EXPECT_EQ(keys.keys()[2].array_size(read_only), 3u);
  // An element's keys are named with its index and reach that element.
  KeyTable<Plan> second;
  keys.keys()[2].array_element(1, second);
  ASSERT_EQ(second.keys().size(), 2u);
  EXPECT_EQ(second.keys()[0].name, "plan.points[1].x_m");
  second.keys()[0].set_number(plan, 3.0);
  EXPECT_EQ(plan.points[1].x_m, 3.0);
  EXPECT_EQ(plan.points[0].x_m, 1.0);
}

TEST(Keys, ChecksNameTheKeyTheValueAndTheRange) {
  EXPECT_EQ(rejected(Plan{}), "accepted");
  Plan far;
  far.origin.x_m = 12.0;
  EXPECT_EQ(rejected(far), "plan.origin.x_m | plan.origin.x_m = 12: must be in [0, 10]");
  Plan none;
  none.points[2].count = 0;
  EXPECT_EQ(rejected(none),
            "plan.points[2].count | plan.points[2].count = 0: must be an integer in [1, 9]");
  Plan many;
  many.points.resize(5);
  EXPECT_EQ(rejected(many), "plan.points | plan.points = 5: must be a count in [0, 4]");
  Plan fine;
  fine.fine = true;
  fine.origin.count = 1;
  EXPECT_EQ(rejected(fine), "plan.fine | plan.fine = 'true': must be false with count 1");
  // Declaration order: the first key that breaks its range is the one named.
  Plan both = far;
  both.points[0].x_m = nan;
  EXPECT_EQ(rejected(both).substr(0, 16), "plan.origin.x_m ");
}

TEST(Keys, AKeyThatTakesNoEffectIsNotChecked) {
  KeyTable<Point> keys;
  keys.number("x_m", FOGRADAR_KEY_FIELD(x_m), closed(0.0, 10.0), "distance")
      .when([](const Point& p) { return p.count > 1; }, "with count > 1");
  Point p{.x_m = -5.0, .count = 1};
  EXPECT_FALSE(keys.keys()[0].takes_effect(p));
  EXPECT_NO_THROW(keys.check(p));
  p.count = 2;
  EXPECT_THROW(keys.check(p), InvalidParameter);
}

// A bound other keys set (Key::within): the range as usual where some value meets it, and in words
// where none can, not as an interval such as [16, 5].
TEST(Keys, ACrossKeyBoundThatNoValueMeetsSaysSo) {
  struct Pair {
    std::int64_t samples = 8;
    double room = 5.12;  // the other key: at most this many samples
  };
  KeyTable<Pair> keys("p.");
  keys.integer("samples", FOGRADAR_KEY_FIELD(samples), 16, 65536, "n").within([](const Pair& p) {
    return CrossBound{.range = closed(16.0, std::floor(p.room)),
                      .low_text = "16",
                      .high_text = message_number(std::floor(p.room)),
                      .integer = true,
                      .note = ": they fit in p.room = " + message_number(p.room)};
  });
  const auto message = [&keys](const Pair& p) -> std::string {
    try {
      keys.check(p);
    } catch (const InvalidParameter& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_EQ(message({.samples = 20, .room = 5.12}),
            "p.samples = 20: must be an integer >= 16 and <= 5: they fit in p.room = 5.12; no "
            "integer is both: the keys named leave it no value");
  EXPECT_EQ(message({.samples = 20, .room = 18.5}),
            "p.samples = 20: must be an integer in [16, 18]: they fit in p.room = 18.5");
  EXPECT_EQ(message({.samples = 18, .room = 18.5}), "accepted");
  // Emptiness as the values the key takes see it: integers in (2, 3), numbers in [1, 1).
  const auto bound = [](Interval range, bool integer) {
    return CrossBound{
        .range = range, .low_text = "q = 7", .high_text = "5", .integer = integer, .note = ""};
  };
  EXPECT_TRUE(bound(open(2.0, 3.0), true).empty());
  EXPECT_FALSE(bound(open(2.0, 3.0), false).empty());
  EXPECT_FALSE(bound(closed(3.0, 3.0), true).empty());
  EXPECT_TRUE(bound({.low = 1.0, .high = 1.0, .high_open = true}, false).empty());
  EXPECT_EQ(bound(open_closed(7.0, 5.0), false).constraint(),
            "a number > q = 7 and <= 5; no number is both: the keys named leave it no value");
  EXPECT_EQ(bound(open_closed(1.0, 5.0), false).constraint(), "in (q = 7, 5]");
}

// One table of names gives the printing, the parsing and the key's choices. The names, the refusal
// message and the documented set are written here independently of the table.
enum class Shade { light, dark, dim };
constexpr auto kShadeNames =
    enum_names<Shade>({{Shade::dark, "dark"}, {Shade::light, "light"}, {Shade::dim, "dim"}});
static_assert(kShadeNames.name(Shade::light) == "light");
static_assert(kShadeNames.name(static_cast<Shade>(7)) == "?");

struct Lamp {
  Shade shade = Shade::light;
};

TEST(EnumNames, ParseNameAndKeyShareOneTable) {
  for (const Shade s : {Shade::light, Shade::dark, Shade::dim}) {
    EXPECT_EQ(kShadeNames.parse(kShadeNames.name(s), "lamp.shade"), s);
  }
  EXPECT_EQ(kShadeNames.allowed(), "one of dark, light, dim");
  EXPECT_EQ(kShadeNames.names(), (std::vector<std::string>{"dark", "light", "dim"}));
  try {
    kShadeNames.parse("Dark", "lamp.shade");
    ADD_FAILURE() << "accepted a name in another case";
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.field(), "lamp.shade");
    EXPECT_STREQ(error.what(), "lamp.shade = 'Dark': must be one of dark, light, dim");
  }
  KeyTable<Lamp> keys("lamp.");
  const Key<Lamp>& key = keys.choice("shade", FOGRADAR_KEY_FIELD(shade), kShadeNames, "its shade");
  EXPECT_EQ(key.allowed, "`dark`, `light`, `dim`");
  EXPECT_EQ(key.choices, (std::vector<std::string>{"dark", "light", "dim"}));
  Lamp lamp;
  key.set_text(lamp, "dim");
  EXPECT_EQ(lamp.shade, Shade::dim);
  EXPECT_EQ(key.get_text(lamp), "dim");
  EXPECT_THROW(key.set_text(lamp, "bright"), InvalidParameter);
}

}  // namespace
}  // namespace fogradar
