// Four-lane vector types of GCC and Clang (vector extensions): one AVX register, or two SSE2
// registers on the x86-64 baseline, with the same lane-wise IEEE arithmetic either way. Used by the
// few hot loops that are compiled for several instruction sets (target_clones); internal to
// fogradar, not part of the public API.
#pragma once

#include <cstdint>
#include <cstring>

#include "fogradar/core/detail/lanes_as.hpp"

namespace fogradar::detail {

using f64x4 = double __attribute__((vector_size(32)));
using u64x4 = std::uint64_t __attribute__((vector_size(32)));

[[gnu::always_inline]] inline f64x4 load4(const double* from) {
  f64x4 v;
  std::memcpy(&v, from, sizeof v);
  return v;
}

[[gnu::always_inline]] inline void store4(double* to, f64x4 v) { std::memcpy(to, &v, sizeof v); }

[[gnu::always_inline]] inline double sum_lanes(f64x4 v) { return (v[0] + v[1]) + (v[2] + v[3]); }

}  // namespace fogradar::detail

// The clones the loader chooses between (GCC on x86-64; elsewhere the one portable version):
// x86-64-v4 (AVX-512), AVX2 and the baseline. Defining FOGRADAR_SIMD_NO_AVX512 leaves out the
// first, and defining FOGRADAR_SIMD_CLONES empty builds only the baseline version: that is how the
// tests check, on an AVX-512 machine, the clones its loader would not pick (docs/architecture.md).
// FOGRADAR_SIMD_AVX2 and FOGRADAR_SIMD_AVX512 say which clones exist, for the loop that is written
// out per instruction set instead (complex_normal_generator.cpp).
#ifndef FOGRADAR_SIMD_CLONES
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    defined(FOGRADAR_SIMD_NO_AVX512)
#define FOGRADAR_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#define FOGRADAR_SIMD_AVX2 1
#elif defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FOGRADAR_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#define FOGRADAR_SIMD_AVX2 1
#define FOGRADAR_SIMD_AVX512 1
#else
#define FOGRADAR_SIMD_CLONES
#endif
#endif
