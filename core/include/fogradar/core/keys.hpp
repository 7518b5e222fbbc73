// Scenario keys, declared once beside the parameters they set: a key's
// dotted name as the user writes it, its type, the values it allows, its meaning, and the accessors
// that read and write its field. That one declaration drives the scenario reader and writer
// (experiment/), the checks of the parameters' validate() and their messages, and the key tables of
// docs/scenario.md (`fogradar scenario --keys`). Nothing here knows TOML.
//
// A table is declared over one parameter struct P, with a prefix ("radar."):
//
//   KeyTable<RadarParams> keys("radar.");
//   keys.number("tx_power_dbm", FOGRADAR_KEY_FIELD(tx_power_dbm), closed(-30.0, 50.0), "P_t");
//
// and lifted into a larger struct with include(table, projection), so that a sensor's keys, its
// CFAR's and its target's become one table over the sensor's parameters, and every sensor's one
// table over the scenario.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/error.hpp"

// A field accessor for KeyTable: a generic lambda returning a reference to `member` of the struct
// it is given, const or not (`FOGRADAR_KEY_FIELD(roi.target.log_sigma)`).
#define FOGRADAR_KEY_FIELD(...) \
  [](auto& p_) -> auto& { return p_.__VA_ARGS__; }

namespace fogradar {

enum class KeyType {
  number,       // a TOML float or integer, read as a double
  integer,      // a TOML integer
  boolean,      // true or false
  choice,       // one name of a closed set (an enum)
  name_list,    // an array of names
  table_array,  // an array of tables, each with the keys of its element table
  order,        // one name of a closed set, or an array naming each of n indices once
  retired,      // no longer read: refused with what replaced it
};

// A number key's allowed values; an open end excludes its bound, an infinite one is no bound.
struct Interval {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool low_open = false;
  bool high_open = false;

  bool contains(double value) const;  // false for NaN and infinities: every key is finite
  // As the bad-input message states it after "must be ": "in [0, 40]", "in (0, 10000]",
  // "finite and > 0" (the wording of core/error.hpp's require_* checks, ten significant digits).
  std::string constraint() const;
  // As docs/scenario.md states it: "[0, 40]", "(0, 1e4]", "> 0" (shortest exact numbers).
  std::string doc() const;
};
Interval closed(double low, double high);       // [low, high]
Interval open_closed(double low, double high);  // (low, high]
Interval open(double low, double high);         // (low, high)
Interval positive();                            // (0, inf): "finite and > 0"

// The range other keys leave a key ("radar.samples_per_chirp": at most radar.chirp_duration_s x
// radar.sample_rate_hz samples), with how each end reads in a message. Where the other keys leave
// no value at all, constraint() says so in words: an interval such as [16, 5] reads as a range to
// meet, not as keys that contradict each other.
struct CrossBound {
  Interval range;
  std::string low_text;   // "16", "lidar.min_range_m = 0.1"
  std::string high_text;  // "radar.centre_frequency_hz / 2 = 3.85e+10"
  bool integer = false;
  std::string note;  // after the range: ": the samples fit in the chirp, ..." or " (...)"

  bool empty() const;  // no value (no integer, for an integer key) is in the range
  bool admits(double value) const { return range.contains(value); }
  // After "must be ": "an integer in [16, 5120]: the samples fit ..."; for an empty range "an
  // integer >= 16 and <= 5: the samples fit ...; no integer is both: the keys named leave it no
  // value".
  std::string constraint() const;
};

// Shortest text that reads back to exactly `value`, exponent without '+' or leading zeros ("1e9",
// "2.5e-7", "0.1"): numbers in docs/scenario.md.
std::string doc_number(double value);

template <class P>
class KeyTable;

// One key of a table over P. The accessors of its type are set (number: get_number/set_number, and
// so on); `check` throws InvalidParameter naming `name` when P holds a value the key does not
// allow.
template <class P>
struct Key {
  std::string name;  // as the user writes it: "radar.tx_power_dbm", "lidar.background[2].x0_m"
  KeyType type = KeyType::number;
  std::string allowed;  // the allowed values as docs/scenario.md states them
  std::string meaning;  // docs/scenario.md (Markdown); for a retired key, what replaced it

