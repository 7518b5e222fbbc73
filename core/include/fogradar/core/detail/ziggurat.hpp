// The ziggurat of the exponential distribution (Marsaglia & Tsang, "The Ziggurat Method for
// Generating Random Variables", J. Stat. Softw. 5(8), 2000) used by ComplexNormalGenerator for the
// power |z|^2 of each sample: 2048 layers of equal area v under f(x) = exp(-x), x >= 0; layer 0 is
// the base strip [0, r] x [0, f(r)] plus the tail x > r, layer i >= 1 the rectangle
// [0, x_i] x [f(x_i), f(x_{i+1})].
// A 32-bit word draws one sample (Doornik's remedy, "An Improved Ziggurat Method to Generate
// Normal Random Samples", 2005: the layer and the uniform come from disjoint bits): bits 0-10 the
// layer i, bits 11-31 a uniform u = k 2^-21, x = u x_i. With probability 0.99658, x < x_{i+1} and x
// is the sample (the fast path); otherwise the wedge test or the tail, r + Exp(1) (the exponential
// is memoryless), decides with further words.
// Everything is built from IEEE-exact operations and fdlibm's log, never libm or FMA, so the table
// (computed at compile time) and the samples are the same on every machine. Internal to fogradar;
// the tests check the table against libm and the published r of the 256-layer ziggurat.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "fogradar/core/detail/lanes_as.hpp"

