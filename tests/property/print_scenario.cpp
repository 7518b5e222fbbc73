// `property_scenario SEED`: prints the property checker's scenario for SEED as TOML (what
// `fogradar run --scenario` reads), for the Python stability check and bench/estimate_ratio.py.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include "scenario_generator.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: property_scenario SEED\n";
    return 2;
  }
  const std::string text = argv[1];
  std::uint64_t seed = 0;
  try {
    std::size_t used = 0;
    seed = std::stoull(text, &used);
    if (used != text.size() || text.front() == '-') throw std::invalid_argument(text);
  } catch (const std::exception&) {
    std::cerr << "property_scenario: SEED '" << text
              << "' is not an unsigned integer in [0, 18446744073709551615]\n";
    return 2;
  }
  std::cout << fogradar::property::draw_scenario(seed).toml;
  return 0;
}