  std::function<double(const P&)> get_number;
  std::function<void(P&, double)> set_number;
  // A number key's own allowed values, for a front end that states them in its own unit (the
  // whole line where a check stated in words bounds the key instead).
  Interval range;
  std::function<std::int64_t(const P&)> get_integer;
  std::function<void(P&, std::int64_t)> set_integer;
  std::int64_t integer_low = 0;
  std::int64_t integer_high = 0;
  std::function<bool(const P&)> get_boolean;
  std::function<void(P&, bool)> set_boolean;
  // choice: the name of the value; setting an unknown name throws InvalidParameter naming `name`.
  std::function<std::string(const P&)> get_text;
  std::function<void(P&, std::string_view)> set_text;
  std::vector<std::string> choices;
  std::function<std::vector<std::string>(const P&)> get_list;
  std::function<void(P&, const std::vector<std::string>&)> set_list;
  // order: the indices when the value is a list (get_text then returns ""), and n.
  std::function<std::vector<std::size_t>(const P&)> get_indices;
  std::function<void(P&, const std::vector<std::size_t>&)> set_indices;
  std::function<std::size_t(const P&)> index_count;
  // table_array: element count, resizing, and element i's keys (named "<name>[i].<key>").
  std::function<std::size_t(const P&)> array_size;
  std::function<void(P&, std::size_t)> array_resize;
  std::function<void(std::size_t, KeyTable<P>&)> array_element;
  std::size_t array_max = 0;

  std::function<void(const P&)> check;
  // The bounds other keys set (within()): checked after every key's own check, so that a value
  // outside its own range is named itself rather than through a bound it makes meaningless.
  std::function<void(const P&)> cross_check;
  // Where set, the key takes effect only while `applies` holds: it is written only then, and a file
  // that gives it otherwise is refused saying `applies_text`.
  std::function<bool(const P&)> applies;
  std::string applies_text;
  // Keys of one group are alternatives (fog density: LWC, extinction or visibility): at most one of
  // them may be given, and the one given selects itself.
  std::string group;

  // Adds a check run after the key's own (a bound that involves other keys).
  Key& with_check(std::function<void(const P&)> extra) {
    check = [own = std::move(check), extra = std::move(extra)](const P& p) {
      if (own) own(p);
      extra(p);
    };
    return *this;
  }
  Key& when(std::function<bool(const P&)> predicate, std::string text) {
    applies = std::move(predicate);
    applies_text = std::move(text);
    return *this;
  }
  Key& in_group(std::string name_of_group) {
    group = std::move(name_of_group);
    return *this;
  }
  // Adds the check of a bound other keys set (a number or integer key): `bound(p)` gives the range
  // they leave, and a value outside it is refused with CrossBound::constraint().
  Key& within(std::function<CrossBound(const P&)> bound) {
    const auto value = get_number ? get_number : [get = get_integer](const P& p) {
      return static_cast<double>(get(p));
    };
    cross_check = [name = name, value, bound = std::move(bound),
                   earlier = std::move(cross_check)](const P& p) {
      if (earlier) earlier(p);
      const double v = value(p);
      const CrossBound b = bound(p);
      if (!b.admits(v)) throw_invalid(name, v, b.constraint());
    };
    return *this;
  }
  // Its own check, then its bounds across keys (the one key alone: a reader's probe).
  void check_alone(const P& p) const {
    if (check) check(p);
    if (cross_check) cross_check(p);
  }
  // Replaces the allowed-values text of docs/scenario.md.
  Key& documented_as(std::string text) {
    allowed = std::move(text);
    return *this;
  }

  bool takes_effect(const P& p) const { return !applies || applies(p); }
  // The section the key is written in ("radar", "processing.cfar") and its name there.
  std::string_view section() const;
  std::string_view short_name() const;
};

template <class P>
class KeyTable {
 public:
  KeyTable() = default;
  // Names are declared relative to `prefix` ("radar." or "" for full names).
  explicit KeyTable(std::string prefix) : prefix_(std::move(prefix)) {}

  const std::vector<Key<P>>& keys() const { return keys_; }
  const std::string& prefix() const { return prefix_; }
  // The key named `name` in full, to amend after include(); FOGRADAR_CHECKs that it is declared.
  Key<P>& at(std::string_view name) {
    for (Key<P>& key : keys_) {
      if (key.name == name) return key;
    }
    check_failed("key declared", __FILE__, __LINE__);
  }

