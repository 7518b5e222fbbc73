// The sweep file's reader: its [sweep], [[axis]], [uncertain] and [[plot]] tables into a SweepSpec,
// each key at its line, and every axis and [uncertain] key checked against the base scenario's.
#include "fogradar/sweep/spec.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>

#include "engine.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/experiment/scenario_values.hpp"
#include "spec_parts.hpp"

namespace fogradar::sweep {

using detail::fail;
using detail::integer_value;
using detail::kept;
using detail::number_value;
using detail::shortest;

namespace {

// Largest counts a sweep file may ask for: far beyond any study, far below memory limits.
constexpr std::int64_t max_replications = 1000;
constexpr std::int64_t max_range_count = 10000;
constexpr std::int64_t max_setups = 100000;

std::size_t line_of(const toml::node& node) { return node.source().begin.line; }

std::string toml_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

// What a TOML value is, in a message's words.
std::string type_of(const toml::node& node) {
  if (node.is_number()) return "a number";
  if (node.is_string()) return "a string";
  if (node.is_boolean()) return "a boolean";
  if (node.is_array()) return "an array";
  if (node.is_table()) return "a table";
  return "a date or time";
}

// Reads the tables of a sweep file, each key at its line, refusing what it does not know.
class Reader {
 public:
  Reader(std::string_view source) : source_(source) {}

  [[noreturn]] void fail_at(const toml::node& node, const std::string& key,
                            const std::string& message) const {
    fail(source_, line_of(node), key, message);
  }

  void only(const toml::table& table, const std::string& name,
            std::initializer_list<std::string_view> known) const {
    for (const auto& [key, node] : table) {
      if (std::find(known.begin(), known.end(), key.str()) != known.end()) continue;
      std::string listed;
      for (const std::string_view k : known)
        listed += (listed.empty() ? "" : ", ") + std::string(k);
      const std::string full =
          name.empty() ? std::string(key.str()) : name + "." + std::string(key.str());
      fail_at(node, full, "unknown key '" + full + "' (known: " + listed + ")");
    }
  }

  const toml::table& table(const toml::node& node, const std::string& name) const {
    if (const toml::table* t = node.as_table()) return *t;
    fail_at(node, name, name + ": must be a table");
  }

  std::string string(const toml::node& node, const std::string& name,
                     std::initializer_list<std::string_view> allowed = {}) const {
    const std::optional<std::string> value = node.value<std::string>();
    std::string listed;
    for (const std::string_view a : allowed)
      listed += (listed.empty() ? "" : ", ") + toml_string(a);
    if (!value)
      fail_at(node, name, name + ": must be a string" + (listed.empty() ? "" : " of " + listed));
    if (allowed.size() != 0 && std::find(allowed.begin(), allowed.end(), *value) == allowed.end()) {
      fail_at(node, name, name + " = " + toml_string(*value) + ": must be one of " + listed);
    }
    return *value;
  }

  std::int64_t integer(const toml::node& node, const std::string& name, std::int64_t low,
                       std::int64_t high) const {
    const std::string range =
        "an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]";
    if (!node.is_integer()) fail_at(node, name, name + ": must be " + range);
    const std::int64_t value = *node.value<std::int64_t>();
    if (value < low || value > high) {
      fail_at(node, name, name + " = " + std::to_string(value) + ": must be " + range);
    }
    return value;
  }

  double number(const toml::node& node, const std::string& name) const {
    if (!node.is_number()) fail_at(node, name, name + ": must be a number");
    const double value = *node.value<double>();
    if (!std::isfinite(value)) fail_at(node, name, name + ": must be finite");
    return value;
  }

  // A value a scenario key takes: a number, a boolean, a string, an array of them
  // (experiment.switching_order = [3, 1, 2, 0]) or of inline tables (chamber.layers).
  Value value(const toml::node& node, const std::string& name) const {
    if (node.is_integer()) return integer_value(*node.value<std::int64_t>());
    if (node.is_floating_point()) return number_value(number(node, name));
    if (node.is_boolean()) {
      const std::string text = *node.value<bool>() ? "true" : "false";
      return {text, text, std::nullopt, kept(node)};
    }
    if (node.is_string()) {
      const std::string text = *node.value<std::string>();
      return {toml_string(text), text, std::nullopt, kept(node)};
    }
    if (node.is_array() || node.is_table()) {
      const std::string text = written(node, name);
      return {text, text, std::nullopt, kept(node)};
    }
    fail_at(node, name,
            name + ": must be a key's value (a number, a boolean, a string or an array)");
  }

  std::string_view source() const { return source_; }

