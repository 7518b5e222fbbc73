// The numbers of the CSV the sweep writes, in their shortest form.
#include <charconv>
#include <string>

#include "engine.hpp"

namespace fogradar::sweep::detail {

std::string shortest(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace fogradar::sweep::detail