  // Checks every key that takes effect, in declaration order (validate() of the parameters), then
  // the bounds across keys, in the same order.
  void check(const P& p) const {
    for (const Key<P>& key : keys_) {
      if (key.check && key.takes_effect(p)) key.check(p);
    }
    for (const Key<P>& key : keys_) {
      if (key.cross_check && key.takes_effect(p)) key.cross_check(p);
    }
  }

  // A number key whose field returns double&.
  template <class Field>
  Key<P>& number(std::string_view name, Field field, Interval range, std::string meaning) {
    return number(
        name, [field](const P& p) { return static_cast<double>(field(p)); },
        [field](P& p, double v) { field(p) = v; }, range, std::move(meaning));
  }
  // A number key read and written through functions (a variant alternative).
  Key<P>& number(std::string_view name, std::function<double(const P&)> get,
                 std::function<void(P&, double)> set, Interval range, std::string meaning) {
    Key<P>& key = add(name, KeyType::number, range.doc(), std::move(meaning));
    key.get_number = std::move(get);
    key.set_number = std::move(set);
    key.range = range;
    key.check = [name = key.name, get = key.get_number, range](const P& p) {
      const double value = get(p);
      if (!range.contains(value)) throw_invalid(name, value, range.constraint());
    };
    return key;
  }
  // A number key whose bound involves other keys: `allowed` states it, `check` checks it.
  template <class Field>
  Key<P>& number(std::string_view name, Field field, std::string allowed,
                 std::function<void(const P&)> check, std::string meaning) {
    Key<P>& key = add(name, KeyType::number, std::move(allowed), std::move(meaning));
    key.get_number = [field](const P& p) { return static_cast<double>(field(p)); };
    key.set_number = [field](P& p, double v) { field(p) = v; };
    key.check = std::move(check);
    return key;
  }