 private:
  // An array or inline table as one line of TOML, its numbers as value() writes them.
  std::string written(const toml::node& node, const std::string& name) const {
    if (const toml::array* array = node.as_array()) {
      std::string text = "[";
      for (const toml::node& element : *array)
        text += (text.size() > 1 ? ", " : "") + written(element, name);
      return text + "]";
    }
    if (const toml::table* table = node.as_table()) {
      std::string text = "{";
      for (const auto& [key, element] : *table) {
        const std::string_view k = key.str();
        const bool bare = !k.empty() && std::all_of(k.begin(), k.end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
        });
        text += (text.size() > 1 ? ", " : " ") + (bare ? std::string(k) : toml_string(k)) + " = " +
                written(element, name);
      }
      return text + (text.size() > 1 ? " }" : "}");
    }
    return value(node, name).toml;
  }

  std::string_view source_;
};

std::vector<Value> range_values(const Reader& r, const toml::table& range,
                                const std::string& name) {
  r.only(range, name, {"from", "to", "count", "spacing"});
  const auto need = [&](std::string_view key) -> const toml::node& {
    if (const toml::node* node = range.get(key)) return *node;
    r.fail_at(range, name + "." + std::string(key), name + "." + std::string(key) + " is missing");
  };
  const toml::node& from_node = need("from");
  const toml::node& to_node = need("to");
  const double from = r.number(from_node, name + ".from");
  const double to = r.number(to_node, name + ".to");
  const std::int64_t count = r.integer(need("count"), name + ".count", 2, max_range_count);
  const std::string spacing =
      range.get("spacing") ? r.string(*range.get("spacing"), name + ".spacing", {"linear", "log"})
                           : "linear";
  if (!(to > from))
    r.fail_at(to_node, name + ".to",
              name + ".to = " + shortest(to) + ": must be > from = " + shortest(from));
  std::vector<Value> values;
  const double steps = static_cast<double>(count - 1);
  if (spacing == "log") {
    if (!(from > 0.0))
      r.fail_at(from_node, name + ".from",
                name + ".from = " + shortest(from) + ": must be > 0 for spacing = \"log\"");
    const double a = std::log(from), b = std::log(to);
    for (std::int64_t i = 0; i < count; ++i) {
      // The ends exactly as written; between them exp of the evenly spaced logarithms.
      const double v = i == 0           ? from
                       : i == count - 1 ? to
                                        : std::exp(a + static_cast<double>(i) / steps * (b - a));
      values.push_back(number_value(v));
    }
    return values;
  }
  const bool integers =
      from_node.is_integer() && to_node.is_integer() &&
      (static_cast<std::int64_t>(to) - static_cast<std::int64_t>(from)) % (count - 1) == 0;
  for (std::int64_t i = 0; i < count; ++i) {
    if (integers) {
      const std::int64_t step =
          (static_cast<std::int64_t>(to) - static_cast<std::int64_t>(from)) / (count - 1);
      values.push_back(integer_value(static_cast<std::int64_t>(from) + i * step));
    } else {
      values.push_back(
          number_value(i == count - 1 ? to : from + static_cast<double>(i) / steps * (to - from)));
    }
  }
  return values;
}

Axis read_axis(const Reader& r, const toml::table& t, const std::string& name) {
  r.only(t, name, {"key", "keys", "values", "range"});
  Axis axis;
  axis.line = line_of(t);
  const toml::node* key = t.get("key");
  const toml::node* keys = t.get("keys");
  if ((key != nullptr) == (keys != nullptr)) {
    r.fail_at(
        t, name + ".key",
        name + ": give key (one key) or keys (keys zipped), not " + (key ? "both" : "neither"));
  }
  if (key) {
    axis.keys.push_back(r.string(*key, name + ".key"));
  } else {
    const toml::array* list = keys->as_array();
    if (list == nullptr || list->empty())
      r.fail_at(*keys, name + ".keys", name + ".keys: must be a non-empty array of scenario keys");
    for (const toml::node& k : *list) axis.keys.push_back(r.string(k, name + ".keys"));
  }
  for (const std::string& k : axis.keys) {
    if (k.empty() || k.find('.') == std::string::npos) {
      r.fail_at(
          t, name + ".key",
          name + ": '" + k + "' is no scenario key (section.key, e.g. fog.extinction_per_km)");
    }
    if (k == "experiment.seed") {
      r.fail_at(
          t, name + ".key",
          name +
              ": experiment.seed is set by the sweep ([sweep] seed = \"common\" or \"by_values\")");
    }
    if (std::count(axis.keys.begin(), axis.keys.end(), k) > 1)
      r.fail_at(t, name + ".keys", name + ".keys: '" + k + "' is named twice");
  }
  const toml::node* values = t.get("values");
  const toml::node* range = t.get("range");
  if ((values != nullptr) == (range != nullptr)) {
    r.fail_at(t, name + ".values",
              name + ": give values (a list) or range (from, to, count, spacing), not " +
                  (values ? "both" : "neither"));
  }
  if (range) {
    if (axis.keys.size() != 1)
      r.fail_at(*range, name + ".range", name + ".range: one key only; zipped keys take values");
    for (Value& v : range_values(r, r.table(*range, name + ".range"), name + ".range"))
      axis.positions.push_back({std::move(v)});
    return axis;
  }
  const toml::array* list = values->as_array();
  if (list == nullptr || list->empty())
    r.fail_at(*values, name + ".values", name + ".values: must be a non-empty array");
  for (const toml::node& position : *list) {
    if (axis.keys.size() == 1) {
      axis.positions.push_back({r.value(position, name + ".values")});
      continue;
    }
    const toml::array* row = position.as_array();
    if (row == nullptr || row->size() != axis.keys.size()) {
      r.fail_at(position, name + ".values",
                name + ".values: each position is an array of " + std::to_string(axis.keys.size()) +
                    " values, one per key of keys (zipped axes of one length)");
    }
    std::vector<Value> zipped;
    for (const toml::node& v : *row) zipped.push_back(r.value(v, name + ".values"));
    axis.positions.push_back(std::move(zipped));
  }
  for (std::size_t i = 0; i < axis.positions.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      bool same = true;
      for (std::size_t k = 0; k < axis.keys.size(); ++k)
        same = same && axis.positions[i][k].toml == axis.positions[j][k].toml;
      if (same)
        r.fail_at(*values, name + ".values",
                  name + ".values: position " + std::to_string(i) + " repeats position " +
                      std::to_string(j));
    }
  }
  return axis;
}

