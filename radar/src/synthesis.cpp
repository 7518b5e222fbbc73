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
// Static tones summed in one pass over the row: each pass loads and stores the row once for up to
// this many tones instead of once per tone.
constexpr std::size_t tones_per_pass = 4;

// One tone a exp(i 2 pi f n / fs) as add_tone_blocks sums it: `powers` holds s^0..s^15 as (Re, Im)
// pairs and `rotated` as (-Im, Re) pairs, s = exp(i 2 pi f / fs); block_step = s^16. The arrays
// are left uninitialised: fill_tone_powers writes every value before any is read, and zeroing and
// copying these 544 bytes per tone (rep stos, rep movs) cost a third of synthesize_frame's own
// time.
struct TonePhasors {
  std::array<double, 2 * tone_block> powers, rotated;
  std::complex<double> amplitude, block_step;
};

// Fills the powers and the block steps of tones[0..count) from their steps s (in block_step on
// entry): s^j by repeated multiplication, s^16 = block_step on return. The 64 block steps
// (N = 1024) and the 16 powers keep the rounding error near (N/16 + 16) eps; the recurrence leaves
// no long dependency chain in add_tone_blocks, so the adds vectorise. The tones' chains of products
// are independent and interleaved here (each the product sequence of a tone alone).
void fill_tone_powers(TonePhasors* tones, std::size_t count) {
  std::array<std::complex<double>, tones_per_pass> power, step;
  for (std::size_t t = 0; t < count; ++t) {
    power[t] = 1.0;
    step[t] = tones[t].block_step;
  }
  for (std::size_t j = 0; j < tone_block; ++j) {
    for (std::size_t t = 0; t < count; ++t) {
      tones[t].powers[2 * j] = power[t].real();
      tones[t].powers[2 * j + 1] = power[t].imag();
      tones[t].rotated[2 * j] = -power[t].imag();
      tones[t].rotated[2 * j + 1] = power[t].real();
      power[t] *= step[t];
    }
  }
  for (std::size_t t = 0; t < count; ++t) tones[t].block_step = power[t];
}

// Sets a tone's amplitude and step s = exp(i 2 pi f / fs), before fill_tone_powers.
void set_tone_step(TonePhasors& tone, std::complex<double> amplitude, double frequency_hz,
                   double sample_rate_hz) {
  tone.amplitude = amplitude;
  tone.block_step = std::polar(1.0, 2.0 * pi * frequency_hz / sample_rate_hz);
}

// row[n] += a_t s_t^n for n = 0..N-1 (interleaved re, im) and each of `count` tones in turn:
// blocks of 16 samples, each the block's phasor b times the powers s^0..s^15, with b advanced by
// s^16 from block to block, so b s^j = Re(b) powers + Im(b) rotated. Every value takes the tones'
// terms in their order, each formed as for a tone alone: the sum is the one `count` passes of one
// tone each would give, bit for bit.
template <std::size_t count>
[[gnu::always_inline]] inline void add_tone_blocks_of(double* row, std::size_t n,
                                                      const TonePhasors* tones) {
  std::complex<double> block[count];
  for (std::size_t t = 0; t < count; ++t) block[t] = tones[t].amplitude;
  std::size_t start = 0;
  for (; start + tone_block <= n; start += tone_block) {
    double* out = row + 2 * start;
    for (std::size_t v = 0; v < 2 * tone_block; v += 4) {
      detail::f64x4 sum = detail::load4(out + v);
      for (std::size_t t = 0; t < count; ++t) {
        sum = sum + block[t].real() * detail::load4(tones[t].powers.data() + v) +
              block[t].imag() * detail::load4(tones[t].rotated.data() + v);
      }
      detail::store4(out + v, sum);
    }
    for (std::size_t t = 0; t < count; ++t) block[t] *= tones[t].block_step;
  }
  for (std::size_t j = 0; start + j < n; ++j) {
    for (std::size_t t = 0; t < count; ++t) {
      row[2 * (start + j)] +=
          block[t].real() * tones[t].powers[2 * j] + block[t].imag() * tones[t].rotated[2 * j];
      row[2 * (start + j) + 1] += block[t].real() * tones[t].powers[2 * j + 1] +
                                  block[t].imag() * tones[t].rotated[2 * j + 1];
    }
  }
}

