#include "fogradar/radar/attribution.hpp"

#include <algorithm>
#include <cmath>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/radar/fft.hpp"

namespace fogradar::radar {
namespace {

// An offset in bins on a circle of `period` bins, into [-period / 2, period / 2].
double circular_offset(double offset_bins, double period) noexcept {
  return offset_bins - period * std::round(offset_bins / period);
}

// Fog power per layer, summed coherently over the layer's tones; the layer with the most power.
std::int16_t strongest_layer(std::span<const std::complex<double>> by_layer) noexcept {
  std::int16_t layer = -1;
  double best = 0.0;
  for (std::size_t i = 0; i < by_layer.size(); ++i) {
    if (std::norm(by_layer[i]) > best) {
      best = std::norm(by_layer[i]);
      layer = static_cast<std::int16_t>(i);
    }
  }
  return layer;
}

std::size_t layer_slots(std::span<const Tone> tones) {
  std::size_t slots = 0;
  for (const Tone& tone : tones) {
    if (tone.origin == Origin::fog && tone.layer >= 0) {
      slots = std::max(slots, static_cast<std::size_t>(tone.layer) + 1);
    }
  }
  return slots;
}

Attribution attribution_of(const CellPowers& powers, std::int16_t fog_layer, bool clipped) {
  Attribution a{dominant_origin(powers), -1};
  if (a.origin == Origin::fog) a.layer = fog_layer;
  if (clipped && a.origin == Origin::noise) a.origin = Origin::clipping;
  return a;
}

}  // namespace

Origin dominant_origin(const CellPowers& p) noexcept {
  const double largest = std::max({p.target, p.multipath, p.room, p.fog, p.sidelobe, p.noise});
  if (p.target == largest) return Origin::target;
  if (p.multipath == largest) return Origin::multipath;
  if (p.room == largest) return Origin::room;
  if (p.fog == largest) return Origin::fog;
  return p.sidelobe == largest ? Origin::sidelobe : Origin::noise;
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
  // The first entry after which |W| rises again: the main lobe's first null (or minimum).
  main_lobe_half_width_bins_ = 0.5 * static_cast<double>(n_);
  for (std::size_t j = 1; j < size / 2; ++j) {
    if (std::abs(table_[j + 1]) > std::abs(table_[j])) {
      main_lobe_half_width_bins_ = static_cast<double>(j) / static_cast<double>(oversampling);
      break;
    }
  }
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
      noise_gain_(processor.noise_power_gain()),
      thermal_and_quantisation_w_(0.0),
      phase_noise_incoherent_(
          -std::expm1(-params.phase_noise_rms_rad * params.phase_noise_rms_rad)),
      phase_noise_coherent_(
          std::exp(-0.5 * params.phase_noise_rms_rad * params.phase_noise_rms_rad)),
      chirps_(processor.chirps()),
      samples_(processor.samples()) {
  if (params.thermal_noise) thermal_and_quantisation_w_ += derived.noise_power_w;
  if (params.adc_bits > 0) {
    // The mid-rise step of synthesis.cpp's quantize, q = 2 A / 2^bits; q^2 / 12 per rail.
    const double step = 2.0 * std::sqrt(dbm_to_watt(params.adc_full_scale_dbm)) /
                        std::ldexp(1.0, static_cast<int>(params.adc_bits));
    thermal_and_quantisation_w_ += step * step / 6.0;
  }
}

double OriginClassifier::noise_power(std::span<const Tone> tones) const {
  double signal_w = 0.0;
  if (phase_noise_incoherent_ > 0.0) {
    for (const Tone& tone : tones) signal_w += std::norm(tone.amplitude);
  }
  return noise_gain_ * (thermal_and_quantisation_w_ + phase_noise_incoherent_ * signal_w);
}

std::complex<double> OriginClassifier::tone_at(const Tone& tone, double doppler_cell,
                                               double range_cell, bool& main_lobe) const {
  FOGRADAR_CHECK(tone.origin != Origin::noise);  // a path, never noise
  // The frequencies synthesize_frame gives the tone: beat plus Doppler within a chirp, Doppler
  // from chirp to chirp.
  const double doppler_hz = doppler_shift_hz(tone.radial_velocity_m_per_s, derived_);
  const double beat_hz =
      beat_frequency_hz(tone.path_length_m, derived_.chirp_slope_hz_per_s) + doppler_hz;
  const double u_r = range_cell - beat_hz * range_bins_per_hz_;
  const double u_d = doppler_cell - doppler_hz * doppler_bins_per_hz_;
  main_lobe = std::abs(circular_offset(u_r, static_cast<double>(samples_))) <
                  range_spectrum_.main_lobe_half_width_bins() &&
              std::abs(circular_offset(u_d, static_cast<double>(chirps_))) <
                  doppler_spectrum_.main_lobe_half_width_bins();
  return phase_noise_coherent_ * tone.amplitude * range_spectrum_.at(u_r) *
         doppler_spectrum_.at(u_d);
}

CellContributions OriginClassifier::contributions(std::span<const Tone> tones,
                                                  std::size_t doppler_cell,
                                                  std::size_t range_cell) const {
  CellContributions out;
  out.noise_power = noise_power(tones);
  const double k = static_cast<double>(range_cell), d = static_cast<double>(doppler_cell);
  std::int16_t last_layer = -1;
  for (const Tone& tone : tones) {
    bool main_lobe = false;
    const std::complex<double> value = tone_at(tone, d, k, main_lobe);
    switch (tone.origin) {
      case Origin::target:
        (main_lobe ? out.target : out.target_leak) += value;
        break;
      case Origin::multipath:
        (main_lobe ? out.multipath : out.target_leak) += value;
        break;
      case Origin::room:
        (main_lobe ? out.room : out.room_leak) += value;
        break;
      default:
        if (!main_lobe) {
          out.fog_leak += value;
        } else {
          out.fog += value;
          last_layer = std::max(last_layer, tone.layer);
        }
    }
  }
  // The fog's main lobes summed per layer, one layer at a time (no allocation per cell).
  double best = 0.0;
  for (std::int16_t layer = 0; layer <= last_layer; ++layer) {
    std::complex<double> sum{};
    for (const Tone& tone : tones) {
      if (tone.origin != Origin::fog || tone.layer != layer) continue;
      bool main_lobe = false;
      const std::complex<double> value = tone_at(tone, d, k, main_lobe);
      if (main_lobe) sum += value;
    }
    if (std::norm(sum) > best) {
      best = std::norm(sum);
      out.fog_layer = layer;
    }
  }
  return out;
}

Attribution OriginClassifier::attribution(std::span<const Tone> tones, std::size_t doppler_cell,
                                          std::size_t range_cell, bool clipped) const {
  const CellContributions c = contributions(tones, doppler_cell, range_cell);
  return attribution_of({.target = std::norm(c.target),
                         .multipath = std::norm(c.multipath),
                         .room = std::norm(c.room),
                         .fog = std::norm(c.fog),
                         .sidelobe = std::norm(c.sidelobe()),
                         .noise = c.noise_power},
                        c.fog_layer, clipped);
}

void OriginClassifier::attribute(std::span<const Tone> tones, std::span<Detection> detections,
                                 bool clipped) const {
  for (Detection& detection : detections) {
    const Attribution a = attribution(tones, detection.doppler_cell, detection.range_cell, clipped);
    detection.origin = a.origin;
    detection.layer = a.layer;
  }
}

void OriginClassifier::origin_map(std::span<const Tone> tones, bool clipped,
                                  std::span<std::uint8_t> map,
                                  std::span<std::int16_t> layers) const {
  FOGRADAR_CHECK(map.size() == chirps_ * samples_);
  FOGRADAR_CHECK(layers.empty() || layers.size() == map.size());
  const double range_half = range_spectrum_.main_lobe_half_width_bins();
  const double doppler_half = doppler_spectrum_.main_lobe_half_width_bins();
  // Per group of tones with one Doppler shift, one origin and one layer: sum_t a_t W_r(k - f_t N /
  // fs) over the range cells k, split into the cells inside each tone's range main lobe and the
  // rest; the cell (d, k) adds W_d(d - f_D T_i N_c) times that, a main-lobe part only where d is
  // inside the group's Doppler main lobe.
  struct Group {
    double doppler_hz;
    Origin origin;
    std::int16_t layer;
    std::vector<std::complex<double>> main, leak;
  };
  std::vector<Group> groups;
  for (const Tone& tone : tones) {
    FOGRADAR_CHECK(tone.origin != Origin::noise);
    const double doppler_hz = doppler_shift_hz(tone.radial_velocity_m_per_s, derived_);
    const double beat_hz =
        beat_frequency_hz(tone.path_length_m, derived_.chirp_slope_hz_per_s) + doppler_hz;
    const std::int16_t layer = tone.origin == Origin::fog ? tone.layer : std::int16_t{-1};
    auto group = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
      return g.doppler_hz == doppler_hz && g.origin == tone.origin && g.layer == layer;
    });
    if (group == groups.end()) {
      groups.push_back({doppler_hz, tone.origin, layer, std::vector<std::complex<double>>(samples_),
                        std::vector<std::complex<double>>(samples_)});
      group = groups.end() - 1;
    }
    const double centre = beat_hz * range_bins_per_hz_;
    const std::complex<double> amplitude = phase_noise_coherent_ * tone.amplitude;
    for (std::size_t k = 0; k < samples_; ++k) {
      const double u = static_cast<double>(k) - centre;
      const bool main_lobe =
          std::abs(circular_offset(u, static_cast<double>(samples_))) < range_half;
      (main_lobe ? group->main : group->leak)[k] += amplitude * range_spectrum_.at(u);
    }
  }
  const double noise = noise_power(tones);
  const std::size_t slots = layer_slots(tones);
  std::vector<std::complex<double>> target(samples_), multipath(samples_), room(samples_),
      fog(samples_), leak(samples_), fog_by_layer(slots * samples_), cell_layers(slots);
  const auto main_sum = [&](Origin origin) -> std::vector<std::complex<double>>& {
    switch (origin) {
      case Origin::target:
        return target;
      case Origin::multipath:
        return multipath;
      case Origin::room:
        return room;
      default:
        return fog;
    }
  };
  for (std::size_t d = 0; d < chirps_; ++d) {
    for (auto* sum : {&target, &multipath, &room, &fog}) {
      std::fill(sum->begin(), sum->end(), std::complex<double>{});
    }
    std::fill(leak.begin(), leak.end(), std::complex<double>{});
    std::fill(fog_by_layer.begin(), fog_by_layer.end(), std::complex<double>{});
    for (const Group& g : groups) {
      const double u = static_cast<double>(d) - g.doppler_hz * doppler_bins_per_hz_;
      const std::complex<double> w = doppler_spectrum_.at(u);
      const bool main_lobe =
          std::abs(circular_offset(u, static_cast<double>(chirps_))) < doppler_half;
      if (!main_lobe) {
        for (std::size_t k = 0; k < samples_; ++k) leak[k] += w * (g.main[k] + g.leak[k]);
        continue;
      }
      std::vector<std::complex<double>>& sum = main_sum(g.origin);
      for (std::size_t k = 0; k < samples_; ++k) {
        sum[k] += w * g.main[k];
        leak[k] += w * g.leak[k];
      }
      if (g.origin == Origin::fog && g.layer >= 0) {
        std::complex<double>* row =
            fog_by_layer.data() + static_cast<std::size_t>(g.layer) * samples_;
        for (std::size_t k = 0; k < samples_; ++k) row[k] += w * g.main[k];
      }
    }
    for (std::size_t k = 0; k < samples_; ++k) {
      for (std::size_t i = 0; i < slots; ++i) cell_layers[i] = fog_by_layer[i * samples_ + k];
      const Attribution a = attribution_of({.target = std::norm(target[k]),
                                            .multipath = std::norm(multipath[k]),
                                            .room = std::norm(room[k]),
                                            .fog = std::norm(fog[k]),
                                            .sidelobe = std::norm(leak[k]),
                                            .noise = noise},
                                           strongest_layer(cell_layers), clipped);
      map[d * samples_ + k] = static_cast<std::uint8_t>(a.origin);
      if (!layers.empty()) layers[d * samples_ + k] = a.layer;
    }
  }
}

}  // namespace fogradar::radar
