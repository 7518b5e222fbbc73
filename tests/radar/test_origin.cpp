// Ground truth per detection (attribution.hpp): the window spectrum table against the direct DTFT
// sum, the per-origin cell contributions against FFT-processed frames of each origin's tones alone
// (a second method), the main lobes' half widths against Harris's table and the direct DTFT, the
// noise power against closed forms and Monte-Carlo frames, and the origin of CFAR detections on
// constructed frames: target alone, fog alone, noise alone, a target inside fog, a target side
// lobe, a rectangular window's sidelobe false alarms, and the fog's layers.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "chain_test_support.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/radar/attribution.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/outputs.hpp"
#include "fogradar/radar/results.hpp"
#include "fogradar/radar/synthesis.hpp"
#include "validation.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;
using test::kAllWindows;
using test::reference_noise_power_w;
using test::sum_of;
using test::sum_of_squares;
using test::window_name;

constexpr double kSpeedOfLight = 299'792'458.0;

// Linear interpolation of a complex function on a grid of spacing h errs by at most
// sqrt(2) h^2 / 8 max|f''| (the real-function bound h^2/8 max|f''| per part); for the window DTFT
// |W''(u)| = |sum_n w[n] (2 pi n / N)^2 e^{...}| <= 4 pi^2 sum |w[n]|, so with h = 1/M:
// |W_table(u) - W(u)| <= eps sum|w|, eps = sqrt(2) pi^2 / (2 M^2).
constexpr double kInterpolationEps =
    std::numbers::sqrt2 * std::numbers::pi * std::numbers::pi /
    (2.0 * WindowSpectrum::oversampling * WindowSpectrum::oversampling);

// A small radar: 128 samples x 16 chirps, everything else the paper radar.
RadarParams small_radar(WindowType window = WindowType::hann) {
  RadarParams p;
  p.samples_per_chirp = 128;
  p.chirps_per_frame = 16;
  p.window = window;
  return p;
}

// Two-way path length whose beat frequency S L / c sits at fractional range bin nu (fs / N per
// bin), written out from the FMCW relation (not from the library).
double path_at_bin_m(const RadarParams& p, double nu) {
  const double slope_hz_per_s = p.sweep_bandwidth_hz / p.chirp_duration_s;
  return nu * p.sample_rate_hz / static_cast<double>(p.samples_per_chirp) * kSpeedOfLight /
         slope_hz_per_s;
}

// Amplitude of a tone whose map peak on a bin centre has the given SNR against the thermal noise
// per cell: |a| (sum w_r)(sum w_d) = sqrt(snr k T0 F fs sum w_r^2 sum w_d^2).
double amplitude_for_snr(const RadarParams& p, double snr_db) {
  const auto w_r = make_window(p.window, p.samples_per_chirp);
  const auto w_d = make_window(p.window, p.chirps_per_frame);
  const double noise_per_cell =
      reference_noise_power_w(p) * sum_of_squares(w_r) * sum_of_squares(w_d);
  return std::sqrt(std::pow(10.0, snr_db / 10.0) * noise_per_cell) / (sum_of(w_r) * sum_of(w_d));
}

// The chain's own stages on a constructed list of tones: windowed synthesis (with thermal noise as
// the params say), range and Doppler FFTs, CFAR and estimation, then attribution.
std::vector<Detection> detect(const RadarChain& chain, const std::vector<Tone>& tones,
                              std::uint64_t seed, MeasurementWorkspace& ws) {
  RandomStream rng(seed);
  const FrameWindow window = chain.processor().window();
  synthesize_frame(tones, chain.params(), chain.derived(), rng, ws.frame, &window);
  chain.processor().transform_windowed(ws.frame);
  std::vector<Detection> detections;
  estimate_detections(ws.frame, chain.processor(), chain.cfar(), chain.params(), chain.derived(),
                      ws.estimation, detections);
  chain.origin_classifier().attribute(tones, detections);
  return detections;
}

// The map of a frame of these tones without noise (synthesised, windowed, transformed).
ComplexVector noise_free_map(const RadarChain& chain, const std::vector<Tone>& tones) {
  MeasurementWorkspace ws = chain.make_workspace();
  RandomStream rng(1);
  const FrameWindow window = chain.processor().window();
  synthesize_frame(tones, chain.params(), chain.derived(), rng, ws.frame, &window);
  chain.processor().transform_windowed(ws.frame);
  return ws.frame;
}

// Static fog scatterers, `per_bin` in each range bin of [first_bin, last_bin), each with a complex
// Gaussian amplitude of the given mean SNR (as the scene's clutter model draws them), in chamber
// layer `layer`.
std::vector<Tone> fog_tones(const RadarParams& p, int first_bin, int last_bin, double snr_db,
                            RandomStream& rng, int per_bin = 4, std::int16_t layer = 0) {
  std::vector<Tone> tones;
  const double a = amplitude_for_snr(p, snr_db);
  for (int k = first_bin; k < last_bin; ++k) {
    for (int s = 0; s < per_bin; ++s) {
      tones.push_back({path_at_bin_m(p, k + rng.uniform()), rng.complex_normal(a * a), 0.0,
                       Origin::fog, layer});
    }
  }
  return tones;
}

