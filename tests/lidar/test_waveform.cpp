// The beam waveform against closed forms of the lidar equation (waveform.hpp; Rasshofer et al. 2011
// eq. 1-3) and the receiver's echo extraction on constructed waveforms.
#include <gtest/gtest.h>

#include <boost/math/special_functions/expint.hpp>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/lidar/fog_return.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/lidar/waveform.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "validation.hpp"

namespace fogradar::lidar {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

// A number as a check's id and conditions show it ("12.34", "1e-06").
std::string str(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

constexpr double c = 299792458.0;
constexpr double ln2 = std::numbers::ln2;
constexpr double pi = std::numbers::pi;

const propagation::SegelsteinTable& table() {
  static const propagation::SegelsteinTable instance;
  return instance;
}

// A Gaussian pulse of FWHM f evaluated directly: exp(-4 ln 2 t^2 / f^2).
double gaussian(double t_s, double fwhm_s) {
  return std::exp(-4.0 * ln2 * t_s * t_s / (fwhm_s * fwhm_s));
}

constexpr WaveformGrid grid{
    .sample_interval_s = 0.5e-9, .pulse_fwhm_s = 5e-9, .full_overlap_range_m = 0.5};
constexpr std::size_t samples = 1500;  // 112 m

// A hard target on a sample (2R/c = k dt) peaks at exactly its amplitude rho cos(i)/pi T^2/R^2;
// its neighbours follow the Gaussian. Tolerance 1e-12 relative: the recurrence's rounding over the
// ~20 samples from the support's edge to the peak.
TEST(LidarWaveform, HardTargetPeakIsTheClosedForm) {
  std::vector<double> w(samples, 0.0);
  const std::size_t k = 400;
  const double range_m = c * static_cast<double>(k) * grid.sample_interval_s / 2.0;
  const double amplitude = 0.4 * 0.8 / pi * 0.3 / (range_m * range_m);
  EXPECT_DOUBLE_EQ(hard_target_peak(0.4, 0.8, 0.3, range_m), amplitude);
  add_hard_target(w, grid, range_m, amplitude);
  validate({.id = "lidar.waveform.hard_target.peak",
            .group = "lidar",
            .quantity = "hard-target waveform peak",
            .unit = "1/(m^2 sr)",
            .conditions = "target on sample 400 (R = " + str(range_m) +
                          " m), rho 0.4, cos i 0.8, "
                          "T^2 0.3",
            .reference = amplitude,
            .source = "closed form: lidar equation rho cos(i) / pi T^2 / R^2 (Rasshofer et al. "
                      "2011 eq. 1-3)",
            .value = w[k],
            .tolerance = 1e-12,
            .kind = Tolerance::relative});
  for (const std::size_t j : {k - 7, k - 3, k + 1, k + 9}) {
    const double t = (static_cast<double>(j) - static_cast<double>(k)) * grid.sample_interval_s;
    const long offset = static_cast<long>(j) - static_cast<long>(k);
    validate({.id = "lidar.waveform.hard_target.sample" + std::string(offset > 0 ? "+" : "") +
                    std::to_string(offset),
              .group = "lidar",
              .quantity = "hard-target waveform sample beside the peak",
              .unit = "1/(m^2 sr)",
              .conditions = std::to_string(offset) + " samples from the peak, 5 ns FWHM pulse",
              .reference = amplitude * gaussian(t, grid.pulse_fwhm_s),
              .source = "closed form: peak amplitude times the Gaussian pulse "
                        "exp(-4 ln 2 t^2 / fwhm^2)",
              .value = w[j],
              .tolerance = 1e-12 * amplitude,
              .kind = Tolerance::absolute});
  }
  EXPECT_EQ(w[k - 21], 0.0);  // beyond the 2 FWHM (20-sample) support
}

// Inside a thick non-absorbing layer (no change of the integrand over the pulse but 1/r^2), the
// waveform is beta_pi (c tau_e / 2) / r^2 with tau_e = fwhm sqrt(pi / (4 ln 2)) the pulse's energy
// width (Rasshofer et al. 2011 eq. 3 with T = 1). Tolerance 1e-4: the 1/r^2 curvature over the
// pulse, 3 (sigma_r / r)^2 = 3e-5 at r = 100 m, sigma_r = 0.32 m.
TEST(LidarWaveform, ThickTransparentLayerPlateau) {
  std::vector<double> w(samples, 0.0);
  const double beta = 2e-3;
  FogReturn(grid).add(w, {.start_m = 50.0,
                          .end_m = 150.0,
                          .extinction_per_m = 0.0,
                          .backscatter_per_m_sr = beta,
                          .transmittance_at_start = 1.0});
  const double tau_e = grid.pulse_fwhm_s * std::sqrt(pi / (4.0 * ln2));
  for (const std::size_t k : {800u, 900u, 1000u}) {
    const double r = c * static_cast<double>(k) * grid.sample_interval_s / 2.0;
    const double expected = beta * (c * tau_e / 2.0) / (r * r);
    validate({.id = "lidar.waveform.transparent_layer.plateau.sample" + std::to_string(k),
              .group = "lidar",
              .quantity = "fog waveform inside a thick transparent layer",
              .unit = "1/(m^2 sr)",
              .conditions = "r = " + str(r) + " m, beta_pi 2e-3 /(m sr), alpha 0, 5 ns FWHM",
              .reference = expected,
              .source = "closed form: beta_pi (c tau_e / 2) / r^2 (Rasshofer et al. 2011 eq. 3, "
                        "T = 1)",
              .value = w[k],
              .tolerance = 1e-4,
              .kind = Tolerance::relative});
  }
}

// An absorbing layer [a, b] (alpha = 0.9 /m, the study's fog): the waveform's time integral equals
// tau_e beta_pi T^2(a) integral_a^b exp(-2 alpha (r - a)) / r^2 dr, and that integral is, with
// k = 2 alpha, e^(k a) [e^(-k a)/a - e^(-k b)/b - k (E1(k a) - E1(k b))] (integration by parts;
// E1 the exponential integral, Boost.Math expint). The sample sum times dt is the trapezoidal rule
// of a function vanishing at both ends. Tolerance 1e-5: the pulse is evaluated within 2 FWHM of
// its centre, and the cut-off tails hold 3e-6 of its energy (fog_return.cpp).
TEST(LidarWaveform, AbsorbingLayerEnergyMatchesTheExponentialIntegralForm) {
  std::vector<double> w(samples, 0.0);
  const double a = 5.0, b = 6.0, alpha = 0.9, beta = 0.05, t0 = 0.4;
  FogReturn(grid).add(w, {.start_m = a,
                          .end_m = b,
                          .extinction_per_m = alpha,
                          .backscatter_per_m_sr = beta,
                          .transmittance_at_start = t0});
  double energy = 0.0;
  for (const double v : w) energy += v * grid.sample_interval_s;
  const double k = 2.0 * alpha;
  const double integral =
      std::exp(k * a) * (std::exp(-k * a) / a - std::exp(-k * b) / b -
                         k * (boost::math::expint(1, k * a) - boost::math::expint(1, k * b)));
  const double tau_e = grid.pulse_fwhm_s * std::sqrt(pi / (4.0 * ln2));
  const double expected = tau_e * beta * t0 * integral;
  validate({.id = "lidar.waveform.absorbing_layer.energy",
            .group = "lidar",
            .quantity = "time integral of an absorbing layer's waveform",
            .unit = "s/(m^2 sr)",
            .conditions = "layer 5-6 m, alpha 0.9 /m, beta_pi 0.05 /(m sr), T^2(a) 0.4",
            .reference = expected,
            .source = "closed form: lidar equation integrated by parts with the exponential "
                      "integral E1 (Boost.Math expint)",
            .value = energy,
            .tolerance = 1e-5,
            .kind = Tolerance::relative});
}

// Inside the overlap range the fog return is weighted by O(r) = (r / r_full)^2: with r_full = 20 m,
// a transparent layer from 10 m to 15 m has the constant integrand beta / r_full^2, so its energy
// is tau_e beta (15 - 10) / 400. Tolerance 1e-5 as above.
TEST(LidarWaveform, OverlapFunctionInsideTheFullOverlapRange) {
  std::vector<double> w(samples, 0.0);
  WaveformGrid near_grid = grid;
  near_grid.full_overlap_range_m = 20.0;
  FogReturn(near_grid).add(w, {.start_m = 10.0,
                               .end_m = 15.0,
                               .extinction_per_m = 0.0,
                               .backscatter_per_m_sr = 1e-3,
                               .transmittance_at_start = 1.0});
  double energy = 0.0;
  for (const double v : w) energy += v * grid.sample_interval_s;
  const double tau_e = grid.pulse_fwhm_s * std::sqrt(pi / (4.0 * ln2));
  const double expected = tau_e * 1e-3 * 5.0 / 400.0;
  validate({.id = "lidar.waveform.overlap_range.energy",
            .group = "lidar",
            .quantity = "time integral of a transparent layer's waveform inside the overlap range",
            .unit = "s/(m^2 sr)",
            .conditions = "layer 10-15 m, full overlap at 20 m, beta_pi 1e-3 /(m sr), alpha 0",
            .reference = expected,
            .source = "closed form: tau_e beta_pi (15 - 10) / r_full^2 with O(r) = (r / r_full)^2",
            .value = energy,
            .tolerance = 1e-5,
            .kind = Tolerance::relative});
  validate({.id = "lidar.waveform.overlap.r10m.full20m",
            .group = "lidar",
            .quantity = "overlap function O(r)",
            .unit = "1",
            .conditions = "r = 10 m, full overlap at 20 m",
            .reference = 0.25,
            .source = "closed form: O(r) = (r / r_full)^2",
            .value = overlap(10.0, 20.0),
            .tolerance = 1e-15,
            .kind = Tolerance::absolute});
}

// The target's echo through k active layers falls by exactly exp(-2 alpha_i L_i) per added layer
// (two-way Beer-Lambert), read from the boresight beam's target component. Tolerance 1e-12.
TEST(LidarWaveform, TargetEchoFallsByTheTwoWayBeerLambertLossOfEachLayer) {
  LidarParams params;
  params.fog_fluctuation.log_std = 0.0;
  const propagation::ChamberSpec chamber;
  const Lidar lidar(params, chamber, table());
  const std::vector<double> factors(4, 1.0);
  double previous = 0.0;
  for (std::size_t n = 0; n <= 4; ++n) {
    const BeamWaveform w =
        lidar.waveform(lidar.target_beam(), propagation::first_layers_active(n, 4), factors);
    double peak = 0.0;
    for (const double v : w.target) peak = std::max(peak, v);
    if (n == 0) {
      // Off-grid target: the nearest sample is within dt/2 of the pulse's peak.
      const double range_m = lidar.target_range_m();
      const double dt = params.sample_interval_ns * 1e-9;
      const double tau = 2.0 * range_m / c;
      const double offset = tau - std::round(tau / dt) * dt;
      const double expected = 0.3 / pi / (range_m * range_m) * gaussian(offset, 5e-9);
      validate({.id = "lidar.waveform.target_echo.peak.0layers",
                .group = "lidar",
                .quantity = "target echo peak in clear air",
                .unit = "1/(m^2 sr)",
                .conditions = "study's chamber, 0 active layers, target at " + str(range_m) +
                              " m, nearest sample " + str(offset * 1e9) + " ns off the peak",
                .reference = expected,
                .source = "closed form: lidar equation 0.3 / pi / R^2 times the Gaussian pulse "
                          "at the sample's offset",
                .value = peak,
                .tolerance = 1e-12,
                .kind = Tolerance::relative});
    } else {
      const double loss = std::exp(-2.0 * lidar.layer_extinction_per_m(n - 1) *
                                   (lidar.layer_end_m(n - 1) - lidar.layer_start_m(n - 1)));
      validate({.id = "lidar.waveform.target_echo.layer_loss." + std::to_string(n) + "layers",
                .group = "lidar",
                .quantity = "target echo ratio for one added fog layer",
                .unit = "1",
                .conditions = "study's chamber, layer " + std::to_string(n) + " added (" +
                              std::to_string(n) + " active layers), no fluctuation",
                .reference = loss,
                .source = "closed form: two-way Beer-Lambert loss exp(-2 alpha L)",
                .value = peak / previous,
                .tolerance = 1e-12,
                .kind = Tolerance::absolute});
    }
    previous = peak;
  }
}

// A layer's optical-depth factor f scales both alpha and beta_pi: the target echo through one layer
// falls by exp(-2 f alpha L).
TEST(LidarWaveform, FluctuationFactorScalesTheOpticalDepth) {
  const Lidar lidar(LidarParams{}, propagation::ChamberSpec{}, table());
  const auto active = propagation::first_layers_active(1, 4);
  const BeamWaveform one = lidar.waveform(lidar.target_beam(), active, std::vector<double>(4, 1.0));
  const BeamWaveform scaled =
      lidar.waveform(lidar.target_beam(), active, std::vector<double>{1.7, 1.0, 1.0, 1.0});
  double a = 0.0, b = 0.0;
  for (const double v : one.target) a = std::max(a, v);
  for (const double v : scaled.target) b = std::max(b, v);
  validate({.id = "lidar.waveform.fluctuation_factor.1.7",
            .group = "lidar",
            .quantity = "target echo ratio for an optical-depth factor",
            .unit = "1",
            .conditions = "study's chamber, 1 active layer (1 m), factor 1.7 against 1",
            .reference = std::exp(-2.0 * 0.7 * lidar.layer_extinction_per_m(0)),
            .source = "closed form: two-way Beer-Lambert loss exp(-2 (f - 1) alpha L)",
            .value = b / a,
            .tolerance = 1e-12,
            .kind = Tolerance::absolute});
}

// ---- Echo extraction on constructed waveforms (Gaussian pulses evaluated directly here). ----

struct Constructed {
  std::vector<double> w = std::vector<double>(samples, 0.0);
  void add(double range_m, double peak) {
    for (std::size_t k = 0; k < w.size(); ++k) {
      w[k] += peak * gaussian(static_cast<double>(k) * grid.sample_interval_s - 2.0 * range_m / c,
                              grid.pulse_fwhm_s);
    }
  }
};

EchoDetector detector(std::size_t max_echoes = 3, double separation_m = 1.0) {
  return {.threshold = 1.0,
          .sample_interval_s = grid.sample_interval_s,
          .range_offset_m = c * grid.pulse_fwhm_s / 4.0,
          .min_range_m = 0.1,
          .min_separation_m = separation_m,
          .max_echoes = max_echoes};
}

// An echo of peak exactly twice the threshold crosses it at half maximum, which the range offset
// c fwhm / 4 calibrates to the true range. Tolerance 3 mm: linear interpolation of the Gaussian's
// flank between samples 7.5 cm apart (curvature error below 1 mm) plus rounding.
TEST(LidarEchoes, OneEchoAtTwiceTheThresholdReadsItsRange) {
  Constructed w;
  w.add(12.34, 2.0);
  const DetectedEchoes e = extract_echoes(w.w, detector());
  ASSERT_EQ(e.count, 1u);
  validate({.id = "lidar.echoes.range.twice_threshold",
            .group = "lidar",
            .quantity = "echo range read at the threshold crossing",
            .unit = "m",
            .conditions = "constructed Gaussian echo at 12.34 m, peak 2 x threshold",
            .reference = 12.34,
            .source = "constructed waveform: the echo's true range (half-maximum crossing, offset "
                      "c fwhm / 4)",
            .value = e.echoes[0].range_m,
            .tolerance = 3e-3,
            .kind = Tolerance::absolute});
  // The peak sample is within dt/2 of the pulse centre: peak in [2 p(dt/2), 2].
  validate({.id = "lidar.echoes.peak.twice_threshold.upper",
            .group = "lidar",
            .quantity = "echo peak sample",
            .unit = "threshold",
            .conditions = "constructed Gaussian echo at 12.34 m, peak 2 x threshold",
            .reference = 2.0,
            .source = "constructed waveform: the pulse's peak 2",
            .value = e.echoes[0].peak,
            .tolerance = 0.0,
            .kind = Tolerance::at_most});
  validate({.id = "lidar.echoes.peak.twice_threshold.lower",
            .group = "lidar",
            .quantity = "echo peak sample",
            .unit = "threshold",
            .conditions = "constructed Gaussian echo at 12.34 m, peak 2 x threshold",
            .reference = 2.0 * gaussian(0.25e-9, grid.pulse_fwhm_s),
            .source = "closed form: the Gaussian pulse 2 p(dt/2) half a sample off its centre",
            .value = e.echoes[0].peak,
            .tolerance = 0.0,
            .kind = Tolerance::at_least});
}

// A stronger echo crosses earlier on its leading edge (the range walk the study's Fig. 5 shows as
// fog points "shifted from their origin position"): peak P crosses at t = -fwhm/2 sqrt(log2 P) from
// its centre, reading R + c fwhm/4 (1 - sqrt(log2 P)). Tolerance 3 mm as above.
TEST(LidarEchoes, StrongerEchoReadsNearerByTheLeadingEdgeWalk) {
  for (const double peak : {1.5, 8.0, 100.0}) {
    Constructed w;
    w.add(20.0, peak);
    const DetectedEchoes e = extract_echoes(w.w, detector());
    ASSERT_EQ(e.count, 1u);
    const double expected = 20.0 + c * grid.pulse_fwhm_s / 4.0 * (1.0 - std::sqrt(std::log2(peak)));
    validate({.id = "lidar.echoes.range_walk.peak" + str(peak),
              .group = "lidar",
              .quantity = "echo range read at the threshold crossing",
              .unit = "m",
              .conditions = "constructed Gaussian echo at 20 m, peak " + str(peak) + " x threshold",
              .reference = expected,
              .source = "closed form: leading-edge walk R + c fwhm / 4 (1 - sqrt(log2 P))",
              .value = e.echoes[0].range_m,
              .tolerance = 3e-3,
              .kind = Tolerance::absolute});
  }
}

TEST(LidarEchoes, TwoThreeAndFourEchoesInRangeOrder) {
  const double ranges[] = {5.0, 9.0, 14.0, 20.0};
  const double peaks[] = {6.0, 3.0, 2.0, 10.0};
  for (std::size_t n = 2; n <= 4; ++n) {
    Constructed w;
    for (std::size_t i = 0; i < n; ++i) w.add(ranges[i], peaks[i]);
    const DetectedEchoes e = extract_echoes(w.w, detector(3));
    ASSERT_EQ(e.count, std::min<std::size_t>(n, 3))
        << n;  // the fourth (strongest) is beyond max_echoes
    for (std::size_t i = 0; i < e.count; ++i) {
      const double walk = c * grid.pulse_fwhm_s / 4.0 * (1.0 - std::sqrt(std::log2(peaks[i])));
      const std::string id =
          "lidar.echoes.multiple." + std::to_string(n) + "echoes.echo" + std::to_string(i);
      const std::string conditions = std::to_string(n) + " constructed echoes; echo " +
                                     std::to_string(i) + " at " + str(ranges[i]) + " m, peak " +
                                     str(peaks[i]) + " x threshold";
      validate({.id = id + ".range",
                .group = "lidar",
                .quantity = "echo range read at the threshold crossing",
                .unit = "m",
                .conditions = conditions,
                .reference = ranges[i] + walk,
                .source = "closed form: leading-edge walk R + c fwhm / 4 (1 - sqrt(log2 P))",
                .value = e.echoes[i].range_m,
                .tolerance = 3e-3,
                .kind = Tolerance::absolute});
      validate({.id = id + ".peak",
                .group = "lidar",
                .quantity = "echo peak",
                .unit = "threshold",
                .conditions = conditions,
                .reference = peaks[i],
                .source = "constructed waveform: the echo's peak",
                .value = e.echoes[i].peak,
                .tolerance = 0.02,
                .kind = Tolerance::relative});
    }
  }
}

// Two echoes 1.5 m apart, each above threshold with the signal falling below it between them: with
// a 2 m minimum separation they merge into one echo at the first leading edge with the larger peak;
// with 1 m they are two.
TEST(LidarEchoes, EchoesCloserThanTheSeparationMerge) {
  Constructed w;
  w.add(10.0, 3.0);
  w.add(11.5, 5.0);
  ASSERT_LT(w.w[static_cast<std::size_t>(std::round(2.0 * 10.75 / c / grid.sample_interval_s))],
            1.0);
  const DetectedEchoes merged = extract_echoes(w.w, detector(3, 2.0));
  ASSERT_EQ(merged.count, 1u);
  const auto check_peak = [](const std::string& id, const std::string& conditions, double reference,
                             double value) {
    validate(
        {.id = "lidar.echoes.separation." + id,
         .group = "lidar",
         .quantity = "echo peak",
         .unit = "threshold",
         .conditions = "constructed echoes at 10 m (peak 3) and 11.5 m (peak 5), " + conditions,
         .reference = reference,
         .source = "constructed waveform: the echoes' peaks (merged: the larger)",
         .value = value,
         .tolerance = 0.02,
         .kind = Tolerance::relative});
  };
  check_peak("2m.merged.peak", "2 m minimum separation, merged", 5.0, merged.echoes[0].peak);
  const DetectedEchoes split = extract_echoes(w.w, detector(3, 1.0));
  ASSERT_EQ(split.count, 2u);
  check_peak("1m.echo0.peak", "1 m minimum separation, first echo", 3.0, split.echoes[0].peak);
  check_peak("1m.echo1.peak", "1 m minimum separation, second echo", 5.0, split.echoes[1].peak);
}

// A fog layer and a stronger hard target merged into one echo (leading edges closer than the
// minimum separation) are attributed to the return whose leading edge made the echo: the fog's.
// Constructed from closed forms: a transparent layer [5, 6] m whose plateau beta_pi (c tau_e / 2)
// / r^2 is 2 thresholds at 5 m (Rasshofer et al. 2011 eq. 3), then a Gaussian echo of peak 5 at
// 6.5 m, 3 m minimum separation. The echo's range is the fog's leading edge (the plateau's half
// height at the layer's edge, read at 5 m + c fwhm / 4 by the calibration; 5 cm for the 1/r^2
// fall across the pulse's extent, 4 cm here); its attribution sample, the first local maximum of
// the noise-free return after that edge, lies inside the layer; its peak (the intensity) is still
// the target's 5 (2 %, as the other peaks). A lone Gaussian echo is attributed at its own peak: the
// sample nearest its centre, within half a sample (c dt / 4 in range).
TEST(LidarEchoes, MergedFogAndTargetEchoIsAttributedToTheFogWhoseEdgeItReads) {
  const double dr = c * grid.sample_interval_s / 2.0;
  const double tau_e = grid.pulse_fwhm_s * std::sqrt(pi / (4.0 * ln2));
  std::vector<double> w(samples, 0.0);
  FogReturn(grid).add(w, {.start_m = 5.0,
                          .end_m = 6.0,
                          .extinction_per_m = 0.0,
                          .backscatter_per_m_sr = 2.0 * 25.0 / (c * tau_e / 2.0),
                          .transmittance_at_start = 1.0});
  Constructed target;
  target.add(6.5, 5.0);
  for (std::size_t k = 0; k < samples; ++k) w[k] += target.w[k];
  const DetectedEchoes merged = extract_echoes(w, detector(3, 3.0));
  ASSERT_EQ(merged.count, 1u);
  const DetectedEcho& echo = merged.echoes[0];
  const std::string conditions =
      "transparent layer [5, 6] m at 2 thresholds, Gaussian echo of peak 5 at 6.5 m, 3 m minimum "
      "separation";
  validate({.id = "lidar.echoes.merged_fog_target.range",
            .group = "lidar",
            .quantity = "merged echo's range (its leading edge)",
            .unit = "m",
            .conditions = conditions,
            .reference = 5.0 + c * grid.pulse_fwhm_s / 4.0,
            .source = "closed form: the plateau's half height at the layer's edge, plus the "
                      "calibration c fwhm / 4",
            .value = echo.range_m,
            .tolerance = 0.05,
            .kind = Tolerance::absolute});
  const double attributed_m = static_cast<double>(attribution_sample(w, echo)) * dr;
  validate({.id = "lidar.echoes.merged_fog_target.attribution.after_layer_start",
            .group = "lidar",
            .quantity = "merged echo's attribution range",
            .unit = "m",
            .conditions = conditions,
            .reference = 5.0,
            .source = "constructed waveform: the fog layer starts at 5 m",
            .value = attributed_m,
            .tolerance = 0.0,
            .kind = Tolerance::at_least});
  validate({.id = "lidar.echoes.merged_fog_target.attribution.before_layer_end",
            .group = "lidar",
            .quantity = "merged echo's attribution range",
            .unit = "m",
            .conditions = conditions,
            .reference = 6.0,
            .source = "constructed waveform: the fog layer ends at 6 m, the target is at 6.5 m",
            .value = attributed_m,
            .tolerance = 0.0,
            .kind = Tolerance::at_most});
  validate({.id = "lidar.echoes.merged_fog_target.peak",
            .group = "lidar",
            .quantity = "merged echo's peak (its intensity)",
            .unit = "threshold",
            .conditions = conditions,
            .reference = 5.0,
            .source = "constructed waveform: the target echo's peak, the larger",
            .value = echo.peak,
            .tolerance = 0.02,
            .kind = Tolerance::relative});

  Constructed lone;
  lone.add(12.34, 3.0);
  const DetectedEchoes single = extract_echoes(lone.w, detector());
  ASSERT_EQ(single.count, 1u);
  validate({.id = "lidar.echoes.lone.attribution",
            .group = "lidar",
            .quantity = "lone echo's attribution range",
            .unit = "m",
            .conditions = "constructed Gaussian echo at 12.34 m, peak 3 x threshold",
            .reference = 12.34,
            .source = "constructed waveform: the pulse's centre; its nearest sample is the peak",
            .value = static_cast<double>(attribution_sample(lone.w, single.echoes[0])) * dr,
            .tolerance = dr / 2.0,
            .kind = Tolerance::absolute});
}

TEST(LidarEchoes, BelowThresholdAndTooNearGiveNothing) {
  Constructed weak;
  weak.add(10.0, 0.99);
  EXPECT_EQ(extract_echoes(weak.w, detector()).count, 0u);
  Constructed near;
  near.add(0.2, 4.0);  // already above the threshold at t = 0: no leading edge in the record
  EXPECT_EQ(extract_echoes(near.w, detector()).count, 0u);
  Constructed inside;
  inside.add(0.6, 1.5);  // its leading edge is in the record, its range below min_range 1 m
  EchoDetector far_minimum = detector();
  EXPECT_EQ(extract_echoes(inside.w, far_minimum).count, 1u);
  far_minimum.min_range_m = 1.0;
  EXPECT_EQ(extract_echoes(inside.w, far_minimum).count, 0u);
}

// Intensity = min(saturation, scale peak / threshold): the clear-weather target (peak ~3 x
// threshold by the datasheet margin) saturates when the saturation is set below scale x 3.
TEST(LidarEchoes, IntensitySaturates) {
  LidarParams params;
  params.intensity_scale = 100.0;
  params.intensity_saturation = 250.0;
  params.background.clear();
  const Lidar lidar(params, propagation::ChamberSpec{}, table());
  RandomStream stream(7);
  const LidarScan scan =
      lidar.measure(propagation::first_layers_active(0, 4), std::vector<double>(4, 1.0), stream);
  ASSERT_TRUE(scan.target_detected);
  EXPECT_EQ(scan.target_intensity, 250.0);
  params.intensity_saturation = 1e6;
  const Lidar unsaturated(params, propagation::ChamberSpec{}, table());
  RandomStream again(7);
  const LidarScan free = unsaturated.measure(propagation::first_layers_active(0, 4),
                                             std::vector<double>(4, 1.0), again);
  EXPECT_GT(free.target_intensity, 250.0);
  EXPECT_LT(free.target_intensity, 400.0);
}

}  // namespace
}  // namespace fogradar::lidar
