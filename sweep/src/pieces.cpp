// Reading the points' committed pieces: their numbers, their sensors (envelope.cpp, tables.cpp,
// plots.cpp).
#include <algorithm>
#include <charconv>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine.hpp"
#include "fogradar/stats/box_plot.hpp"

namespace fogradar::sweep::detail {

using nlohmann::json;

std::optional<double> number_of(const std::string& text) {
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::vector<std::string> sensor_order(const std::vector<json>& pieces) {
  std::vector<std::string> order;
  for (const json& piece : pieces) {
    for (const json& run : piece["runs"]) {
      for (const json& s : run["sensors"]) {
        const std::string name = s["sensor"];
        if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
      }
    }
  }
  return order;
}

const json* sensor_of(const json& sensors, const std::string& name) {
  for (const json& s : sensors) {
    if (s["sensor"] == name) return &s;
  }
  return nullptr;
}

double quantile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return stats::quantile_type7(values, p);
}

}  // namespace fogradar::sweep::detail