// The sensors' one code table (sensor/origin.hpp): the radar's codes as they always were, the
// lidar's background, the ADC's clipping, the sidelobes, the radar's ghosts and room after them.
TEST(Origin, NamesAndDominance) {
  EXPECT_EQ(to_string(Origin::target), "target");
  EXPECT_EQ(to_string(Origin::fog), "fog");
  EXPECT_EQ(to_string(Origin::noise), "noise");
  EXPECT_EQ(to_string(Origin::clipping), "clipping");
  EXPECT_EQ(to_string(Origin::sidelobe), "sidelobe");
  EXPECT_EQ(to_string(Origin::multipath), "multipath");
  EXPECT_EQ(to_string(Origin::room), "room");
  EXPECT_EQ(sensor::origin_labels(),
            (std::vector<std::string>{"noise", "target", "fog", "background", "clipping",
                                      "sidelobe", "multipath", "room"}));
  EXPECT_EQ(static_cast<int>(Origin::noise), 0);
  EXPECT_EQ(static_cast<int>(Origin::target), 1);
  EXPECT_EQ(static_cast<int>(Origin::fog), 2);
  EXPECT_EQ(static_cast<int>(Origin::sidelobe), 5);
  EXPECT_EQ(static_cast<int>(Origin::multipath), 6);
  EXPECT_EQ(static_cast<int>(Origin::room), 7);
  const auto dominant = [](double target, double multipath, double room, double fog,
                           double sidelobe, double noise) {
    return dominant_origin({.target = target,
                            .multipath = multipath,
                            .room = room,
                            .fog = fog,
                            .sidelobe = sidelobe,
                            .noise = noise});
  };
  EXPECT_EQ(dominant(2.0, 0.0, 0.0, 1.0, 0.5, 1.5), Origin::target);
  EXPECT_EQ(dominant(1.0, 0.0, 0.0, 2.0, 0.5, 1.5), Origin::fog);
  EXPECT_EQ(dominant(1.0, 0.0, 0.0, 1.2, 0.5, 1.5), Origin::noise);
  EXPECT_EQ(dominant(1.0, 0.0, 0.0, 1.2, 1.6, 1.5), Origin::sidelobe);
  EXPECT_EQ(dominant(1.0, 3.0, 2.0, 1.2, 1.6, 1.5), Origin::multipath);
  EXPECT_EQ(dominant(1.0, 2.0, 3.0, 1.2, 1.6, 1.5), Origin::room);
  // Ties: target, then multipath, room, fog, sidelobe.
  EXPECT_EQ(dominant(1.0, 1.0, 1.0, 1.0, 1.0, 1.0), Origin::target);
  EXPECT_EQ(dominant(0.0, 1.0, 1.0, 1.0, 1.0, 1.0), Origin::multipath);
  EXPECT_EQ(dominant(0.0, 0.0, 1.0, 1.0, 1.0, 1.0), Origin::room);
  EXPECT_EQ(dominant(0.0, 0.0, 0.0, 1.0, 1.0, 1.0), Origin::fog);
  EXPECT_EQ(dominant(0.0, 0.0, 0.0, 0.0, 1.0, 1.0), Origin::sidelobe);
  EXPECT_EQ(dominant(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), Origin::target);
}

class Spectrum : public ::testing::TestWithParam<WindowType> {};

// The table against the direct sum W(u) = sum_n w[n] exp(-i 2 pi n u / N) at 2000 offsets spread
// over three periods (the table is one period), N = 16, 50, 128: within the interpolation bound
// eps sum|w| derived above.
TEST_P(Spectrum, TableMatchesTheDirectDtftSum) {
  RandomStream rng(3);
  for (const std::size_t n : {std::size_t{16}, std::size_t{50}, std::size_t{128}}) {
    const std::vector<double> w = make_window(GetParam(), n);
    const WindowSpectrum spectrum(w);
    double sum_abs = 0.0;
    for (double v : w) sum_abs += std::abs(v);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const double u = (rng.uniform() * 3.0 - 1.5) * static_cast<double>(n);
      std::complex<double> direct{};
      for (std::size_t m = 0; m < n; ++m) {
        direct += w[m] * std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(m) * u /
                                             static_cast<double>(n));
      }
      worst = std::max(worst, std::abs(spectrum.at(u) - direct) / sum_abs);
    }
    std::printf("[ measured ] %s N = %zu: worst |table - direct| = %.2e sum|w| (bound %.2e)\n",
                std::string(to_string(GetParam())).c_str(), n, worst, kInterpolationEps);
    const std::string name(to_string(GetParam()));
    const std::string id = "radar.origin.window_spectrum." + name + ".N" + std::to_string(n);
    const std::string conditions = name + " window, N = " + std::to_string(n);
    fogradar::testing::validate(
        {.id = id + ".interpolation_error",
         .group = "radar: signal processing",
         .quantity = "worst |table - direct DTFT| / sum|w| over 2000 offsets",
         .unit = "1",
         .conditions = conditions + ", offsets over three periods",
         .reference = kInterpolationEps,
         .source = "direct DTFT sum (this test); linear-interpolation bound sqrt(2) pi^2 / (2 M^2)",
         .value = worst,
         .tolerance = 0.0,
         .kind = Tolerance::at_most});
    // On the table's own grid the value is the zero-padded FFT's, equal to the sum to rounding.
    fogradar::testing::validate({.id = id + ".at_zero",
                                 .group = "radar: signal processing",
                                 .quantity = "real part of the table's W(0)",
                                 .unit = "1",
                                 .conditions = conditions,
                                 .reference = sum_of(w),
                                 .source = "DTFT at 0: sum of the window samples",
                                 .value = spectrum.at(0.0).real(),
                                 .tolerance = 1e-12 * sum_abs,
                                 .kind = Tolerance::absolute});
  }
}

