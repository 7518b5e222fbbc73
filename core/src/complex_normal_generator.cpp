#include "fogradar/core/complex_normal_generator.hpp"

#include <array>
#include <cmath>
#include <cstring>

#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/detail/ziggurat.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar {
namespace {

using detail::f64x4;
using detail::u64x4;
using f32x8 = float __attribute__((vector_size(32)));
using u32x8 = std::uint32_t __attribute__((vector_size(32)));

constexpr detail::ZigguratTable kZiggurat = detail::make_ziggurat_table();

// Word w of lane l at word[w][l].
struct LaneStates {
  u64x4 word[4];
};

// The lane states move between memory and vectors only at the ends of a call and around the rare
// slow path; copying the whole struct with memcpy made GCC keep it in memory, so that every step
// of the generator waited for a store and a reload.
[[gnu::always_inline]] inline void store_lanes(std::uint64_t* to, u64x4 v) { std::memcpy(to, &v, sizeof v); }

[[gnu::always_inline]] inline u64x4 load_lanes(const std::uint64_t* from) {
  u64x4 v;
  std::memcpy(&v, from, sizeof v);
  return v;
}

// Whether any lane of a comparison result is set: the two halves or-ed, then two 64-bit words
// (fewer extractions than four).
[[gnu::always_inline]] inline bool any_lane(u32x8 mask) {
  using u32x4 = std::uint32_t __attribute__((vector_size(16)));
  using u64x2 = std::uint64_t __attribute__((vector_size(16)));
  const u32x4 halves = __builtin_shufflevector(mask, mask, 0, 1, 2, 3) | __builtin_shufflevector(mask, mask, 4, 5, 6, 7);
  const u64x2 words = detail::lanes_as<u64x2>(halves);
  return (words[0] | words[1]) != 0;
}

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

// Samples 0..7 of a group (real and imaginary part of four complex samples; sample h came from
// the half-word h of the group, lane h / 2) whose fast path failed: finished in order h = 0..7,
// each drawing its further words from its own lane. Out of line and in memory: it runs for ~2 % of
// the groups, and the vector clones must not pass vector arguments to it (their ABIs differ).
[[gnu::noinline]] void finish_slow_samples(std::uint64_t* lane_words, const std::uint32_t* sample_words,
                                           float* samples) {
  for (std::size_t h = 0; h < 8; ++h) {
    float x = 0.0F;
    if (detail::ziggurat_fast(sample_words[h], kZiggurat, x)) continue;
    const std::size_t lane = h / 2;
    std::array<std::uint64_t, 4> state{};
    for (std::size_t w = 0; w < 4; ++w) state[w] = lane_words[w * 4 + lane];
    samples[h] = detail::ziggurat_normal(sample_words[h], kZiggurat, [&] { return xoshiro256pp_next(state); });
    for (std::size_t w = 0; w < 4; ++w) lane_words[w * 4 + lane] = state[w];
  }
}

// The {x_i, x_{i+1}} floats of sample h's layer, as one 64-bit word.
[[gnu::always_inline]] inline std::uint64_t layer_bits(const u32x8& words, int h) {
  std::uint64_t bits;
  std::memcpy(&bits, kZiggurat.fast[words[h] & (detail::ziggurat_layers - 1)].data(), sizeof bits);
  return bits;
}

// Four complex samples from one word per lane: lane l's low half is the real part of sample l, its
// high half the imaginary part, so the eight floats come out interleaved (re, im, re, im, ...).
// Weighted: each sum base + scale x is then multiplied by row_weight * weights[i] (the frame window
// applied in the same pass, with the products the separate window pass would form).
template <bool weighted>
[[gnu::always_inline]] inline void add_four(LaneStates& state, double scale, const double* base, double* out,
                                            double row_weight, const double* weights) {
  const u32x8 words = detail::lanes_as<u32x8>(next(state));
  // Each layer's {width, covered} pair as one 64-bit load per sample, then split into two vectors.
  const f32x8 first_pairs = detail::lanes_as<f32x8>(
      u64x4{layer_bits(words, 0), layer_bits(words, 1), layer_bits(words, 2), layer_bits(words, 3)});
  const f32x8 last_pairs = detail::lanes_as<f32x8>(
      u64x4{layer_bits(words, 4), layer_bits(words, 5), layer_bits(words, 6), layer_bits(words, 7)});
  const f32x8 width = __builtin_shufflevector(first_pairs, last_pairs, 0, 2, 4, 6, 8, 10, 12, 14);
  const f32x8 covered = __builtin_shufflevector(first_pairs, last_pairs, 1, 3, 5, 7, 9, 11, 13, 15);
  const f32x8 magnitude = detail::layer_uniform<f32x8>(words) * width;
  f32x8 samples = detail::with_sign(magnitude, words);
  if (any_lane(detail::lanes_as<u32x8>(magnitude >= covered))) [[unlikely]] {
    alignas(32) std::uint64_t lane_words[16];
    alignas(32) std::uint32_t sample_words[8];
    alignas(32) float finished[8];
    for (std::size_t w = 0; w < 4; ++w) store_lanes(lane_words + 4 * w, state.word[w]);
    std::memcpy(sample_words, &words, sizeof sample_words);
    std::memcpy(finished, &samples, sizeof finished);
    finish_slow_samples(lane_words, sample_words, finished);
    for (std::size_t w = 0; w < 4; ++w) state.word[w] = load_lanes(lane_words + 4 * w);
    std::memcpy(&samples, finished, sizeof finished);
  }
  const f64x4 low = __builtin_convertvector(__builtin_shufflevector(samples, samples, 0, 1, 2, 3), f64x4) * scale;
  const f64x4 high = __builtin_convertvector(__builtin_shufflevector(samples, samples, 4, 5, 6, 7), f64x4) * scale;
  f64x4 first = detail::load4(base) + low;
  f64x4 last = detail::load4(base + 4) + high;
  if constexpr (weighted) {
    first *= row_weight * detail::load4(weights);
    last *= row_weight * detail::load4(weights + 4);
  }
  detail::store4(out, first);
  detail::store4(out + 4, last);
}

template <bool weighted>
[[gnu::always_inline]] inline void add_complex_normal_body(std::uint64_t* state_words, const double* base, double* out,
                                                           std::size_t count, double scale, double row_weight,
                                                           const double* weights) {
  LaneStates state;
  for (std::size_t w = 0; w < 4; ++w) state.word[w] = load_lanes(state_words + 4 * w);
  std::size_t j = 0;
  for (; j + 4 <= count; j += 4) {
    add_four<weighted>(state, scale, base + 2 * j, out + 2 * j, row_weight, weighted ? weights + 2 * j : nullptr);
  }
  if (j < count) {
    double tail[8] = {};
    add_four<false>(state, scale, tail, tail, row_weight, nullptr);
    for (std::size_t i = 0; i < 2 * (count - j); ++i) {
      const double sum = base[2 * j + i] + tail[i];
      out[2 * j + i] = weighted ? sum * (row_weight * weights[2 * j + i]) : sum;
    }
  }
  for (std::size_t w = 0; w < 4; ++w) store_lanes(state_words + 4 * w, state.word[w]);
}

// One body, compiled for AVX-512, AVX2 and the x86-64 baseline (SSE2); the loader picks the clone.
FOGRADAR_SIMD_CLONES
void add_complex_normal(std::uint64_t* state_words, const double* base, double* out, std::size_t count,
                        double scale) {
  add_complex_normal_body<false>(state_words, base, out, count, scale, 1.0, nullptr);
}

FOGRADAR_SIMD_CLONES
void add_weighted_complex_normal(std::uint64_t* state_words, const double* base, double* out, std::size_t count,
                                 double scale, double row_weight, const double* weights) {
  add_complex_normal_body<true>(state_words, base, out, count, scale, row_weight, weights);
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
                     reinterpret_cast<double*>(out.data()), out.size(), std::sqrt(0.5 * variance));
}

void ComplexNormalGenerator::add_weighted(std::span<const std::complex<double>> base,
                                          std::span<std::complex<double>> out, double variance, double row_weight,
                                          std::span<const double> part_weights) {
  FOGRADAR_CHECK(variance >= 0.0 && base.size() == out.size() && part_weights.size() == 2 * out.size());
  add_weighted_complex_normal(state_.data(), reinterpret_cast<const double*>(base.data()),
                              reinterpret_cast<double*>(out.data()), out.size(), std::sqrt(0.5 * variance),
                              row_weight, part_weights.data());
}

}  // namespace fogradar
