// The ziggurat of the normal distribution (Marsaglia & Tsang, "The Ziggurat Method for Generating
// Random Variables", J. Stat. Softw. 5(8), 2000) used by ComplexNormalGenerator: 2048 layers of
// equal area v under f(x) = exp(-x^2/2), x >= 0; layer 0 is the base strip [0, r] x [0, f(r)] plus
// the tail x > r, layer i >= 1 the rectangle [0, x_i] x [f(x_i), f(x_{i+1})].
// A 32-bit word draws one sample (Doornik's remedy, "An Improved Ziggurat Method to Generate
// Normal Random Samples", 2005: the layer, the sign and the uniform come from disjoint bits):
// bits 0-10 the layer i, bit 11 the sign, bits 12-31 a uniform u = k 2^-20, x = u x_i. With
// probability 0.9977, x < x_{i+1} and x is the sample (the fast path); otherwise the wedge test or
// Marsaglia's tail method (Ann. Math. Stat. 35, 1964) decides with further words.
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
  const double k = static_cast<double>(static_cast<std::int64_t>((bits >> 52) + (halve >> 52)) - 1023);
  const double f = one_plus_f - 1.0;
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double w = z * z;
  const double r = z * (lg1 + w * (lg3 + w * (lg5 + w * lg7))) + w * (lg2 + w * (lg4 + w * lg6));
  const double half_f_squared = 0.5 * f * f;
  return k * ln2_hi - ((half_f_squared - (s * (half_f_squared + r) + k * ln2_lo)) - f);
}

// sqrt(a) for normal a > 0 within 1 ulp, by Newton's iteration y <- (y + a/y)/2 from the halved
// exponent (relative error < 6 %, squared at every step): std::sqrt is not constexpr in C++20.
constexpr double sqrt_newton(double a) {
  double y = std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) >> 1) + 0x1FF8'0000'0000'0000ULL);
  for (int step = 0; step < 6; ++step) y = 0.5 * (y + a / y);
  return y;
}

inline constexpr int ziggurat_index_bits = 11;
inline constexpr std::size_t ziggurat_layers = std::size_t{1} << ziggurat_index_bits;
inline constexpr int ziggurat_uniform_bits = 32 - ziggurat_index_bits - 1;
// r, f(r) = exp(-r^2/2) and v = r f(r) + sqrt(pi/2) erfc(r/sqrt 2) for 2048 layers: r solves
// "the recursion x_{i+1} = f^-1(f(x_i) + v/x_i) closes the top layer with area v", found by
// bisection in 50-digit arithmetic (mpmath); each constant is that root's value correctly rounded
// (f(r) and v are taken at the exact root, so they sit 1-2 ulp from libm's values at the rounded r).
// The tests recompute all three with libm.
inline constexpr double ziggurat_r = 0x1.0dd903462b3f1p+2;     // 4.216370409511897
inline constexpr double ziggurat_f_r = 0x1.2139508669177p-13;  // 1.37912695390995e-4
inline constexpr double ziggurat_v = 0x1.412ea7ab08321p-11;    // 6.126065176240461e-4

struct ZigguratTable {
  // {x_i, x_{i+1}} in single precision: the fast path's width of layer i and the part of it that
  // lies under f in full (x_0 = v / f(r), the base strip's width as if it held the tail; x_2048 = 0).
  std::array<std::array<float, 2>, ziggurat_layers> fast{};
  std::array<double, ziggurat_layers + 1> x{};
  std::array<double, ziggurat_layers + 1> f{};  // f(x_i); f_0 = 0 (the strip reaches the x axis)
};

// x_1 = r, f_{i+1} = f_i + v / x_i (layer i has area x_i (f_{i+1} - f_i) = v),
// x_{i+1} = sqrt(-2 ln f_{i+1}); the top layer ends at x_2048 = 0, f = 1.
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
    x[i + 1] = sqrt_newton(-2.0 * log_positive(f[i + 1]));
  }
  x[ziggurat_layers] = 0.0;
  f[ziggurat_layers] = 1.0;
  for (std::size_t i = 0; i < ziggurat_layers; ++i) {
    table.fast[i] = {static_cast<float>(x[i]), static_cast<float>(x[i + 1])};
  }
  return table;
}

// The bit layout of a sample word, for one word (Float = float, Word = std::uint32_t) or for
// the lanes of a vector of them (the generator's f32x8, u32x8).

// u in [0, 1) from the top 20 bits of a sample word, exactly (a float has 23 mantissa bits).
template <class Float, class Word>
[[gnu::always_inline]] inline Float layer_uniform(Word word) {
  constexpr int shift = 32 - ziggurat_uniform_bits;
  return lanes_as<Float>(((word >> shift) << (23 - ziggurat_uniform_bits)) | 0x3F80'0000U) - 1.0F;
}

// |x| with the sign of bit 11 of the sample word.
template <class Float, class Word>
[[gnu::always_inline]] inline Float with_sign(Float magnitude, Word word) {
  return lanes_as<Float>(lanes_as<Word>(magnitude) ^ ((word << (31 - ziggurat_index_bits)) & 0x8000'0000U));
}

// The fast path: x = u x_i, taken when x < x_{i+1}. Returns false (and x) otherwise.
inline bool ziggurat_fast(std::uint32_t word, const ZigguratTable& table, float& x) {
  const auto& layer = table.fast[word & (ziggurat_layers - 1)];
  x = layer_uniform<float>(word) * layer[0];
  return x < layer[1];
}

// One N(0, 1) sample from `word` and, where the fast path fails, further 64-bit words from
// `next_word` (in the order drawn; a new layer is tried with the low 32 bits of a fresh word).
template <class NextWord>
float ziggurat_normal(std::uint32_t word, const ZigguratTable& table, NextWord&& next_word) {
  const auto uniform_open_zero = [&] { return 2.0 - mantissa_in_one_two(next_word()); };  // (0, 1]
  for (;;) {
    float x = 0.0F;
    if (ziggurat_fast(word, table, x)) return with_sign(x, word);
    const std::size_t i = word & (ziggurat_layers - 1);
    if (i == 0) {
      // Tail x > r: x = r + a with a = -ln(U1)/r, accepted when -2 ln(U2) > a^2.
      for (;;) {
        const double a = -log_positive(uniform_open_zero()) / ziggurat_r;
        const double b = -log_positive(uniform_open_zero());
        if (b + b > a * a) return with_sign(static_cast<float>(ziggurat_r + a), word);
      }
    }
    // Wedge: a uniform height y in the layer lies under f at x iff ln y < -x^2/2.
    const double y = table.f[i] + (mantissa_in_one_two(next_word()) - 1.0) * (table.f[i + 1] - table.f[i]);
    const double xd = x;
    if (log_positive(y) < -0.5 * xd * xd) return with_sign(x, word);
    word = static_cast<std::uint32_t>(next_word());
  }
}

}  // namespace fogradar::detail