INSTANTIATE_TEST_SUITE_P(AllWindows, Spectrum, ::testing::ValuesIn(kAllWindows), window_name);

class Contributions : public ::testing::TestWithParam<WindowType> {};

// The classifier's target and fog contributions at every cell of the map against the FFT-processed,
// noise-free frame of the target tones alone and of the fog tones alone (the chain's synthesis and
// transforms: a second method). A tone's error is at most (2 eps + eps^2) |a| sum w_r sum w_d (the
// product of two interpolated factors, each within eps sum|w|); the tolerance is that bound summed
// over the tones. The expected noise power is k T0 F fs sum w_r^2 sum w_d^2 (relative 1e-12).
TEST_P(Contributions, EqualTheProcessedFrameOfEachOriginsTones) {
  RadarParams p = small_radar(GetParam());
  const RadarChain chain(p);
  RandomStream rng(11);
  const double a = amplitude_for_snr(p, 40.0);
  const std::vector<Tone> target{
      {path_at_bin_m(p, 20.37), {a, 0.3 * a}, 1.3, Origin::target},
      {path_at_bin_m(p, 21.9), {-0.2 * a, 0.5 * a}, -0.4, Origin::target}};
  const std::vector<Tone> fog = fog_tones(p, 40, 46, 20.0, rng);
  std::vector<Tone> all = target;
  all.insert(all.end(), fog.begin(), fog.end());
  p.thermal_noise = false;
  const RadarChain noise_free(p);
  const ComplexVector target_map = noise_free_map(noise_free, target);
  const ComplexVector fog_map = noise_free_map(noise_free, fog);

  const auto w_r = make_window(p.window, p.samples_per_chirp);
  const auto w_d = make_window(p.window, p.chirps_per_frame);
  const auto bound = [&](const std::vector<Tone>& tones) {
    double amplitude_sum = 0.0;
    for (const Tone& t : tones) amplitude_sum += std::abs(t.amplitude);
    return (2.0 * kInterpolationEps + kInterpolationEps * kInterpolationEps) * amplitude_sum *
           sum_of(w_r) * sum_of(w_d);
  };
  const double target_tol = bound(target), fog_tol = bound(fog);
  double worst_target = 0.0, worst_fog = 0.0;
  for (std::size_t d = 0; d < p.chirps_per_frame; ++d) {
    for (std::size_t k = 0; k < p.samples_per_chirp; ++k) {
      const CellContributions c = chain.origin_classifier().contributions(all, d, k);
      const std::size_t cell = d * p.samples_per_chirp + k;
      worst_target = std::max(worst_target, std::abs(c.target + c.target_leak - target_map[cell]));
      worst_fog = std::max(worst_fog, std::abs(c.fog + c.fog_leak - fog_map[cell]));
    }
  }
  std::printf("[ measured ] %s: worst |T - map| %.2e of bound %.2e, |F - map| %.2e of bound %.2e\n",
              std::string(to_string(p.window)).c_str(), worst_target, target_tol, worst_fog,
              fog_tol);
  EXPECT_LE(worst_target, target_tol);
  EXPECT_LE(worst_fog, fog_tol);
  const double noise = chain.origin_classifier().contributions(all, 0, 0).noise_power;
  fogradar::testing::validate(
      {.id = "radar.origin.noise_power." + std::string(to_string(p.window)),
       .group = "radar: SNR",
       .quantity = "thermal noise power per map cell",
       .unit = "W",
       .conditions = std::string(to_string(p.window)) + " window, 128 samples x 16 chirps",
       .reference = reference_noise_power_w(p) * sum_of_squares(w_r) * sum_of_squares(w_d),
       .source = "k T0 F fs sum w_r^2 sum w_d^2 (white noise through the windowed 2-D DFT)",
       .value = noise,
       .tolerance = 1e-12,
       .kind = Tolerance::relative});
  EXPECT_EQ(noise_free.origin_classifier().contributions(all, 0, 0).noise_power, 0.0);
}

INSTANTIATE_TEST_SUITE_P(AllWindows, Contributions, ::testing::ValuesIn(kAllWindows), window_name);

// A lone moving target at 30 dB SNR (range bin 20.3, 1.1 m/s): it is detected, and every detection
// at its cell (within 1 cell) is target; anything else is a noise false alarm.
TEST(OriginOfDetections, TargetAlone) {
  const RadarParams p = small_radar();
  const RadarChain chain(p);
  MeasurementWorkspace ws = chain.make_workspace();
  const double a = amplitude_for_snr(p, 30.0);
  const std::vector<Tone> tones{{path_at_bin_m(p, 20.3), {a, 0.0}, 1.1, Origin::target}};
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const std::vector<Detection> detections = detect(chain, tones, seed, ws);
    std::size_t at_target = 0;
    for (const Detection& det : detections) {
      const bool near = std::abs(static_cast<double>(det.range_cell) - 20.3) <= 1.0;
      EXPECT_EQ(det.origin, near ? Origin::target : Origin::noise)
          << det.range_cell << ' ' << det.doppler_cell;
      at_target += near ? 1 : 0;
    }
    EXPECT_EQ(at_target, 1u) << seed;
  }
}

