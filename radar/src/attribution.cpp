#include "fogradar/radar/attribution.hpp"

#include <algorithm>
#include <cmath>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/radar/fft.hpp"

namespace fogradar::radar {

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
                                        : 0.0),
      chirps_(processor.chirps()),
      samples_(processor.samples()) {}

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
                                  std::size_t range_cell, bool clipped) const {
  const CellContributions c = contributions(tones, doppler_cell, range_cell);
  const Origin origin = dominant_origin(std::norm(c.target), std::norm(c.fog), c.noise_power);
  return clipped && origin == Origin::noise ? Origin::clipping : origin;
}

void OriginClassifier::attribute(std::span<const Tone> tones, std::span<Detection> detections,
                                 bool clipped) const {
  for (Detection& detection : detections) {
    detection.origin = classify(tones, detection.doppler_cell, detection.range_cell, clipped);
  }
}

void OriginClassifier::origin_map(std::span<const Tone> tones, bool clipped,
                                  std::span<std::uint8_t> map) const {
  FOGRADAR_CHECK(map.size() == chirps_ * samples_);
  // Per group of tones with one Doppler shift and one origin: sum_t a_t W_r(k - f_t N / fs) over
  // the range cells k; the cell (d, k) adds W_d(d - f_D T_i N_c) times that.
  struct Group {
    double doppler_hz;
    Origin origin;
    std::vector<std::complex<double>> profile;
  };
  std::vector<Group> groups;
  for (const Tone& tone : tones) {
    FOGRADAR_CHECK(tone.origin != Origin::noise);
    const double doppler_hz = doppler_shift_hz(tone.radial_velocity_m_per_s, derived_);
    const double beat_hz =
        beat_frequency_hz(tone.path_length_m, derived_.chirp_slope_hz_per_s) + doppler_hz;
    auto group = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
      return g.doppler_hz == doppler_hz && g.origin == tone.origin;
    });
    if (group == groups.end()) {
      groups.push_back({doppler_hz, tone.origin, std::vector<std::complex<double>>(samples_)});
      group = groups.end() - 1;
    }
    const double centre = beat_hz * range_bins_per_hz_;
    for (std::size_t k = 0; k < samples_; ++k) {
      group->profile[k] += tone.amplitude * range_spectrum_.at(static_cast<double>(k) - centre);
    }
  }
  std::vector<std::complex<double>> target(samples_), fog(samples_);
  for (std::size_t d = 0; d < chirps_; ++d) {
    std::fill(target.begin(), target.end(), std::complex<double>{});
    std::fill(fog.begin(), fog.end(), std::complex<double>{});
    for (const Group& g : groups) {
      const std::complex<double> w =
          doppler_spectrum_.at(static_cast<double>(d) - g.doppler_hz * doppler_bins_per_hz_);
      std::vector<std::complex<double>>& sum = g.origin == Origin::target ? target : fog;
      for (std::size_t k = 0; k < samples_; ++k) sum[k] += w * g.profile[k];
    }
    for (std::size_t k = 0; k < samples_; ++k) {
      Origin origin = dominant_origin(std::norm(target[k]), std::norm(fog[k]), noise_power_);
      if (clipped && origin == Origin::noise) origin = Origin::clipping;
      map[d * samples_ + k] = static_cast<std::uint8_t>(origin);
    }
  }
}

}  // namespace fogradar::radar
