// The uncertainty envelope's tables: the quantiles over the setups of every statistic and limit.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine.hpp"

namespace fogradar::sweep::detail {

using nlohmann::json;

namespace {

// The quantiles of envelope.csv, as its columns name them.
constexpr double envelope_levels[] = {0.05, 0.25, 0.5, 0.75, 0.95};
constexpr const char* envelope_columns = "p05,p25,p50,p75,p95";

}  // namespace

// Per point x sensor x step x statistic: how many setups gave a value and its quantiles.
std::string envelope_csv(const std::vector<json>& pieces) {
  std::string out =
      std::string("point,sensor,active_layers,statistic,setups,") + envelope_columns + "\n";
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const json& setups = pieces[p]["setups"];
    if (setups.empty()) continue;
    for (const json& s0 : setups[0]["sensors"]) {
      const std::string sensor = s0["sensor"];
      const std::vector<std::string> columns = s0["columns"];
      const std::size_t layers = static_cast<std::size_t>(
          std::find(columns.begin(), columns.end(), "active_layers") - columns.begin());
      for (std::size_t row = 0; row < s0["rows"].size(); ++row) {
        for (std::size_t c = 0; c < columns.size(); ++c) {
          if (is_step_column(columns[c])) continue;
          std::vector<double> values;
          bool numeric = true;
          for (const json& setup : setups) {
            const json* s = sensor_of(setup["sensors"], sensor);
            const std::string text = (*s)["rows"][row][c];
            const std::optional<double> v = number_of(text);
            if (!text.empty() && !v) numeric = false;
            if (v && std::isfinite(*v)) values.push_back(*v);
          }
          if (!numeric) continue;  // a list (the outliers): not a statistic
          out += std::to_string(p) + "," + csv_field(sensor) + "," +
                 s0["rows"][row][layers].get<std::string>() + "," + csv_field(columns[c]) + "," +
                 std::to_string(values.size());
          for (const double level : envelope_levels) {
            out += ',';
            if (!values.empty()) out += shortest(quantile(values, level));
          }
          out += "\n";
        }
      }
    }
  }
  return out;
}

std::string envelope_limits_csv(const std::vector<json>& pieces) {
  std::string out = "point,sensor,layers_to_failure,setups,fraction\n";
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const json& setups = pieces[p]["setups"];
    if (setups.empty()) continue;
    for (const json& s0 : setups[0]["sensors"]) {
      const std::string sensor = s0["sensor"];
      std::map<std::size_t, std::size_t> counts;  // limit + 1, 0 = not reached, so it sorts last
      for (const json& setup : setups) {
        const json& limit = (*sensor_of(setup["sensors"], sensor))["limit"];
        ++counts[limit.is_null() ? 0 : limit.get<std::size_t>() + 1];
      }
      const auto row = [&](std::size_t key, std::size_t n) {
        out += std::to_string(p) + "," + csv_field(sensor) + "," +
               (key == 0 ? std::string() : std::to_string(key - 1)) + "," + std::to_string(n) +
               "," + shortest(static_cast<double>(n) / static_cast<double>(setups.size())) + "\n";
      };
      for (const auto& [key, n] : counts) {
        if (key != 0) row(key, n);
      }
      if (counts.contains(0)) row(0, counts.at(0));
    }
  }
  return out;
}

}  // namespace fogradar::sweep::detail