// Fog alone: static clutter, 4 scatterers per bin in bins 40-42 at 30 dB mean SNR each (a patch
// narrower than the CFAR's guard cells, so that the range CFAR detects it; a homogeneous clutter
// region wider than the training window raises its own threshold); every detection lies in the fog
// (bins 38-44) and is fog.
TEST(OriginOfDetections, FogAlone) {
  const RadarParams p = small_radar();
  const RadarChain chain(p);
  MeasurementWorkspace ws = chain.make_workspace();
  std::size_t count = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    RandomStream rng(100 + seed);
    const std::vector<Tone> tones = fog_tones(p, 40, 43, 30.0, rng);
    for (const Detection& det : detect(chain, tones, seed, ws)) {
      EXPECT_GE(det.range_cell, 38u);
      EXPECT_LE(det.range_cell, 44u);
      EXPECT_EQ(det.origin, Origin::fog) << det.range_cell << ' ' << det.doppler_cell;
      ++count;
    }
  }
  EXPECT_GT(count, 0u);
}

// Noise alone with P_fa = 1e-2 (about 20 false-alarm cells per 2048-cell frame): every detection is
// noise.
TEST(OriginOfDetections, NoiseAlone) {
  RadarParams p = small_radar();
  p.cfar.false_alarm_probability = 1e-2;
  const RadarChain chain(p);
  MeasurementWorkspace ws = chain.make_workspace();
  std::size_t count = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    for (const Detection& det : detect(chain, {}, seed, ws)) {
      EXPECT_EQ(det.origin, Origin::noise);
      ++count;
    }
  }
  EXPECT_GT(count, 10u);
}

// A static 45 dB target at range bin 30.5 inside fog (bins 26-35, 15 dB per scatterer), and a
// denser fog patch (bins 50-52, 30 dB per scatterer): the detection at the target's cell is target;
// detections 5 or more bins from it are fog (a Hann side lobe 5 bins out is below -50 dB, so the
// target adds < -5 dB SNR there, under the fog's 15 dB).
TEST(OriginOfDetections, TargetInFog) {
  const RadarParams p = small_radar();
  const RadarChain chain(p);
  MeasurementWorkspace ws = chain.make_workspace();
  const double a = amplitude_for_snr(p, 45.0);
  std::size_t fog_count = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    RandomStream rng(200 + seed);
    std::vector<Tone> tones = fog_tones(p, 26, 36, 15.0, rng);
    const std::vector<Tone> patch = fog_tones(p, 50, 53, 30.0, rng);
    tones.insert(tones.end(), patch.begin(), patch.end());
    tones.push_back({path_at_bin_m(p, 30.5), {0.0, a}, 0.0, Origin::target});
    std::size_t at_target = 0;
    for (const Detection& det : detect(chain, tones, seed, ws)) {
      const double distance = std::abs(static_cast<double>(det.range_cell) - 30.5);
      if (distance <= 1.0 && det.doppler_cell == 0) {
        EXPECT_EQ(det.origin, Origin::target);
        ++at_target;
      } else if (distance >= 5.0) {
        EXPECT_EQ(det.origin, Origin::fog) << det.range_cell << ' ' << det.doppler_cell;
        ++fog_count;
      }
    }
    EXPECT_EQ(at_target, 1u) << seed;
  }
  EXPECT_GT(fog_count, 0u);
}

// A target side lobe: a cell 5.6 range bins and 2.7 Doppler bins from a 120 dB target (Hann: the
// 2-D side lobe there is -90.6 dB, i.e. about 29 dB above the noise), outside the Hann main lobe
// (2 bins) in both, is sidelobe; with the target at 30 dB the same cell's side lobe is far under
// the noise and the cell is noise. The side lobe's level is checked against the direct 2-D DTFT
// sum first.
TEST(OriginOfDetections, TargetSideLobe) {
  const RadarParams p = small_radar();
  const RadarChain chain(p);
  const double nu_r = 20.4, nu_d = 5.3;  // Doppler bin 5.3: v = -nu_d lambda / (2 N_c T_i)
  const double lambda_m = kSpeedOfLight / p.centre_frequency_hz;
  const double v =
      -nu_d * lambda_m / (2.0 * static_cast<double>(p.chirps_per_frame) * p.chirp_interval_s);
  // Range bin of the beat including the Doppler shift within the chirp (-2 v / lambda).
  const double doppler_range_bins =
      -2.0 * v / lambda_m * static_cast<double>(p.samples_per_chirp) / p.sample_rate_hz;
  const std::size_t d = 8, k = 26;  // 2.7 Doppler and ~5.6 range bins away
  const auto w_r = make_window(p.window, p.samples_per_chirp);
  const auto w_d = make_window(p.window, p.chirps_per_frame);
  std::complex<double> direct_r{}, direct_d{};
  const double u_r = static_cast<double>(k) - nu_r - doppler_range_bins;
  for (std::size_t n = 0; n < w_r.size(); ++n) {
    direct_r +=
        w_r[n] * std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(n) * u_r / 128.0);
  }
  for (std::size_t c = 0; c < w_d.size(); ++c) {
    direct_d += w_d[c] * std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(c) *
                                             (8.0 - nu_d) / 16.0);
  }
  const double side_lobe_db =
      20.0 * std::log10(std::abs(direct_r * direct_d) / (sum_of(w_r) * sum_of(w_d)));
  std::printf("[ measured ] side lobe at (%zu, %zu): %.1f dB re the peak\n", d, k, side_lobe_db);
  ASSERT_LT(side_lobe_db, -60.0);
  ASSERT_GT(side_lobe_db + 120.0, 10.0);
  for (const double snr_db : {120.0, 30.0}) {
    const double a = amplitude_for_snr(p, snr_db);
    const std::vector<Tone> tones{{path_at_bin_m(p, nu_r), {a, 0.0}, v, Origin::target}};
    const Origin expected = side_lobe_db + snr_db > 0.0 ? Origin::sidelobe : Origin::noise;
    EXPECT_EQ(chain.origin_classifier().classify(tones, d, k), expected) << snr_db;
  }
}

