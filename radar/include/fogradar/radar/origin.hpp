// What produced a detection: the ground truth the simulation knows and a real radar does not.
#pragma once

#include <cstdint>
#include <string_view>

namespace fogradar::radar {

// target: a path of a target scattering centre (direct or via the floor); fog: the fog's volume
// clutter; noise: the receiver's thermal noise (a false alarm).
enum class Origin : std::uint8_t { noise, target, fog };

// "noise", "target", "fog".
std::string_view to_string(Origin origin) noexcept;

// The origin whose expected power in a cell is largest: |T|^2 of the target paths, |F|^2 of the fog
// clutter, the thermal noise's E|N|^2 (all in the same units); ties go to target, then fog.
Origin dominant_origin(double target_power, double fog_power, double noise_power) noexcept;

}  // namespace fogradar::radar
