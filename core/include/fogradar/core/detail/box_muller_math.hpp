// Kernels of the vectorised Box–Muller generator (complex_normal_generator.hpp), written once for a
// scalar `double` and for GCC/Clang vector types. They use only +, -, *, / (IEEE-exact operations)
// and integer bit operations, never FMA or libm, so each lane of a vector instruction yields the
// bits of the scalar version on every instruction set: the noise does not depend on the machine.
// Internal to fogradar (the tests check the kernels against libm and the vector path against the
// scalar path); not part of the public API.
#pragma once

#include <bit>
#include <cstdint>

#include "fogradar/core/detail/simd.hpp"

namespace fogradar::detail {

// The floating-point type with the lanes of U, and the integer type with the bits of F.
template <class T>
struct lanes_of;
template <>
struct lanes_of<double> {
  using floating = double;
  using bits = std::uint64_t;
};
template <>
struct lanes_of<std::uint64_t> : lanes_of<double> {};
template <>
struct lanes_of<f64x4> {
  using floating = f64x4;
  using bits = u64x4;
};
template <>
struct lanes_of<u64x4> : lanes_of<f64x4> {};

// 1 + (top 52 bits of `word`) 2^-52: a double in [1, 2) with 52 random mantissa bits.
template <class U>
[[gnu::always_inline]] inline typename lanes_of<U>::floating mantissa_in_one_two(U word) {
  return std::bit_cast<typename lanes_of<U>::floating>((word >> 12) | 0x3FF0'0000'0000'0000ULL);
}

// ln(x) for normal x > 0, fdlibm __ieee754_log (e_log.c, Sun Microsystems 1993; error < 1 ulp):
//   x = 2^k (1 + f) with sqrt(2)/2 <= 1 + f < sqrt(2), s = f / (2 + f),
//   ln(1 + f) = f - (f^2/2 - s (f^2/2 + R(s^2))), R the Remez polynomial Lg1 s^2 + ... + Lg7 s^14,
//   ln x = k ln2_hi + (ln(1 + f) + k ln2_lo).
// fdlibm switches to f - s (f - R) for mantissas within ~1.5 % below sqrt(2); this branch-free form
// uses the first expression everywhere (checked against libm in test_complex_normal.cpp).
template <class F>
[[gnu::always_inline]] inline F log_positive(F x) {
  using U = typename lanes_of<F>::bits;
  constexpr double ln2_hi = 6.93147180369123816490e-01;  // 3fe62e42 fee00000
  constexpr double ln2_lo = 1.90821492927058770002e-10;  // 3dea39ef 35793c76
  constexpr double lg1 = 6.666666666666735130e-01, lg2 = 3.999999999940941908e-01,
                   lg3 = 2.857142874366239149e-01, lg4 = 2.222219843214978396e-01,
                   lg5 = 1.818357216161805012e-01, lg6 = 1.531383769920937332e-01,
                   lg7 = 1.479819860511658591e-01;
  const U bits = std::bit_cast<U>(x);
  const U mantissa = bits & 0x000F'FFFF'FFFF'FFFFULL;
  // Carry into bit 52 iff the mantissa is >= sqrt(2) - 1: then 1 + f is halved and k raised by 1.
  const U halve = (mantissa + 0x0009'5F64'0000'0000ULL) & 0x0010'0000'0000'0000ULL;
  const F one_plus_f = std::bit_cast<F>(mantissa | (halve ^ 0x3FF0'0000'0000'0000ULL));
  // k + 1023 + 2^52 as a double, exactly, then minus the offsets (all integers below 2^53).
  const U biased_k = (bits >> 52) + (halve >> 52);
  const F k = std::bit_cast<F>(biased_k | 0x4330'0000'0000'0000ULL) - (0x1p52 + 1023.0);
  const F f = one_plus_f - 1.0;
  const F s = f / (2.0 + f);
  const F z = s * s;
  const F w = z * z;
  const F r = z * (lg1 + w * (lg3 + w * (lg5 + w * lg7))) + w * (lg2 + w * (lg4 + w * lg6));
  const F half_f_squared = 0.5 * f * f;
  return k * ln2_hi - ((half_f_squared - (s * (half_f_squared + r) + k * ln2_lo)) - f);
}

// sin x for |x| <= pi/4, fdlibm __kernel_sin (k_sin.c, Sun 1993): x + x^3 (S1 + x^2 (S2 + ... S6 x^8)).
template <class F>
[[gnu::always_inline]] inline F sin_quarter(F x) {
  constexpr double s1 = -1.66666666666666324348e-01, s2 = 8.33333333332248946124e-03,
                   s3 = -1.98412698298579493134e-04, s4 = 2.75573137070700676789e-06,
                   s5 = -2.50507602534068634195e-08, s6 = 1.58969099521155010221e-10;
  const F z = x * x;
  const F r = s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)));
  return x + (z * x) * (s1 + z * r);
}

// cos x for |x| <= pi/4, fdlibm __kernel_cos coefficients (k_cos.c, Sun 1993) with the branch-free
// final sum of FreeBSD msun k_cos.c: w = 1 - z/2, cos x = w + (((1 - w) - z/2) + z^2 C(z)).
template <class F>
[[gnu::always_inline]] inline F cos_quarter(F x) {
  constexpr double c1 = 4.16666666666666019037e-02, c2 = -1.38888888888741095749e-03,
                   c3 = 2.48015872894767294178e-05, c4 = -2.75573143513906633035e-07,
                   c5 = 2.08757232129817482790e-09, c6 = -1.13596475577881948265e-11;
  const F z = x * x;
  const F r = z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * c6)))));
  const F half_z = 0.5 * z;
  const F w = 1.0 - half_z;
  return w + (((1.0 - w) - half_z) + z * r);
}

// One circular complex Gaussian CN(0, variance) per lane from two 64-bit random words (Box & Muller
// 1958, Ann. Math. Stat. 29(2) 610): |z|^2 = -variance ln u with u = 2 - m in (0, 1] from the top
// 52 bits of `radius_word` (m in [1, 2)); phase = q pi/2 + theta with the quadrant q from the top
// 2 bits of `phase_word` and theta in [-pi/4, pi/4) from its next 52 bits, so sin and cos need only
// the quarter-range kernels. `sqrt_lanes` takes the square root of every lane (a vector square root
// has no portable operator). Writes the real and imaginary parts.
template <class F, class U, class Sqrt>
[[gnu::always_inline]] inline void box_muller(U radius_word, U phase_word, double variance, Sqrt sqrt_lanes,
                                              F& real, F& imag) {
  constexpr double half_pi = 1.57079632679489661923;
  const F u = 2.0 - mantissa_in_one_two(radius_word);
  const F radius = sqrt_lanes(F{} - variance * log_positive(u));
  const F theta = (mantissa_in_one_two(phase_word << 2) - 1.5) * half_pi;
  const F sin_theta = sin_quarter(theta);
  const F cos_theta = cos_quarter(theta);
  // Rotation by q pi/2: (cos, sin) -> (-sin, cos) -> (-cos, -sin) -> (sin, -cos).
  const U quadrant = phase_word >> 62;
  const auto odd = (quadrant & 1) != 0;
  const U real_sign = (((quadrant + 1) >> 1) & 1) << 63;
  const U imag_sign = (quadrant >> 1) << 63;
  real = radius * std::bit_cast<F>(std::bit_cast<U>(odd ? sin_theta : cos_theta) ^ real_sign);
  imag = radius * std::bit_cast<F>(std::bit_cast<U>(odd ? cos_theta : sin_theta) ^ imag_sign);
}

}  // namespace fogradar::detail
