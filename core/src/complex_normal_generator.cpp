#include "fogradar/core/complex_normal_generator.hpp"

#include <cmath>
#include <cstring>

#include "fogradar/core/detail/box_muller_math.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar {
namespace {

using detail::f64x4;
using detail::u64x4;

struct LaneStates {
  u64x4 word[4];
};

[[gnu::always_inline]] inline u64x4 rotl(u64x4 x, int k) { return (x << k) | (x >> (64 - k)); }

// xoshiro256++ next() in every lane (Blackman & Vigna, ACM TOMS 47(4), 2021).
[[gnu::always_inline]] inline u64x4 next(LaneStates& state) {
  u64x4* s = state.word;
  const u64x4 result = rotl(s[0] + s[3], 23) + s[0];
  const u64x4 t = s[1] << 17;
  s[2] ^= s[0];
  s[3] ^= s[1];
  s[1] ^= s[2];
  s[0] ^= s[3];
  s[2] ^= t;
  s[3] = rotl(s[3], 45);
  return result;
}

[[gnu::always_inline]] inline f64x4 sqrt_lanes(f64x4 x) {
  // A loop of std::sqrt: with -fno-math-errno (set for this file) the compiler emits one vector
  // square root; IEEE square roots are exact, so any instruction set gives the same bits.
  f64x4 root;
  for (int l = 0; l < 4; ++l) root[l] = std::sqrt(x[l]);
  return root;
}

// Four complex samples, interleaved (re, im, re, im, ...): out[0..7] = base[0..7] + samples.
[[gnu::always_inline]] inline void add_four(LaneStates& state, double variance, const double* base, double* out) {
  const u64x4 radius_word = next(state);
  const u64x4 phase_word = next(state);
  f64x4 real, imag;
  detail::box_muller(radius_word, phase_word, variance, sqrt_lanes, real, imag);
  detail::store4(out, detail::load4(base) + __builtin_shufflevector(real, imag, 0, 4, 1, 5));
  detail::store4(out + 4, detail::load4(base + 4) + __builtin_shufflevector(real, imag, 2, 6, 3, 7));
}

// One body, compiled for AVX2 and for the x86-64 baseline (SSE2); the loader picks the clone.
FOGRADAR_SIMD_CLONES
void add_complex_normal(std::uint64_t* state_words, const double* base, double* out, std::size_t count,
                        double variance) {
  LaneStates state;
  std::memcpy(&state, state_words, sizeof state);
  std::size_t j = 0;
  for (; j + 4 <= count; j += 4) add_four(state, variance, base + 2 * j, out + 2 * j);
  if (j < count) {
    double tail[8] = {};
    add_four(state, variance, tail, tail);
    for (std::size_t i = 0; i < 2 * (count - j); ++i) out[2 * j + i] = base[2 * j + i] + tail[i];
  }
  std::memcpy(state_words, &state, sizeof state);
}

}  // namespace

ComplexNormalGenerator::ComplexNormalGenerator(RandomStream& parent) {
  for (std::size_t l = 0; l < lanes; ++l) {
    std::uint64_t seed = parent();
    for (std::size_t w = 0; w < 4; ++w) state_[w * lanes + l] = splitmix64(seed);
  }
}

void ComplexNormalGenerator::add(std::span<std::complex<double>> samples, double variance) {
  add(samples, samples, variance);
}

void ComplexNormalGenerator::add(std::span<const std::complex<double>> base, std::span<std::complex<double>> out,
                                 double variance) {
  FOGRADAR_CHECK(variance >= 0.0 && base.size() == out.size());
  // std::complex<double> is layout-compatible with double[2] ([complex.numbers.general]).
  add_complex_normal(state_.data(), reinterpret_cast<const double*>(base.data()),
                     reinterpret_cast<double*>(out.data()), out.size(), variance);
}

}  // namespace fogradar
