#include "fogradar/radar/attribution.hpp"

#include <cmath>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/radar/fft.hpp"

namespace fogradar::radar {

std::string_view to_string(Origin origin) noexcept {
  switch (origin) {
    case Origin::noise:
      return "noise";
    case Origin::target:
      return "target";
    case Origin::fog:
      return "fog";
  }
  return "?";
}

Origin dominant_origin(double target_power, double fog_power, double noise_power) noexcept {
  if (target_power >= fog_power && target_power >= noise_power) return Origin::target;
  return fog_power >= noise_power ? Origin::fog : Origin::noise;
}

WindowSpectrum::WindowSpectrum(std::span<const double> window) : n_(window.size()) {
  FOGRADAR_CHECK(n_ > 0);
  // W(j / M) = sum_n w[n] exp(-i 2 pi n j / (N M)): the DFT of the window zero-padded to N M.
  const std::size_t size = n_ * oversampling;
  ComplexVector padded(size);
  for (std::size_t n = 0; n < n_; ++n) padded[n] = window[n];
  ComplexVector spectrum(size);
  FftPlan(size, FftDirection::forward).execute(padded, spectrum);
  table_.assign(spectrum.begin(), spectrum.end());
  table_.push_back(table_.front());  // one period: W(N) = W(0)
}

std::complex<double> WindowSpectrum::at(double offset_bins) const noexcept {
  const double period = static_cast<double>(table_.size() - 1);
  double x = offset_bins * static_cast<double>(oversampling);
  x -= period * std::floor(x / period);  // into [0, period], period only by rounding
  const auto j = std::min(static_cast<std::size_t>(x), table_.size() - 2);
  const double t = x - static_cast<double>(j);
  return table_[j] + t * (table_[j + 1] - table_[j]);
}

OriginClassifier::OriginClassifier(const RangeDopplerProcessor& processor,
                                   const RadarParams& params, const RadarDerived& derived)
    : range_spectrum_(processor.range_window()),
      doppler_spectrum_(processor.doppler_window()),
      range_bins_per_hz_(static_cast<double>(processor.samples()) / params.sample_rate_hz),
      doppler_bins_per_hz_(params.chirp_interval_s * static_cast<double>(processor.chirps())),
      derived_(derived),
      noise_power_(params.thermal_noise ? derived.noise_power_w * processor.noise_power_gain()
                                        : 0.0) {}

CellContributions OriginClassifier::contributions(std::span<const Tone> tones,
                                                  std::size_t doppler_cell,
                                                  std::size_t range_cell) const {
  CellContributions out;
  out.noise_power = noise_power_;
  const double k = static_cast<double>(range_cell), d = static_cast<double>(doppler_cell);
  for (const Tone& tone : tones) {
    FOGRADAR_CHECK(tone.origin != Origin::noise);  // a path, never noise
    // The frequencies synthesize_frame gives the tone: beat plus Doppler within a chirp, Doppler
    // from chirp to chirp.
    const double doppler_hz = doppler_shift_hz(tone.radial_velocity_m_per_s, derived_);
    const double beat_hz =
        beat_frequency_hz(tone.path_length_m, derived_.chirp_slope_hz_per_s) + doppler_hz;
    const std::complex<double> value = tone.amplitude *
                                       range_spectrum_.at(k - beat_hz * range_bins_per_hz_) *
                                       doppler_spectrum_.at(d - doppler_hz * doppler_bins_per_hz_);
    (tone.origin == Origin::target ? out.target : out.fog) += value;
  }
  return out;
}

Origin OriginClassifier::classify(std::span<const Tone> tones, std::size_t doppler_cell,
                                  std::size_t range_cell) const {
  const CellContributions c = contributions(tones, doppler_cell, range_cell);
  return dominant_origin(std::norm(c.target), std::norm(c.fog), c.noise_power);
}

void OriginClassifier::attribute(std::span<const Tone> tones,
                                 std::span<Detection> detections) const {
  for (Detection& detection : detections) {
    detection.origin = classify(tones, detection.doppler_cell, detection.range_cell);
  }
}

}  // namespace fogradar::radar
