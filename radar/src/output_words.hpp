// Words shared by the radar's printed table (outputs.cpp) and its plots' captions (plots.cpp).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "fogradar/radar/results.hpp"

namespace fogradar::radar {

// "1 active layer", "3 active layers".
inline std::string counted(std::size_t count, std::string_view noun) {
  return std::to_string(count) + " " + std::string(noun) + (count == 1 ? "" : "s");
}

// A step where fewer than half the measurements detected the target, but some did: its RCS
// statistics describe the surviving detections only, a sample biased towards strong echoes.
inline bool survivors_only(const StepSummary& s) {
  return s.detections > 0 && s.detection_rate < 0.5;
}

}  // namespace fogradar::radar
