// One table of an enumeration's names, from which its printing, its parsing, its refusal message
// and its scenario key's set of choices all follow, so that no name is written twice.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fogradar/core/error.hpp"

namespace fogradar {

template <class Enum, std::size_t N>
class EnumNames {
 public:
  using Entry = std::pair<Enum, std::string_view>;

  constexpr explicit EnumNames(const std::array<Entry, N>& entries) : entries_(entries) {}

  // The value's name; "?" for a value the table does not hold (a cast integer).
  constexpr std::string_view name(Enum value) const noexcept {
    for (const auto& [candidate, text] : entries_) {
      if (candidate == value) return text;
    }
    return "?";
  }

  // The value named `text`; any other text throws InvalidParameter
  // "<field> = '<text>': must be one of a, b, c".
  Enum parse(std::string_view text, std::string_view field) const {
    for (const auto& [value, candidate] : entries_) {
      if (candidate == text) return value;
    }
    throw_invalid(field, text, allowed());
  }

  // "one of a, b, c", in the table's order.
  std::string allowed() const {
    std::string text = "one of ";
    for (std::size_t i = 0; i < N; ++i)
      text += (i == 0 ? "" : ", ") + std::string(entries_[i].second);
    return text;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    out.reserve(N);
    for (const auto& entry : entries_) out.emplace_back(entry.second);
    return out;
  }

 private:
  std::array<Entry, N> entries_;
};

// `constexpr auto kNames = enum_names<Colour>({{Colour::red, "red"}, {Colour::blue, "blue"}});`
template <class Enum, std::size_t N>
constexpr EnumNames<Enum, N> enum_names(const std::pair<Enum, std::string_view> (&entries)[N]) {
  std::array<std::pair<Enum, std::string_view>, N> table{};
  for (std::size_t i = 0; i < N; ++i) table[i] = entries[i];
  return EnumNames<Enum, N>(table);
}

}  // namespace fogradar
