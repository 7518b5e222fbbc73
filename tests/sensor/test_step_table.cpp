// The step table's generators against texts written out by hand. References:
//   [RFC4180] Y. Shafranovich, "Common Format and MIME Type for Comma-Separated Values (CSV)
//             Files", RFC 4180 (2005), §2: a field holding a comma, a quote or a line break is
//             enclosed in quotes, a quote inside one doubled.
//   [RFC6901] P. Bryan et al., "JavaScript Object Notation (JSON) Pointer", RFC 6901 (2013): "/a/b"
//             names member b of member a, "/a/0" element 0 of array a.
//   [C17]     ISO/IEC 9899:2018 §7.21.6.1, printf's %.Nf (N decimals, "-0.000" keeps its sign) and
//             %.Ng (N significant digits, trailing zeros removed).
// Exact text: every expectation is a string compared byte for byte.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "fogradar/sensor/step_table.hpp"

namespace fogradar::sensor {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

StepTable two_steps() {
  StepTable t(2);
  t.integer("active_layers", "", {0, 1});
  t.number("median", "dbsm", {10.25, nan});
  t.number("rate", "", {1.0 / 3.0, 0.5}).csv_digits(10);
  t.numbers("outliers", "", {{1.5, -2.0}, {}});
  t.text("note", "", {"plain", "a, \"quoted\" one"});
  return t;
}

TEST(StepTable, CsvHeadersAreNameAndUnitAndNumbersKeepTheirDeclaredDigits) {
  // The shortest exact form of 10.25, NaN as an empty field, 1/3 to 10 significant digits,
  // a list joined by ';', integers as written.
  EXPECT_EQ(two_steps().csv(),
            "active_layers,median_dbsm,rate,outliers,note\n"
            "0,10.25,0.3333333333,1.5;-2,plain\n"
            "1,,0.5,,\"a, \"\"quoted\"\" one\"\n");
}

TEST(StepTable, CsvFieldsAreQuotedAsRfc4180Says) {
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
}

TEST(StepTable, SweepCellsAreTheCsvFieldsUnquotedAndOnlyTheCsvColumns) {
  StepTable t = two_steps();
  t.number("json_only", "", {1.0, 2.0}).in_csv(false);
  EXPECT_EQ(t.csv_headers(),
            (std::vector<std::string>{"active_layers", "median_dbsm", "rate", "outliers", "note"}));
  const std::vector<std::vector<std::string>> cells = t.csv_cells();
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[1], (std::vector<std::string>{"1", "", "0.5", "", "a, \"quoted\" one"}));
}

TEST(StepTable, JsonPlacesEachColumnAtItsPointer) {
  StepTable t(2);
  t.integer("active_layers", "", {0, 1});
  t.number("mean", "", {2.5, nan}).in_json("/intensity/mean");
  t.integer("n", "", {3, 0}).in_json("/intensity/n").in_csv(false);
  t.number("low", "db", {-1.0, nan}).in_json("/interval_db/0");
  t.number("high", "db", {1.0, nan}).in_json("/interval_db/1");
  t.numbers("outliers", "", {{4.0}, {}});
  t.integer("csv_only", "", {1, 0}).in_json("");
  const nlohmann::json expected = nlohmann::json::parse(R"([
    {"active_layers": 0, "intensity": {"mean": 2.5, "n": 3}, "interval_db": [-1.0, 1.0],
     "outliers": [4.0]},
    {"active_layers": 1, "intensity": {"mean": null, "n": 0}, "interval_db": [null, null],
     "outliers": []}])");
  EXPECT_EQ(t.json(), expected) << t.json().dump(1);
  // Integers stay integers and numbers numbers in the written text.
  EXPECT_EQ(t.json()[0]["active_layers"].dump(), "0");
  EXPECT_EQ(t.json()[0]["interval_db"][1].dump(), "1.0");
}

TEST(StepTable, PrintedCellsAreRightAlignedWithTwoHeadingLines) {
  StepTable t(2);
  t.integer("active_layers", "", {0, 12});
  t.number("rate", "", {0.5, 0.25});
  t.number("shift", "db", {-0.0001, nan});
  t.print("active_layers", {.heads = {"layers", ""}, .width = 6});
  t.print("rate", {.heads = {"det.", "%"}, .width = 6, .precision = 1, .scale = 100.0});
  // printf keeps the sign of -0.000 [C17]; a missing value shows as an en dash, one column wide.
  t.print("shift_db", {.heads = {"shift", "dB"}, .width = 7, .missing = "\u2013"});
  EXPECT_EQ(t.printed(),
            "layers   det.   shift\n"
            "            %      dB\n"
            "     0   50.0  -0.000\n"
            "    12   25.0       \u2013\n");
}

TEST(StepTable, AHeadingSpansTheColumnsAfterItThatHaveNone) {
  StepTable t(1);
  t.number("low", "", {-0.25});
  t.number("high", "", {0.125});
  t.number("p", "", {0.6903});
  t.print("low", {.heads = {"95 % interval"}, .width = 7});
  t.print("high", {.heads = {}, .width = 7});
  // %.3g: three significant digits, the trailing zero dropped [C17].
  t.print("p", {.heads = {"p"}, .width = 5, .general = true});
  EXPECT_EQ(t.printed(),
            "  95 % interval     p\n"
            " -0.250   0.125  0.69\n");
}

TEST(StepTable, LayoutIndentsAndJoinsAndSignlessZeroFollowsTheStatsFormat) {
  StepTable t(2);
  t.integer("active_layers", "", {0, 1});
  t.number("contrast", "", {-0.0004, nan});
  t.integer("clear", "", {564, 560});
  t.print_layout("  ", "");
  t.print("active_layers", {.heads = {"layers"}, .width = 6});
  t.print("contrast", {.heads = {"contrast"}, .width = 10, .signless_zero = true});
  // A cell wider than its width is not cut; width 0 adds no padding.
  t.print("clear", {.heads = {" (clear)"}, .width = 0, .prefix = " (", .suffix = ")"});
  EXPECT_EQ(t.printed(),
            "  layers  contrast (clear)\n"
            "       0     0.000 (564)\n"
            "       1           (560)\n");
}

TEST(StepTable, ALookupOfAnUnknownColumnNamesIt) {
  const StepTable t = two_steps();
  EXPECT_EQ(t.column("median_dbsm").text(0), "10.25");
  try {
    (void)t.column("mean_dbsm");
    FAIL() << "no throw";
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("mean_dbsm"), std::string::npos);
  }
}

}  // namespace
}  // namespace fogradar::sensor
