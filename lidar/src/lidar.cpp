#include "fogradar/lidar/lidar.hpp"

#include <algorithm>
#include <array>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "fogradar/core/complex_normal_generator.hpp"
#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/propagation/water_film.hpp"

namespace fogradar::lidar {
namespace {

constexpr double degree_rad = pi / 180.0;

}  // namespace

Origin dominant_origin(double target, double fog, double background, double noise_std) noexcept {
  const double largest = std::max({target, fog, background});
  if (largest < noise_std) return Origin::noise;
  if (target == largest) return Origin::target;
  return fog == largest ? Origin::fog : Origin::background;
}

std::span<const double> FogFluctuationSeries::scan(std::size_t scan_index) const {
  FOGRADAR_CHECK((scan_index + 1) * layer_count <= factors.size());
  return std::span<const double>(factors).subspan(scan_index * layer_count, layer_count);
}

Lidar::Lidar(const LidarParams& params, const propagation::ChamberSpec& chamber,
             const propagation::SegelsteinTable& table, std::span<const Shape> room)
    : params_(params) {
  params_.validate();
  chamber.validate();
  shapes_ = background_shapes(params_.background);
  shapes_.insert(shapes_.end(), room.begin(), room.end());
  target_range_m_ = chamber.target_range_m();
  double start_m = chamber.sensor_gap_m;
  for (std::size_t i = 0; i < chamber.layers.size(); ++i) {
    const propagation::FogLayerSpec& spec = chamber.layers[i];
    Layer layer{.start_m = start_m,
                .end_m = start_m + spec.length_m,
                .extinction_per_m = 0.0,
                .backscatter_per_m_sr = 0.0};
    // A layer of the same fog as an earlier one takes its optics (the Mie sums are the start-up).
    std::size_t same = 0;
    while (same < i && chamber.layers[same].fog != spec.fog) ++same;
    if (same < i) {
      layer.extinction_per_m = layers_[same].extinction_per_m;
      layer.backscatter_per_m_sr = layers_[same].backscatter_per_m_sr;
    } else {
      const propagation::FogOptics optics =
          propagation::Fog(spec.fog, table).at_optical_wavelength(params_.wavelength_m);
      layer.extinction_per_m = optics.extinction_per_m;
      // beta_pi = N <dsigma/dOmega(180 deg)> = eta / (4 pi), eta = N <sigma_b>.
      layer.backscatter_per_m_sr = optics.volume_backscatter_m2_per_m3 / (4.0 * pi);
    }
    layers_.push_back(layer);
    start_m = layer.end_m;
  }
  // Optical wavelengths take the Segelstein table at its 25 C, as the fog's optics do.
  const double window_t = propagation::window_film_transmittance(
      params_.window_water_film_m, table.refractive_index(params_.wavelength_m),
      params_.wavelength_m);
  window_two_way_transmittance_ = window_t * window_t;
  beam_count_ = params_.beam_count();
  const double target_angle_deg = std::atan2(params_.target_offset_m, target_range_m_) / degree_rad;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < beam_count_; ++b) {
    const double distance = std::abs(beam_angle_deg(b) - target_angle_deg);
    if (distance < best) {
      best = distance;
      target_beam_ = b;
    }
  }
  grid_ = {.sample_interval_s = params_.sample_interval_ns * 1e-9,
           .pulse_fwhm_s = params_.pulse_width_ns * 1e-9,
           .full_overlap_range_m = params_.overlap_range_m};
  fog_return_ = FogReturn(grid_);
  samples_ = params_.samples_per_beam();
  // The datasheet's detection range: a Lambertian target of threshold_reflectivity at
  // threshold_range_m, normal incidence, clear air, peaks exactly at the threshold.
  const double threshold =
      hard_target_peak(params_.threshold_reflectivity, 1.0, 1.0, params_.threshold_range_m) *
      overlap(params_.threshold_range_m, params_.overlap_range_m);
  // Noise alone exceeds the threshold in a sample with probability P_fa: thr = sigma z_(1-P_fa).
  const boost::math::normal_distribution<double> normal;
  noise_std_ = threshold / boost::math::quantile(
                               boost::math::complement(normal, params_.false_alarm_probability));
  detector_ = {.threshold = threshold,
               .sample_interval_s = grid_.sample_interval_s,
               .range_offset_m = speed_of_light_m_per_s * grid_.pulse_fwhm_s / 4.0,
               .min_range_m = params_.min_range_m,
               .min_separation_m = params_.min_echo_separation_m,
               .max_echoes = params_.max_echoes};
}

