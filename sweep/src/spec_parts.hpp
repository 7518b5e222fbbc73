// The sweep file's parts shared by its reader (spec.cpp) and its points (points.cpp): a value as
// the sweep keeps it, and a refusal pointed at the sweep file's line.
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "fogradar/core/error.hpp"
#include "fogradar/sweep/spec.hpp"

namespace fogradar::sweep::detail {

struct ValueNode {
  std::unique_ptr<toml::node> node;
};

// A copy of `node` that a value keeps.
std::shared_ptr<const ValueNode> kept(const toml::node& node);
// A number (an integer) as a value: its text the shortest that reads back to it.
Value number_value(double value);
Value integer_value(std::int64_t value);

[[noreturn]] inline void fail(std::string_view source, std::size_t line, const std::string& key,
                              const std::string& message) {
  throw InvalidParameter(key, message, {std::string(source), line});
}

}  // namespace fogradar::sweep::detail
