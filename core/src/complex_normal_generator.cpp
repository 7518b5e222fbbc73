#include "fogradar/core/complex_normal_generator.hpp"

#include <array>
#include <cmath>
#include <cstring>

#include "fogradar/core/detail/polar.hpp"
#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/detail/ziggurat.hpp"
#include "fogradar/core/error.hpp"

#if defined(FOGRADAR_SIMD_AVX2)
#include <immintrin.h>
#endif

namespace fogradar {
namespace {

using detail::f64x4;
using detail::u64x4;
using f32x4 = float __attribute__((vector_size(16)));
using f32x8 = float __attribute__((vector_size(32)));
using u32x8 = std::uint32_t __attribute__((vector_size(32)));

constexpr detail::ZigguratTable kZiggurat = detail::make_ziggurat_table();

// Word w of every lane: s_w[l] is word w of lane l. The states move between memory and vectors
// only at the ends of a call and around the rare slow path: four named vectors rather than an
// array, and copies vector by vector, so that GCC keeps them in registers instead of mirroring
// them to the stack at every step.
struct LaneStates {
  u64x4 s0, s1, s2, s3;
};

[[gnu::always_inline]] inline void store_lanes(std::uint64_t* to, u64x4 v) {
  std::memcpy(to, &v, sizeof v);
}

[[gnu::always_inline]] inline u64x4 load_lanes(const std::uint64_t* from) {
  u64x4 v;
  std::memcpy(&v, from, sizeof v);
  return v;
}

// What the kernel does differently per instruction set: whether any lane of a comparison result
// is set, four floats to four doubles, and whether the next group's look-ups are issued early
// (add_complex_normal_body). GCC 12 compiles __builtin_convertvector from four floats
// into two-lane conversions and inserts, and from eight floats into 512-bit registers in the
// AVX-512 version (whose 512-bit instructions then also hold up the 256-bit ones); with either the
// generator took ~1.25 times as long (alternated in one process) as with AVX's four-lane vcvtps2pd.
// AvxLanes' target attribute keeps its functions from being always_inline (GCC refuses to inline
// them into a function without it); the kernels' flatten inlines them.
struct BaselineLanes {
  // With 16 vector registers, two groups in flight spill: 1.07 times the time (alternated in one
  // process) against 0.88 without.
  static constexpr bool issue_next_early = false;
  // The two halves or-ed, then two 64-bit words (fewer extractions than four).
  [[gnu::always_inline]] static bool any(u32x8 mask) {
    using u32x4 = std::uint32_t __attribute__((vector_size(16)));
    using u64x2 = std::uint64_t __attribute__((vector_size(16)));
    const u32x4 halves = __builtin_shufflevector(mask, mask, 0, 1, 2, 3) |
                         __builtin_shufflevector(mask, mask, 4, 5, 6, 7);
    const u64x2 words = detail::lanes_as<u64x2>(halves);
    return (words[0] | words[1]) != 0;
  }
  [[gnu::always_inline]] static f64x4 to_double(f32x4 x) {
    return __builtin_convertvector(x, f64x4);
  }
};

#if defined(FOGRADAR_SIMD_AVX2)
struct AvxLanes {
  static constexpr bool issue_next_early = true;
  [[gnu::target("avx")]] static bool any(u32x8 mask) {
    const auto bits = detail::lanes_as<__m256i>(mask);
    return _mm256_testz_si256(bits, bits) == 0;
  }
  [[gnu::target("avx")]] static f64x4 to_double(f32x4 x) {
    return detail::lanes_as<f64x4>(_mm256_cvtps_pd(detail::lanes_as<__m128>(x)));
  }
};
#endif

// The correctly rounded square root of each lane (IEEE, so every instruction set agrees); built
// with -fno-math-errno (core/CMakeLists.txt), GCC makes the loop one vector square root.
[[gnu::always_inline]] inline f32x8 sqrt_lanes(f32x8 x) {
  for (int l = 0; l < 8; ++l) x[l] = std::sqrt(x[l]);
  return x;
}

[[gnu::always_inline]] inline u64x4 rotl(u64x4 x, int k) { return (x << k) | (x >> (64 - k)); }

// xoshiro256++ next() in every lane (Blackman & Vigna, ACM TOMS 47(4), 2021).
[[gnu::always_inline]] inline u64x4 next(LaneStates& s) {
  const u64x4 result = rotl(s.s0 + s.s3, 23) + s.s0;
  const u64x4 t = s.s1 << 17;
  s.s2 ^= s.s0;
  s.s3 ^= s.s1;
  s.s1 ^= s.s2;
  s.s0 ^= s.s3;
  s.s2 ^= t;
  s.s3 = rotl(s.s3, 45);
  return result;
}

[[gnu::always_inline]] inline LaneStates load_states(const std::uint64_t* words) {
  return {load_lanes(words), load_lanes(words + 4), load_lanes(words + 8), load_lanes(words + 12)};
}

[[gnu::always_inline]] inline void store_states(std::uint64_t* words, const LaneStates& state) {
  store_lanes(words, state.s0);
  store_lanes(words + 4, state.s1);
  store_lanes(words + 8, state.s2);
  store_lanes(words + 12, state.s3);
}

// `vector` with lane `lane` replaced by `value`, by a select: a vector reloaded from memory over
// a scalar store would wait for the store.
template <class Vector, class Scalar>
[[gnu::always_inline]] inline Vector with_lane(Vector vector, std::size_t lane, Scalar value) {
  using Mask = decltype(vector == vector);
  using Index = decltype(Mask{}[0] + 0);
  Mask lanes{};
  for (std::size_t l = 0; l < sizeof(Vector) / sizeof(Scalar); ++l)
    lanes[l] = static_cast<Index>(l);
  return lanes == static_cast<Index>(lane) ? Vector{} + value : vector;
}

// The powers of a group whose fast path failed somewhere, in the vector order of Group (element
// h holds sample 4 (h / 2 mod 2) + 2 (h / 4) + h mod 2, of lane 2 (h / 4) + h mod 2): the failed
// ones finished in sample order, each drawing its further words from its own lane. Inlined into
// each kernel (a call would pass the vectors through memory: the clones' ABIs differ), on its
// cold path (~3 % of the groups). Its copies of the vectors in memory are its own: indexing the
// vectors themselves would make GCC keep the lane states on the stack in the fast path too; the
// results go back by selects.
[[gnu::always_inline]] inline f32x8 finish_slow_powers(LaneStates& state, u32x8 power_words,
                                                       f32x8 power, u32x8 failed) {
  alignas(32) std::uint64_t lane_words[16];
  alignas(32) std::uint32_t words[8];
  alignas(32) std::uint32_t failures[8];
  alignas(32) float powers[8];
  store_states(lane_words, state);
  std::memcpy(words, &power_words, sizeof words);
  std::memcpy(failures, &failed, sizeof failures);
  std::memcpy(powers, &power, sizeof powers);
  for (const std::size_t h : {0, 1, 4, 5, 2, 3, 6, 7}) {
    if (failures[h] == 0) continue;
    const std::size_t lane = 2 * (h / 4) + h % 2;
    std::array<std::uint64_t, 4> lane_state{};
    for (std::size_t w = 0; w < 4; ++w) lane_state[w] = lane_words[w * 4 + lane];
    const float x = detail::ziggurat_slow(words[h], powers[h], kZiggurat,
                                          [&] { return xoshiro256pp_next(lane_state); });
    for (std::size_t w = 0; w < 4; ++w) lane_words[w * 4 + lane] = lane_state[w];
    power = with_lane(power, h, x);
    state = {with_lane(state.s0, lane, lane_state[0]), with_lane(state.s1, lane, lane_state[1]),
             with_lane(state.s2, lane, lane_state[2]), with_lane(state.s3, lane, lane_state[3])};
  }
  return power;
}

// The {x_i, x_{i+1}} floats of the layer that a power word picks, as one 64-bit word.
[[gnu::always_inline]] inline std::uint64_t layer_bits(std::uint32_t power_word) {
  std::uint64_t bits;
  std::memcpy(&bits, kZiggurat.fast[power_word & (detail::ziggurat_layers - 1)].data(),
              sizeof bits);
  return bits;
}

// A group of eight complex samples from two steps of the four lanes: sample 4s + l from lane l's
// word of step s, its low half the power word, its high half the phase word. The vectors hold the
// samples in the order (0, 1, 4, 5 | 2, 3, 6, 7) (step 0 lanes 0-1, step 1 lanes 0-1 | the same for
// lanes 2-3): every rearrangement then stays within 128-bit halves, and interleaving (re, im)
// gives the samples in order.
struct Group {
  u32x8 power_words, phase_words;
  f32x8 width, covered;  // the layers' {x_i, x_{i+1}}
};

[[gnu::always_inline]] inline Group draw_group(LaneStates& state) {
  const u64x4 first = next(state);
  const u64x4 second = next(state);
  const u32x8 first_halves = detail::lanes_as<u32x8>(first);
  const u32x8 second_halves = detail::lanes_as<u32x8>(second);
  // Each layer's {width, covered} pair as one 64-bit load per sample (the index from the 64-bit
  // word, whose low half is the power word), then split into two vectors.
  const f32x8 first_pairs =
      detail::lanes_as<f32x8>(u64x4{layer_bits(static_cast<std::uint32_t>(first[0])),
                                    layer_bits(static_cast<std::uint32_t>(first[1])),
                                    layer_bits(static_cast<std::uint32_t>(first[2])),
                                    layer_bits(static_cast<std::uint32_t>(first[3]))});
  const f32x8 second_pairs =
      detail::lanes_as<f32x8>(u64x4{layer_bits(static_cast<std::uint32_t>(second[0])),
                                    layer_bits(static_cast<std::uint32_t>(second[1])),
                                    layer_bits(static_cast<std::uint32_t>(second[2])),
                                    layer_bits(static_cast<std::uint32_t>(second[3]))});
  return {__builtin_shufflevector(first_halves, second_halves, 0, 2, 8, 10, 4, 6, 12, 14),
          __builtin_shufflevector(first_halves, second_halves, 1, 3, 9, 11, 5, 7, 13, 15),
          __builtin_shufflevector(first_pairs, second_pairs, 0, 2, 8, 10, 4, 6, 12, 14),
          __builtin_shufflevector(first_pairs, second_pairs, 1, 3, 9, 11, 5, 7, 13, 15)};
}

// The group's powers E, the slow ones with further words from the lanes.
template <class Lanes>
[[gnu::always_inline]] inline f32x8 group_powers(const Group& group, LaneStates& state) {
  const f32x8 power = detail::layer_uniform<f32x8>(group.power_words) * group.width;
  const u32x8 failed = detail::lanes_as<u32x8>(power >= group.covered);
  if (Lanes::any(failed)) [[unlikely]]
    return finish_slow_powers(state, group.power_words, power, failed);
  return power;
}

// The group's samples z = scale sqrt(E) e^{i theta} added to base. Weighted: each sum base + z is
// then multiplied by row_weight * weights[i] (the frame window applied in the same pass, with the
// products the separate window pass would form).
template <bool weighted, class Lanes>
[[gnu::always_inline]] inline void add_group(u32x8 phase_words, f32x8 power, double scale,
                                             const double* base, double* out, double row_weight,
                                             const double* weights) {
  f32x8 re, im;
  detail::polar(sqrt_lanes(power), phase_words, re, im);
  // (re, im) interleaved within 128-bit halves: samples 0-1 | 2-3 and 4-5 | 6-7.
  const f32x8 first_four = __builtin_shufflevector(re, im, 0, 8, 1, 9, 4, 12, 5, 13);
  const f32x8 last_four = __builtin_shufflevector(re, im, 2, 10, 3, 11, 6, 14, 7, 15);
  const f64x4 parts[4] = {
      Lanes::to_double(__builtin_shufflevector(first_four, first_four, 0, 1, 2, 3)),
      Lanes::to_double(__builtin_shufflevector(first_four, first_four, 4, 5, 6, 7)),
      Lanes::to_double(__builtin_shufflevector(last_four, last_four, 0, 1, 2, 3)),
      Lanes::to_double(__builtin_shufflevector(last_four, last_four, 4, 5, 6, 7))};
  for (std::size_t p = 0; p < 4; ++p) {
    f64x4 sum = detail::load4(base + 4 * p) + parts[p] * scale;
    if constexpr (weighted) sum *= row_weight * detail::load4(weights + 4 * p);
    detail::store4(out + 4 * p, sum);
  }
}

// Software-pipelined where Lanes::issue_next_early: once a group's powers are final (its slow path
// has drawn its further words), the next group's words are drawn and its table look-ups issued
// before this group's phase, square root and stores, which then hide the look-ups' latency. The
// words are drawn in the same order either way.
template <bool weighted, class Lanes>
[[gnu::always_inline]] inline void add_complex_normal_body(std::uint64_t* state_words,
                                                           const double* base, double* out,
                                                           std::size_t count, double scale,
                                                           double row_weight,
                                                           const double* weights) {
  if (count == 0) return;
  LaneStates state = load_states(state_words);
  std::size_t j = 0;
  Group group;
  if constexpr (Lanes::issue_next_early) {
    group = draw_group(state);
    for (; j + 8 < count; j += 8) {
      const f32x8 power = group_powers<Lanes>(group, state);
      const u32x8 phase_words = group.phase_words;
      group = draw_group(state);
      add_group<weighted, Lanes>(phase_words, power, scale, base + 2 * j, out + 2 * j, row_weight,
                                 weighted ? weights + 2 * j : nullptr);
    }
  } else {
    for (; j + 8 < count; j += 8) {
      group = draw_group(state);
      add_group<weighted, Lanes>(group.phase_words, group_powers<Lanes>(group, state), scale,
                                 base + 2 * j, out + 2 * j, row_weight,
                                 weighted ? weights + 2 * j : nullptr);
    }
    group = draw_group(state);
  }
  const f32x8 power = group_powers<Lanes>(group, state);
  if (j + 8 == count) {
    add_group<weighted, Lanes>(group.phase_words, power, scale, base + 2 * j, out + 2 * j,
                               row_weight, weighted ? weights + 2 * j : nullptr);
  } else {
    // A short last group: its unused samples are discarded.
    double last[16] = {};
    add_group<false, Lanes>(group.phase_words, power, scale, last, last, row_weight, nullptr);
    for (std::size_t i = 0; i < 2 * (count - j); ++i) {
      const double sum = base[2 * j + i] + last[i];
      out[2 * j + i] = weighted ? sum * (row_weight * weights[2 * j + i]) : sum;
    }
  }
  store_states(state_words, state);
}

// One body per instruction set, differing only in Lanes (above), as GCC's function multiversioning:
// the loader picks the version as it picks the clones of detail/simd.hpp.
#define FOGRADAR_NOISE_KERNELS(attributes, Lanes)                                                 \
  attributes void add_complex_normal(std::uint64_t* state_words, const double* base, double* out, \
                                     std::size_t count, double scale) {                           \
    add_complex_normal_body<false, Lanes>(state_words, base, out, count, scale, 1.0, nullptr);    \
  }                                                                                               \
  attributes void add_weighted_complex_normal(std::uint64_t* state_words, const double* base,     \
                                              double* out, std::size_t count, double scale,       \
                                              double row_weight, const double* weights) {         \
    add_complex_normal_body<true, Lanes>(state_words, base, out, count, scale, row_weight,        \
                                         weights);                                                \
  }

#if defined(FOGRADAR_SIMD_AVX2)
FOGRADAR_NOISE_KERNELS(__attribute__((target("default"), flatten)), BaselineLanes)
FOGRADAR_NOISE_KERNELS(__attribute__((target("avx2"), flatten)), AvxLanes)
#if defined(FOGRADAR_SIMD_AVX512)
FOGRADAR_NOISE_KERNELS(__attribute__((target("arch=x86-64-v4"), flatten)), AvxLanes)
#endif
#else
FOGRADAR_NOISE_KERNELS(, BaselineLanes)
#endif
#undef FOGRADAR_NOISE_KERNELS

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

void ComplexNormalGenerator::add(std::span<const std::complex<double>> base,
                                 std::span<std::complex<double>> out, double variance) {
  FOGRADAR_CHECK(variance >= 0.0 && base.size() == out.size());
  // std::complex<double> is layout-compatible with double[2] ([complex.numbers.general]).
  add_complex_normal(state_.data(), reinterpret_cast<const double*>(base.data()),
                     reinterpret_cast<double*>(out.data()), out.size(), std::sqrt(variance));
}

void ComplexNormalGenerator::add_weighted(std::span<const std::complex<double>> base,
                                          std::span<std::complex<double>> out, double variance,
                                          double row_weight, std::span<const double> part_weights) {
  FOGRADAR_CHECK(variance >= 0.0 && base.size() == out.size() &&
                 part_weights.size() == 2 * out.size());
  add_weighted_complex_normal(state_.data(), reinterpret_cast<const double*>(base.data()),
                              reinterpret_cast<double*>(out.data()), out.size(),
                              std::sqrt(variance), row_weight, part_weights.data());
}

}  // namespace fogradar
