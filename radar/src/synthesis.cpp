#include "fogradar/radar/synthesis.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "fogradar/core/complex_normal_generator.hpp"
#include "fogradar/core/constants.hpp"
#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::radar {
namespace {

constexpr std::size_t tone_block = 16;

// row[n] += a s^n for n = 0..N-1 (interleaved re, im): blocks of 16 samples, each the block's
// phasor b times the powers s^0..s^15, with b advanced by s^16 from block to block. `powers` holds
// s^j as (Re, Im) pairs and `rotated` as (-Im, Re) pairs, so b s^j = Re(b) powers + Im(b) rotated.
FOGRADAR_SIMD_CLONES
void add_tone_blocks(double* row, std::size_t n, std::complex<double> amplitude, const double* powers,
                     const double* rotated, std::complex<double> block_step) {
  using detail::f64x4;
  std::complex<double> block = amplitude;
  std::size_t start = 0;
  for (; start + tone_block <= n; start += tone_block) {
    double* out = row + 2 * start;
    for (std::size_t v = 0; v < 2 * tone_block; v += 4) {
      detail::store4(out + v, detail::load4(out + v) + block.real() * detail::load4(powers + v) +
                                  block.imag() * detail::load4(rotated + v));
    }
    block *= block_step;
  }
  for (std::size_t j = 0; start + j < n; ++j) {
    row[2 * (start + j)] += block.real() * powers[2 * j] + block.imag() * rotated[2 * j];
    row[2 * (start + j) + 1] += block.real() * powers[2 * j + 1] + block.imag() * rotated[2 * j + 1];
  }
}

// Adds a exp(i 2 pi f n / fs), n = 0..N-1, to `row`. The 64 block steps (N = 1024) and the 16
// powers keep the rounding error near (N/16 + 16) eps; the recurrence leaves no long dependency
// chain, so the adds vectorise.
void add_tone(std::span<std::complex<double>> row, std::complex<double> amplitude, double frequency_hz,
              double sample_rate_hz) {
  const std::complex<double> step = std::polar(1.0, 2.0 * pi * frequency_hz / sample_rate_hz);
  std::array<double, 2 * tone_block> powers{}, rotated{};
  std::complex<double> power = 1.0;
  for (std::size_t j = 0; j < tone_block; ++j) {
    powers[2 * j] = power.real();
    powers[2 * j + 1] = power.imag();
    rotated[2 * j] = -power.imag();
    rotated[2 * j + 1] = power.real();
    power *= step;
  }
  // std::complex<double> is layout-compatible with double[2] ([complex.numbers.general]).
  add_tone_blocks(reinterpret_cast<double*>(row.data()), row.size(), amplitude, powers.data(), rotated.data(),
                  power);
}

// Mid-rise quantiser of one rail: q (floor(x / q) + 1/2), clipped to the outermost levels.
double quantize_rail(double x, double step, double top_level, bool& clipped) {
  const double level = step * (std::floor(x / step) + 0.5);
  if (level > top_level || level < -top_level) {
    clipped = true;
    return std::clamp(level, -top_level, top_level);
  }
  return level;
}

}  // namespace

std::size_t quantize(std::span<std::complex<double>> samples, unsigned bits, double full_scale_amplitude) {
  FOGRADAR_CHECK(bits > 0 && full_scale_amplitude > 0.0);
  const double step = 2.0 * full_scale_amplitude / std::ldexp(1.0, static_cast<int>(bits));
  const double top_level = full_scale_amplitude - 0.5 * step;
  std::size_t clipped_count = 0;
  for (std::complex<double>& sample : samples) {
    bool clipped = false;
    sample = {quantize_rail(sample.real(), step, top_level, clipped),
              quantize_rail(sample.imag(), step, top_level, clipped)};
    clipped_count += clipped ? 1 : 0;
  }
  return clipped_count;
}

SynthesisReport synthesize_frame(std::span<const Tone> tones, const RadarParams& params,
                                 const RadarDerived& derived, RandomStream& rng,
                                 std::span<std::complex<double>> frame, const FrameWindow* window) {
  const std::size_t columns = params.samples_per_chirp;
  const std::size_t rows = params.chirps_per_frame;
  FOGRADAR_CHECK(frame.size() == rows * columns);
  FOGRADAR_CHECK(window == nullptr || (window->doppler.size() == rows && window->range_pairs.size() == 2 * columns));
  const auto row = [&](std::size_t c) { return frame.subspan(c * columns, columns); };

  // Static paths: one chirp, copied to all. Without phase noise (which multiplies the noise-free
  // signal) the thermal noise is added in the same pass as the copy; chirp 0, the source of the
  // copies, takes its noise last. When nothing follows the noise (no moving path, no ADC), that
  // pass applies the window too.
  std::fill(row(0).begin(), row(0).end(), std::complex<double>{});
  bool moving_paths = false;
  for (const Tone& tone : tones) {
    if (tone.radial_velocity_m_per_s != 0.0) {
      moving_paths = true;
      continue;
    }
    add_tone(row(0), tone.amplitude, beat_frequency_hz(tone.path_length_m, derived.chirp_slope_hz_per_s),
             params.sample_rate_hz);
  }
  const bool noise_with_copy = params.thermal_noise && params.phase_noise_rms_rad == 0.0;
  const bool window_with_noise = window != nullptr && noise_with_copy && !moving_paths && params.adc_bits == 0;
  if (window_with_noise) {
    ComplexNormalGenerator noise(rng);
    for (std::size_t c = 1; c < rows; ++c) {
      noise.add_weighted(row(0), row(c), derived.noise_power_w, window->doppler[c], window->range_pairs);
    }
    noise.add_weighted(row(0), row(0), derived.noise_power_w, window->doppler[0], window->range_pairs);
  } else if (noise_with_copy) {
    ComplexNormalGenerator noise(rng);
    for (std::size_t c = 1; c < rows; ++c) noise.add(row(0), row(c), derived.noise_power_w);
    noise.add(row(0), derived.noise_power_w);
  } else {
    for (std::size_t c = 1; c < rows; ++c) std::copy(row(0).begin(), row(0).end(), row(c).begin());
  }

  // Moving paths: Doppler shift within the chirp and phase progression from chirp to chirp.
  for (const Tone& tone : tones) {
    if (tone.radial_velocity_m_per_s == 0.0) continue;
    const double doppler_hz = doppler_shift_hz(tone.radial_velocity_m_per_s, derived);
    const double frequency_hz = beat_frequency_hz(tone.path_length_m, derived.chirp_slope_hz_per_s) + doppler_hz;
    for (std::size_t c = 0; c < rows; ++c) {
      const double chirp_phase = 2.0 * pi * doppler_hz * static_cast<double>(c) * params.chirp_interval_s;
      add_tone(row(c), tone.amplitude * std::polar(1.0, chirp_phase), frequency_hz, params.sample_rate_hz);
    }
  }

  if (params.phase_noise_rms_rad > 0.0) {
    for (std::complex<double>& sample : frame) {
      sample *= std::polar(1.0, params.phase_noise_rms_rad * rng.normal());
    }
  }
  if (params.thermal_noise && !noise_with_copy) ComplexNormalGenerator(rng).add(frame, derived.noise_power_w);
  SynthesisReport report;
  if (params.adc_bits > 0) {
    report.clipped_samples =
        quantize(frame, params.adc_bits, std::sqrt(dbm_to_watt(params.adc_full_scale_dbm)));
  }
  if (window != nullptr && !window_with_noise) apply_frame_window(*window, frame);
  return report;
}

}  // namespace fogradar::radar