double Lidar::beam_angle_deg(std::size_t beam) const { return params_.beam_angle_deg(beam); }

double Lidar::layer_start_m(std::size_t layer) const { return layers_.at(layer).start_m; }
double Lidar::layer_end_m(std::size_t layer) const { return layers_.at(layer).end_m; }
double Lidar::layer_extinction_per_m(std::size_t layer) const {
  return layers_.at(layer).extinction_per_m;
}
double Lidar::layer_backscatter_per_m_sr(std::size_t layer) const {
  return layers_.at(layer).backscatter_per_m_sr;
}

FogFluctuationSeries Lidar::fog_fluctuation(RandomStream stream) const {
  const FogFluctuation& f = params_.fog_fluctuation;
  const std::size_t n_layers = layers_.size();
  FogFluctuationSeries series{.layer_count = n_layers,
                              .factors = std::vector<double>(params_.scans_per_step * n_layers)};
  // AR(1) in the log with lag-one correlation rho = exp(-scan period / correlation time): a
  // stationary Gauss-Markov series of unit variance; exp(s z - s^2 / 2) has unit mean.
  const double rho = std::exp(-1.0 / (params_.scan_rate_hz * f.correlation_time_s));
  const double innovation = std::sqrt(1.0 - rho * rho);
  std::vector<double> z(n_layers);
  for (std::size_t s = 0; s < params_.scans_per_step; ++s) {
    for (std::size_t i = 0; i < n_layers; ++i) {
      const double e = stream.normal();
      z[i] = s == 0 ? e : rho * z[i] + innovation * e;
      series.factors[s * n_layers + i] = std::exp(f.log_std * z[i] - 0.5 * f.log_std * f.log_std);
    }
  }
  return series;
}

void Lidar::check_inputs(const propagation::ActiveLayers& active,
                         std::span<const double> optical_depth_factors) const {
  if (active.size() != layers_.size()) {
    throw_invalid("active_layers", static_cast<double>(active.size()),
                  "one flag per chamber layer (" + std::to_string(layers_.size()) + ")");
  }
  if (optical_depth_factors.size() != layers_.size()) {
    throw_invalid("optical_depth_factors", static_cast<double>(optical_depth_factors.size()),
                  "one factor per chamber layer (" + std::to_string(layers_.size()) + ")");
  }
  for (const double factor : optical_depth_factors) {
    require_non_negative("optical_depth_factors", factor);
  }
}

Lidar::Hit Lidar::trace(std::size_t beam, const propagation::ActiveLayers& active,
                        std::span<const double> factors, std::vector<FogStretch>& stretches,
                        std::vector<std::int32_t>& stretch_layers) const {
  stretches.clear();
  stretch_layers.clear();
  const double angle = beam_angle_deg(beam) * degree_rad;
  const double ux = std::cos(angle);
  const double uy = std::sin(angle);
  ShapeHit nearest;
  bool is_target = false;
  double reflectivity = 0.0;
  if (params_.target_width_m > 0.0) {
    const double half = 0.5 * params_.target_width_m;
    nearest = intersect(SegmentShape{target_range_m_, params_.target_offset_m - half,
                                     target_range_m_, params_.target_offset_m + half},
                        ux, uy);
    is_target = nearest.range_m < std::numeric_limits<double>::infinity();
    reflectivity = params_.target_reflectivity;
  }
  // The target wins a tie with the background, which keeps its first shape on a tie.
  const FirstHit background = first_hit(shapes_, ux, uy);
  if (background.hit.range_m < nearest.range_m) {
    nearest = background.hit;
    is_target = false;
    reflectivity = shapes_[*background.shape].reflectivity;
  }
  const double end_m = std::min(nearest.range_m, params_.max_range_m);
  // Every echo, the target's, the fog's and the background's, crosses the window twice.
  double transmittance = window_two_way_transmittance_;
  if (ux > 0.0) {
    const double lateral_m = uy == 0.0 ? std::numeric_limits<double>::infinity()
                                       : 0.5 * params_.fog_width_m / std::abs(uy);
    for (std::size_t i = 0; i < layers_.size(); ++i) {
      if (!active[i]) continue;
      const double start = layers_[i].start_m / ux;
      const double stop = std::min({layers_[i].end_m / ux, lateral_m, end_m});
      if (!(stop > start)) continue;
      const double alpha = layers_[i].extinction_per_m * factors[i];
      stretches.push_back({.start_m = start,
                           .end_m = stop,
                           .extinction_per_m = alpha,
                           .backscatter_per_m_sr = layers_[i].backscatter_per_m_sr * factors[i],
                           .transmittance_at_start = transmittance});
      stretch_layers.push_back(static_cast<std::int32_t>(i));
      transmittance *= std::exp(-2.0 * alpha * (stop - start));
    }
  }
  Hit hit;
  if (nearest.range_m <= params_.max_range_m) {
    hit = {.found = true,
           .is_target = is_target,
           .range_m = nearest.range_m,
           .amplitude = hard_target_peak(reflectivity, nearest.cos_incidence, transmittance,
                                         nearest.range_m)};
  }
  return hit;
}

