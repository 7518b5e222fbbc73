// What produced a detection: the ground truth the simulation knows and a real radar does not. The
// radar's origins are the sensors' one code table (sensor/origin.hpp): noise, target (a target
// scattering centre's direct path, with its paths via the room that the radar cannot resolve from
// it), multipath (a resolved path via the room: a ghost), room (a wall's or an object's own echo),
// fog (the fog's volume clutter), clipping (the ADC's clipping products, in a frame that clipped)
// and sidelobe (the echoes' leakage outside their window main lobes).
#pragma once

#include "fogradar/sensor/origin.hpp"

namespace fogradar::radar {

using sensor::Origin;
using sensor::to_string;

// The expected powers in a cell, all in the same units: |T|^2 of the target paths' main lobes,
// |M|^2 of the ghosts', |R|^2 of the room's own echoes', |F|^2 of the fog clutter's, |S|^2 of every
// echo's leakage outside its main lobe, the noise's E|N|^2.
struct CellPowers {
  double target = 0.0;
  double multipath = 0.0;
  double room = 0.0;
  double fog = 0.0;
  double sidelobe = 0.0;
  double noise = 0.0;
};

// The origin whose power is largest; ties go to target, then multipath, room, fog, sidelobe.
Origin dominant_origin(const CellPowers& powers) noexcept;

}  // namespace fogradar::radar