FOGRADAR_SIMD_CLONES
void add_tone_blocks(double* row, std::size_t n, const TonePhasors* tones, std::size_t count) {
  switch (count) {
    case 1:
      return add_tone_blocks_of<1>(row, n, tones);
    case 2:
      return add_tone_blocks_of<2>(row, n, tones);
    case 3:
      return add_tone_blocks_of<3>(row, n, tones);
    case 4:
      return add_tone_blocks_of<4>(row, n, tones);
    default:
      FOGRADAR_CHECK(count <= tones_per_pass);
  }
}

// Adds the tones (powers filled) to `row`, up to tones_per_pass of them per pass over it.
void add_tones(std::span<std::complex<double>> row, std::span<const TonePhasors> tones) {
  // std::complex<double> is layout-compatible with double[2] ([complex.numbers.general]).
  double* values = reinterpret_cast<double*>(row.data());
  for (std::size_t first = 0; first < tones.size(); first += tones_per_pass) {
    add_tone_blocks(values, row.size(), tones.data() + first,
                    std::min(tones_per_pass, tones.size() - first));
  }
}

// Adds a exp(i 2 pi f n / fs), n = 0..N-1, to `row`.
void add_tone(std::span<std::complex<double>> row, std::complex<double> amplitude,
              double frequency_hz, double sample_rate_hz) {
  TonePhasors tone;
  set_tone_step(tone, amplitude, frequency_hz, sample_rate_hz);
  fill_tone_powers(&tone, 1);
  add_tones(row, std::span<const TonePhasors>(&tone, 1));
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

std::size_t quantize(std::span<std::complex<double>> samples, unsigned bits,
                     double full_scale_amplitude) {
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
                                 std::span<std::complex<double>> frame, const FrameWindow* window,
                                 const ChirpTransform* transform, const FrameParts* parts,
                                 const StopToken& stop) {
  const std::size_t columns = params.samples_per_chirp;
  const std::size_t rows = params.chirps_per_frame;
  FOGRADAR_CHECK(frame.size() == rows * columns);
  FOGRADAR_CHECK(window == nullptr ||
                 (window->doppler.size() == rows && window->range_pairs.size() == 2 * columns));
  const auto row = [&](std::size_t c) { return frame.subspan(c * columns, columns); };
  const std::span<std::complex<double>> signal =
      parts ? parts->signal : std::span<std::complex<double>>();
  const std::span<std::complex<double>> kept_noise =
      parts ? parts->noise : std::span<std::complex<double>>();
  FOGRADAR_CHECK(signal.empty() || signal.size() == frame.size());
  FOGRADAR_CHECK(kept_noise.empty() || kept_noise.size() == frame.size());
  FOGRADAR_CHECK((signal.empty() && kept_noise.empty()) || window == nullptr);
  if (!kept_noise.empty()) std::fill(kept_noise.begin(), kept_noise.end(), std::complex<double>{});

  // Static paths: one chirp, copied to all. Without phase noise (which multiplies the noise-free
  // signal) the thermal noise is added in the same pass as the copy; chirp 0, the source of the
  // copies, takes its noise last. When nothing follows the noise (no moving path, no ADC), that
  // pass applies the window too.
  std::fill(row(0).begin(), row(0).end(), std::complex<double>{});
  bool moving_paths = false;
  std::array<TonePhasors, tones_per_pass> pass;
  std::size_t in_pass = 0;
  for (const Tone& tone : tones) {
    if (tone.radial_velocity_m_per_s != 0.0) {
      moving_paths = true;
      continue;
    }
    set_tone_step(pass[in_pass++], tone.amplitude,
                  beat_frequency_hz(tone.path_length_m, derived.chirp_slope_hz_per_s),
                  params.sample_rate_hz);
    if (in_pass == tones_per_pass) {
      fill_tone_powers(pass.data(), in_pass);
      add_tones(row(0), pass);
      in_pass = 0;
    }
  }
  fill_tone_powers(pass.data(), in_pass);
  add_tones(row(0), std::span<const TonePhasors>(pass.data(), in_pass));
  const bool noise_with_copy = params.thermal_noise && params.phase_noise_rms_rad == 0.0;
  const bool window_with_noise =
      window != nullptr && noise_with_copy && !moving_paths && params.adc_bits == 0;
  SynthesisReport report;
  report.samples = frame.size();
  if (window_with_noise) {
    ComplexNormalGenerator noise(rng);
    const bool by_chirp = transform != nullptr && transform->fft != nullptr &&
                          transform->chirp.size() == columns && fft_is_aligned(frame.data()) &&
                          (rows == 1 || fft_is_aligned(row(1).data()));
    // Each chirp's noise (and window) into the chirp buffer, then its range FFT into its row: the
    // values the noise pass writes into the frame, transformed as the batch would transform them.
    const auto finish = [&](std::size_t c) {
      if (by_chirp) {
        noise.add_weighted(row(0), transform->chirp, derived.noise_power_w, window->doppler[c],
                           window->range_pairs);
        transform->fft->execute(transform->chirp, row(c));
      } else {
        noise.add_weighted(row(0), row(c), derived.noise_power_w, window->doppler[c],
                           window->range_pairs);
      }
    };
    // A 65536 x 4096 frame takes about a second here: a stop is seen chirp by chirp.
    for (std::size_t c = 1; c < rows; ++c) {
      stop.check();
      finish(c);
    }
    finish(0);
    report.range_transformed = by_chirp;
  } else if (noise_with_copy) {
    for (std::size_t c = 0; c < rows && !signal.empty(); ++c) {
      std::copy(row(0).begin(), row(0).end(), signal.begin() + c * columns);
    }
    ComplexNormalGenerator noise(rng);
    if (kept_noise.empty()) {
      for (std::size_t c = 1; c < rows; ++c) {
        stop.check();
        noise.add(row(0), row(c), derived.noise_power_w);
      }
      noise.add(row(0), derived.noise_power_w);
    } else {
      // The same draws onto zero (each value as it would be added), then the same sums.
      const auto noise_row = [&](std::size_t c) {
        return kept_noise.subspan(c * columns, columns);
      };
      for (std::size_t c = 1; c < rows; ++c) noise.add(noise_row(c), derived.noise_power_w);
      noise.add(noise_row(0), derived.noise_power_w);
      for (std::size_t c = 1; c < rows; ++c) {
        for (std::size_t n = 0; n < columns; ++n) row(c)[n] = row(0)[n] + noise_row(c)[n];
      }
      for (std::size_t n = 0; n < columns; ++n) row(0)[n] += noise_row(0)[n];
    }
  } else {
    for (std::size_t c = 1; c < rows; ++c) std::copy(row(0).begin(), row(0).end(), row(c).begin());
  }

  // Moving paths: Doppler shift within the chirp and phase progression from chirp to chirp.
  for (const Tone& tone : tones) {
    if (tone.radial_velocity_m_per_s == 0.0) continue;
    const double doppler_hz = doppler_shift_hz(tone.radial_velocity_m_per_s, derived);
    const double frequency_hz =
        beat_frequency_hz(tone.path_length_m, derived.chirp_slope_hz_per_s) + doppler_hz;
    for (std::size_t c = 0; c < rows; ++c) {
      const double chirp_phase =
          2.0 * pi * doppler_hz * static_cast<double>(c) * params.chirp_interval_s;
      add_tone(row(c), tone.amplitude * std::polar(1.0, chirp_phase), frequency_hz,
               params.sample_rate_hz);
      if (!signal.empty() && noise_with_copy) {
        add_tone(signal.subspan(c * columns, columns),
                 tone.amplitude * std::polar(1.0, chirp_phase), frequency_hz,
                 params.sample_rate_hz);
      }
    }
  }

  if (params.phase_noise_rms_rad > 0.0) {
    for (std::complex<double>& sample : frame) {
      sample *= std::polar(1.0, params.phase_noise_rms_rad * rng.normal());
    }
  }
  if (!noise_with_copy && !signal.empty()) std::copy(frame.begin(), frame.end(), signal.begin());
  if (params.thermal_noise && !noise_with_copy) {
    if (kept_noise.empty()) {
      ComplexNormalGenerator(rng).add(frame, derived.noise_power_w);
    } else {
      ComplexNormalGenerator(rng).add(kept_noise, derived.noise_power_w);
      for (std::size_t i = 0; i < frame.size(); ++i) frame[i] += kept_noise[i];
    }
  }
  if (params.adc_bits > 0) {
    report.clipped_samples =
        quantize(frame, params.adc_bits, std::sqrt(dbm_to_watt(params.adc_full_scale_dbm)));
  }
  if (window != nullptr && !window_with_noise) apply_frame_window(*window, frame);
  return report;
}

}  // namespace fogradar::radar