BeamWaveform Lidar::waveform(std::size_t beam, const propagation::ActiveLayers& active,
                             std::span<const double> optical_depth_factors) const {
  check_inputs(active, optical_depth_factors);
  FOGRADAR_CHECK(beam < beam_count_);
  BeamWaveform out{.target = std::vector<double>(samples_),
                   .fog = std::vector<double>(samples_),
                   .background = std::vector<double>(samples_)};
  std::vector<FogStretch> stretches;
  std::vector<std::int32_t> stretch_layers;
  const Hit hit = trace(beam, active, optical_depth_factors, stretches, stretch_layers);
  out.crosses_fog = !stretches.empty();
  out.hits = hit.found;
  fog_return_.add(out.fog, stretches);
  if (hit.found) {
    add_hard_target(hit.is_target ? out.target : out.background, grid_, hit.range_m, hit.amplitude);
  }
  return out;
}

LidarScan Lidar::measure(const propagation::ActiveLayers& active,
                         std::span<const double> optical_depth_factors, RandomStream& stream,
                         std::span<double> waveforms, const StopToken& stop,
                         std::vector<OriginRun>* origins) const {
  check_inputs(active, optical_depth_factors);
  FOGRADAR_CHECK(waveforms.empty() || waveforms.size() == beam_count_ * samples_);
  LidarScan scan;
  if (origins != nullptr) origins->clear();
  ComplexNormalGenerator generator(stream);
  // Two real samples per complex one: each part of CN(0, 2 sigma^2) is N(0, sigma^2), read as the
  // array of doubles a std::complex<double> array is ([complex.numbers]).
  std::vector<std::complex<double>> noise((samples_ + 1) / 2);
  const double noise_variance = 2.0 * noise_std_ * noise_std_;
  // The components and their sum stay zero outside the samples a beam's signal touches, [lo, hi).
  std::vector<double> target(samples_), fog(samples_), background(samples_), noise_free(samples_),
      received(samples_);
  std::vector<FogStretch> stretches;
  std::vector<std::int32_t> stretch_layers;
  stretches.reserve(layers_.size());
  stretch_layers.reserve(layers_.size());
  // Each stretch's own share of the fog return, samples [share_first[i], share_first[i] +
  // share_count[i]) at shares[share_at[i]...], made only for a beam through several layers whose
  // fog's layer is asked for.
  std::vector<double> shares;
  std::vector<std::size_t> share_first, share_count, share_at;
  const double support_s = 2.0 * grid_.pulse_fwhm_s;
  const auto sample_at = [&](double range_m, double shift_s) {
    const double k =
        std::floor((2.0 * range_m / speed_of_light_m_per_s + shift_s) / grid_.sample_interval_s);
    return static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(samples_)));
  };
  for (std::size_t beam = 0; beam < beam_count_; ++beam) {
    // A beam is at most 1e6 samples, a few ms: a scan stops within one.
    stop.check();
    const Hit hit = trace(beam, active, optical_depth_factors, stretches, stretch_layers);
    std::fill(noise.begin(), noise.end(), std::complex<double>{});
    generator.add(noise, noise_variance);
    const double* noise_samples = reinterpret_cast<const double*>(noise.data());
    std::copy(noise_samples, noise_samples + samples_, received.begin());
    const bool through_fog = !stretches.empty();
    std::size_t lo = samples_, hi = 0;
    if (through_fog) {
      lo = sample_at(stretches.front().start_m, -support_s);
      hi = sample_at(stretches.back().end_m, support_s) + 1;
      fog_return_.add(fog, stretches);
    }
    if (hit.found) {
      lo = std::min(lo, sample_at(hit.range_m, -support_s));
      hi = std::max(hi, sample_at(hit.range_m, support_s) + 1);
      add_hard_target(hit.is_target ? target : background, grid_, hit.range_m, hit.amplitude);
    }
    hi = std::min(hi, samples_);
    for (std::size_t k = lo; k < hi; ++k) {
      noise_free[k] = target[k] + fog[k] + background[k];
      received[k] += noise_free[k];
    }
    bool shares_made = false;
    // The layer whose fog contributes most to sample k (the nearer on a tie), for a fog sample.
    const auto fog_layer = [&](std::size_t k) {
      if (stretch_layers.size() == 1) return stretch_layers.front();
      if (!shares_made) {
        shares_made = true;
        shares.clear();
        share_first.clear();
        share_count.clear();
        share_at.clear();
        for (const FogStretch& stretch : stretches) {
          // One sample beyond the stretch's support either side: its every non-zero sample.
          const std::size_t first = sample_at(stretch.start_m, -support_s);
          const std::size_t end = std::min(samples_, sample_at(stretch.end_m, support_s) + 2);
          const std::size_t from = first == 0 ? 0 : first - 1;
          share_first.push_back(from);
          share_count.push_back(end - from);
          share_at.push_back(shares.size());
          shares.resize(shares.size() + (end - from), 0.0);
          fog_return_.add(std::span<double>(shares).subspan(share_at.back(), end - from), stretch,
                          from);
        }
      }
      std::int32_t layer = no_layer;
      double largest = 0.0;
      for (std::size_t i = 0; i < stretches.size(); ++i) {
        if (k < share_first[i] || k >= share_first[i] + share_count[i]) continue;
        const double share = shares[share_at[i] + (k - share_first[i])];
        if (share > largest) {
          largest = share;
          layer = stretch_layers[i];
        }
      }
      return layer;
    };
    if (!waveforms.empty()) {
      std::copy(received.begin(), received.end(), waveforms.begin() + beam * samples_);
    }
    if (through_fog) ++scan.beams_through_fog;
    const bool exceeds =
        lo < hi || *std::max_element(received.begin(), received.end()) >= detector_.threshold;
    if (exceeds) {
      const DetectedEchoes echoes = extract_echoes(received, detector_);
      bool fog_echo = false;
      double strongest_fog = 0.0;
      for (std::size_t e = 0; e < echoes.count; ++e) {
        const DetectedEcho& echo = echoes.echoes[e];
        const std::size_t k = attribution_sample(noise_free, echo);
        const Origin origin = dominant_origin(target[k], fog[k], background[k], noise_std_);
        const double intensity =
            std::min(params_.intensity_saturation,
                     params_.intensity_scale * echo.peak / detector_.threshold);
        scan.echoes.push_back(
            {.beam = static_cast<std::uint32_t>(beam),
             .index = static_cast<std::uint8_t>(e),
             .origin = origin,
             .range_m = echo.range_m,
             .attributed_range_m =
                 static_cast<double>(k) * speed_of_light_m_per_s * grid_.sample_interval_s / 2.0,
             .intensity = intensity,
             .layer = origin == Origin::fog ? fog_layer(k) : no_layer});
        if (origin == Origin::fog) {
          fog_echo = true;
          strongest_fog = std::max(strongest_fog, intensity);
        }
        if (beam == target_beam_ && origin == Origin::target) {
          scan.target_detected = true;
          scan.target_intensity = std::max(scan.target_intensity, intensity);
        }
      }
      if (through_fog) {
        if (fog_echo) ++scan.beams_through_fog_with_fog_echo;
        if (echoes.count > 0)
          scan.first_echo_range_through_fog_m.push_back(echoes.echoes[0].range_m);
      }
      if (beam == target_beam_ && scan.target_detected && fog_echo &&
          strongest_fog >= scan.target_intensity) {
        scan.fog_outshines_target = true;
      }
    }
    if (origins != nullptr) {
      const double dr = speed_of_light_m_per_s * grid_.sample_interval_s / 2.0;
      Origin current = Origin::noise;
      std::int32_t current_layer = no_layer;
      for (std::size_t k = lo; k <= hi; ++k) {
        const Origin here =
            k < hi ? dominant_origin(target[k], fog[k], background[k], noise_std_) : Origin::noise;
        const std::int32_t here_layer = here == Origin::fog ? fog_layer(k) : no_layer;
        if (here == current && here_layer == current_layer) continue;
        const double range_m = static_cast<double>(k) * dr;
        if (current != Origin::noise) origins->back().end_m = range_m;
        if (here != Origin::noise) {
          origins->push_back({.beam = static_cast<std::uint32_t>(beam),
                              .origin = here,
                              .start_m = range_m,
                              .end_m = range_m,
                              .layer = here_layer});
        }
        current = here;
        current_layer = here_layer;
      }
    }
    for (std::size_t k = lo; k < hi; ++k) target[k] = fog[k] = background[k] = noise_free[k] = 0.0;
  }
  return scan;
}

}  // namespace fogradar::lidar
