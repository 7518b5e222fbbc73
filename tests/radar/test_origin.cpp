// Ground truth per detection (attribution.hpp): the window spectrum table against the direct DTFT
// sum, the per-origin cell contributions against FFT-processed frames of each origin's tones alone
// (a second method), and the origin of CFAR detections on constructed frames: target alone, fog
// alone, noise alone, a target inside fog, and a target side lobe.
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
// Gaussian amplitude of the given mean SNR (as the scene's clutter model draws them).
std::vector<Tone> fog_tones(const RadarParams& p, int first_bin, int last_bin, double snr_db,
                            RandomStream& rng, int per_bin = 4) {
  std::vector<Tone> tones;
  const double a = amplitude_for_snr(p, snr_db);
  for (int k = first_bin; k < last_bin; ++k) {
    for (int s = 0; s < per_bin; ++s) {
      tones.push_back(
          {path_at_bin_m(p, k + rng.uniform()), rng.complex_normal(a * a), 0.0, Origin::fog});
    }
  }
  return tones;
}

// The sensors' one code table (sensor/origin.hpp): the radar's codes as they always were, the
// lidar's background and the ADC's clipping after them.
TEST(Origin, NamesAndDominance) {
  EXPECT_EQ(to_string(Origin::target), "target");
  EXPECT_EQ(to_string(Origin::fog), "fog");
  EXPECT_EQ(to_string(Origin::noise), "noise");
  EXPECT_EQ(to_string(Origin::clipping), "clipping");
  EXPECT_EQ(sensor::origin_labels(),
            (std::vector<std::string>{"noise", "target", "fog", "background", "clipping"}));
  EXPECT_EQ(static_cast<int>(Origin::noise), 0);
  EXPECT_EQ(static_cast<int>(Origin::target), 1);
  EXPECT_EQ(static_cast<int>(Origin::fog), 2);
  EXPECT_EQ(dominant_origin(2.0, 1.0, 1.5), Origin::target);
  EXPECT_EQ(dominant_origin(1.0, 2.0, 1.5), Origin::fog);
  EXPECT_EQ(dominant_origin(1.0, 1.2, 1.5), Origin::noise);
  EXPECT_EQ(dominant_origin(1.0, 1.0, 1.0), Origin::target);  // ties: target, then fog
  EXPECT_EQ(dominant_origin(0.0, 1.0, 1.0), Origin::fog);
  EXPECT_EQ(dominant_origin(0.0, 0.0, 0.0), Origin::target);
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
      worst_target = std::max(worst_target, std::abs(c.target - target_map[cell]));
      worst_fog = std::max(worst_fog, std::abs(c.fog - fog_map[cell]));
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
// 2-D side lobe there is -90.6 dB, i.e. about 29 dB above the noise) is target; with the target at
// 30 dB the same cell's side lobe is far under the noise and the cell is noise. The side lobe's
// level is checked against the direct 2-D DTFT sum first.
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
    const Origin expected = side_lobe_db + snr_db > 0.0 ? Origin::target : Origin::noise;
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
    estimate_detections(ws.frame, chain.processor(), chain.cfar(), chain.params(),
                        chain.derived(), ws.estimation, detections);
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
  std::vector<std::uint8_t> map(chirps * samples);
  for (const bool clipped : {false, true}) {
    chain.origin_classifier().origin_map(tones, clipped, map);
    std::size_t counts[5] = {};
    for (std::size_t d = 0; d < chirps; ++d) {
      for (std::size_t k = 0; k < samples; ++k) {
        const Origin expected = chain.origin_classifier().classify(tones, d, k, clipped);
        ASSERT_EQ(map[d * samples + k], static_cast<std::uint8_t>(expected)) << d << ' ' << k;
        ++counts[map[d * samples + k]];
      }
    }
    EXPECT_GT(counts[static_cast<int>(Origin::target)], 0u);
    EXPECT_GT(counts[static_cast<int>(Origin::fog)], 0u);
    EXPECT_GT(counts[static_cast<int>(clipped ? Origin::clipping : Origin::noise)], 0u);
    EXPECT_EQ(counts[static_cast<int>(clipped ? Origin::noise : Origin::clipping)], 0u);
  }
}

}  // namespace
}  // namespace fogradar::radar
