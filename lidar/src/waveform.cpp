#include "fogradar/lidar/waveform.hpp"

#include <algorithm>
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
double gaussian_exponent_per_s2(double fwhm_s) {
  return 4.0 * std::numbers::ln2 / (fwhm_s * fwhm_s);
}

// waveform[k] += weight p(k dt - tau) over the samples within support_fwhm of tau, by the exact
// multiplicative recurrence of exp(-A x^2) along x = k dt - tau (no exp per sample).
void add_pulse(std::span<double> waveform, const WaveformGrid& grid, double tau, double weight) {
  const double dt = grid.sample_interval_s;
  const double half_s = support_fwhm * grid.pulse_fwhm_s;
  const double first = std::ceil((tau - half_s) / dt);
  const double last = std::floor((tau + half_s) / dt);
  const double end = static_cast<double>(waveform.size());
  if (last < 0.0 || first >= end) return;
  const auto k0 = static_cast<std::size_t>(std::max(first, 0.0));
  const auto k1 = static_cast<std::size_t>(std::min(last, end - 1.0));
  const double a = gaussian_exponent_per_s2(grid.pulse_fwhm_s);
  const double x0 = static_cast<double>(k0) * dt - tau;
  double g = weight * std::exp(-a * x0 * x0);
  double h = std::exp(-a * (2.0 * x0 * dt + dt * dt));
  const double d = std::exp(-2.0 * a * dt * dt);
  for (std::size_t k = k0; k <= k1; ++k) {
    waveform[k] += g;
    g *= h;
    h *= d;
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
  add_pulse(waveform, grid, 2.0 * range_m / speed_of_light_m_per_s,
            amplitude * overlap(range_m, grid.full_overlap_range_m));
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
