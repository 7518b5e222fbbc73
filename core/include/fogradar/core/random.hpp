// Seeded, reproducible random streams. Every measurement gets its own stream derived from
// (seed, step, index), so results do not depend on thread count or scheduling.
// Generator: xoshiro256++ (Blackman & Vigna, ACM TOMS 47(4), 2021); seeding and stream derivation
// by SplitMix64 (Steele, Lea & Flood, OOPSLA 2014), as the xoshiro authors recommend.
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>

#include "fogradar/core/constants.hpp"

namespace fogradar {

// One SplitMix64 step: advances `state` and returns a well-mixed 64-bit value.
constexpr std::uint64_t splitmix64(std::uint64_t& state) {
  state += 0x9E3779B97F4A7C15ULL;
  std::uint64_t z = state;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// xoshiro256++ next() on a state of four words: the update of RandomStream, also run by
// ComplexNormalGenerator on one of its SIMD lanes.
constexpr std::uint64_t xoshiro256pp_next(std::array<std::uint64_t, 4>& s) {
  const auto rotl = [](std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); };
  const std::uint64_t result = rotl(s[0] + s[3], 23) + s[0];
  const std::uint64_t t = s[1] << 17;
  s[2] ^= s[0];
  s[3] ^= s[1];
  s[1] ^= s[2];
  s[0] ^= s[3];
  s[2] ^= t;
  s[3] = rotl(s[3], 45);
  return result;
}

class RandomStream {
 public:
  using result_type = std::uint64_t;

  // The stream for (seed, a, b): distinct triples give statistically independent streams.
  explicit RandomStream(std::uint64_t seed, std::uint64_t a = 0, std::uint64_t b = 0) {
    std::uint64_t mix = seed;
    mix = splitmix64(mix) ^ a;
    mix = splitmix64(mix) ^ b;
    for (std::uint64_t& word : state_) word = splitmix64(mix);
  }

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

  // xoshiro256++ next().
  result_type operator()() { return xoshiro256pp_next(state_); }

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>((*this)() >> 11) * 0x1.0p-53; }

  // Uniform in (0, 1]: safe for log().
  double uniform_open_zero() { return 1.0 - uniform(); }

  // Exponential with unit mean: -ln U.
  double exponential() { return -std::log(uniform_open_zero()); }

  // Circular complex Gaussian CN(0, variance) by Box-Muller: |z|^2 ~ variance * Exp(1) and a
  // uniform phase, i.e. a Rayleigh amplitude with a random phase.
  std::complex<double> complex_normal(double variance) {
    const double radius = std::sqrt(variance * exponential());
    const double phase = 2.0 * pi * uniform();
    return {radius * std::cos(phase), radius * std::sin(phase)};
  }

  // Standard normal (the real part of CN(0, 2)).
  double normal() { return complex_normal(2.0).real(); }

 private:
  std::array<std::uint64_t, 4> state_{};
};

// The stream of item `index` (a measurement, a scan, a frame, or a per-step series the sensor
// defines) at step `step` of the sensor whose stream key is `sensor_key` (sensor/sensor.hpp: each
// sensor declares its own, distinct in one registry), so adding a sensor to a scenario never
// changes another sensor's numbers. Key 0's streams (the radar's) are RandomStream(seed, step,
// index), the streams of every earlier version; another key's seed word is first mixed with the key
// by one more SplitMix64 step, which makes its triples distinct from key 0's.
inline RandomStream sensor_stream(std::uint64_t seed, std::uint64_t sensor_key, std::uint64_t step,
                                  std::uint64_t index) {
  if (sensor_key == 0) return RandomStream(seed, step, index);
  std::uint64_t mix = seed ^ (sensor_key << 56);
  return RandomStream(splitmix64(mix), step, index);
}

}  // namespace fogradar
