// A swept value as the sweep keeps it: its TOML text, its text in tables, its number and its node.
#include <memory>
#include <string>
#include <type_traits>

#include "engine.hpp"
#include "spec_parts.hpp"

namespace fogradar::sweep::detail {

std::shared_ptr<const ValueNode> kept(const toml::node& node) {
  auto value = std::make_shared<ValueNode>();
  node.visit([&value](const auto& n) {
    value->node = std::make_unique<std::remove_cvref_t<decltype(n)>>(n);
  });
  return value;
}

Value number_value(double value) {
  std::string text = shortest(value);
  std::string literal = text;
  if (literal.find_first_of(".e") == std::string::npos) literal += ".0";
  return {literal, literal, value, kept(toml::value<double>(value))};
}

Value integer_value(std::int64_t value) {
  const std::string text = std::to_string(value);
  return {text, text, static_cast<double>(value), kept(toml::value<std::int64_t>(value))};
}

}  // namespace fogradar::sweep::detail