// A fully clipped ADC (full scale at the thermal noise's power, a 60 dB target): the frame clips,
// and its detections away from the target's cell are the clipping's harmonics and intermodulation
// products, never noise. The same tones without the ADC give fewer detections outside the target
// (noise false alarms alone): the clipping makes them, not the tones.
TEST(OriginOfDetections, ClippingProductsAreClipping) {
  RadarParams p = small_radar();
  p.adc_bits = 10;
  p.adc_full_scale_dbm = 10.0 * std::log10(reference_noise_power_w(p) / 1e-3);
  RadarParams ideal = p;
  ideal.adc_bits = 0;
  const RadarChain chain(p), ideal_chain(ideal);
  MeasurementWorkspace ws = chain.make_workspace();
  const double a = amplitude_for_snr(p, 60.0);
  const std::vector<Tone> tones{{path_at_bin_m(p, 20.3), {a, 0.0}, 0.0, Origin::target}};
  std::size_t clipping = 0, ideal_others = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    RandomStream rng(seed);
    const FrameWindow window = chain.processor().window();
    const SynthesisReport report =
        synthesize_frame(tones, chain.params(), chain.derived(), rng, ws.frame, &window);
    ASSERT_GT(report.clipped_samples, report.samples / 2);
    chain.processor().transform_windowed(ws.frame);
    std::vector<Detection> detections;
    estimate_detections(ws.frame, chain.processor(), chain.cfar(), chain.params(), chain.derived(),
                        ws.estimation, detections);
    chain.origin_classifier().attribute(tones, detections, report.clipped_samples > 0);
    for (const Detection& det : detections) {
      EXPECT_NE(det.origin, Origin::noise) << det.range_cell << ' ' << det.doppler_cell;
      clipping += det.origin == Origin::clipping ? 1 : 0;
    }
    MeasurementWorkspace ideal_ws = ideal_chain.make_workspace();
    for (const Detection& det : detect(ideal_chain, tones, seed, ideal_ws)) {
      ideal_others += det.origin == Origin::target ? 0 : 1;
    }
  }
  EXPECT_GT(clipping, ideal_others);
}

// The map of origins (OriginClassifier::origin_map) against classify at every cell, for a moving
// target in fog, with and without clipping: the grouped sums give the same origin wherever the
// powers do not tie (none does here).
TEST(OriginMap, EqualsClassifyAtEveryCell) {
  const RadarParams p = small_radar();
  const RadarChain chain(p);
  RandomStream rng(7);
  std::vector<Tone> tones = fog_tones(p, 26, 36, 15.0, rng);
  tones.push_back({path_at_bin_m(p, 30.5), {0.0, amplitude_for_snr(p, 45.0)}, 1.1, Origin::target});
  tones.push_back({path_at_bin_m(p, 12.2), {amplitude_for_snr(p, 25.0), 0.0}, 0.0, Origin::target});
  const std::size_t chirps = p.chirps_per_frame, samples = p.samples_per_chirp;
  const std::vector<Tone> far_fog = fog_tones(p, 60, 64, 20.0, rng, 4, 2);
  tones.insert(tones.end(), far_fog.begin(), far_fog.end());
  std::vector<std::uint8_t> map(chirps * samples);
  std::vector<std::int16_t> layers(chirps * samples);
  for (const bool clipped : {false, true}) {
    chain.origin_classifier().origin_map(tones, clipped, map, layers);
    std::size_t counts[6] = {}, layer_counts[3] = {};
    for (std::size_t d = 0; d < chirps; ++d) {
      for (std::size_t k = 0; k < samples; ++k) {
        const Attribution expected = chain.origin_classifier().attribution(tones, d, k, clipped);
        ASSERT_EQ(map[d * samples + k], static_cast<std::uint8_t>(expected.origin))
            << d << ' ' << k;
        ASSERT_EQ(layers[d * samples + k], expected.layer) << d << ' ' << k;
        ++counts[map[d * samples + k]];
        if (expected.origin == Origin::fog) {
          ASSERT_GE(expected.layer, 0);
          ++layer_counts[expected.layer];
        } else {
          ASSERT_EQ(expected.layer, -1);
        }
      }
    }
    EXPECT_GT(layer_counts[0], 0u);
    EXPECT_EQ(layer_counts[1], 0u);
    EXPECT_GT(layer_counts[2], 0u);
    EXPECT_GT(counts[static_cast<int>(Origin::target)], 0u);
    EXPECT_GT(counts[static_cast<int>(Origin::fog)], 0u);
    EXPECT_GT(counts[static_cast<int>(Origin::sidelobe)], 0u);
    EXPECT_GT(counts[static_cast<int>(clipped ? Origin::clipping : Origin::noise)], 0u);
    EXPECT_EQ(counts[static_cast<int>(clipped ? Origin::noise : Origin::clipping)], 0u);
  }
}

