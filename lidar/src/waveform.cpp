#include "fogradar/lidar/waveform.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::lidar {
namespace {

// The pulse is evaluated within this many FWHM of its centre: p(2 fwhm) = 2^-16 = 1.5e-5 of the
// peak, and the cut-off tails hold erfc(4 sqrt(ln 2)) = 3e-6 of the pulse's energy.
constexpr double support_fwhm = 2.0;
// Composite Gauss-Legendre panels of at most this fraction of the pulse's range FWHM c fwhm / 2:
// the integrand, a Gaussian of that width times a smooth factor, is sampled by 8 nodes per FWHM
// (tests/lidar: the plateau to 1e-4 and the absorbing layer's energy to 1e-7 of the closed forms).
constexpr double panel_fwhm_fraction = 1.0;
// Even order: its abscissae are four +/- pairs, none at the panel's centre.
constexpr std::size_t nodes = 8;
using Rule = boost::math::quadrature::gauss<double, nodes>;

double gaussian_exponent_per_s2(double fwhm_s) {
  return 4.0 * std::numbers::ln2 / (fwhm_s * fwhm_s);
}

// waveform[k] += sum_j weights[j] p(k dt - taus[j]) over the samples within support_fwhm of any
// tau_j (so each pulse is evaluated at least that far from its centre), by the exact multiplicative
// recurrence of exp(-A x^2) along x = k dt - tau_j (no exp per sample): the nodes' recurrences are
// independent and run side by side.
// waveform[0] is sample `offset` of the record.
template <std::size_t N>
void add_pulses(std::span<double> waveform, const WaveformGrid& grid,
                const std::array<double, N>& taus, const std::array<double, N>& weights,
                std::size_t offset = 0) {
  const double dt = grid.sample_interval_s;
  const double half_s = support_fwhm * grid.pulse_fwhm_s;
  const auto [low, high] = std::minmax_element(taus.begin(), taus.end());
  const double first = std::ceil((*low - half_s) / dt);
  const double last = std::floor((*high + half_s) / dt);
  const double begin = static_cast<double>(offset);
  const double end = begin + static_cast<double>(waveform.size());
  if (last < begin || first >= end) return;
  const auto k0 = static_cast<std::size_t>(std::max(first, begin));
  const auto k1 = static_cast<std::size_t>(std::min(last, end - 1.0));
  const double a = gaussian_exponent_per_s2(grid.pulse_fwhm_s);
  std::array<double, N> g{}, h{};
  for (std::size_t j = 0; j < N; ++j) {
    const double x0 = static_cast<double>(k0) * dt - taus[j];
    g[j] = weights[j] * std::exp(-a * x0 * x0);
    h[j] = std::exp(-a * (2.0 * x0 * dt + dt * dt));
  }
  const double d = std::exp(-2.0 * a * dt * dt);
  for (std::size_t k = k0; k <= k1; ++k) {
    double sum = 0.0;
    for (std::size_t j = 0; j < N; ++j) {
      sum += g[j];
      g[j] *= h[j];
      h[j] *= d;
    }
    waveform[k - offset] += sum;
  }
}

}  // namespace

double pulse_shape(double t_s, double fwhm_s) {
  return std::exp(-gaussian_exponent_per_s2(fwhm_s) * t_s * t_s);
}

double pulse_energy_width_s(double fwhm_s) {
  return fwhm_s * std::sqrt(pi / (4.0 * std::numbers::ln2));
}

double overlap(double range_m, double full_overlap_range_m) {
  if (range_m >= full_overlap_range_m) return 1.0;
  const double ratio = range_m / full_overlap_range_m;
  return ratio * ratio;
}

double hard_target_peak(double reflectivity, double cos_incidence, double two_way_transmittance,
                        double range_m) {
  return reflectivity * cos_incidence / pi * two_way_transmittance / (range_m * range_m);
}

void add_hard_target(std::span<double> waveform, const WaveformGrid& grid, double range_m,
                     double amplitude) {
  add_pulses<1>(waveform, grid, {2.0 * range_m / speed_of_light_m_per_s},
                {amplitude * overlap(range_m, grid.full_overlap_range_m)});
}

