// A sweep's points: the grid of its axes in value order, each point's seed, the draws of
// [uncertain] and every point's scenarios read over the base.
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>
#include <numeric>

#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/experiment/scenario_values.hpp"
#include "fogradar/sweep/spec.hpp"
#include "spec_parts.hpp"

namespace fogradar::sweep {

using detail::fail;
using detail::integer_value;
using detail::number_value;

namespace {

// The [uncertain] draws' random streams: RandomStream(seed, draws_stream, key index).
constexpr std::uint64_t draws_stream = 0x5357454550ULL;  // "SWEEP"
// The largest grid a sweep file may ask for: far beyond any study, far below memory limits.
constexpr std::size_t max_points = 1000000;

// FNV-1a over the text, then SplitMix64: a seed from a point's values, in [0, 2^63).
std::uint64_t seed_of(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  return splitmix64(hash) >> 1;
}

// An unbiased integer in [0, n) (rejection of the low remainder).
std::uint64_t bounded(RandomStream& stream, std::uint64_t n) {
  const std::uint64_t threshold = (0 - n) % n;
  for (;;) {
    const std::uint64_t r = stream();
    if (r >= threshold) return r % n;
  }
}

// The [uncertain] draws, setup by setup, key by key: Latin hypercube (each key's N strata in a
// random order, a uniform point in each) or plain Monte Carlo, through each key's inverse CDF.
std::vector<std::vector<Value>> draws(const Uncertain& u, std::uint64_t seed) {
  std::vector<std::vector<Value>> values(u.setups, std::vector<Value>(u.keys.size()));
  for (std::size_t k = 0; k < u.keys.size(); ++k) {
    RandomStream stream(seed, draws_stream, k);
    std::vector<std::size_t> strata(u.setups);
    std::iota(strata.begin(), strata.end(), std::size_t{0});
    if (u.sampling == Sampling::latin_hypercube) {
      for (std::size_t i = u.setups; i > 1; --i)
        std::swap(strata[i - 1], strata[bounded(stream, i)]);
    }
    for (std::size_t s = 0; s < u.setups; ++s) {
      // In (0, 1): an inverse CDF is finite there.
      const double jitter = stream.uniform() + 0x1.0p-54;
      const double p =
          u.sampling == Sampling::latin_hypercube
              ? (static_cast<double>(strata[s]) + jitter) / static_cast<double>(u.setups)
              : jitter;
      values[s][k] = u.keys[k].distribution.drawn_at(p);
    }
  }
  return values;
}

}  // namespace

Value Distribution::drawn_at(double u) const {
  switch (kind) {
    case Kind::uniform:
      return number_value(low + u * (high - low));
    case Kind::normal:
      return number_value(
          boost::math::quantile(boost::math::normal_distribution<double>(mean, std), u));
    case Kind::truncated_normal: {
      const boost::math::normal_distribution<double> n(mean, std);
      const double a = boost::math::cdf(n, low), b = boost::math::cdf(n, high);
      return number_value(std::clamp(boost::math::quantile(n, a + u * (b - a)), low, high));
    }
    case Kind::discrete: {
      double cumulative = 0.0;
      for (std::size_t i = 0; i < values.size(); ++i) {
        cumulative += weights[i];
        if (u < cumulative) return values[i];
      }
      return values.back();
    }
  }
  return number_value(std::numeric_limits<double>::quiet_NaN());
}

std::string Point::label() const {
  std::string text;
  for (const auto& [key, value] : values)
    text += (text.empty() ? "" : ", ") + key + " = " + value.text;
  return text.empty() ? "the base scenario" : text;
}

std::vector<Point> expand(const SweepSpec& spec) {
  // Each axis's positions by value: the file's order does not matter.
  std::vector<std::vector<std::size_t>> order;
  std::size_t count = 1;
  for (const Axis& axis : spec.axes) {
    std::vector<std::size_t> o(axis.positions.size());
    std::iota(o.begin(), o.end(), std::size_t{0});
    std::stable_sort(o.begin(), o.end(), [&](std::size_t a, std::size_t b) {
      const Value& x = axis.positions[a][0];
      const Value& y = axis.positions[b][0];
      if (x.number && y.number) return *x.number < *y.number;
      if (x.number != y.number) return x.number.has_value();
      return x.text < y.text;
    });
    order.push_back(std::move(o));
    count *= axis.positions.size();
    if (count > max_points) {
      throw_invalid("axis", static_cast<double>(count),
                    "a grid of at most " + std::to_string(max_points) + " points");
    }
  }
  const std::uint64_t base_seed = spec.base.experiment.seed;
  std::vector<std::vector<Value>> drawn;
  if (spec.uncertain) drawn = draws(*spec.uncertain, base_seed);
  std::vector<Point> points;
  std::vector<std::size_t> at(spec.axes.size(), 0);
  for (std::size_t index = 0; index < count; ++index) {
    Point point;
    point.index = index;
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      const Axis& axis = spec.axes[a];
      const std::vector<Value>& position = axis.positions[order[a][at[a]]];
      for (std::size_t k = 0; k < axis.keys.size(); ++k)
        point.values.emplace_back(axis.keys[k], position[k]);
    }
    if (spec.seed_mode == SeedMode::by_values) {
      std::vector<std::string> lines;
      for (const auto& [key, value] : point.values)
        lines.push_back(key + " = " + value.toml + "\n");
      std::sort(lines.begin(), lines.end());
      point.seed = seed_of(std::accumulate(lines.begin(), lines.end(), std::string()));
    } else {
      point.seed = base_seed;
    }
    std::vector<std::pair<std::string, Value>> with_seed = point.values;
    with_seed.emplace_back("experiment.seed", integer_value(static_cast<std::int64_t>(point.seed)));
    const std::string label = spec.source + " point " + std::to_string(index);
    const auto read = [&](const std::vector<std::pair<std::string, Value>>& values,
                          const std::string& what) {
      try {
        std::vector<experiment::KeyValue> given;
        for (const auto& [key, value] : values) given.push_back({key, value.node->node.get()});
        return experiment::set_values_over(spec.base, given, label);
      } catch (const InvalidParameter& e) {
        // The sweep's own location replaces the point's.
        const std::string& message = e.message();
        for (std::size_t a = 0; a < spec.axes.size(); ++a) {
          const Axis& axis = spec.axes[a];
          if (std::find(axis.keys.begin(), axis.keys.end(), e.field()) == axis.keys.end()) continue;
          const auto value = std::find_if(values.begin(), values.end(),
                                          [&](const auto& v) { return v.first == e.field(); });
          fail(spec.source, axis.line, e.field(),
               "axis[" + std::to_string(a) + "] value " + value->second.text + " of " + e.field() +
                   what + ": " + message);
        }
        if (spec.uncertain) {
          for (const UncertainKey& u : spec.uncertain->keys) {
            if (u.key != e.field()) continue;
            const auto value = std::find_if(values.begin(), values.end(),
                                            [&](const auto& v) { return v.first == e.field(); });
            fail(spec.source, 1, "uncertain.keys." + u.key,
                 "uncertain.keys." + u.key + " drew " + value->second.text + what + ": " + message);
          }
        }
        fail(spec.source, spec.axes.empty() ? 1 : spec.axes.front().line, e.field(),
             point.label() + what + ": " + message);
      }
    };
    point.scenario = read(with_seed, "");
    for (std::size_t s = 0; s < drawn.size(); ++s) {
      std::vector<std::pair<std::string, Value>> setup;
      for (std::size_t k = 0; k < spec.uncertain->keys.size(); ++k) {
        setup.emplace_back(spec.uncertain->keys[k].key, drawn[s][k]);
      }
      std::vector<std::pair<std::string, Value>> all = with_seed;
      all.insert(all.end(), setup.begin(), setup.end());
      point.setups.push_back(read(all, " (setup " + std::to_string(s) + " of [uncertain])"));
      point.setup_values.push_back(std::move(setup));
    }
    points.push_back(std::move(point));
    for (std::size_t a = spec.axes.size(); a-- > 0;) {
      if (++at[a] < spec.axes[a].positions.size()) break;
      at[a] = 0;
    }
  }
  return points;
}

}  // namespace fogradar::sweep
