#include "fogradar/experiment/raw.hpp"

#include <algorithm>
#include <charconv>
#include <sstream>

#include "fogradar/core/error.hpp"

namespace fogradar::experiment {
namespace {

std::string mib_text(std::size_t bytes) {
  std::ostringstream text;
  text.precision(6);
  text << static_cast<double>(bytes) / static_cast<double>(std::size_t{1} << 20) << " MiB";
  return text.str();
}

// A comma-separated list of indices and ranges "a-b" in [0, count), ascending and distinct;
// `noun` names what the indices count in the message.
std::vector<std::size_t> parse_indices(const std::string& text, std::string_view option,
                                       std::size_t count, std::string_view noun) {
  const std::string allowed = "a comma-separated list of " + std::string(noun) +
                              " and ranges a-b in [0, " + std::to_string(count - 1) +
                              "] (e.g. 0,4 or 0-2,4)";
  const auto number = [&](std::string_view digits) {
    std::size_t value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() ||
        value >= count) {
      throw_invalid(option, text, allowed);
    }
    return value;
  };
  std::vector<std::size_t> indices;
  std::string_view rest(text);
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view token = rest.substr(0, comma);
    const std::size_t dash = token.find('-');
    const std::size_t first = number(token.substr(0, dash));
    const std::size_t last =
        dash == std::string_view::npos ? first : number(token.substr(dash + 1));
    if (last < first) throw_invalid(option, text, allowed);
    for (std::size_t i = first; i <= last; ++i) indices.push_back(i);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

std::string joined(const std::vector<std::string>& parts, std::string_view separator) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : std::string(separator)) + part;
  return text;
}

// Indices as --raw-steps and --raw-items take them: "0-4", "0,2-3".
std::string index_ranges(const std::vector<std::size_t>& indices) {
  std::string text;
  for (std::size_t i = 0; i < indices.size();) {
    std::size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    text += (text.empty() ? "" : ",") + std::to_string(indices[i]);
    if (j > i) text += "-" + std::to_string(indices[j]);
    i = j + 1;
  }
  return text;
}

}  // namespace

RawPlan resolve_raw(const Scenario& scenario, const RawRequest& request) {
  const sensor::Context context = scenario.context();
  RawPlan plan;
  plan.path = request.path;
  std::vector<std::string> offered;
  for (const std::string& name : scenario.experiment.sensors) {
    RawPlan::Sensor s{name, scenario.configure(name)->raw_kinds(), {}, {}};
    for (const sensor::RawKind& kind : s.kinds) offered.push_back(name + "." + kind.name);
    plan.sensors.push_back(std::move(s));
  }
  // --raw-select: every kind offered by default.
  if (request.kinds.empty()) {
    for (RawPlan::Sensor& s : plan.sensors) {
      for (std::size_t k = 0; k < s.kinds.size(); ++k) {
        if (s.kinds[k].by_default) s.chosen.push_back(k);
      }
    }
  } else {
    std::string_view rest(request.kinds);
    while (true) {
      const std::size_t comma = rest.find(',');
      const std::string token(rest.substr(0, comma));
      bool found = false;
      for (RawPlan::Sensor& s : plan.sensors) {
        for (std::size_t k = 0; k < s.kinds.size(); ++k) {
          if (token != s.name + "." + s.kinds[k].name) continue;
          if (std::find(s.chosen.begin(), s.chosen.end(), k) == s.chosen.end())
            s.chosen.push_back(k);
          found = true;
        }
      }
      if (!found) {
        throw_invalid(
            "--raw-select", request.kinds,
            "a comma-separated list of the running sensors' kinds: " + joined(offered, ", "));
      }
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    for (RawPlan::Sensor& s : plan.sensors) std::sort(s.chosen.begin(), s.chosen.end());
  }
  if (request.steps.empty()) {
    for (std::size_t k = 0; k < context.steps; ++k) plan.steps.push_back(k);
  } else {
    plan.steps = parse_indices(request.steps, "--raw-steps", context.steps, "steps");
  }
  std::size_t most_items = 0;
  for (const RawPlan::Sensor& s : plan.sensors) {
    if (s.chosen.empty()) continue;
    most_items = std::max(most_items, scenario.configure(s.name)->items_per_step());
  }
  if (most_items == 0) {
    throw_invalid("--raw-select", request.kinds,
                  "a list naming a kind of a running sensor: " + joined(offered, ", "));
  }
  std::vector<std::size_t> items;
  if (request.items.empty()) {
    for (std::size_t i = 0; i < std::min<std::size_t>(most_items, 10); ++i) items.push_back(i);
  } else {
    items = parse_indices(request.items, "--raw-items", most_items, "items");
  }
  for (RawPlan::Sensor& s : plan.sensors) {
    if (s.chosen.empty()) continue;
    const std::size_t count = scenario.configure(s.name)->items_per_step();
    for (const std::size_t i : items) {
      if (i < count) s.items.push_back(i);
    }
    for (const std::size_t k : s.chosen) {
      plan.bytes += plan.steps.size() * s.items.size() * s.kinds[k].item_bytes();
    }
  }
  const double limit_bytes = request.limit_mib * static_cast<double>(std::size_t{1} << 20);
  if (static_cast<double>(plan.bytes) > limit_bytes) {
    std::ostringstream limit;
    limit.precision(6);
    limit << request.limit_mib;
    std::vector<std::string> kinds;
    for (const RawPlan::Sensor& s : plan.sensors) {
      for (const std::size_t k : s.chosen) kinds.push_back(s.name + "." + s.kinds[k].name);
    }
    // Each option as typed, or the default in force where it was not given.
    const auto option = [](std::string_view name, const std::string& typed,
                           const std::string& by_default) {
      return typed.empty() ? std::string(name) + " not given: " + by_default
                           : std::string(name) + " = '" + typed + "'";
    };
    throw InvalidParameter(
        "--raw-limit-mib",
        "--raw needs an estimated " + mib_text(plan.bytes) + ", more than the limit of " +
            limit.str() + " MiB (--raw-limit-mib; default 4096): fewer kinds (" +
            option("--raw-select", request.kinds,
                   "every kind of the sensors that run, " + joined(kinds, ",")) +
            "), steps (" +
            option("--raw-steps", request.steps, "every step, " + index_ranges(plan.steps)) +
            ") or items (" +
            option("--raw-items", request.items, "the first ten, " + index_ranges(items)) + ")");
  }
  return plan;
}

}  // namespace fogradar::experiment
