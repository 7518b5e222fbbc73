// What produced a detection: the ground truth the simulation knows and a real radar does not. The
// radar's origins are the sensors' one code table (sensor/origin.hpp): noise, target (a path of a
// target scattering centre, direct or via the floor), fog (the fog's volume clutter), clipping
// (the ADC's clipping products, in a frame that clipped) and sidelobe (the echoes' leakage outside
// their window main lobes).
#pragma once

#include "fogradar/sensor/origin.hpp"

namespace fogradar::radar {

using sensor::Origin;
using sensor::to_string;

// The origin whose expected power in a cell is largest: |T|^2 of the target paths' main lobes,
// |F|^2 of the fog clutter's, |S|^2 of every echo's leakage outside its main lobe, the noise's
// E|N|^2 (all in the same units); ties go to target, then fog, then sidelobe.
Origin dominant_origin(double target_power, double fog_power, double sidelobe_power,
                       double noise_power) noexcept;

}  // namespace fogradar::radar
