// What produced a detection or an echo: the ground truth the simulation knows and a real sensor
// does not. One code table for every sensor, so that a code means the same in every file (the
// raw-data file stores it as an HDF5 enumeration with these names).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fogradar::sensor {

// noise: the receiver's noise alone (a false alarm); target: the target's echo (radar: the direct
// path of a target scattering centre, with the paths via the room that its range and Doppler
// resolution cannot tell from it); fog: the fog's volume echo of an active layer; background: a
// static surface of the chamber other than the target (the lidar's walls and barrels); clipping: a
// product of the ADC's clipping (harmonics and intermodulation of the clipped echoes), in a frame
// that clipped, where neither target nor fog explains the cell; sidelobe: the radar's "sidelobe
// false alarm", a cell outside the window main lobe of every strong echo where the echoes' leakage
// (the range and Doppler windows' sidelobes, summed coherently over every echo) outweighs both the
// main-lobe echoes and the noise (radar/attribution.hpp); multipath: a ghost of the target, its
// echo via the room's walls, floor or ceiling resolved from its direct path (radar); room: the
// room's own echo, a wall's specular return or an object standing in the hall (radar). The codes
// are stored in raw files: a new origin takes the next code.
enum class Origin : std::uint8_t {
  noise = 0,
  target = 1,
  fog = 2,
  background = 3,
  clipping = 4,
  sidelobe = 5,
  multipath = 6,
  room = 7
};

inline constexpr std::array<std::string_view, 8> origin_names{
    "noise", "target", "fog", "background", "clipping", "sidelobe", "multipath", "room"};

// "noise", "target", "fog", "background", "clipping", "sidelobe", "multipath", "room".
constexpr std::string_view to_string(Origin origin) noexcept {
  const auto code = static_cast<std::size_t>(origin);
  return code < origin_names.size() ? origin_names[code] : "?";
}

// The table's names in code order: an enumeration column's labels (RawColumn::labels).
inline std::vector<std::string> origin_labels() {
  return {origin_names.begin(), origin_names.end()};
}

}  // namespace fogradar::sensor
