// libFuzzer target (scripts/fuzz.sh, docs/architecture.md "Fuzzing"): arbitrary bytes as a scenario
// file, through everything `fogradar run` does before its first frame: parse_scenario (the byte
// check, toml++, the readers, Scenario::validate), the memory estimate, the chamber and scene, the
// radar chain (plans, windows, CFAR design), RadarChain::check_compatible and the lidar and camera
// as the run builds them (each layer's fog resolved at their wavelengths). Bad input must end in
// InvalidParameter; anything else (another exception, a failed FOGRADAR_CHECK, a sanitizer report,
// a hang) is a finding. A scenario that reads must also survive to_toml and read back the same.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fogradar/camera/camera.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/radar/measurement.hpp"

namespace {

// Chains larger than this are refused as `fogradar run` refuses them over its limit; the fuzzer's
// own limit (-rss_limit_mb=2048 in scripts/fuzz.sh) must stay above it.
constexpr std::size_t chain_memory_limit_bytes = std::size_t{512} << 20;

void set_up_chain(const fogradar::experiment::Scenario& scenario) {
  using namespace fogradar;
  static const propagation::SegelsteinTable table;  // immutable, costly to build: made once
  experiment::require_memory_within(scenario, 1, chain_memory_limit_bytes);
  const propagation::Chamber chamber(scenario.chamber_spec(), scenario.radar.centre_frequency_hz,
                                     table);
  const radar::Scene scene = scenario.scene();
  const radar::RadarChain chain(scenario.radar);
  chain.check_compatible(scene, chamber);
  if (scenario.runs(SensorId::lidar)) {
    const lidar::Lidar lidar(scenario.lidar, scenario.chamber_spec(), table);
  }
  if (scenario.runs(SensorId::camera)) {
    const camera::Camera camera(scenario.camera, scenario.chamber_spec(), table);
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
    set_up_chain(scenario);
  } catch (const fogradar::InvalidParameter&) {
  }
  return 0;
}