// The main lobe's half width the spectrum finds from the window's own DTFT table: Harris 1978,
// Table 1 (first null at 1 bin rectangular, 2 Hann and Hamming, 4 for the 4-term Blackman-Harris),
// to the table's grid (1/16 bin); and for every window the first local minimum of |W(u)| of the
// direct DTFT sum on a grid of 1/256 bin (a second method), within one table step.
TEST_P(Spectrum, MainLobeHalfWidth) {
  const WindowType type = GetParam();
  const std::size_t n = 128;
  const std::vector<double> w = make_window(type, n);
  const WindowSpectrum spectrum(w);
  const double step = 1.0 / static_cast<double>(WindowSpectrum::oversampling);
  const auto magnitude = [&](double u) {
    std::complex<double> sum{};
    for (std::size_t j = 0; j < n; ++j) {
      sum += w[j] * std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(j) * u /
                                        static_cast<double>(n));
    }
    return std::abs(sum);
  };
  double direct = 0.0;
  for (double u = 1.0 / 256.0; u < 64.0; u += 1.0 / 256.0) {
    if (magnitude(u + 1.0 / 256.0) > magnitude(u)) {
      direct = u;
      break;
    }
  }
  std::printf("[ measured ] %s: main-lobe half width %.4f bins (direct DTFT %.4f)\n",
              std::string(to_string(type)).c_str(), spectrum.main_lobe_half_width_bins(), direct);
  EXPECT_NEAR(spectrum.main_lobe_half_width_bins(), direct, step);
  const double harris = type == WindowType::rectangular       ? 1.0
                        : type == WindowType::blackman_harris ? 4.0
                        : type == WindowType::chebyshev       ? direct
                                                              : 2.0;
  EXPECT_NEAR(spectrum.main_lobe_half_width_bins(), harris, step);
}

// The rectangular window's sidelobe false alarms: a 90 dB target between range bins and Doppler
// bins over 8 chirps (a rectangular window's sidelobes fall off only as 1/u: -13 dB at 1.5 bins):
// no CFAR detection outside its main lobe is target, the one at its peak is; cells in its range
// and Doppler sidelobes are sidelobe.
TEST(OriginOfDetections, RectangularSidelobesAreSidelobe) {
  RadarParams p = small_radar(WindowType::rectangular);
  p.chirps_per_frame = 8;
  const RadarChain chain(p);
  MeasurementWorkspace ws = chain.make_workspace();
  const double nu_r = 20.5, nu_d = 2.5;
  const double lambda_m = kSpeedOfLight / p.centre_frequency_hz;
  const double v =
      -nu_d * lambda_m / (2.0 * static_cast<double>(p.chirps_per_frame) * p.chirp_interval_s);
  const double a = amplitude_for_snr(p, 90.0);
  const std::vector<Tone> tones{{path_at_bin_m(p, nu_r), {a, 0.0}, v, Origin::target}};
  // The tone's peak as synthesize_frame places it (the chain's Doppler sign convention).
  const double doppler_hz = doppler_shift_hz(v, chain.derived());
  const double peak_d = doppler_hz * p.chirp_interval_s * 8.0;
  const double peak_r =
      nu_r + doppler_hz * static_cast<double>(p.samples_per_chirp) / p.sample_rate_hz;
  std::size_t sidelobes = 0, at_target = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    for (const Detection& det : detect(chain, tones, seed, ws)) {
      const double u_r = static_cast<double>(det.range_cell) - peak_r;
      double u_d = static_cast<double>(det.doppler_cell) - peak_d;
      u_d -= 8.0 * std::round(u_d / 8.0);
      if (std::abs(u_r) < 1.0 && std::abs(u_d) < 1.0) {
        EXPECT_EQ(det.origin, Origin::target) << det.range_cell << ' ' << det.doppler_cell;
        ++at_target;
      } else {
        EXPECT_NE(det.origin, Origin::target) << det.range_cell << ' ' << det.doppler_cell;
        sidelobes += det.origin == Origin::sidelobe ? 1 : 0;
      }
    }
  }
  EXPECT_GE(at_target, 4u);
  std::printf("[ measured ] %zu sidelobe detections in 4 frames\n", sidelobes);
  // The cells themselves: the target's peak cell is target; a cell 3.5 Doppler bins off in the
  // target's range column (rectangular Doppler sidelobe about -21 dB, 69 dB above the noise) and
  // one 5.5 range bins off in its Doppler row are sidelobe.
  const auto cell_d = [&](double offset) {
    return static_cast<std::size_t>(std::lround(peak_d + offset + 16.0)) % 8;
  };
  const auto cell_r = [&](double offset) {
    return static_cast<std::size_t>(std::lround(peak_r + offset));
  };
  const OriginClassifier& classifier = chain.origin_classifier();
  EXPECT_EQ(classifier.classify(tones, cell_d(0.0), cell_r(0.0)), Origin::target);
  EXPECT_EQ(classifier.classify(tones, cell_d(3.5), cell_r(0.0)), Origin::sidelobe);
  EXPECT_EQ(classifier.classify(tones, cell_d(0.0), cell_r(5.5)), Origin::sidelobe);
}

