// Thermal noise for whole frames: circular complex Gaussian samples, eight at a time in SIMD lanes.
// Scalar Box–Muller through libm (RandomStream::complex_normal) costs ~40 ns per sample, five times
// a frame's FFTs; this generator runs four xoshiro256++ streams side by side (one per SIMD lane,
// the vectorisation the xoshiro authors describe) and turns each 64-bit word into one complex
// sample z = sqrt(variance E) e^{i theta} (a circular Gaussian's power is exponential and
// independent of its uniform phase): E ~ Exp(1) from the low half by a single-precision exponential
// ziggurat (detail/ziggurat.hpp), theta from the high half by float sine and cosine polynomials
// (detail/polar.hpp). One table look-up per sample: ~2 ns per sample (docs/performance.md).
// Precision: each part is a float times sqrt(variance) in double: float(sqrt E) times the float
// cosine or sine, with E = u x_i from a 21-bit uniform (relative error ~2e-7, the polynomials' 1e-7
// included; far below any noise statistic the simulator measures); theta takes 2^24 equally spaced
// values. The ziggurat is exact up to that quantisation, tail included: E reaches r - ln 2^-52 = 46
// (|z|^2 = 46 variance, probability 1e-20).
// Reproducibility: the lanes are seeded from the caller's RandomStream, and the arithmetic uses
// only IEEE-exact operations (multiplication, addition, square root, conversion) without FMA or
// libm, so the samples depend on the seed alone, not on the thread count or on which instruction
// set (AVX-512, AVX2 or the x86-64 baseline) the library picks at run time.
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fogradar/core/random.hpp"

namespace fogradar {

class ComplexNormalGenerator {
 public:
  static constexpr std::size_t lanes = 4;

  // Lane l's xoshiro256++ state is the SplitMix64 sequence started at the l-th of `lanes` draws
  // from `parent` (the seeding the xoshiro authors recommend), so the generator is a pure function
  // of the parent stream's state, and `parent` advances by `lanes` draws.
  explicit ComplexNormalGenerator(RandomStream& parent);

  // samples[j] += z_j with z_j ~ CN(0, variance) independent (E|z|^2 = variance), for all j.
  // Samples come in groups of eight from two steps of the four lanes: sample 8g + 4s + l uses lane
  // l's word of step s (its low half the power, its high half the phase; the ~0.34 % of powers that
  // leave the ziggurat's fast path take further words of the same lane, after both steps, in
  // sample order); a call whose length is not a multiple of 8 discards the unused samples of its
  // last group, so the samples depend on how a buffer is split into calls. variance >= 0.
  void add(std::span<std::complex<double>> samples, double variance);

  // out[j] = base[j] + z_j with the same samples z_j as add(): one pass that writes a noisy copy
  // of `base` (the static chirp copied into every chirp of a frame). base.size() == out.size();
  // base may be out itself.
  void add(std::span<const std::complex<double>> base, std::span<std::complex<double>> out,
           double variance);

  // The same pass with weights: Re out[j] = Re(base[j] + z_j) (row_weight part_weights[2j]) and
  // Im out[j] = Im(base[j] + z_j) (row_weight part_weights[2j + 1]), the same z_j as add(), so that
  // a separable window (row_weight a chirp's Doppler weight, part_weights the range weights, each
  // twice) costs no pass of its own. part_weights.size() == 2 out.size().
  void add_weighted(std::span<const std::complex<double>> base, std::span<std::complex<double>> out,
                    double variance, double row_weight, std::span<const double> part_weights);

 private:
  // Word w of lane l at state_[w * lanes + l] (structure of arrays: one vector per word).
  alignas(32) std::array<std::uint64_t, 4 * lanes> state_{};
};

}  // namespace fogradar