namespace fogradar::detail {

// 1 + (top 52 bits of `word`) 2^-52: a double in [1, 2) with 52 random mantissa bits.
constexpr double mantissa_in_one_two(std::uint64_t word) {
  return std::bit_cast<double>((word >> 12) | 0x3FF0'0000'0000'0000ULL);
}

// ln(x) for normal x > 0, fdlibm __ieee754_log (e_log.c, Sun Microsystems 1993; error < 1 ulp):
//   x = 2^k (1 + f) with sqrt(2)/2 <= 1 + f < sqrt(2), s = f / (2 + f),
//   ln(1 + f) = f - (f^2/2 - s (f^2/2 + R(s^2))), R the Remez polynomial Lg1 s^2 + ... + Lg7 s^14,
//   ln x = k ln2_hi + (ln(1 + f) + k ln2_lo).
// fdlibm switches to f - s (f - R) for mantissas within ~1.5 % below sqrt(2); this branch-free form
// uses the first expression everywhere (checked against libm in test_complex_normal.cpp).
constexpr double log_positive(double x) {
  constexpr double ln2_hi = 6.93147180369123816490e-01;  // 3fe62e42 fee00000
  constexpr double ln2_lo = 1.90821492927058770002e-10;  // 3dea39ef 35793c76
  constexpr double lg1 = 6.666666666666735130e-01, lg2 = 3.999999999940941908e-01,
                   lg3 = 2.857142874366239149e-01, lg4 = 2.222219843214978396e-01,
                   lg5 = 1.818357216161805012e-01, lg6 = 1.531383769920937332e-01,
                   lg7 = 1.479819860511658591e-01;
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
  const std::uint64_t mantissa = bits & 0x000F'FFFF'FFFF'FFFFULL;
  // Carry into bit 52 iff the mantissa is >= sqrt(2) - 1: then 1 + f is halved and k raised by 1.
  const std::uint64_t halve = (mantissa + 0x0009'5F64'0000'0000ULL) & 0x0010'0000'0000'0000ULL;
  const double one_plus_f = std::bit_cast<double>(mantissa | (halve ^ 0x3FF0'0000'0000'0000ULL));
  const double k =
      static_cast<double>(static_cast<std::int64_t>((bits >> 52) + (halve >> 52)) - 1023);
  const double f = one_plus_f - 1.0;
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double w = z * z;
  const double r = z * (lg1 + w * (lg3 + w * (lg5 + w * lg7))) + w * (lg2 + w * (lg4 + w * lg6));
  const double half_f_squared = 0.5 * f * f;
  return k * ln2_hi - ((half_f_squared - (s * (half_f_squared + r) + k * ln2_lo)) - f);
}

inline constexpr int ziggurat_index_bits = 11;
inline constexpr std::size_t ziggurat_layers = std::size_t{1} << ziggurat_index_bits;
inline constexpr int ziggurat_uniform_bits = 32 - ziggurat_index_bits;
// r, f(r) = exp(-r) and v = r f(r) + exp(-r) for 2048 layers: r solves "the recursion
// x_{i+1} = f^-1(f(x_i) + v/x_i) closes the top layer with area v", found by bisection in 50-digit
// arithmetic (mpmath); each constant is that root's value correctly rounded (f(r) and v taken at
// the exact root). The tests recompute all three with libm.
inline constexpr double ziggurat_r = 0x1.40bb92a1ff2a6p+3;     // 10.02289706840504
inline constexpr double ziggurat_f_r = 0x1.74389b46b1a48p-15;  // 4.437221519064789e-5
inline constexpr double ziggurat_v = 0x1.006f48073a080p-11;    // 4.891103607436303e-4

struct ZigguratTable {
  // {x_i, x_{i+1}} in single precision: the fast path's width of layer i and the part of it that
  // lies under f in full (x_0 = v / f(r), the base strip's width as if it held the tail; x_2048 =
  // 0).
  std::array<std::array<float, 2>, ziggurat_layers> fast{};
  std::array<double, ziggurat_layers + 1> x{};
  std::array<double, ziggurat_layers + 1> f{};  // f(x_i); f_0 = 0 (the strip reaches the x axis)
};

// x_1 = r, f_{i+1} = f_i + v / x_i (layer i has area x_i (f_{i+1} - f_i) = v),
// x_{i+1} = -ln f_{i+1}; the top layer ends at x_2048 = 0, f = 1.
constexpr ZigguratTable make_ziggurat_table() {
  ZigguratTable table;
  auto& x = table.x;
  auto& f = table.f;
  x[0] = ziggurat_v / ziggurat_f_r;
  f[0] = 0.0;
  x[1] = ziggurat_r;
  f[1] = ziggurat_f_r;
  for (std::size_t i = 1; i + 1 < ziggurat_layers; ++i) {
    f[i + 1] = f[i] + ziggurat_v / x[i];
    x[i + 1] = -log_positive(f[i + 1]);
  }
  x[ziggurat_layers] = 0.0;
  f[ziggurat_layers] = 1.0;
  for (std::size_t i = 0; i < ziggurat_layers; ++i) {
    table.fast[i] = {static_cast<float>(x[i]), static_cast<float>(x[i + 1])};
  }
  return table;
}

// u in [0, 1) from the top 21 bits of a sample word, exactly (a float has 23 mantissa bits); for
// one word (Float = float, Word = std::uint32_t) or for the lanes of a vector of them.
template <class Float, class Word>
[[gnu::always_inline]] inline Float layer_uniform(Word word) {
  return lanes_as<Float>(((word >> ziggurat_index_bits) << (23 - ziggurat_uniform_bits)) |
                         0x3F80'0000U) -
         1.0F;
}

// The fast path: x = u x_i, taken when x < x_{i+1}. Returns false (and x) otherwise.
inline bool ziggurat_fast(std::uint32_t word, const ZigguratTable& table, float& x) {
  const auto& layer = table.fast[word & (ziggurat_layers - 1)];
  x = layer_uniform<float>(word) * layer[0];
  return x < layer[1];
}

// The rest of a sample whose fast path failed on `word` with x = u x_i: the tail or the wedge,
// then new layers, with further 64-bit words from `next_word` (in the order drawn; a new layer is
// tried with the low 32 bits of a fresh word).
template <class NextWord>
float ziggurat_slow(std::uint32_t word, float x, const ZigguratTable& table, NextWord&& next_word) {
  for (;;) {
    const std::size_t i = word & (ziggurat_layers - 1);
    if (i == 0) {
      // Tail x > r: r - ln U with U in (0, 1].
      return static_cast<float>(ziggurat_r - log_positive(2.0 - mantissa_in_one_two(next_word())));
    }
    // Wedge: a uniform height y in the layer lies under f at x iff ln y < -x.
    const double y =
        table.f[i] + (mantissa_in_one_two(next_word()) - 1.0) * (table.f[i + 1] - table.f[i]);
    if (log_positive(y) < -static_cast<double>(x)) return x;
    word = static_cast<std::uint32_t>(next_word());
    if (ziggurat_fast(word, table, x)) return x;
  }
}

// One Exp(1) sample from `word` and, where the fast path fails, further words from `next_word`.
template <class NextWord>
float ziggurat_exponential(std::uint32_t word, const ZigguratTable& table, NextWord&& next_word) {
  float x = 0.0F;
  if (ziggurat_fast(word, table, x)) return x;
  return ziggurat_slow(word, x, table, next_word);
}

}  // namespace fogradar::detail
