// std::bit_cast for the functions built as SIMD clones (detail/simd.hpp), for vectors and scalars
// alike. Everything that takes or returns a vector there must be inlined: a clone built for AVX2
// passes vectors in registers, an out-of-line function built for the baseline expects them in
// memory, and an unoptimised build (which does not inline std::bit_cast) would call one from the
// other and crash. Internal to fogradar.
#pragma once

#include <cstring>

namespace fogradar::detail {

template <class To, class From>
[[gnu::always_inline]] inline To lanes_as(From from) {
  static_assert(sizeof(To) == sizeof(From));
  To to;
  std::memcpy(&to, &from, sizeof to);
  return to;
}

}  // namespace fogradar::detail