// The fog's layer: two fog patches of layers 1 (bins 30-33) and 3 (bins 70-73); every fog
// detection names the layer of the patch it lies in.
TEST(OriginOfDetections, FogNamesItsLayer) {
  const RadarParams p = small_radar();
  const RadarChain chain(p);
  MeasurementWorkspace ws = chain.make_workspace();
  std::size_t counts[2] = {};
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    RandomStream rng(300 + seed);
    std::vector<Tone> tones = fog_tones(p, 30, 33, 30.0, rng, 4, 1);
    const std::vector<Tone> far = fog_tones(p, 70, 73, 30.0, rng, 4, 3);
    tones.insert(tones.end(), far.begin(), far.end());
    for (const Detection& det : detect(chain, tones, seed, ws)) {
      if (det.origin != Origin::fog) {
        EXPECT_EQ(det.layer, -1);
        continue;
      }
      const bool near = det.range_cell < 50;
      EXPECT_EQ(det.layer, near ? 1 : 3) << det.range_cell;
      ++counts[near ? 0 : 1];
    }
  }
  EXPECT_GT(counts[0], 0u);
  EXPECT_GT(counts[1], 0u);
}

// Mean |Y|^2 over the cells of `frames` frames of these tones (synthesised with the params' noises
// and ADC, windowed, transformed) outside a (2 x range_half + 1) x (2 x doppler_half + 1) box
// around (d0, k0): a Monte-Carlo estimate of the noise power per cell.
double mean_cell_power(const RadarChain& chain, const std::vector<Tone>& tones, int frames,
                       std::size_t d0, std::size_t k0, int half) {
  MeasurementWorkspace ws = chain.make_workspace();
  const FrameWindow window = chain.processor().window();
  const std::size_t chirps = chain.params().chirps_per_frame;
  const std::size_t samples = chain.params().samples_per_chirp;
  double sum = 0.0;
  std::size_t count = 0;
  for (int f = 0; f < frames; ++f) {
    RandomStream rng(500 + static_cast<std::uint64_t>(f));
    synthesize_frame(tones, chain.params(), chain.derived(), rng, ws.frame, &window);
    chain.processor().transform_windowed(ws.frame);
    for (std::size_t d = 0; d < chirps; ++d) {
      for (std::size_t k = 0; k < samples; ++k) {
        const auto dd = static_cast<long>(d) - static_cast<long>(d0);
        const auto dk = static_cast<long>(k) - static_cast<long>(k0);
        const long wrapped = std::min(std::labs(dd), static_cast<long>(chirps) - std::labs(dd));
        if (wrapped <= half && std::labs(dk) <= half) continue;
        sum += std::norm(ws.frame[d * samples + k]);
        ++count;
      }
    }
  }
  return sum / static_cast<double>(count);
}

// The noise power the attribution compares with (OriginClassifier::noise_power), three ways:
// - thermal only: k T0 F fs sum w_r^2 sum w_d^2 (closed form), and the mean cell power of 8
//   noise-only frames (2048 cells each; 16384 exponential cells, relative sd < 1 %): within 4 %;
// - white phase noise of 0.3 rad rms on a static 60 dB tone on a bin centre (periodic Hann: the
//   tone reaches only its 3 x 3 cells, every other cell holds only phase noise), no thermal noise:
//   the coherent part a e^{-sigma^2/2} and the white power |a|^2 (1 - e^{-sigma^2}) per sample
//   (E e^{i phi} = e^{-sigma^2/2} for phi ~ N(0, sigma^2)), times the window gains (closed form,
//   1e-12) and the mean cell power of 8 frames away from the tone (within 4 %);
// - an 8-bit ADC on thermal noise of 1 LSB rms per rail (Widrow's condition holds to e^{-2 pi^2}
//   there; full scale 128 LSB: no clipping): q^2 / 6 added per sample (q^2 / 12 per rail; closed
//   form, 1e-12), 7.7 % of the total, and the mean cell power of 8 frames within 3 %.
TEST(NoisePower, ThermalPhaseNoiseAndQuantisation) {
  RadarParams p = small_radar();
  const auto w_r = make_window(p.window, p.samples_per_chirp);
  const auto w_d = make_window(p.window, p.chirps_per_frame);
  const double gain = sum_of_squares(w_r) * sum_of_squares(w_d);
  const double thermal_w = reference_noise_power_w(p);
  {
    const RadarChain chain(p);
    const double classifier = chain.origin_classifier().noise_power({});
    EXPECT_NEAR(classifier, thermal_w * gain, 1e-12 * thermal_w * gain);
    const double measured = mean_cell_power(chain, {}, 8, 0, 0, -1);
    std::printf("[ measured ] thermal: mean cell power / noise_power = %.4f\n",
                measured / classifier);
    EXPECT_NEAR(measured / classifier, 1.0, 0.04);
  }
  {
    RadarParams q = p;
    q.thermal_noise = false;
    q.phase_noise_rms_rad = 0.3;
    const RadarChain chain(q);
    const double a = amplitude_for_snr(p, 60.0);
    const std::vector<Tone> tones{{path_at_bin_m(q, 30.0), {a, 0.0}, 0.0, Origin::target}};
    const double sigma2 = 0.3 * 0.3;
    const double reference = a * a * (1.0 - std::exp(-sigma2)) * gain;
    const double classifier = chain.origin_classifier().noise_power(tones);
    EXPECT_NEAR(classifier, reference, 1e-12 * reference);
    const double measured = mean_cell_power(chain, tones, 8, 0, 30, 1);
    std::printf("[ measured ] phase noise: mean cell power / noise_power = %.4f\n",
                measured / classifier);
    EXPECT_NEAR(measured / classifier, 1.0, 0.04);
    // The coherent part: the tone's peak cell against a e^{-sigma^2/2} sum w_r sum w_d.
    const CellContributions c = chain.origin_classifier().contributions(tones, 0, 30);
    const double peak = a * std::exp(-0.5 * sigma2) * sum_of(w_r) * sum_of(w_d);
    EXPECT_NEAR(std::abs(c.target), peak, 1e-3 * peak);
  }
  {
    RadarParams q = p;
    q.adc_bits = 8;
    const double step = std::sqrt(0.5 * thermal_w);  // sd per rail sqrt(N0 / 2) = q
    const double full_scale = 128.0 * step;
    q.adc_full_scale_dbm = 10.0 * std::log10(full_scale * full_scale / 1e-3);
    const RadarChain chain(q);
    const double classifier = chain.origin_classifier().noise_power({});
    const double reference = (thermal_w + step * step / 6.0) * gain;
    EXPECT_NEAR(classifier, reference, 1e-12 * reference);
    const double measured = mean_cell_power(chain, {}, 8, 0, 0, -1);
    std::printf("[ measured ] ADC: mean cell power / noise_power = %.4f\n", measured / classifier);
    EXPECT_NEAR(measured / classifier, 1.0, 0.03);
  }
}