Distribution read_distribution(const Reader& r, const toml::table& t, const std::string& name) {
  Distribution d;
  const toml::node* kind = t.get("distribution");
  if (kind == nullptr) r.fail_at(t, name + ".distribution", name + ".distribution is missing");
  const std::string k = r.string(*kind, name + ".distribution",
                                 {"uniform", "normal", "truncated_normal", "discrete"});
  const auto need = [&](std::string_view key) -> double {
    const toml::node* node = t.get(key);
    if (node == nullptr)
      r.fail_at(t, name + "." + std::string(key),
                name + "." + std::string(key) + " is missing for distribution = " + toml_string(k));
    return r.number(*node, name + "." + std::string(key));
  };
  if (k == "uniform" || k == "truncated_normal") {
    r.only(t, name,
           k == "uniform" ? std::initializer_list<std::string_view>{"distribution", "low", "high"}
                          : std::initializer_list<std::string_view>{"distribution", "mean", "std",
                                                                    "low", "high"});
    d.kind = k == "uniform" ? Distribution::Kind::uniform : Distribution::Kind::truncated_normal;
    d.low = need("low");
    d.high = need("high");
    if (!(d.high > d.low))
      r.fail_at(*t.get("high"), name + ".high",
                name + ".high = " + shortest(d.high) + ": must be > low = " + shortest(d.low));
  }
  if (k == "normal" || k == "truncated_normal") {
    if (k == "normal") r.only(t, name, {"distribution", "mean", "std"});
    d.kind = k == "normal" ? Distribution::Kind::normal : Distribution::Kind::truncated_normal;
    d.mean = need("mean");
    d.std = need("std");
    if (!(d.std > 0.0))
      r.fail_at(*t.get("std"), name + ".std", name + ".std = " + shortest(d.std) + ": must be > 0");
  }
  if (k == "discrete") {
    r.only(t, name, {"distribution", "values", "weights"});
    d.kind = Distribution::Kind::discrete;
    const toml::node* values = t.get("values");
    const toml::array* list = values ? values->as_array() : nullptr;
    const std::string allowed =
        "a non-empty array of numbers, strings or booleans, all of one type";
    if (list == nullptr || list->empty())
      r.fail_at(values ? *values : static_cast<const toml::node&>(t), name + ".values",
                name + ".values: must be " + allowed);
    const toml::node& first = (*list)[0];
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::node& v = (*list)[i];
      const bool drawable = v.is_number() || v.is_string() || v.is_boolean();
      if (!drawable || type_of(v) != type_of(first)) {
        const std::string which = "values[" + std::to_string(i) + "] is " + type_of(v);
        r.fail_at(v, name + ".values",
                  name + ".values: must be " + allowed + "; " + which +
                      (i == 0 ? "" : ", values[0] " + type_of(first)));
      }
      d.values.push_back(r.value(v, name + ".values"));
    }
    if (const toml::node* weights = t.get("weights")) {
      const toml::array* w = weights->as_array();
      if (w == nullptr || w->size() != d.values.size())
        r.fail_at(*weights, name + ".weights",
                  name + ".weights: must be an array as long as values (" +
                      std::to_string(d.values.size()) + ")");
      for (const toml::node& v : *w) {
        const double weight = r.number(v, name + ".weights");
        if (!(weight > 0.0))
          r.fail_at(v, name + ".weights", name + ".weights: every weight must be > 0");
        d.weights.push_back(weight);
      }
    } else {
      d.weights.assign(d.values.size(), 1.0);
    }
    const double total = std::accumulate(d.weights.begin(), d.weights.end(), 0.0);
    for (double& w : d.weights) w /= total;
  }
  return d;
}

