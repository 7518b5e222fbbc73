// A sensor's per-step statistics as typed columns, declared once: its <name>_summary.csv, the steps
// of its JSON summary, the table `fogradar run` prints, a sweep's rows and the Python summary
// DataFrame are all generated from them.
//
// A column has a name, a unit (its CSV header is name_unit, or the name alone without one) and one
// value per step: an integer, a number, a text, or a list of numbers (CSV: joined by ';'; JSON: an
// array). It appears in the CSV, in each step's JSON object at a JSON pointer (RFC 6901: "/n", a
// nested "/target_intensity/mean", an array element "/median_shift_ci95_db/0"), or in both. The
// printed table is a view over the columns in an order of its own, each with its heading and
// format; a column only the printed table shows (a derived figure, a decorated layer count) is
// declared printed_only().
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fogradar::sensor {

enum class ColumnType { integer, number, text, numbers };

// How the printed table shows one column: right-aligned in `width` characters (UTF-8 code points;
// a longer cell is not cut).
struct Printed {
  // Its heading, one entry per heading line; empty: the previous column's heading spans both.
  std::vector<std::string> heads = {};
  std::size_t width = 0;
  // Numbers: scale x value, in fixed notation with `precision` decimals (printf's %.Nf) or general
  // notation with `precision` significant digits (%.Ng).
  bool general = false;
  int precision = 3;
  double scale = 1.0;
  // A non-finite number's text; none: as printf writes it.
  std::optional<std::string> missing = std::nullopt;
  // stats::format_fixed's and format_number's rules: no sign on a value that prints as zero, NaN
  // as an empty cell.
  bool signless_zero = false;
  std::string prefix = {}, suffix = {};
};

struct Column {
  std::string name;
  std::string unit;
  ColumnType type = ColumnType::number;
  std::vector<std::int64_t> integers = {};
  std::vector<double> numbers = {};
  std::vector<std::string> texts = {};
  std::vector<std::vector<double>> lists = {};
  // CSV numbers: stats::format_number's significant digits, 0 the shortest exact form.
  int digits = 0;
  bool csv = true;
  // Where a step's JSON object holds the value (a JSON pointer); empty: not in the JSON.
  std::string json = {};

  // The CSV header: "mean_dbsm" for name "mean" and unit "dbsm".
  std::string header() const { return unit.empty() ? name : name + "_" + unit; }
  // Step `step`'s value as its CSV field before quoting (NaN: empty).
  std::string text(std::size_t step) const;
  nlohmann::json json_value(std::size_t step) const;
  // Step `step`'s printed cell, before alignment.
  std::string printed(std::size_t step, const Printed& how) const;

  // Fluent settings for a column just declared.
  Column& csv_digits(int significant_digits);
  Column& in_csv(bool shown);
  Column& in_json(std::string pointer);
  // Neither in the CSV nor in the JSON: a figure only the printed table shows.
  Column& printed_only();
};

class StepTable {
 public:
  StepTable() = default;
  explicit StepTable(std::size_t steps) : steps_(steps) {}

  std::size_t steps() const { return steps_; }
  const std::vector<Column>& columns() const { return columns_; }
  // Throws std::out_of_range naming `header` when no column has that header.
  const Column& column(std::string_view header) const;

  // Declares a column, in the CSV and at "/<header>" in the JSON; `values` holds one per step.
  Column& integer(std::string name, std::string unit, std::vector<std::int64_t> values);
  Column& number(std::string name, std::string unit, std::vector<double> values);
  Column& text(std::string name, std::string unit, std::vector<std::string> values);
  Column& numbers(std::string name, std::string unit, std::vector<std::vector<double>> values);

  // The same, the values taken from each of `steps` by `value`.
  template <class Steps, class F>
  Column& integer(std::string name, std::string unit, const Steps& steps, F value) {
    std::vector<std::int64_t> v;
    for (const auto& s : steps) v.push_back(static_cast<std::int64_t>(value(s)));
    return integer(std::move(name), std::move(unit), std::move(v));
  }
  template <class Steps, class F>
  Column& number(std::string name, std::string unit, const Steps& steps, F value) {
    std::vector<double> v;
    for (const auto& s : steps) v.push_back(static_cast<double>(value(s)));
    return number(std::move(name), std::move(unit), std::move(v));
  }
  template <class Steps, class F>
  Column& text(std::string name, std::string unit, const Steps& steps, F value) {
    std::vector<std::string> v;
    for (const auto& s : steps) v.emplace_back(value(s));
    return text(std::move(name), std::move(unit), std::move(v));
  }
  template <class Steps, class F>
  Column& numbers(std::string name, std::string unit, const Steps& steps, F value) {
    std::vector<std::vector<double>> v;
    for (const auto& s : steps) v.emplace_back(value(s));
    return numbers(std::move(name), std::move(unit), std::move(v));
  }

  // Adds the column of header `header` to the printed table, after those added before.
  void print(std::string_view header, Printed how);
  // The printed table's lines begin with `indent`; its cells are joined by `separator`.
  void print_layout(std::string indent, std::string separator);

  // The CSV columns' headers and, per step, their fields before quoting: a sweep's rows.
  std::vector<std::string> csv_headers() const;
  std::vector<std::vector<std::string>> csv_cells() const;
  // <name>_summary.csv: the header line and one line per step (RFC 4180 quoting).
  std::string csv() const;
  // One JSON object per step.
  nlohmann::json json() const;
  // The printed table: its heading lines, then one line per step.
  std::string printed() const;

 private:
  Column& add(Column column);

  std::size_t steps_ = 0;
  std::vector<Column> columns_;
  std::vector<std::pair<std::size_t, Printed>> printed_;
  std::string indent_;
  std::string separator_ = " ";
};

// A CSV field as RFC 4180 writes it: quoted when it holds a comma, a quote or a line break.
std::string csv_field(std::string_view text);

}  // namespace fogradar::sensor