// The quantisation error of Gaussian samples spanning many steps (sd 16 q per rail, no clipping):
// its mean |e|^2 per complex sample is q^2 / 6 (Widrow's uniform error, q^2 / 12 per rail). 10^5
// samples: |e|^2 has relative sd 0.63, so the mean's is 0.2 %; tolerance 1 %.
TEST(NoisePower, QuantisationErrorOfGaussianSamples) {
  const unsigned bits = 8;
  const double full_scale = 1.0;
  const double step = 2.0 * full_scale / 256.0;
  RandomStream rng(77);
  std::vector<std::complex<double>> samples(100000);
  for (auto& s : samples) s = {16.0 * step * rng.normal(), 16.0 * step * rng.normal()};
  std::vector<std::complex<double>> quantised = samples;
  EXPECT_EQ(quantize(quantised, bits, full_scale), 0u);
  double error = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) error += std::norm(quantised[i] - samples[i]);
  error /= static_cast<double>(samples.size());
  std::printf("[ measured ] mean |e|^2 / (q^2 / 6) = %.4f\n", error / (step * step / 6.0));
  EXPECT_NEAR(error / (step * step / 6.0), 1.0, 0.01);
}

// The record and the summary count each origin apart: sidelobe detections are neither noise false
// alarms nor fog, the room's ghosts and own echoes are counted as themselves; a fog detection keeps
// its layer and its peak cell.
TEST(OriginRecords, SidelobesAreCountedApart) {
  Measurement m;
  const Origin origins[] = {Origin::target, Origin::sidelobe, Origin::sidelobe,
                            Origin::noise,  Origin::fog,      Origin::multipath,
                            Origin::room,   Origin::room,     Origin::room};
  for (std::size_t i = 0; i < std::size(origins); ++i) {
    Detection d;
    d.range_m = 3.0 + static_cast<double>(i);
    d.range_cell = 10 + i;
    d.doppler_cell = i;
    d.origin = origins[i];
    d.layer = origins[i] == Origin::fog ? std::int16_t{1} : std::int16_t{-1};
    m.detections.push_back(d);
  }
  const MeasurementRecord r = record_of(m, 10.0, 0.5);
  EXPECT_EQ(r.sidelobe_detections, 2u);
  EXPECT_EQ(r.false_alarms, 1u);
  EXPECT_EQ(r.fog_detections, 1u);
  EXPECT_EQ(r.multipath_detections, 1u);
  EXPECT_EQ(r.room_detections, 3u);
  EXPECT_EQ(r.detections[4].layer, 1);
  EXPECT_EQ(r.detections[4].range_cell, 14u);
  EXPECT_EQ(r.detections[4].doppler_cell, 4u);
  EXPECT_EQ(r.detections[0].layer, -1);
  StepResult step;
  step.records = {r, r};
  step.records[1].sidelobe_detections = 1;
  step.records[1].room_detections = 0;
  const RadarSummary summary = summarize({step}, 0.0, 0.0);
  EXPECT_EQ(summary.steps[0].sidelobe_detections_per_frame, 1.5);
  EXPECT_EQ(summary.steps[0].false_alarms_per_frame, 1.0);
  EXPECT_EQ(summary.steps[0].multipath_detections_per_frame, 1.0);
  EXPECT_EQ(summary.steps[0].room_detections_per_frame, 1.5);
  const std::string csv = step_table(summary).csv();
  EXPECT_NE(csv.find(",multipath_detections_per_frame,room_detections_per_frame\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find(",1,1.5\n"), std::string::npos) << csv;
  const nlohmann::json steps = summary_json(summary)["steps"];
  EXPECT_EQ(steps[0]["room_detections_per_frame"].get<double>(), 1.5);
  const std::string printed = summary_table(summary);
  EXPECT_NE(printed.find("room detections (its objects' and back wall's own echoes): 1.500 per "
                         "frame at 0 active layers"),
            std::string::npos)
      << printed;
  EXPECT_NE(printed.find("multipath detections (ghosts of the target via the room, misses in the "
                         "gate): 1.000 per frame"),
            std::string::npos)
      << printed;
}

}  // namespace
}  // namespace fogradar::radar
