// The CSV the sweep writes (RFC 4180 fields, numbers in their shortest form) and the sensors'
// summary CSV it reads.
#include <charconv>
#include <sstream>
#include <string>
#include <vector>

#include "engine.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::sweep::detail {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t comma = line.find(','); comma != std::string::npos;
       comma = line.find(',', start)) {
    fields.push_back(line.substr(start, comma - start));
    start = comma + 1;
  }
  fields.push_back(line.substr(start));
  return fields;
}

}  // namespace

std::string shortest(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

Table parse_csv(const std::string& text) {
  Table table;
  std::istringstream in(text);
  std::string line;
  if (std::getline(in, line)) table.columns = split(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    table.rows.push_back(split(line));
    FOGRADAR_CHECK(table.rows.back().size() == table.columns.size());
  }
  return table;
}

}  // namespace fogradar::sweep::detail