EnvelopePlot read_plot(const Reader& r, const toml::table& t, const std::string& name) {
  r.only(t, name, {"sensor", "statistic", "box", "y_label", "references", "reference_label"});
  EnvelopePlot plot;
  const auto need = [&](std::string_view key) -> const toml::node& {
    if (const toml::node* node = t.get(key)) return *node;
    r.fail_at(t, name + "." + std::string(key), name + "." + std::string(key) + " is missing");
  };
  plot.sensor = r.string(need("sensor"), name + ".sensor");
  plot.statistic = r.string(need("statistic"), name + ".statistic");
  plot.y_label = t.get("y_label") ? r.string(*t.get("y_label"), name + ".y_label") : plot.statistic;
  plot.reference_label = t.get("reference_label")
                             ? r.string(*t.get("reference_label"), name + ".reference_label")
                             : "reference";
  if (const toml::node* box = t.get("box")) {
    const toml::array* list = box->as_array();
    if (list == nullptr || list->size() != 5)
      r.fail_at(*box, name + ".box",
                name + ".box: must name 5 columns: whisker_low, q1, median, q3, whisker_high");
    for (const toml::node& c : *list) plot.box.push_back(r.string(c, name + ".box"));
  }
  if (const toml::node* references = t.get("references")) {
    const toml::array* list = references->as_array();
    if (list == nullptr)
      r.fail_at(*references, name + ".references",
                name + ".references: must be an array of tables {active_layers, value}");
    for (const toml::node& item : *list) {
      const toml::table& ref = r.table(item, name + ".references");
      r.only(ref, name + ".references", {"active_layers", "value"});
      const toml::node* layers = ref.get("active_layers");
      const toml::node* value = ref.get("value");
      if (!layers || !value)
        r.fail_at(ref, name + ".references",
                  name + ".references: each needs active_layers and value");
      plot.references.push_back({static_cast<std::size_t>(r.integer(
                                     *layers, name + ".references.active_layers", 0, 100000)),
                                 r.number(*value, name + ".references.value")});
    }
  }
  return plot;
}

}  // namespace

