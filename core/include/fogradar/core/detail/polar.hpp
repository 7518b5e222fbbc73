// The phase of ComplexNormalGenerator's samples: a 32-bit word picks theta on a lattice of 2^24
// equally spaced angles, theta = (j + 1/2) 2 pi / 2^24 - pi/4, and radius e^{i theta} is formed
// with float polynomials for sine and cosine, no table and no libm. Bits 10-31 of the word give t =
// (k + 1/2) 2^-22 - 1/2 in (-1/2, 1/2) and phi = pi t / 2 in
// (-pi/4, pi/4); bit 0 swaps cosine and sine (the angle pi/2 - phi, which continues the lattice
// into (pi/4, 3pi/4)), bit 1 negates both (the angle + pi). Bits 2-9 are not used. sin(pi t/2) = t
// (S0 + S1 t^2 + S2 t^4 + S3 t^6), cos(pi t/2) = 1 + C1 t^2 + C2 t^4 + C3 t^6: minimax (Lawson)
// fits on [0, 1/2] rounded to float, evaluated by Horner's rule with plain multiplications and
// additions (no FMA, so every instruction set computes the same bits); the tests measure their
// errors over all 2^22 arguments against libm.
// For one word (Float = float, Word = std::uint32_t) or for the lanes of a vector of them.
// Internal to fogradar.
#pragma once

#include <cstdint>

#include "fogradar/core/detail/lanes_as.hpp"

namespace fogradar::detail {

inline constexpr float phase_sin_s0 = 0x1.921fb4p+0F;   // 1.5707963
inline constexpr float phase_sin_s1 = -0x1.4abba8p-1F;  // -0.64596295
inline constexpr float phase_sin_s2 = 0x1.465a3ep-4F;   // 0.079675905
inline constexpr float phase_sin_s3 = -0x1.2cf5d4p-8F;  // -0.0045922892
inline constexpr float phase_cos_c1 = -0x1.3bd3a2p+0F;  // -1.233698
inline constexpr float phase_cos_c2 = 0x1.03b162p-2F;   // 0.25360635
inline constexpr float phase_cos_c3 = -0x1.4ea9eep-6F;  // -0.020426257

// t = (k + 1/2) 2^-22 - 1/2 for k = bits 10-31 of `word`, exactly: the mantissa 1 + (2k + 1) 2^-23.
template <class Float, class Word>
[[gnu::always_inline]] inline Float phase_fraction(Word word) {
  return lanes_as<Float>((word >> 9) | 0x3F80'0001U) - 1.5F;
}

// re + i im = radius e^{i theta(word)}.
template <class Float, class Word>
[[gnu::always_inline]] inline void polar(Float radius, Word word, Float& re, Float& im) {
  const Float t = phase_fraction<Float>(word);
  const Float t2 = t * t;
  const Float sine =
      t * (phase_sin_s0 + t2 * (phase_sin_s1 + t2 * (phase_sin_s2 + t2 * phase_sin_s3)));
  const Float cosine = 1.0F + t2 * (phase_cos_c1 + t2 * (phase_cos_c2 + t2 * phase_cos_c3));
  const Word swap = Word{} - (word & 1U);  // all ones where bit 0 is set
  const Word differ = (lanes_as<Word>(cosine) ^ lanes_as<Word>(sine)) & swap;
  const Float signed_radius =
      lanes_as<Float>(lanes_as<Word>(radius) ^ ((word << 30) & 0x8000'0000U));
  re = signed_radius * lanes_as<Float>(lanes_as<Word>(cosine) ^ differ);
  im = signed_radius * lanes_as<Float>(lanes_as<Word>(sine) ^ differ);
}

}  // namespace fogradar::detail