void add_fog_stretch(std::span<double> waveform, const WaveformGrid& grid, const FogStretch& fog,
                     std::size_t first_sample) {
  if (!(fog.end_m > fog.start_m) || fog.backscatter_per_m_sr == 0.0) return;
  const double panel_m = panel_fwhm_fraction * speed_of_light_m_per_s * grid.pulse_fwhm_s / 2.0;
  // Panel edges: uniform over the stretch, plus the overlap function's kink where it falls inside.
  const auto panels_in = [&](double a, double b) {
    return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil((b - a) / panel_m)));
  };
  const auto integrate = [&](double a, double b) {
    const std::size_t panels = panels_in(a, b);
    const double width = (b - a) / static_cast<double>(panels);
    const auto& x = Rule::abscissa();  // the positive half of the symmetric 8-point rule
    const auto& w = Rule::weights();
    std::array<double, nodes> taus{}, weights{};
    for (std::size_t p = 0; p < panels; ++p) {
      const double mid = a + (static_cast<double>(p) + 0.5) * width;
      const double half = 0.5 * width;
      for (std::size_t i = 0; i < nodes; ++i) {
        const double sign = i % 2 == 0 ? -1.0 : 1.0;
        const double r = mid + sign * half * x[i / 2];
        // beta_pi T^2(r) / r^2 O(r) times the node's weight; the sample at t sees p(t - 2r/c).
        taus[i] = 2.0 * r / speed_of_light_m_per_s;
        weights[i] = half * w[i / 2] * fog.backscatter_per_m_sr * fog.transmittance_at_start *
                     std::exp(-2.0 * fog.extinction_per_m * (r - fog.start_m)) / (r * r) *
                     overlap(r, grid.full_overlap_range_m);
      }
      add_pulses(waveform, grid, taus, weights, first_sample);
    }
  };
  const double kink = grid.full_overlap_range_m;
  if (kink > fog.start_m && kink < fog.end_m) {
    integrate(fog.start_m, kink);
    integrate(kink, fog.end_m);
  } else {
    integrate(fog.start_m, fog.end_m);
  }
}

DetectedEchoes extract_echoes(std::span<const double> waveform, const EchoDetector& detector) {
  FOGRADAR_CHECK(detector.max_echoes >= 1 && detector.max_echoes <= DetectedEchoes::capacity);
  DetectedEchoes out;
  const double dr = speed_of_light_m_per_s * detector.sample_interval_s / 2.0;
  const double threshold = detector.threshold;
  bool inside = false;
  bool recording = false;  // the current echo is kept (not too near, not beyond max_echoes)
  bool any = false;
  double last_start_m = 0.0;  // leading edge of the latest echo, kept or not
  for (std::size_t k = 0; k < waveform.size(); ++k) {
    const double v = waveform[k];
    if (!inside) {
      if (!(v >= threshold)) continue;
      inside = true;
      const double before = k == 0 ? 0.0 : waveform[k - 1];
      // Range of the crossing, linear between the samples around it; a record that starts above
      // the threshold has no leading edge in it and counts as nearer than any min_range_m.
      const double range_m =
          k == 0 ? -std::numeric_limits<double>::infinity()
                 : (static_cast<double>(k) - 1.0 + (threshold - before) / (v - before)) * dr +
                       detector.range_offset_m;
      if (any && range_m - last_start_m < detector.min_separation_m) {
        // Merges into the previous echo (recording stays as it was for that echo).
      } else {
        any = true;
        last_start_m = range_m;
        if (range_m < detector.min_range_m) {
          recording = false;
        } else if (out.count == detector.max_echoes) {
          break;
        } else {
          recording = true;
          out.echoes[out.count++] = {
              .range_m = range_m, .peak = v, .first_sample = k, .last_sample = k};
          continue;
        }
      }
    } else if (!(v >= threshold)) {
      inside = false;
      continue;
    }
    if (recording) {
      DetectedEcho& echo = out.echoes[out.count - 1];
      echo.last_sample = k;
      echo.peak = std::max(echo.peak, v);
    }
  }
  return out;
}

std::size_t attribution_sample(std::span<const double> noise_free, const DetectedEcho& echo) {
  std::size_t k = echo.first_sample;
  while (k < echo.last_sample && noise_free[k + 1] > noise_free[k]) ++k;
  return k;
}

}  // namespace fogradar::lidar