SweepSpec parse_sweep(std::string_view text, std::string_view source,
                      const std::filesystem::path& directory) {
  SweepSpec spec;
  spec.source = std::string(source);
  spec.text = std::string(text);
  spec.directory = directory;
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    fail(source, e.source().begin.line, "toml",
         std::string("malformed TOML: ") + std::string(e.description()));
  }
  const Reader r(source);
  r.only(root, "", {"sweep", "axis", "uncertain"});
  std::string base = "paper";
  if (const toml::node* sweep = root.get("sweep")) {
    const toml::table& t = r.table(*sweep, "sweep");
    r.only(t, "sweep", {"base", "replications", "seed"});
    if (const toml::node* b = t.get("base")) base = r.string(*b, "sweep.base");
    if (const toml::node* n = t.get("replications"))
      spec.replications =
          static_cast<std::size_t>(r.integer(*n, "sweep.replications", 1, max_replications));
    if (const toml::node* s = t.get("seed"))
      spec.seed_mode = r.string(*s, "sweep.seed", {"common", "by_values"}) == "common"
                           ? SeedMode::common
                           : SeedMode::by_values;
  }
  spec.base_name = base;
  spec.base = base == "paper" ? experiment::paper_scenario()
                              : experiment::load_scenario_file((directory / base).string());
  std::set<std::string> swept;
  if (const toml::node* axes = root.get("axis")) {
    const toml::array* list = axes->as_array();
    if (list == nullptr) r.fail_at(*axes, "axis", "axis: must be an array of tables [[axis]]");
    for (std::size_t i = 0; i < list->size(); ++i) {
      const std::string name = "axis[" + std::to_string(i) + "]";
      const toml::table& t = r.table((*list)[i], name);
      Axis axis = read_axis(r, t, name);
      const toml::node& named = t.get("key") ? *t.get("key") : *t.get("keys");
      for (const std::string& k : axis.keys) {
        try {
          experiment::require_key(spec.base, k);
        } catch (const InvalidParameter& e) {
          r.fail_at(named, name + ".key", name + ": " + e.what());
        }
        if (!swept.insert(k).second)
          r.fail_at((*list)[i], name + ".key", name + ": '" + k + "' is swept by another axis too");
      }
      spec.axes.push_back(std::move(axis));
    }
  }
  if (const toml::node* uncertain = root.get("uncertain")) {
    const toml::table& t = r.table(*uncertain, "uncertain");
    r.only(t, "uncertain", {"setups", "sampling", "keys", "plot"});
    Uncertain u;
    const toml::node* setups = t.get("setups");
    if (setups == nullptr) r.fail_at(t, "uncertain.setups", "uncertain.setups is missing");
    u.setups = static_cast<std::size_t>(r.integer(*setups, "uncertain.setups", 2, max_setups));
    if (const toml::node* s = t.get("sampling"))
      u.sampling = r.string(*s, "uncertain.sampling", {"latin_hypercube", "monte_carlo"}) ==
                           "latin_hypercube"
                       ? Sampling::latin_hypercube
                       : Sampling::monte_carlo;
    const toml::node* keys = t.get("keys");
    if (keys == nullptr)
      r.fail_at(t, "uncertain.keys",
                "uncertain.keys is missing: a table of scenario keys and their distributions");
    for (const auto& [key, node] : r.table(*keys, "uncertain.keys")) {
      const std::string k(key.str()), name = "uncertain.keys." + k;
      if (swept.contains(k)) r.fail_at(node, name, name + ": swept by an axis too");
      if (k == "experiment.seed" || k.find('.') == std::string::npos)
        r.fail_at(node, name, name + ": must be a scenario key other than experiment.seed");
      try {
        experiment::require_key(spec.base, k);
      } catch (const InvalidParameter& e) {
        r.fail_at(node, name, name + ": " + e.what());
      }
      u.keys.push_back({k, read_distribution(r, r.table(node, name), name)});
    }
    if (u.keys.empty()) r.fail_at(*keys, "uncertain.keys", "uncertain.keys: name at least one key");
    if (const toml::node* plots = t.get("plot")) {
      const toml::array* list = plots->as_array();
      if (list == nullptr)
        r.fail_at(*plots, "uncertain.plot",
                  "uncertain.plot: must be an array of tables [[uncertain.plot]]");
      for (std::size_t i = 0; i < list->size(); ++i) {
        const std::string name = "uncertain.plot[" + std::to_string(i) + "]";
        u.plots.push_back(read_plot(r, r.table((*list)[i], name), name));
      }
    }
    spec.uncertain = std::move(u);
  }
  // An array of tables swept whole and a key of one of its elements: the element would be set
  // twice, once by each.
  const auto fail_keys = [&](const std::string& key, const std::string& message) {
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      const Axis& axis = spec.axes[a];
      if (std::find(axis.keys.begin(), axis.keys.end(), key) != axis.keys.end())
        fail(source, axis.line, "axis[" + std::to_string(a) + "].key",
             "axis[" + std::to_string(a) + "]: " + message);
    }
    fail(source, 1, "uncertain.keys." + key, "uncertain.keys." + key + ": " + message);
  };
  std::vector<std::string> all(swept.begin(), swept.end());
  if (spec.uncertain) {
    for (const UncertainKey& u : spec.uncertain->keys) all.push_back(u.key);
  }
  for (const std::string& key : all) {
    if (key.find('[') == std::string::npos) continue;  // an element's key
    const std::string array = key.substr(0, key.find('['));
    if (std::find(all.begin(), all.end(), array) != all.end())
      fail_keys(key, "'" + key + "' is an element of " + array + ", which is swept whole too");
  }
  return spec;
}

SweepSpec load_sweep_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code error;
  if (!in || std::filesystem::is_directory(path, error)) {
    throw_invalid("--sweep", path, "a readable sweep file (TOML, docs/sweep.md)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str().size() > experiment::max_scenario_file_bytes) {
    throw_invalid("--sweep", path, "a sweep file of at most 1 MiB");
  }
  return parse_sweep(text.str(), path, std::filesystem::path(path).parent_path());
}

}  // namespace fogradar::sweep
