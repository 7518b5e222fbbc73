#include "fogradar/sensor/step_table.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::sensor {
namespace {

// printf's %.Nf or %.Ng of `v` ("nan", "-inf" and "-0.000" as printf writes them).
std::string printf_number(double v, bool general, int precision) {
  std::array<char, 400> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), v,
                    general ? std::chars_format::general : std::chars_format::fixed, precision);
  FOGRADAR_CHECK(result.ec == std::errc());
  return std::string(buffer.data(), result.ptr);
}

// Characters as a terminal counts them: UTF-8 code points.
std::size_t display_width(std::string_view text) {
  return static_cast<std::size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

std::string right_aligned(const std::string& text, std::size_t width) {
  const std::size_t shown = display_width(text);
  if (shown >= width) return text;
  std::string out(width - shown, ' ');
  out += text;
  return out;
}

}  // namespace

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string Column::text(std::size_t step) const {
  switch (type) {
    case ColumnType::integer:
      return std::to_string(integers.at(step));
    case ColumnType::number:
      return stats::format_number(numbers.at(step), digits);
    case ColumnType::text:
      return texts.at(step);
    case ColumnType::numbers: {
      std::string joined;
      for (const double v : lists.at(step)) {
        if (!joined.empty()) joined += ';';
        joined += stats::format_number(v, digits);
      }
      return joined;
    }
  }
  return {};
}

nlohmann::json Column::json_value(std::size_t step) const {
  switch (type) {
    case ColumnType::integer:
      return integers.at(step);
    case ColumnType::number: {
      const double v = numbers.at(step);
      return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    }
    case ColumnType::text:
      return texts.at(step);
    case ColumnType::numbers:
      return lists.at(step);
  }
  return nullptr;
}

std::string Column::printed(std::size_t step, const Printed& how) const {
  std::string cell;
  if (type == ColumnType::number) {
    const double v = how.scale * numbers.at(step);
    if (!std::isfinite(v) && how.missing) {
      cell = *how.missing;
    } else if (how.signless_zero) {
      cell = how.general ? stats::format_number(v, how.precision)
                         : stats::format_fixed(v, how.precision);
    } else {
      cell = printf_number(v, how.general, how.precision);
    }
  } else {
    cell = text(step);
  }
  std::string out = how.prefix;
  out += cell;
  out += how.suffix;
  return out;
}

Column& Column::csv_digits(int significant_digits) {
  digits = significant_digits;
  return *this;
}

Column& Column::in_csv(bool shown) {
  csv = shown;
  return *this;
}

Column& Column::in_json(std::string pointer) {
  json = std::move(pointer);
  return *this;
}

Column& Column::printed_only() {
  csv = false;
  json.clear();
  return *this;
}

const Column& StepTable::column(std::string_view header) const {
  for (const Column& c : columns_) {
    if (c.header() == header) return c;
  }
  throw std::out_of_range("no step-table column " + std::string(header));
}

Column& StepTable::add(Column column) {
  const std::size_t values =
      column.integers.size() + column.numbers.size() + column.texts.size() + column.lists.size();
  FOGRADAR_CHECK(values == steps_);
  column.json = '/';
  column.json += column.header();
  columns_.push_back(std::move(column));
  return columns_.back();
}

Column& StepTable::integer(std::string name, std::string unit, std::vector<std::int64_t> values) {
  return add({.name = std::move(name),
              .unit = std::move(unit),
              .type = ColumnType::integer,
              .integers = std::move(values)});
}

Column& StepTable::number(std::string name, std::string unit, std::vector<double> values) {
  return add({.name = std::move(name),
              .unit = std::move(unit),
              .type = ColumnType::number,
              .numbers = std::move(values)});
}

Column& StepTable::text(std::string name, std::string unit, std::vector<std::string> values) {
  return add({.name = std::move(name),
              .unit = std::move(unit),
              .type = ColumnType::text,
              .texts = std::move(values)});
}

Column& StepTable::numbers(std::string name, std::string unit,
                           std::vector<std::vector<double>> values) {
  return add({.name = std::move(name),
              .unit = std::move(unit),
              .type = ColumnType::numbers,
              .lists = std::move(values)});
}

void StepTable::print(std::string_view header, Printed how) {
  const Column& c = column(header);
  printed_.emplace_back(static_cast<std::size_t>(&c - columns_.data()), std::move(how));
}

void StepTable::print_layout(std::string indent, std::string separator) {
  indent_ = std::move(indent);
  separator_ = std::move(separator);
}

std::vector<std::string> StepTable::csv_headers() const {
  std::vector<std::string> headers;
  for (const Column& c : columns_) {
    if (c.csv) headers.push_back(c.header());
  }
  return headers;
}

std::vector<std::vector<std::string>> StepTable::csv_cells() const {
  std::vector<std::vector<std::string>> rows(steps_);
  for (std::size_t k = 0; k < steps_; ++k) {
    for (const Column& c : columns_) {
      if (c.csv) rows[k].push_back(c.text(k));
    }
  }
  return rows;
}

std::string StepTable::csv() const {
  const auto line = [](const std::vector<std::string>& fields) {
    std::string out;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (i > 0) out += ',';
      out += csv_field(fields[i]);
    }
    out += '\n';
    return out;
  };
  std::string out = line(csv_headers());
  for (const std::vector<std::string>& row : csv_cells()) out += line(row);
  return out;
}

nlohmann::json StepTable::json() const {
  nlohmann::json steps = nlohmann::json::array();
  for (std::size_t k = 0; k < steps_; ++k) {
    nlohmann::json step = nlohmann::json::object();
    for (const Column& c : columns_) {
      if (!c.json.empty()) step[nlohmann::json::json_pointer(c.json)] = c.json_value(k);
    }
    steps.push_back(std::move(step));
  }
  return steps;
}

std::string StepTable::printed() const {
  // A heading spans its column and those after it that have none.
  struct Group {
    const std::vector<std::string>* heads;
    std::size_t width;
  };
  std::vector<Group> groups;
  std::size_t lines = 0;
  for (const auto& [index, how] : printed_) {
    if (how.heads.empty() && !groups.empty()) {
      groups.back().width += display_width(separator_) + how.width;
    } else {
      groups.push_back({&how.heads, how.width});
    }
    lines = std::max(lines, how.heads.size());
  }
  std::string out;
  for (std::size_t l = 0; l < lines; ++l) {
    out += indent_;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const std::vector<std::string>& heads = *groups[g].heads;
      if (g > 0) out += separator_;
      out += right_aligned(l < heads.size() ? heads[l] : std::string(), groups[g].width);
    }
    out += '\n';
  }
  for (std::size_t k = 0; k < steps_; ++k) {
    out += indent_;
    for (std::size_t i = 0; i < printed_.size(); ++i) {
      const auto& [index, how] = printed_[i];
      if (i > 0) out += separator_;
      out += right_aligned(columns_[index].printed(k, how), how.width);
    }
    out += '\n';
  }
  return out;
}

}  // namespace fogradar::sensor
