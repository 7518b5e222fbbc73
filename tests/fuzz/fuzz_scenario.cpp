// libFuzzer target (scripts/fuzz.sh, docs/architecture.md "Fuzzing"): arbitrary bytes as a scenario
// file, through everything `fogradar run` does before its first item: parse_scenario (the byte
// check, toml++, the key readers, Scenario::validate), the memory estimate and every running
// sensor as the run builds it (ConfiguredSensor::make: the radar's chamber, scene and chain with
// its plans, windows and CFAR design and RadarChain::check_compatible; the lidar and the camera
// with each layer's fog resolved at their wavelengths). Bad input must end in InvalidParameter;
// anything else (another exception, a failed FOGRADAR_CHECK, a sanitizer report, a hang) is a
// finding. A scenario that reads must also survive to_toml and read back the same.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/propagation/water.hpp"

namespace {

// Chains larger than this are refused as `fogradar run` refuses them over its limit; the fuzzer's
// own limit (-rss_limit_mb=2048 in scripts/fuzz.sh) must stay above it.
constexpr std::size_t chain_memory_limit_bytes = std::size_t{512} << 20;

void set_up_sensors(const fogradar::experiment::Scenario& scenario) {
  using namespace fogradar;
  static const propagation::SegelsteinTable table;  // immutable, costly to build: made once
  experiment::require_memory_within(scenario, 1, chain_memory_limit_bytes);
  for (const std::string& name : scenario.experiment.sensors) {
    scenario.configure(name)->make(table, StopToken());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fogradar::experiment::Scenario scenario;
  try {
    scenario = fogradar::experiment::parse_scenario(text, "fuzz.toml");
  } catch (const fogradar::InvalidParameter&) {
    return 0;
  }
  // The resolved scenario written out must read back to itself (scenario.toml reproduces a run).
  const std::string written = fogradar::experiment::to_toml(scenario);
  if (fogradar::experiment::to_toml(
          fogradar::experiment::parse_scenario(written, "written.toml")) != written) {
    std::abort();
  }
  try {
    set_up_sensors(scenario);
  } catch (const fogradar::InvalidParameter&) {
  }
  return 0;
}