  // An integer key in [low, high] whose field is any integer type holding that range.
  template <class Field>
  Key<P>& integer(std::string_view name, Field field, std::int64_t low, std::int64_t high,
                  std::string meaning) {
    using Integer = std::remove_cvref_t<decltype(field(std::declval<P&>()))>;
    static_assert(std::is_integral_v<Integer>);
    Key<P>& key = add(name, KeyType::integer,
                      "integer [" + std::to_string(low) + ", " + std::to_string(high) + "]",
                      std::move(meaning));
    key.integer_low = low;
    key.integer_high = high;
    key.get_integer = [field](const P& p) { return static_cast<std::int64_t>(field(p)); };
    key.set_integer = [field](P& p, std::int64_t v) { field(p) = static_cast<Integer>(v); };
    key.check = [name = key.name, field, low, high](const P& p) {
      const auto value = field(p);
      if (std::cmp_less(value, low) || std::cmp_greater(value, high)) {
        throw_invalid(name, static_cast<double>(value),
                      "an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
      }
    };
    return key;
  }
  // An integer key read and written through functions (an enum written as a number).
  Key<P>& integer(std::string_view name, std::function<std::int64_t(const P&)> get,
                  std::function<void(P&, std::int64_t)> set, std::string allowed,
                  std::string meaning) {
    Key<P>& key = add(name, KeyType::integer, std::move(allowed), std::move(meaning));
    key.integer_low = std::numeric_limits<std::int64_t>::min();
    key.integer_high = std::numeric_limits<std::int64_t>::max();
    key.get_integer = std::move(get);
    key.set_integer = std::move(set);
    return key;
  }

  template <class Field>
  Key<P>& boolean(std::string_view name, Field field, std::string meaning) {
    Key<P>& key = add(name, KeyType::boolean, "boolean", std::move(meaning));
    key.get_boolean = [field](const P& p) { return static_cast<bool>(field(p)); };
    key.set_boolean = [field](P& p, bool v) { field(p) = v; };
    return key;
  }
  Key<P>& boolean(std::string_view name, std::function<bool(const P&)> get,
                  std::function<void(P&, bool)> set, std::string meaning) {
    Key<P>& key = add(name, KeyType::boolean, "boolean", std::move(meaning));
    key.get_boolean = std::move(get);
    key.set_boolean = std::move(set);
    return key;
  }

  // A choice among `names`: `parse(text, key name)` returns the value or throws InvalidParameter
  // naming the key with the allowed set (the module's own parse_* function); `name_of(value)` is
  // its inverse.
  template <class Field, class Parse, class NameOf>
  Key<P>& choice(std::string_view name, Field field, std::vector<std::string> names, Parse parse,
                 NameOf name_of, std::string meaning) {
    std::string allowed;
    for (const std::string& n : names) allowed += (allowed.empty() ? "`" : ", `") + n + "`";
    Key<P>& key = add(name, KeyType::choice, std::move(allowed), std::move(meaning));
    key.choices = std::move(names);
    key.get_text = [field, name_of](const P& p) { return std::string(name_of(field(p))); };
    key.set_text = [field, parse, key_name = key.name](P& p, std::string_view text) {
      field(p) = parse(text, key_name);
    };
    return key;
  }
  // A choice among the names of one EnumNames table: its parse, its name_of and its set.
  template <class Field, class Enum, std::size_t N>
  Key<P>& choice(std::string_view name, Field field, const EnumNames<Enum, N>& names,
                 std::string meaning) {
    return choice(
        name, field, names.names(),
        [names](std::string_view text, std::string_view key) { return names.parse(text, key); },
        [names](Enum value) { return names.name(value); }, std::move(meaning));
  }
  // A choice read and written through functions (a variant's alternative selected by name).
  Key<P>& choice(std::string_view name, std::function<std::string(const P&)> get,
                 std::function<void(P&, std::string_view)> set, std::vector<std::string> names,
                 std::string meaning) {
    std::string allowed;
    for (const std::string& n : names) allowed += (allowed.empty() ? "`" : ", `") + n + "`";
    Key<P>& key = add(name, KeyType::choice, std::move(allowed), std::move(meaning));
    key.choices = std::move(names);
    key.get_text = std::move(get);
    key.set_text = std::move(set);
    return key;
  }

  Key<P>& name_list(std::string_view name, std::function<std::vector<std::string>(const P&)> get,
                    std::function<void(P&, const std::vector<std::string>&)> set,
                    std::string allowed, std::string meaning) {
    Key<P>& key = add(name, KeyType::name_list, std::move(allowed), std::move(meaning));
    key.get_list = std::move(get);
    key.set_list = std::move(set);
    return key;
  }

  // An order of `count(p)` things: one of `names` (get_text/set_text), or an array naming each
  // index 0 .. count - 1 once (get_indices/set_indices, which take or give an empty list for a
  // name).
  Key<P>& order(std::string_view name, std::function<std::string(const P&)> get_name,
                std::function<void(P&, std::string_view)> set_name,
                std::function<std::vector<std::size_t>(const P&)> get_list,
                std::function<void(P&, const std::vector<std::size_t>&)> set_list,
                std::function<std::size_t(const P&)> count, std::vector<std::string> names,
                std::string allowed, std::string meaning) {
    Key<P>& key = add(name, KeyType::order, std::move(allowed), std::move(meaning));
    key.choices = std::move(names);
    key.get_text = std::move(get_name);
    key.set_text = std::move(set_name);
    key.get_indices = std::move(get_list);
    key.set_indices = std::move(set_list);
    key.index_count = std::move(count);
    key.check = [full = key.name, get = key.get_indices, n = key.index_count](const P& p) {
      const std::vector<std::size_t> indices = get(p);
      if (indices.empty()) return;
      std::vector<bool> seen(n(p), false);
      bool each_once = indices.size() == seen.size();
      for (const std::size_t i : indices) {
        if (!each_once) break;
        each_once = i < seen.size() && !seen[i];
        if (each_once) seen[i] = true;
      }
      if (!each_once) {
        std::string listed;
        for (const std::size_t i : indices)
          listed += (listed.empty() ? "[" : ", ") + std::to_string(i);
        throw InvalidParameter(full, full + " = " + listed +
                                         "]: must be an array naming each of 0 … " +
                                         std::to_string(seen.size() - 1) + " once");
      }
    };
    return key;
  }

  // An array of tables [[name]] whose field is a std::vector<Element>; `element_keys(prefix)`
  // declares one element's keys under `prefix` ("lidar.background[2]."). At most `max_count`.
  template <class Field, class Element>
  Key<P>& table_array(std::string_view name, Field field,
                      KeyTable<Element> (*element_keys)(std::string prefix), std::size_t max_count,
                      std::string allowed, std::string meaning) {
    Key<P>& key = add(name, KeyType::table_array, std::move(allowed), std::move(meaning));
    key.array_max = max_count;
    key.array_size = [field](const P& p) { return field(p).size(); };
    key.array_resize = [field](P& p, std::size_t n) { field(p).resize(n); };
    key.array_element = [field, element_keys, full = key.name](std::size_t i, KeyTable<P>& out) {
      out.include(
          element_keys(full + "[" + std::to_string(i) + "]."),
          [ field, i ](auto& p) -> auto& { return field(p)[i]; });
    };
    key.check = [field, element_keys, full = key.name, max_count](const P& p) {
      const auto& elements = field(p);
      if (elements.size() > max_count) {
        throw_invalid(full, static_cast<double>(elements.size()),
                      "a count in [0, " + std::to_string(max_count) + "]");
      }
      if (elements.empty()) return;
      // One table checks every element; the element that fails is checked again under its own
      // name ("lidar.background[2].x0_m") for the message.
      const KeyTable<Element> any_element = element_keys(full + "[].");
      for (std::size_t i = 0; i < elements.size(); ++i) {
        try {
          any_element.check(elements[i]);
        } catch (const InvalidParameter&) {
          element_keys(full + "[" + std::to_string(i) + "].").check(elements[i]);
          throw;
        }
      }
    };
    return key;
  }

  // A key no longer read: a file that gives it is refused with `replacement`.
  Key<P>& retired(std::string_view name, std::string replacement) {
    return add(name, KeyType::retired, "", std::move(replacement));
  }

  // Appends `table`'s keys (over Sub, already named in full) reached through `project`, a generic
  // lambda from P& (or const P&) to Sub& (const Sub&).
  template <class Sub, class Projection>
  void include(const KeyTable<Sub>& table, Projection project) {
    for (const Key<Sub>& sub : table.keys()) keys_.push_back(lift(sub, project));
  }
  template <class Sub, class Projection>
  void include(KeyTable<Sub>&& table, Projection project) {
    for (Key<Sub>& sub : table.keys_) keys_.push_back(lift(std::move(sub), project));
  }
  // The table with its keys under section `from` ("radar.") moved under `to` ("radar_24."): their
  // names, texts and messages (with_section_renamed); the keys elsewhere are left out. A second
  // sensor of a kind takes the kind's keys so.
  KeyTable renamed(std::string_view from, std::string_view to) const {
    KeyTable out(prefix_);
    for (const Key<P>& key : keys_) {
      if (!std::string_view(key.name).starts_with(from)) continue;
      out.keys_.push_back(renamed_key(key, std::string(from), std::string(to)));
    }
    return out;
  }

  // Appends `table`'s keys (over P, already named in full) as they are.
  void append(KeyTable&& table) {
    keys_.insert(keys_.end(), std::make_move_iterator(table.keys_.begin()),
                 std::make_move_iterator(table.keys_.end()));
  }

 private:
  Key<P>& add(std::string_view name, KeyType type, std::string allowed, std::string meaning) {
    Key<P> key;
    key.name = prefix_ + std::string(name);
    key.type = type;
    key.allowed = std::move(allowed);
    key.meaning = std::move(meaning);
    keys_.push_back(std::move(key));
    return keys_.back();
  }

  template <class Sub>
  friend class KeyTable;

  // `f` rethrowing its InvalidParameter renamed.
  template <class R, class... A>
  static void rename_errors(std::function<R(A...)>& f, const std::string& from,
                            const std::string& to) {
    if (!f) return;
    f = [f = std::move(f), from, to](A... a) -> R {
      try {
        return f(std::forward<A>(a)...);
      } catch (const InvalidParameter& e) {
        throw with_section_renamed(e, from, to);
      }
    };
  }

  static Key<P> renamed_key(Key<P> key, const std::string& from, const std::string& to) {
    key.name = with_section_renamed(key.name, from, to);
    key.allowed = with_section_renamed(key.allowed, from, to);
    key.meaning = with_section_renamed(key.meaning, from, to);
    key.applies_text = with_section_renamed(key.applies_text, from, to);
    rename_errors(key.set_number, from, to);
    rename_errors(key.set_integer, from, to);
    rename_errors(key.set_boolean, from, to);
    rename_errors(key.set_text, from, to);
    rename_errors(key.set_list, from, to);
    rename_errors(key.set_indices, from, to);
    rename_errors(key.array_resize, from, to);
    rename_errors(key.check, from, to);
    rename_errors(key.cross_check, from, to);
    if (key.array_element) {
      key.array_element = [f = std::move(key.array_element), from, to](std::size_t i,
                                                                       KeyTable<P>& out) {
        KeyTable<P> element;
        f(i, element);
        KeyTable<P> moved = element.renamed(from, to);
        out.keys_.insert(out.keys_.end(), std::make_move_iterator(moved.keys_.begin()),
                         std::make_move_iterator(moved.keys_.end()));
      };
    }
    return key;
  }

  template <class Sub, class Projection>
  static Key<P> lift(Key<Sub> sub, Projection project) {
    Key<P> key;
    key.name = std::move(sub.name);
    key.type = sub.type;
    key.allowed = std::move(sub.allowed);
    key.meaning = std::move(sub.meaning);
    key.range = sub.range;
    key.integer_low = sub.integer_low;
    key.integer_high = sub.integer_high;
    key.choices = std::move(sub.choices);
    key.array_max = sub.array_max;
    key.applies_text = std::move(sub.applies_text);
    key.group = std::move(sub.group);
    // const P& -> const Sub& and P& -> Sub& through the same generic projection.
    const auto reading = [project](auto f) {
      return [project, f = std::move(f)](const P& p) { return f(project(p)); };
    };
    const auto writing = [project](auto f) {
      return [project, f = std::move(f)](P& p, const auto& value) { f(project(p), value); };
    };
    if (sub.get_number) key.get_number = reading(std::move(sub.get_number));
    if (sub.set_number) key.set_number = writing(std::move(sub.set_number));
    if (sub.get_integer) key.get_integer = reading(std::move(sub.get_integer));
    if (sub.set_integer) key.set_integer = writing(std::move(sub.set_integer));
    if (sub.get_boolean) key.get_boolean = reading(std::move(sub.get_boolean));
    if (sub.set_boolean) key.set_boolean = writing(std::move(sub.set_boolean));
    if (sub.get_text) key.get_text = reading(std::move(sub.get_text));
    if (sub.set_text) {
      key.set_text = [project, f = std::move(sub.set_text)](P& p, std::string_view v) {
        f(project(p), v);
      };
    }
    if (sub.get_list) key.get_list = reading(std::move(sub.get_list));
    if (sub.set_list) key.set_list = writing(std::move(sub.set_list));
    if (sub.get_indices) key.get_indices = reading(std::move(sub.get_indices));
    if (sub.set_indices) key.set_indices = writing(std::move(sub.set_indices));
    if (sub.index_count) key.index_count = reading(std::move(sub.index_count));
    if (sub.array_size) key.array_size = reading(std::move(sub.array_size));
    if (sub.array_resize) {
      key.array_resize = [project, f = std::move(sub.array_resize)](P& p, std::size_t n) {
        f(project(p), n);
      };
    }
    if (sub.array_element) {
      key.array_element = [project, f = std::move(sub.array_element)](std::size_t i,
                                                                      KeyTable<P>& out) {
        KeyTable<Sub> element;
        f(i, element);
        out.include(std::move(element), project);
      };
    }
    if (sub.check) key.check = [project, f = std::move(sub.check)](const P& p) { f(project(p)); };
    if (sub.cross_check) {
      key.cross_check = [project, f = std::move(sub.cross_check)](const P& p) { f(project(p)); };
    }
    if (sub.applies) key.applies = reading(std::move(sub.applies));
    return key;
  }

  std::string prefix_;
  std::vector<Key<P>> keys_;
};

template <class P>
std::string_view Key<P>::section() const {
  const std::string_view full(name);
  const std::size_t dot = full.rfind('.');
  return dot == std::string_view::npos ? std::string_view{} : full.substr(0, dot);
}

template <class P>
std::string_view Key<P>::short_name() const {
  const std::string_view full(name);
  const std::size_t dot = full.rfind('.');
  return dot == std::string_view::npos ? full : full.substr(dot + 1);
}

}  // namespace fogradar
