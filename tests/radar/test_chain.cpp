// End-to-end tests of the FMCW radar chain: scene -> beat signal -> window/FFT -> CFAR -> RCS.
// Every test names its independent reference and tolerance; Monte Carlo tests use fixed seeds
// (RandomStream(seed, a, b)) and statistically sized bounds. References:
//   [Sk]   M. I. Skolnik, Introduction to Radar Systems, 3rd ed.: radar equation (eq. 2.1),
//          Swerling models (sec. 2.8).
//   [H78]  F. J. Harris, Proc. IEEE 66(1), 1978: window sums, ENBW, coherent gain.
//   [OS]   Oppenheim & Schafer, Discrete-Time Signal Processing, 3rd ed.: DTFT of a DFT.
//   [W]    B. Widrow, I. Kollar, Quantization Noise, 2008: uniform error q^2/12 per rail.
//   [Ri14] M. A. Richards, Fundamentals of Radar Signal Processing, 2nd ed., sec. 6.5: CA-CFAR
//          Pfa = E[exp(-alpha Z)] = (1 + alpha/N)^-N for iid reference cells; for correlated
//          Gaussian reference cells the same expectation is 1 / det(I + (alpha/N) C).
//   [Pap]  The study (Hasirlioglu et al., IEEE VTC2017-Spring): eq. 7 (RCS), eq. 4 (virtual layer
//   model).
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/gamma.hpp>
#include <cctype>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "chain_test_support.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/propagation/layer_model.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/outputs.hpp"
#include "fogradar/radar/results.hpp"
#include "fogradar/radar/sensor.hpp"
#include "validation.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;
using test::kAllWindows;
using test::make_chamber;
using test::paper_chamber_spec;
using test::reference_noise_power_w;
using test::reference_range_bin_m;
using test::reference_received_power_w;
using test::strongest;
using test::sum_of;
using test::sum_of_squares;
using test::window_name;

constexpr double kC = 299'792'458.0;

// A number as check ids and conditions show it ("1e-06", "7.77", "512").
std::string id_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// An id part from free text: letters and digits kept, every other run of characters one '_'.
std::string id_slug(const std::string& text) {
  std::string slug;
  for (const char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0) {
      slug += c;
    } else if (!slug.empty() && slug.back() != '_') {
      slug += '_';
    }
  }
  while (!slug.empty() && slug.back() == '_') slug.pop_back();
  return slug;
}

// --- Read-back checks ------------------------------------------------------------------------
// A detection read back against what the test set: the three records share their group, quantity,
// unit and source wherever the reference is the set value itself. `prefix` + ".rcs" etc. is the id.

void validate_set_rcs(const std::string& prefix, const std::string& conditions, double set_rcs_dbsm,
                      double rcs_dbsm, double tolerance_db) {
  fogradar::testing::validate({.id = prefix + ".rcs",
                               .group = "radar: RCS",
                               .quantity = "RCS read back",
                               .unit = "dBsm",
                               .conditions = conditions,
                               .reference = set_rcs_dbsm,
                               .source = "the set RCS",
                               .value = rcs_dbsm,
                               .tolerance = tolerance_db,
                               .kind = Tolerance::absolute});
}

void validate_set_range(const std::string& prefix, const std::string& conditions,
                        double set_range_m, double range_m, double tolerance_m) {
  fogradar::testing::validate({.id = prefix + ".range",
                               .group = "radar: signal processing",
                               .quantity = "range read back",
                               .unit = "m",
                               .conditions = conditions,
                               .reference = set_range_m,
                               .source = "the set range",
                               .value = range_m,
                               .tolerance = tolerance_m,
                               .kind = Tolerance::absolute});
}

// `unit` is "m/s", or "velocity bins" where both values are divided by the bin width.
void validate_set_velocity(const std::string& prefix, const std::string& conditions,
                           const std::string& unit, double set_velocity, double velocity,
                           double tolerance) {
  fogradar::testing::validate({.id = prefix + ".velocity",
                               .group = "radar: Doppler",
                               .quantity = "radial velocity read back",
                               .unit = unit,
                               .conditions = conditions,
                               .reference = set_velocity,
                               .source = "the set velocity",
                               .value = velocity,
                               .tolerance = tolerance,
                               .kind = Tolerance::absolute});
}

// --- Statistics helpers -----------------------------------------------------------------------

// Two-sided 99.9 % acceptance interval for the count of a Binomial(n, p).
std::pair<double, double> binomial_interval(double n, double p) {
  const boost::math::binomial_distribution<double> dist(n, p);
  return {boost::math::quantile(dist, 0.0005),
          boost::math::quantile(boost::math::complement(dist, 0.0005))};
}

// Pearson chi-square goodness of fit of `values` to the unit exponential, with `bins`
// equiprobable cells (edges -ln(1 - i/bins)); no parameter is estimated, so df = bins - 1.
// Returns the p-value.
double exponential_chi_square_p_value(const std::vector<double>& values, unsigned bins) {
  std::vector<double> counts(bins, 0.0);
  for (const double v : values) {
    const double u = 1.0 - std::exp(-v);  // exponential CDF
    const auto cell = std::min<std::size_t>(bins - 1, static_cast<std::size_t>(u * bins));
    counts[cell] += 1.0;
  }
  const double expected = static_cast<double>(values.size()) / bins;
  double statistic = 0.0;
  for (const double c : counts) statistic += (c - expected) * (c - expected) / expected;
  const boost::math::chi_squared_distribution<double> dist(bins - 1.0);
  return boost::math::cdf(boost::math::complement(dist, statistic));
}

// Sum of w^2 of a periodic cosine-sum window w[j] = sum_k (-1)^k a_k cos(2 pi k j / N), exactly
// N (a_0^2 + sum_{k>=1} a_k^2 / 2) for N > 2K (orthogonality of the DFT basis) [H78 Table 1].
double cosine_window_sum_of_squares(WindowType type, std::size_t n) {
  std::vector<double> a;
  switch (type) {
    case WindowType::rectangular:
      a = {1.0};
      break;
    case WindowType::hann:
      a = {0.5, 0.5};
      break;
    case WindowType::hamming:
      a = {0.54, 0.46};
      break;
    case WindowType::blackman_harris:
      a = {0.35875, 0.48829, 0.14128, 0.01168};
      break;
    case WindowType::chebyshev:
      return std::numeric_limits<double>::quiet_NaN();
  }
  double s = a[0] * a[0];
  for (std::size_t k = 1; k < a.size(); ++k) s += 0.5 * a[k] * a[k];
  return static_cast<double>(n) * s;
}

// The window's noise power gain sum(w^2): the closed form for cosine windows, the samples for
// Dolph-Chebyshev (which has no closed form; its samples are tested in test_window.cpp).
double window_noise_gain(WindowType type, std::size_t n) {
  if (type == WindowType::chebyshev) return sum_of_squares(make_window(type, n));
  return cosine_window_sum_of_squares(type, n);
}

// Correlation coefficient of DFT bins k and k + lag of windowed white noise:
//   rho(lag) = sum_j w_j^2 exp(-i 2 pi j lag / N) / sum_j w_j^2   (direct sum).
std::complex<double> bin_correlation(const std::vector<double>& w, long lag) {
  const double n = static_cast<double>(w.size());
  std::complex<double> s{};
  for (std::size_t j = 0; j < w.size(); ++j) {
    s += w[j] * w[j] *
         std::polar(
             1.0, -2.0 * std::numbers::pi * static_cast<double>(j) * static_cast<double>(lag) / n);
  }
  return s / sum_of_squares(w);
}

// Smallest lag from which every |rho(lag)| (up to N/2) stays below `limit`: a stride at which
// windowed-noise bins are (nearly) independent.
std::size_t decorrelation_stride(const std::vector<double>& w, double limit) {
  std::size_t stride = w.size() / 2;
  for (std::size_t lag = w.size() / 2; lag >= 1; --lag) {
    if (std::abs(bin_correlation(w, static_cast<long>(lag))) >= limit) break;
    stride = lag;
  }
  return stride;
}

// Determinant of a small complex matrix by Gaussian elimination with partial pivoting.
std::complex<double> determinant(std::vector<std::vector<std::complex<double>>> m) {
  const std::size_t n = m.size();
  std::complex<double> det = 1.0;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < n; ++r) {
      if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
    }
    if (pivot != c) {
      std::swap(m[pivot], m[c]);
      det = -det;
    }
    det *= m[c][c];
    for (std::size_t r = c + 1; r < n; ++r) {
      const std::complex<double> f = m[r][c] / m[c][c];
      for (std::size_t k = c; k < n; ++k) m[r][k] -= f * m[c][k];
    }
  }
  return det;
}

RadarParams noise_free(RadarParams p) {
  p.thermal_noise = false;
  return p;
}

// --- Noise only -------------------------------------------------------------------------------

class NoiseOnly : public ::testing::TestWithParam<WindowType> {};

// Mean cell power of the processed noise-only map equals k T0 F fs * sum(w_r^2) * sum(w_d^2)
// (white noise through a windowed 2-D DFT, Parseval), reference written out in the test with the
// closed-form window sums [H78]. Tolerance 2 % (the issue's); the statistical 1-sigma error of
// the mean over M = 8 paper frames (262'144 cells, correlated by the window) is
// sqrt(S_r S_d / M) with S = N sum w^4 / (sum w^2)^2: 0.20 % rectangular, 0.38 % Hann, 0.54 %
// Blackman-Harris. The cells are also exponential: chi-square GoF (20 equiprobable cells, no fitted
// parameter, mean fixed to the prediction), significance 1e-3, on cells spaced by a stride at
// which the window's bin correlation |rho| < 0.01 (exactly 0 for rectangular, Hann, Hamming).
TEST_P(NoiseOnly, MeanCellPowerIsKT0FfsTimesWindowGainsAndExponential) {
  RadarParams p;  // paper radar, thermal noise on
  p.window = GetParam();
  const RadarDerived d = derive(p);
  const RangeDopplerProcessor processor(p);
  const std::size_t rows = p.chirps_per_frame, cols = p.samples_per_chirp;
  const double expected_w = reference_noise_power_w(p) * window_noise_gain(p.window, cols) *
                            window_noise_gain(p.window, rows);
  const auto range_window = make_window(p.window, cols);
  const auto doppler_window = make_window(p.window, rows);
  const std::size_t range_stride = decorrelation_stride(range_window, 0.01);
  const std::size_t doppler_stride = decorrelation_stride(doppler_window, 0.01);

  ComplexVector frame(rows * cols);
  std::vector<double> power(rows * cols);
  constexpr int kFrames = 8;
  double sum_w = 0.0;
  std::vector<double> normalised;
  for (int f = 0; f < kFrames; ++f) {
    RandomStream rng(2024, 1, static_cast<std::uint64_t>(f));
    synthesize_frame({}, p, d, rng, frame);
    processor.process(frame, power);
    for (const double v : power) sum_w += v;
    for (std::size_t r = 0; r < rows; r += doppler_stride) {
      for (std::size_t k = 0; k < cols; k += range_stride)
        normalised.push_back(power[r * cols + k] / expected_w);
    }
  }
  const double mean_w = sum_w / static_cast<double>(kFrames * rows * cols);
  const double p_value = exponential_chi_square_p_value(normalised, 20);
  std::printf(
      "[ measured ] noise-only %s: mean cell power / (k T0 F fs sum w_r^2 sum w_d^2) = %.4f; "
      "chi-square GoF on %zu cells (stride %zu x %zu): p = %.3f\n",
      std::string(to_string(p.window)).c_str(), mean_w / expected_w, normalised.size(),
      doppler_stride, range_stride, p_value);
  const std::string name(to_string(p.window));
  const std::string conditions = "paper radar (64 x 512), " + name + " window";
  fogradar::testing::validate(
      {.id = "radar.chain.noise_only." + name + ".mean_cell_power",
       .group = "radar: SNR",
       .quantity = "mean cell power of the noise-only map",
       .unit = "W",
       .conditions = conditions + ", 8 frames",
       .reference = expected_w,
       .source = "k T0 F fs sum w_r^2 sum w_d^2 (Parseval; window sums closed form [H78])",
       .value = mean_w,
       .tolerance = 0.02,
       .kind = Tolerance::relative});
  fogradar::testing::validate(
      {.id = "radar.chain.noise_only." + name + ".exponential_gof_p_value",
       .group = "radar: SNR",
       .quantity = "chi-square goodness-of-fit p-value of the cell powers",
       .unit = "1",
       .conditions = conditions + ", " + std::to_string(normalised.size()) +
                     " decorrelated cells, 20 equiprobable cells",
       .reference = 1e-3,
       .source = "unit exponential with the predicted mean (complex Gaussian noise)",
       .value = p_value,
       .tolerance = 0.0,
       .kind = Tolerance::at_least});
  // The chain's own noise gain (used for SNR) agrees with the closed form.
  const double gains = window_noise_gain(p.window, cols) * window_noise_gain(p.window, rows);
  if (p.window == WindowType::chebyshev) {
    // No closed form: the reference is the sum over the library's own window samples.
    EXPECT_NEAR(processor.noise_power_gain() / gains, 1.0, 1e-12);
  } else {
    fogradar::testing::validate(
        {.id = "radar.chain.noise_only." + name + ".noise_power_gain",
         .group = "radar: SNR",
         .quantity = "noise power gain sum w_r^2 sum w_d^2",
         .unit = "1",
         .conditions = conditions,
         .reference = gains,
         .source = "closed form N (a0^2 + sum a_k^2 / 2) per cosine window [H78 Table 1]",
         .value = processor.noise_power_gain(),
         .tolerance = 1e-12,
         .kind = Tolerance::relative});
  }
  fogradar::testing::validate({.id = "radar.chain.noise_only." + name + ".noise_power",
                               .group = "radar: SNR",
                               .quantity = "thermal noise power k T0 F fs",
                               .unit = "W",
                               .conditions = conditions,
                               .reference = reference_noise_power_w(p),
                               .source = "k T0 F fs written out (reference_noise_power_w)",
                               .value = d.noise_power_w,
                               .tolerance = 1e-12,
                               .kind = Tolerance::relative});
}

INSTANTIATE_TEST_SUITE_P(AllWindows, NoiseOnly, ::testing::ValuesIn(kAllWindows), window_name);

// --- CFAR through the chain -------------------------------------------------------------------

// CA-CFAR at design Pfa 1e-3 on the chain's noise-only range-Doppler map, rectangular window:
// the 2-D DFT of white Gaussian noise is white Gaussian, so every cell is iid exponential and the
// design Pfa must hold [Ri14]. >= 1e6 cells (31 paper frames); interior and edge cells (the first
// and last g + n = 10 of each range profile) separately, each within its binomial 99.9 % interval.
TEST(ChainCfar, CaFalseAlarmRateOnNoiseMapRectangularWindow) {
  RadarParams p;
  p.window = WindowType::rectangular;
  p.cfar.false_alarm_probability = 1e-3;
  const RadarDerived d = derive(p);
  const RangeDopplerProcessor processor(p);
  const CfarDetector cfar(p.cfar);
  const std::size_t rows = p.chirps_per_frame, cols = p.samples_per_chirp;
  const std::size_t edge = p.cfar.guard_cells + p.cfar.training_cells;
  ComplexVector frame(rows * cols);
  std::vector<double> power(rows * cols);
  CfarWorkspace ws;
  constexpr int kFrames = 31;
  double interior = 0, edges = 0;
  for (int f = 0; f < kFrames; ++f) {
    RandomStream rng(2024, 2, static_cast<std::uint64_t>(f));
    synthesize_frame({}, p, d, rng, frame);
    processor.process(frame, power);
    for (std::size_t r = 0; r < rows; ++r) {
      cfar.detect(std::span<const double>(power).subspan(r * cols, cols), ws);
      for (const std::size_t k : ws.detections)
        (k < edge || k >= cols - edge ? edges : interior) += 1.0;
    }
  }
  const double interior_cells = static_cast<double>(kFrames * rows * (cols - 2 * edge));
  const double edge_cells = static_cast<double>(kFrames * rows * 2 * edge);
  const auto [il, ih] = binomial_interval(interior_cells, 1e-3);
  const auto [el, eh] = binomial_interval(edge_cells, 1e-3);
  std::printf(
      "[ measured ] chain CA-CFAR (rectangular) Pfa interior %.4e (%.0f/%.0f, accept [%.0f, "
      "%.0f]), "
      "edge %.4e (%.0f/%.0f, accept [%.0f, %.0f])\n",
      interior / interior_cells, interior, interior_cells, il, ih, edges / edge_cells, edges,
      edge_cells, el, eh);
  const struct {
    const char* cells;
    double alarms, count, low, high;
  } groups[] = {{"interior", interior, interior_cells, il, ih},
                {"edge", edges, edge_cells, el, eh}};
  for (const auto& group : groups) {
    // The counts' interval as rates: dividing by the cell count keeps the order.
    fogradar::testing::validate(
        {.id = "radar.chain.cfar.ca_rectangular.realised_pfa." + std::string(group.cells),
         .group = "radar: CFAR",
         .quantity = std::string("realised P_fa on the noise-only map, ") + group.cells + " cells",
         .unit = "1",
         .conditions = "CA-CFAR, 16 training cells, guard 2, rectangular window, 31 paper frames",
         .reference = 1e-3,
         .source = "design P_fa: iid exponential cells [Ri14] (binomial interval, Boost.Math)",
         .value = group.alarms / group.count,
         .tolerance = 0.0,
         .kind = Tolerance::statistical,
         .samples = static_cast<std::size_t>(group.count),
         .interval_low = group.low / group.count,
         .interval_high = group.high / group.count,
         .confidence = "99.9 % two-sided binomial interval of the design P_fa",
         .plot = "cfar_pfa",
         .x = 1e-3,
         .x_label = "design P_fa"});
  }
}

// With the default Hann window neighbouring range cells of the noise map are correlated
// (rho(1) = -2/3, rho(2) = 1/6, 0 beyond for the periodic Hann window), so the CA reference cells
// are not iid and the real Pfa exceeds the design value. Reference: for a cell under test
// independent of its reference cells (true here: guard 2 >= the correlation length), Pfa =
// E[exp(-alpha Z / s^2)] = 1 / det(I + (alpha/N) C) with C the reference cells' correlation
// matrix [Ri14 sec. 6.5 generalised; MGF of a complex Gaussian quadratic form]. Interior cells
// at range index = 0 mod 3 (independent cells under test), single-chirp frames; acceptance: the
// binomial 99.9 % interval around the predicted Pfa.
TEST(ChainCfar, CaFalseAlarmRateWithHannWindowMatchesCorrelatedCellPrediction) {
  RadarParams p;
  p.window = WindowType::hann;
  p.chirps_per_frame = 1;
  p.cfar.false_alarm_probability = 1e-3;
  const RadarDerived d = derive(p);
  const RangeDopplerProcessor processor(p);
  const CfarDetector cfar(p.cfar);
  const std::size_t cols = p.samples_per_chirp;
  const unsigned g = p.cfar.guard_cells, n = p.cfar.training_cells;
  const std::size_t edge = g + n;

  // Predicted Pfa from the correlation of the reference cells.
  const auto w = make_window(p.window, cols);
  std::vector<long> offsets;
  for (long i = -static_cast<long>(g + n); i <= static_cast<long>(g + n); ++i) {
    if (std::abs(i) > static_cast<long>(g)) offsets.push_back(i);
  }
  const double big_n = 2.0 * n;
  const auto correlated_pfa = [&](double design_pfa) {
    const double alpha =
        big_n * (std::pow(design_pfa, -1.0 / big_n) - 1.0);  // [Ri14] CA closed form
    std::vector<std::vector<std::complex<double>>> m(
        offsets.size(), std::vector<std::complex<double>>(offsets.size()));
    for (std::size_t i = 0; i < offsets.size(); ++i) {
      for (std::size_t j = 0; j < offsets.size(); ++j) {
        m[i][j] =
            (i == j ? 1.0 : 0.0) + alpha / big_n * bin_correlation(w, offsets[j] - offsets[i]);
      }
    }
    return 1.0 / determinant(m).real();
  };
  const double predicted_pfa = correlated_pfa(1e-3);
  std::printf(
      "[ measured ] CA N=16 g=2 with Hann range window: predicted real Pfa %.3e at design 1e-3, "
      "%.3e at "
      "design 1e-6 (the paper default)\n",
      predicted_pfa, correlated_pfa(1e-6));
  for (long lag = g + 1; lag <= static_cast<long>(g + n); ++lag) {
    ASSERT_LT(std::abs(bin_correlation(w, lag)), 1e-12)
        << "cell under test correlated with lag " << lag;
  }

  ComplexVector frame(cols);
  std::vector<double> power(cols);
  CfarWorkspace ws;
  constexpr int kFrames = 1800;
  double alarms = 0, cells = 0;
  for (int f = 0; f < kFrames; ++f) {
    RandomStream rng(2024, 3, static_cast<std::uint64_t>(f));
    synthesize_frame({}, p, d, rng, frame);
    processor.process(frame, power);
    cfar.detect(power, ws);
    for (std::size_t k = edge + (3 - edge % 3) % 3; k < cols - edge; k += 3) cells += 1.0;
    for (const std::size_t k : ws.detections) {
      if (k >= edge && k < cols - edge && k % 3 == 0) alarms += 1.0;
    }
  }
  const auto [low, high] = binomial_interval(cells, predicted_pfa);
  std::printf(
      "[ measured ] chain CA-CFAR (Hann, design Pfa 1e-3) Pfa %.4e (%.0f/%.0f); correlated-cell "
      "prediction %.4e (accept [%.0f, %.0f])\n",
      alarms / cells, alarms, cells, predicted_pfa, low, high);
  // The count's interval as rates: dividing by the cell count keeps the order.
  fogradar::testing::validate(
      {.id = "radar.chain.cfar.ca_hann.realised_pfa.correlated_prediction",
       .group = "radar: CFAR",
       .quantity = "realised P_fa on the noise-only map, interior cells at index 0 mod 3",
       .unit = "1",
       .conditions = "CA-CFAR, 16 training cells, guard 2, Hann window, design P_fa 1e-3, 1800 "
                     "single-chirp frames",
       .reference = predicted_pfa,
       .source = "closed form 1 / det(I + (alpha/N) C) [Ri14 sec. 6.5 generalised] (this test)",
       .value = alarms / cells,
       .tolerance = 0.0,
       .kind = Tolerance::statistical,
       .samples = static_cast<std::size_t>(cells),
       .interval_low = low / cells,
       .interval_high = high / cells,
       .confidence = "99.9 % two-sided binomial interval of the predicted P_fa",
       .plot = "cfar_pfa",
       .x = 1e-3,
       .x_label = "design P_fa"});
  EXPECT_GT(predicted_pfa, 1.5e-3);  // the effect is real, not within noise of the design value
}

// --- Calibration: lone point target, noise off --------------------------------------------------

// A radar with non-unit, unequal P_t, G_t, G_r and another wavelength: calibration errors that
// cancel between the paper radar's equal gains (e.g. G_t used twice) show up here.
RadarParams changed_radar(WindowType window) {
  RadarParams p;
  p.centre_frequency_hz = 79e9;
  p.sweep_bandwidth_hz = 0.8e9;
  p.tx_power_dbm = 3.0;
  p.tx_gain_dbi = 21.0;
  p.rx_gain_dbi = 14.0;
  p.window = window;
  return p;
}

class PointTargetCalibration : public ::testing::TestWithParam<WindowType> {};

// A lone non-fluctuating point target on boresight, noise off: the RCS read back equals the set
// RCS within 0.2 dB and the range within 2 cm, at ranges 3-60 m and 20 sub-bin offsets
// (0, 0.05, ..., 0.95 bin) each. Reference: the set RCS and range. Done for the paper radar
// (frames sized down to 8 chirps: the calibration does not depend on the chirp count; one full
// 64-chirp point is included) and for a radar with P_t = 3 dBm, G_t = 21 dBi, G_r = 14 dBi,
// 79 GHz, 0.8 GHz sweep; the paper radar for an up- and a down-chirp (the changed radar, whose
// gains and wavelength do not interact with the direction, up only, to keep sanitizer runs short).
void check_calibration(const RadarParams& params_in, const char* label,
                       std::initializer_list<SweepDirection> directions) {
  for (const SweepDirection direction : directions) {
    RadarParams params = noise_free(params_in);
    params.sweep_direction = direction;
    const RadarChain chain(params);
    const propagation::Chamber chamber =
        make_chamber(paper_chamber_spec(), params.centre_frequency_hz);
    const propagation::ActiveLayers no_fog =
        propagation::first_layers_active(0, chamber.layer_count());
    const double bin_m = reference_range_bin_m(params);
    constexpr double kRcsDbsm = 7.5;
    constexpr double kRcsTolDb = 0.2;
    constexpr double kRangeTolM = 0.02;
    MeasurementWorkspace ws = chain.make_workspace();
    Measurement m;
    double worst_db = 0.0, worst_m = 0.0;
    int count = 0;
    for (const double nominal_m : {3.0, 7.7, 14.2, 25.0, 38.9, 60.0}) {
      const double base_bin = std::round(nominal_m / bin_m);
      for (int j = 0; j < 20; ++j) {
        const double range_m = (base_bin + 0.05 * j) * bin_m;
        Scene scene = point_target_scene(kRcsDbsm);
        scene.centres[0].range_offset_m = range_m - chamber.target_range_m();
        chain.check_compatible(scene, chamber);
        RandomStream rng(7, static_cast<std::uint64_t>(count));
        chain.measure(scene, chamber, no_fog, rng, ws, m);
        const Detection* det = strongest(m.detections);
        ASSERT_NE(det, nullptr) << label << " range " << range_m;
        const double err_db = det->rcs_dbsm - kRcsDbsm;
        const double err_m = det->range_m - range_m;
        const std::string id = "radar.chain.calibration." + id_slug(label) + "." +
                               std::string(to_string(params.window)) + "." +
                               std::string(to_string(direction)) + ".R" + id_number(nominal_m) +
                               "m.offset" + id_number(0.05 * j);
        const std::string conditions =
            std::string(label) + ", " + std::string(to_string(params.window)) + " window, " +
            std::string(to_string(direction)) + "-chirp, noise off, range " + id_number(range_m) +
            " m (" + id_number(0.05 * j) + " bin past a bin centre)";
        validate_set_rcs(id, conditions, kRcsDbsm, det->rcs_dbsm, kRcsTolDb);
        validate_set_range(id, conditions, range_m, det->range_m, kRangeTolM);
        worst_db = std::max(worst_db, std::abs(err_db));
        worst_m = std::max(worst_m, std::abs(err_m));
        ++count;
      }
    }
    std::printf(
        "[ measured ] calibration %s %s %s-chirp: %d points 3-60 m x 20 sub-bin offsets, worst "
        "|RCS "
        "error| %.2e dB, worst |range error| %.2e m\n",
        label, std::string(to_string(params.window)).c_str(),
        std::string(to_string(direction)).c_str(), count, worst_db, worst_m);
  }
}

TEST_P(PointTargetCalibration, PaperRadarReadsBackRcsAndRange) {
  RadarParams p;
  p.window = GetParam();
  p.chirps_per_frame = 8;
  check_calibration(p, "paper radar (8 chirps)", {SweepDirection::up, SweepDirection::down});
}

TEST_P(PointTargetCalibration, ChangedPowerGainsAndWavelengthReadBackRcsAndRange) {
  RadarParams p = changed_radar(GetParam());
  p.chirps_per_frame = 8;
  check_calibration(p, "Pt 3 dBm, Gt 21 dBi, Gr 14 dBi, 79 GHz", {SweepDirection::up});
}

INSTANTIATE_TEST_SUITE_P(AllWindows, PointTargetCalibration, ::testing::ValuesIn(kAllWindows),
                         window_name);

// The full paper frame (64 x 512, Hann) at the example's 25 m and a half-bin offset: the RCS
// within 0.2 dB, the range within 2 cm, and the SNR equal to the radar-equation prediction
// P_r (N CG_r N_c CG_d)^2 / (k T0 F fs sum w_r^2 sum w_d^2) within 0.01 dB (noise-free SNR is
// defined against the chain's thermal noise per cell).
TEST(PointTargetCalibration, FullPaperFrameAndSnr) {
  const RadarParams p = noise_free(RadarParams{});
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const double range_m =
      (std::round(25.0 / reference_range_bin_m(p)) + 0.5) * reference_range_bin_m(p);
  Scene scene = point_target_scene(10.0);
  scene.centres[0].range_offset_m = range_m - chamber.target_range_m();
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement m;
  RandomStream rng(1);
  chain.measure(scene, chamber, no_fog, rng, ws, m);
  const Detection* det = strongest(m.detections);
  ASSERT_NE(det, nullptr);
  const auto w_r = make_window(p.window, p.samples_per_chirp);
  const auto w_d = make_window(p.window, p.chirps_per_frame);
  const double expected_snr_db =
      10.0 * std::log10(reference_received_power_w(p, 10.0, range_m) *
                        std::pow(sum_of(w_r) * sum_of(w_d), 2) /
                        (reference_noise_power_w(p) * sum_of_squares(w_r) * sum_of_squares(w_d)));
  std::printf(
      "[ measured ] paper frame 10 dBsm at %.4f m: RCS %.5f dBsm, range %.5f m, SNR %.3f dB "
      "(expected %.3f dB)\n",
      range_m, det->rcs_dbsm, det->range_m, det->snr_db, expected_snr_db);
  const std::string conditions = "paper frame 64 x 512, Hann, noise off, 10 dBsm at " +
                                 id_number(range_m) + " m (half-bin offset)";
  validate_set_rcs("radar.chain.full_paper_frame", conditions, 10.0, det->rcs_dbsm, 0.2);
  validate_set_range("radar.chain.full_paper_frame", conditions, range_m, det->range_m, 0.02);
  fogradar::testing::validate(
      {.id = "radar.chain.full_paper_frame.snr",
       .group = "radar: SNR",
       .quantity = "SNR of the detection",
       .unit = "dB",
       .conditions = conditions,
       .reference = expected_snr_db,
       .source = "radar equation P_r (N CG_r N_c CG_d)^2 / (k T0 F fs sum w_r^2 sum w_d^2) "
                 "(Skolnik eq. 2.1, this test)",
       .value = det->snr_db,
       .tolerance = 0.01,
       .kind = Tolerance::absolute});
  fogradar::testing::validate({.id = "radar.chain.full_paper_frame.velocity",
                               .group = "radar: Doppler",
                               .quantity = "radial velocity read back",
                               .unit = "m/s",
                               .conditions = conditions,
                               .reference = 0.0,
                               .source = "the set (static) target",
                               .value = det->radial_velocity_m_per_s,
                               .tolerance = 1e-9,
                               .kind = Tolerance::absolute});
  // The chamber target is at 10 m, so the 25 m target is not associated (gate 0.5 m).
  EXPECT_FALSE(m.target.has_value());
}

// The DTFT interpolation of estimate_detections: sum_m X[m] K(nu - m) equals the direct DTFT
// sum_n x[n] exp(-i 2 pi nu n / N) of the time signal [OS sec. 8.4], within 1e-9 relative.
TEST(Estimation, DirichletKernelInterpolatesTheDftToTheDtft) {
  for (const std::size_t n : {std::size_t{16}, std::size_t{64}, std::size_t{512}}) {
    std::vector<std::complex<double>> x(n), spectrum(n), kernel(n);
    RandomStream rng(5, n);
    for (auto& v : x) v = rng.complex_normal(1.0);
    FftPlan plan(n, FftDirection::forward, {.alignment = FftAlignment::unaligned});
    plan.execute(x, spectrum);
    for (const double nu : {0.0, 0.3, 2.5, 7.77, static_cast<double>(n) - 0.4}) {
      dirichlet_kernel(nu, n, kernel);
      std::complex<double> interpolated{}, direct{};
      for (std::size_t k = 0; k < n; ++k) interpolated += spectrum[k] * kernel[k];
      for (std::size_t j = 0; j < n; ++j) {
        direct += x[j] * std::polar(1.0, -2.0 * std::numbers::pi * nu * static_cast<double>(j) /
                                             static_cast<double>(n));
      }
      fogradar::testing::validate(
          {.id = "radar.chain.dirichlet_kernel.N" + std::to_string(n) + ".nu" + id_number(nu),
           .group = "radar: signal processing",
           .quantity = "|sum_m X[m] K(nu - m) - DTFT(nu)|",
           .unit = "1",
           .conditions =
               "N = " + std::to_string(n) + ", nu = " + id_number(nu) + ", complex Gaussian signal",
           .reference = 1e-9 * std::abs(direct) + 1e-12,
           .source = "direct DTFT sum of the time signal [OS sec. 8.4] (bound 1e-9 |DTFT| + 1e-12)",
           .value = std::abs(interpolated - direct),
           .tolerance = 0.0,
           .kind = Tolerance::at_most});
    }
  }
}

// The order in which rows_times_interleaved_kernels forms its sums (estimation.cpp), one double at
// a time: per stripe of 2048 / objects / 16 * 16 doubles, per row and kernel, the products of value
// i into partial sum (i - begin) / 4 % groups, lane i % 4 (groups 4 for one kernel, else 2; steps
// of 4 past the last whole group into sum 0), the sums added lane-wise in group order, the lanes
// paired as (0 + 2, 1 + 3), an odd last complex value added after them, the row's sum then added to
// the stripes before it. Every instruction-set version must form exactly these sums: the same bits.
std::vector<std::complex<double>> rows_times_kernels_in_order(const std::vector<double>& map,
                                                              std::size_t rows, std::size_t columns,
                                                              const std::vector<double>& k_re,
                                                              const std::vector<double>& k_im,
                                                              std::size_t objects) {
  const std::size_t values = 2 * columns, stripe = 2048 / objects / 16 * 16,
                    groups = objects == 1 ? 4 : 2;
  std::vector<std::complex<double>> out(objects * rows);
  for (std::size_t begin = 0; begin < values; begin += stripe) {
    const std::size_t end = std::min(values, begin + stripe);
    for (std::size_t r = 0; r < rows; ++r) {
      const double* x = map.data() + r * values;
      for (std::size_t o = 0; o < objects; ++o) {
        const double* kr = k_re.data() + o * values;
        const double* ki = k_im.data() + o * values;
        double by_re[4][4] = {}, by_im[4][4] = {};  // [partial sum][lane]
        std::size_t i = begin;
        for (; i + 4 * groups <= end; i += 4 * groups) {
          for (std::size_t g = 0; g < groups; ++g) {
            for (std::size_t l = 0; l < 4; ++l) {
              by_re[g][l] += x[i + 4 * g + l] * kr[i + 4 * g + l];
              by_im[g][l] += x[i + 4 * g + l] * ki[i + 4 * g + l];
            }
          }
        }
        for (; i + 4 <= end; i += 4) {
          for (std::size_t l = 0; l < 4; ++l) {
            by_re[0][l] += x[i + l] * kr[i + l];
            by_im[0][l] += x[i + l] * ki[i + l];
          }
        }
        double all_re[4], all_im[4];
        for (std::size_t l = 0; l < 4; ++l) {
          all_re[l] = by_re[0][l];
          all_im[l] = by_im[0][l];
          for (std::size_t g = 1; g < groups; ++g) {
            all_re[l] += by_re[g][l];
            all_im[l] += by_im[g][l];
          }
        }
        double re = (all_re[0] + all_re[2]) - (all_im[1] + all_im[3]);
        double im = (all_re[1] + all_re[3]) + (all_im[0] + all_im[2]);
        if (i < end) {
          re += x[i] * kr[i] - x[i + 1] * ki[i];
          im += x[i] * ki[i] + x[i + 1] * kr[i];
        }
        std::complex<double> row_sum{};
        row_sum += std::complex<double>(re, im);
        out[o * rows + r] += row_sum;
      }
    }
  }
  return out;
}

// rows_times_interleaved_kernels against the order above (reference; tolerance: identical bits) and
// against the plain complex sum sum_m X_r[m] K_o[m] (within 1e-13 of sum_m |X_r[m]| |K_o[m]|: a
// few hundred roundings of at most 2^-53 each), on random maps: 1 to 4 kernels, column counts odd
// and even, below one vector step and over one stripe (1031 and 2049 columns for one kernel, over
// 1024, 512, 336 and 256 columns for 1 to 4 kernels), 1 to 9 rows. On an AVX-512 machine this
// checks the eight-lane body; the baseline build (scripts/test.sh --baseline) checks the others.
TEST(Estimation, RowsTimesKernelsFormsItsSumsInTheDocumentedOrder) {
  RandomStream rng(17);
  for (const std::size_t objects : {1u, 2u, 3u, 4u}) {
    for (const std::size_t columns : {1u, 3u, 8u, 13u, 64u, 255u, 257u, 337u, 513u, 1031u, 2049u}) {
      for (const std::size_t rows : {1u, 2u, 9u}) {
        const std::size_t values = 2 * columns;
        std::vector<double> map(rows * values), k_re(objects * values), k_im(objects * values);
        for (double& v : map) v = rng.complex_normal(1.0).real();
        for (std::size_t j = 0; j < objects * columns; ++j) {
          const std::complex<double> k = rng.complex_normal(1.0);
          k_re[2 * j] = k_re[2 * j + 1] = k.real();
          k_im[2 * j] = k_im[2 * j + 1] = k.imag();
        }
        std::vector<std::complex<double>> out(objects * rows);
        rows_times_interleaved_kernels(map.data(), rows, columns, k_re.data(), k_im.data(), objects,
                                       out.data());
        const auto expected = rows_times_kernels_in_order(map, rows, columns, k_re, k_im, objects);
        EXPECT_EQ(std::memcmp(out.data(), expected.data(), out.size() * sizeof out[0]), 0)
            << objects << " kernels, " << columns << " columns, " << rows << " rows";
        for (std::size_t o = 0; o < objects; ++o) {
          for (std::size_t r = 0; r < rows; ++r) {
            std::complex<double> sum{};
            double scale = 0.0;
            for (std::size_t m = 0; m < columns; ++m) {
              const std::complex<double> x(map[r * values + 2 * m], map[r * values + 2 * m + 1]);
              const std::complex<double> k(k_re[o * values + 2 * m], k_im[o * values + 2 * m]);
              sum += x * k;
              scale += std::abs(x) * std::abs(k);
            }
            fogradar::testing::validate(
                {.id = "radar.chain.rows_times_kernels." + std::to_string(objects) + "_kernels." +
                       std::to_string(columns) + "_columns." + std::to_string(rows) +
                       "_rows.kernel" + std::to_string(o) + ".row" + std::to_string(r),
                 .group = "radar: signal processing",
                 .quantity = "|row x kernel - plain complex sum|",
                 .unit = "1",
                 .conditions = std::to_string(objects) + " kernels, " + std::to_string(columns) +
                               " columns, " + std::to_string(rows) + " rows, kernel " +
                               std::to_string(o) + ", row " + std::to_string(r),
                 .reference = 1e-13 * scale,
                 .source = "plain complex sum sum_m X_r[m] K_o[m] (bound 1e-13 sum |X| |K|)",
                 .value = std::abs(out[o * rows + r] - sum),
                 .tolerance = 0.0,
                 .kind = Tolerance::at_most});
          }
        }
      }
    }
  }
}

// The CFAR of estimate_detections runs four Doppler rows at a time and the last rows % 4 one by
// one: every row must be searched, its detections in its own row. Reference: the construction.
// Isolated cells of power 1 on a zero map, at least 30 cells apart within a row (beyond every
// cell's reference cells, g + 2n = 18 away, and the edge cells' 2g + 3n - 1 = 29), never 8-adjacent
// across rows (Doppler wraps): each such cell has a zero threshold and is detected, as its own
// one-cell object, and no zero cell is. 3, 4, 7 and 8 rows: only the last rows, only batches, and
// both; CA (the sums) and OS (one row at a time inside a batch); cells at the first and last range
// cell.
TEST(Estimation, EveryDopplerRowIsSearchedInBatchesOfFourAndTheRest) {
  for (const CfarKind kind : {CfarKind::ca, CfarKind::os}) {
    for (const std::size_t rows : {3u, 4u, 7u, 8u}) {
      RadarParams p;
      p.samples_per_chirp = 99;
      p.chirps_per_frame = rows;
      p.cfar.kind = kind;
      const RangeDopplerProcessor processor(p);
      const CfarDetector cfar(p.cfar);
      const RadarDerived derived = derive(p);
      const std::size_t columns = p.samples_per_chirp;
      ComplexVector map(rows * columns);
      std::set<std::pair<std::size_t, std::size_t>> placed;  // (Doppler cell, range cell)
      for (std::size_t d = 0; d < rows; ++d) {
        const bool odd_last = rows % 2 == 1 && d == rows - 1;  // next to row 0 across the wrap
        const std::vector<std::size_t> cells = odd_last     ? std::vector<std::size_t>{45}
                                               : d % 2 == 0 ? std::vector<std::size_t>{0, 60}
                                                            : std::vector<std::size_t>{30, 98};
        for (const std::size_t k : cells) {
          map[d * columns + k] = {0.6, -0.8};
          placed.insert({d, k});
        }
      }
      EstimationWorkspace ws;
      std::vector<Detection> detections;
      estimate_detections(map, processor, cfar, p, derived, ws, detections);
      std::set<std::pair<std::size_t, std::size_t>> found;
      for (const Detection& det : detections) {
        EXPECT_EQ(det.cells, 1u) << to_string(kind) << ", " << rows << " rows";
        found.insert({det.doppler_cell, det.range_cell});
      }
      EXPECT_EQ(found, placed) << to_string(kind) << ", " << rows << " rows";
      EXPECT_EQ(detections.size(), placed.size()) << to_string(kind) << ", " << rows << " rows";
    }
  }
}

// The peak power estimate_detections reports is |X(nu, mu)|^2 at the (range, Doppler) bin it
// reports, X the 2-D DTFT of the windowed frame: checked against that DTFT summed directly over
// the time samples in long double [OS sec. 8.4], within 1e-9 relative. One to six tones on white
// noise (each its own object), an odd column count (499) and 16 chirps: the row interpolation
// runs in batches of 1, 2, 3 and 4 objects, with its column stripes ending inside a row and the
// odd last column, and the Doppler search on the interpolated rows.
TEST(Estimation, PeakPowerIsTheDirectTwoDimensionalDtftForEveryBatchSize) {
  RadarParams p;
  p.samples_per_chirp = 499;
  p.chirps_per_frame = 16;
  const RangeDopplerProcessor processor(p);
  const CfarDetector cfar(p.cfar);
  const RadarDerived derived = derive(p);
  const std::size_t rows = p.chirps_per_frame, columns = p.samples_per_chirp;
  const double gain = processor.coherent_amplitude_gain();
  using Wide = std::complex<long double>;
  const long double two_pi = 2.0L * std::numbers::pi_v<long double>;
  double worst = 0.0;
  for (std::size_t tones = 1; tones <= 6; ++tones) {
    std::size_t index = 0;
    ComplexVector frame(rows * columns), map(frame.size());
    RandomStream rng(11, tones);
    for (auto& v : frame) v = rng.complex_normal(1.0);
    for (std::size_t i = 0; i < tones; ++i) {
      const double nu = 30.3 + 70.7 * static_cast<double>(i),
                   mu = 1.3 + 2.6 * static_cast<double>(i);
      for (std::size_t c = 0; c < rows; ++c) {
        for (std::size_t n = 0; n < columns; ++n) {
          frame[c * columns + n] +=
              std::polar(1.0, 2.0 * std::numbers::pi *
                                  (nu * static_cast<double>(n) / static_cast<double>(columns) +
                                   mu * static_cast<double>(c) / static_cast<double>(rows)));
        }
      }
    }
    std::copy(frame.begin(), frame.end(), map.begin());
    processor.transform(map);
    EstimationWorkspace ws;
    std::vector<Detection> detections;
    estimate_detections(map, processor, cfar, p, derived, ws, detections);
    ASSERT_GE(detections.size(), tones) << tones << " tones";
    for (const Detection& det : detections) {
      Wide direct{};
      for (std::size_t c = 0; c < rows; ++c) {
        for (std::size_t n = 0; n < columns; ++n) {
          const long double phase =
              -two_pi * (static_cast<long double>(det.range_bin) * n / columns +
                         static_cast<long double>(det.doppler_bin) * c / rows);
          const long double w =
              static_cast<long double>(processor.doppler_window()[c]) * processor.range_window()[n];
          direct += w * Wide(frame[c * columns + n]) * std::polar(1.0L, phase);
        }
      }
      const double expected = static_cast<double>(std::norm(direct));
      const double reported = det.received_power_w * gain * gain;
      worst = std::max(worst, std::abs(reported - expected) / expected);
      fogradar::testing::validate(
          {.id = "radar.chain.peak_power." + std::to_string(tones) + "_tones.detection" +
                 std::to_string(index++),
           .group = "radar: signal processing",
           .quantity = "peak power |X(nu, mu)|^2 of the detection",
           .unit = "1",
           .conditions = std::to_string(tones) + " tones on white noise, 499 x 16, range bin " +
                         id_number(det.range_bin) + ", Doppler bin " + id_number(det.doppler_bin),
           .reference = expected,
           .source = "direct 2-D DTFT of the windowed frame in long double [OS sec. 8.4]",
           .value = reported,
           .tolerance = 1e-9,
           .kind = Tolerance::relative});
    }
  }
  std::printf(
      "[ measured ] peak power vs direct 2-D DTFT, 1-6 objects, 499 x 16: worst relative error "
      "%.1e\n",
      worst);
}

// --- Fog --------------------------------------------------------------------------------------

// An artificially lossy fog (LWC 50 g/m^3, the default 1 um droplets) in the paper chamber, target
// 10 dBsm at 10 m, noise off: with k of the 4 layers on, the RCS estimate drops by the channel's
// two-way attenuation 2 sum a_i * 1 m within 0.1 dB, and by the virtual layer model's eq. 4
// (object_intensity with one virtual layer per metre, tau = exp(-alpha_ext * 1 m)) within 0.1 dB.
TEST(Fog, LossyFogLowersRcsByTwoWayAttenuation) {
  const RadarParams p = noise_free(RadarParams{});
  const RadarChain chain(p);
  propagation::FogSpec fog;
  fog.density = propagation::LiquidWaterContent{50.0};
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(fog), p.centre_frequency_hz);
  const Scene scene = point_target_scene(10.0);
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement m;
  double clear_dbsm = 0.0;
  for (std::size_t layers = 0; layers <= chamber.layer_count(); ++layers) {
    const auto active = propagation::first_layers_active(layers, chamber.layer_count());
    RandomStream rng(9, layers);
    chain.measure(scene, chamber, active, rng, ws, m);
    ASSERT_TRUE(m.target.has_value()) << layers << " layers";
    if (layers == 0) clear_dbsm = m.target->rcs_dbsm;
    const double drop_db = clear_dbsm - m.target->rcs_dbsm;
    // Independent of the chamber: 2 x (specific attenuation) x (1 m per active layer).
    const double path_db = 2.0 * chamber.layer(0).optics.specific_attenuation_db_per_km * 1e-3 *
                           static_cast<double>(layers);
    const propagation::VirtualLayer layer = propagation::virtual_layer_from_fog(
        chamber.layer(0).optics.extinction_per_m,
        chamber.layer(0).optics.volume_backscatter_m2_per_m3, 1.0);
    const double eq4_db = -10.0 * std::log10(propagation::object_intensity(
                                      static_cast<unsigned>(layers), layer.transmittance, 1.0));
    std::printf(
        "[ measured ] lossy fog (50 g/m^3) %zu layers: RCS drop %.4f dB, 2 a L = %.4f dB (error "
        "%.1e dB), "
        "eq. 4 = %.4f dB (error %.1e dB)\n",
        layers, drop_db, path_db, drop_db - path_db, eq4_db, drop_db - eq4_db);
    fogradar::testing::validate(
        {.id = "radar.chain.lossy_fog.rcs_drop." + std::to_string(layers) + "_layers",
         .group = "radar: RCS",
         .quantity = "RCS drop against the clear chamber",
         .unit = "dB",
         .conditions = "LWC 50 g/m^3, 1 um droplets, " + std::to_string(layers) +
                       " of 4 one-metre layers on, 10 dBsm at 10 m, noise off",
         .reference = path_db,
         .source = "two-way attenuation 2 x specific attenuation x 1 m per active layer",
         .value = drop_db,
         .tolerance = 0.1,
         .kind = Tolerance::absolute});
    EXPECT_NEAR(drop_db, eq4_db, 0.1);
    EXPECT_NEAR(drop_db, chamber.two_way_attenuation_db(10.0, active), 0.1);
  }
  EXPECT_GT(2.0 * chamber.layer(0).optics.specific_attenuation_db_per_km * 4e-3,
            0.3);  // a visible effect
}

// --- Water-covered sensor and target -----------------------------------------------------------

// Airy's single film at normal incidence, written out here (Born & Wolf sec. 7.6.1; Orfanidis,
// Electromagnetic Waves and Antennas, sec. 5.4), exp(-i omega t): r01 = (1 - m)/(1 + m),
// delta = 2 pi m t / lambda. In air the power transmittance is |t01 t10 e^{i delta} / (1 + r01 r10
// e^{2 i delta})|^2; on a perfect conductor (r12 = -1) the reflectance is
// |(r01 - e^{2 i delta}) / (1 - r01 e^{2 i delta})|^2.
struct Airy {
  std::complex<double> m;
  double wavelength_m;
  std::complex<double> phase(double t_m) const {
    return std::complex<double>{0.0, 2.0 * std::numbers::pi / wavelength_m} * m * t_m;
  }
  double in_air_transmittance(double t_m) const {
    const std::complex<double> r01 = (1.0 - m) / (1.0 + m);
    const std::complex<double> t01 = 2.0 / (1.0 + m), t10 = 2.0 * m / (1.0 + m);
    return std::norm(t01 * t10 * std::exp(phase(t_m)) /
                     (1.0 - r01 * r01 * std::exp(2.0 * phase(t_m))));
  }
  double on_conductor_reflectance(double t_m) const {
    const std::complex<double> r01 = (1.0 - m) / (1.0 + m);
    const std::complex<double> e = std::exp(2.0 * phase(t_m));
    return std::norm((r01 - e) / (1.0 - r01 * e));
  }
};

// The radar made through its kind (configure, make) and the report of a run begun on it, before any
// measurement: the chain, scene, chamber and film losses the sensor was made with.
std::shared_ptr<const RadarReport> made_radar(const SensorParams& params,
                                              const sensor::Context& context) {
  const std::shared_ptr<const sensor::Sensor> made =
      sensor_kind()
          ->configure(sensor::ParamsOf<SensorParams>(params), context)
          ->make(test::segelstein_table(), StopToken());
  return std::dynamic_pointer_cast<const RadarReport>(
      std::shared_ptr<const sensor::SensorSummary>(made->begin_run()->summarize()));
}

// The study's water-covered sensor and target through the scenario's keys (the radar's kind): a
// point target of 10 dBsm at 10 m in the paper chamber, no fog switched on, thermal noise on. The
// films take the fog's water index at 77 GHz (Liebe, 20 C). The made radar's losses equal Airy's
// closed forms to 1e-9 dB (film only, no radome), and the median RCS of 20 measurements drops by
// the sum of the losses within 0.02 dB: the wet and dry frames share their streams and differ by
// the noise's effect alone, a power estimate at detection SNR rho scattering by sqrt(2 / rho)
// relative (0.011 dB at the 55 dB the test requires), the median of 20 frames by about 0.003 dB.
TEST(WaterFilm, RcsDropsByTheFilmsPredictedTwoWayLoss) {
  sensor::Context context;
  context.chamber = paper_chamber_spec();
  context.steps = 1;
  SensorParams dry;
  dry.measurements_per_step = 20;
  dry.radar.chirps_per_frame = 16;
  dry.target.model = TargetModel::point;
  context.room.floor.present = false;
  context.target.micro_motion_std_m = 0.0;
  dry.target.height_m = dry.target.sensor_height_m;
  struct Case {
    const char* name;
    double radome_m, radome_film_m, target_film_m;
  };
  const Case cases[] = {{"radome_film_only", 0.0, 0.1e-3, 0.0},
                        {"target_film_only", 0.0, 0.0, 0.2e-3},
                        {"half_wave_radome_and_both_films", 1.1432e-3, 0.1e-3, 0.1e-3}};
  const auto median_rcs_dbsm = [&](const RadarReport& sensor, double* snr_db) {
    const propagation::ActiveLayers none = context.active(0);
    MeasurementWorkspace ws = sensor.chain().make_workspace();
    Measurement m;
    std::vector<double> rcs;
    for (std::size_t i = 0; i < dry.measurements_per_step; ++i) {
      RandomStream rng(context.seed, 0, i);
      sensor.chain().measure(sensor.scene(), sensor.chamber(), none, rng, ws, m);
      EXPECT_TRUE(m.target.has_value());
      if (!m.target) continue;
      rcs.push_back(m.target->rcs_dbsm);
      *snr_db = std::min(*snr_db, m.target->snr_db);
    }
    std::sort(rcs.begin(), rcs.end());
    return 0.5 * (rcs[rcs.size() / 2 - 1] + rcs[rcs.size() / 2]);
  };
  double dry_snr_db = std::numeric_limits<double>::infinity();
  const std::shared_ptr<const RadarReport> dry_made = made_radar(dry, context);
  const RadarReport& dry_sensor = *dry_made;
  EXPECT_EQ(dry_sensor.radome_two_way_loss_db(), 0.0);
  EXPECT_EQ(dry_sensor.target_film_loss_db(), 0.0);
  const double dry_dbsm = median_rcs_dbsm(dry_sensor, &dry_snr_db);
  const Airy water{dry_sensor.chamber().layer(0).optics.refractive_index,
                   299'792'458.0 / dry.radar.centre_frequency_hz};
  for (const Case& c : cases) {
    SensorParams wet = dry;
    wet.radar.radome.thickness_m = c.radome_m;
    wet.radar.radome.water_film_m = c.radome_film_m;
    sensor::Context wet_context = context;
    wet_context.target.water_film_m = c.target_film_m;
    const std::shared_ptr<const RadarReport> made = made_radar(wet, wet_context);
    const RadarReport& sensor = *made;
    const double loss_db = sensor.radome_two_way_loss_db() + sensor.target_film_loss_db();
    if (c.radome_m == 0.0) {
      EXPECT_NEAR(sensor.radome_two_way_loss_db(),
                  -20.0 * std::log10(water.in_air_transmittance(c.radome_film_m)), 1e-9);
      EXPECT_NEAR(sensor.target_film_loss_db(),
                  -10.0 * std::log10(water.on_conductor_reflectance(c.target_film_m)), 1e-9);
    }
    // Without a radome the reference is Airy's, written out above; with one, the two-layer stack
    // is the transfer matrix's, itself checked against closed forms in tests/propagation.
    const bool airy = c.radome_m == 0.0;
    const double reference_db =
        airy ? -20.0 * std::log10(water.in_air_transmittance(c.radome_film_m)) -
                   10.0 * std::log10(water.on_conductor_reflectance(c.target_film_m))
             : loss_db;
    double wet_snr_db = std::numeric_limits<double>::infinity();
    const double drop_db = dry_dbsm - median_rcs_dbsm(sensor, &wet_snr_db);
    ASSERT_GT(wet_snr_db, 55.0) << c.name;
    std::printf(
        "[ measured ] water films, %s: radome %.4f dB + target film %.4f dB; median RCS drop %.4f "
        "dB (wet SNR %.1f dB)\n",
        c.name, sensor.radome_two_way_loss_db(), sensor.target_film_loss_db(), drop_db, wet_snr_db);
    fogradar::testing::validate(
        {.id = std::string("radar.chain.water_film.rcs_drop.") + c.name,
         .group = "radar: RCS",
         .quantity = "median RCS drop against the dry radar",
         .unit = "dB",
         .conditions = std::string(c.name) + ": radome " + std::to_string(c.radome_m * 1e3) +
                       " mm (eps_r 2.9, tan d 0.01), its film " +
                       std::to_string(c.radome_film_m * 1e3) + " mm, target film " +
                       std::to_string(c.target_film_m * 1e3) +
                       " mm, 77 GHz, point target at 10 m, 20 frames, noise on",
         .reference = reference_db,
         .source = airy ? "Airy's single-film closed forms (Born & Wolf sec. 1.6.4; on a "
                          "conductor r12 = -1), written out in the test"
                        : "transfer-matrix two-way losses (propagation/water_film.hpp, against "
                          "Airy in tests/propagation)",
         .value = drop_db,
         .tolerance = 0.02,
         .kind = Tolerance::absolute});
  }
}

// The losses reach the run's summary: each step's JSON states them beside the fog's, and the
// table's loss column is their sum with the fog's, with a line that names them.
TEST(WaterFilm, LossesReachTheSummaryJsonAndTheLossColumn) {
  sensor::Context context;
  context.chamber = paper_chamber_spec();
  context.steps = 2;
  SensorParams wet;
  wet.measurements_per_step = 1;
  wet.radar.radome.water_film_m = 0.1e-3;
  context.target.water_film_m = 0.1e-3;
  const std::shared_ptr<const RadarReport> report = made_radar(wet, context);
  const RadarReport* sensor = report.get();
  const nlohmann::json json = report->json();
  for (std::size_t k = 0; k < context.steps; ++k) {
    const nlohmann::json& step = json["steps"][k];
    EXPECT_EQ(step["radome_two_way_loss_db"].get<double>(), sensor->radome_two_way_loss_db());
    EXPECT_EQ(step["target_film_loss_db"].get<double>(), sensor->target_film_loss_db());
  }
  const RadarSummary& summary = report->summary();
  const double total_db = summary.steps[1].two_way_attenuation_db +
                          sensor->radome_two_way_loss_db() + sensor->target_film_loss_db();
  char cell[32];
  std::snprintf(cell, sizeof cell, " %8.4f\n", total_db);
  const std::string table = report->table();
  EXPECT_NE(table.find(cell), std::string::npos) << table;
  EXPECT_NE(table.find("of the radome with its water film"), std::string::npos) << table;
  // Dry: no such line.
  sensor::Context dry_context = context;
  dry_context.target.water_film_m = 0.0;
  EXPECT_EQ(made_radar(SensorParams{}, dry_context)->table().find("water film"), std::string::npos);
}

// Fog volume clutter. Derivation of the expected processed cell power (docs/radar.md, "Fog
// clutter"): the fog in [r, r + dr] returns the mean power
//   dP = eta Omega r^2 dr * P_t G_t G_r lambda^2 / ((4 pi)^3 r^4) * T(r)
// (Omega: two-way equivalent beam solid angle, T: two-way transmittance). A scatterer at
// fractional range bin nu contributes |H(nu - k)|^2 / |H(0)|^2 of its power to the point-target
// calibrated cell k (H the DTFT of the range window; the clutter is static, so the Doppler window
// passes it at its coherent gain, exactly removed by the calibration). With dP / dnu ~ constant
// over the window's response, E[cell] = (dP/dnu) * integral |H(u)|^2 du / |H(0)|^2 =
// (dP/dnu) * N sum w^2 / (sum w)^2 = ENBW * eta V P_t G_t G_r lambda^2 / ((4 pi)^3 R^4) * T(R)
// with V = Omega R^2 dR_bin. Test: a strongly backscattering fog (LWC 100 g/m^3, 100 um
// droplets), all four layers on, no target, noise off, 400 frames (4 chirps x 512 samples, paper
// range bin): the mean calibrated power of Doppler bin 0, averaged over the cells at least 3 bins
// inside the fog, over that expected value: within 10 % (statistical 1-sigma ~ 1 %); without
// the ENBW factor it would be off by 1.5 (Hann) and 2.0 (Blackman-Harris).
class FogClutter : public ::testing::TestWithParam<WindowType> {};

TEST_P(FogClutter, MeanCellPowerIsEnbwTimesVolumeRadarEquation) {
  RadarParams p = noise_free(RadarParams{});
  p.window = GetParam();
  p.chirps_per_frame = 4;
  const RadarChain chain(p);
  propagation::FogSpec fog;
  fog.density = propagation::LiquidWaterContent{100.0};
  fog.droplets = propagation::Monodisperse{100e-6};
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(fog), p.centre_frequency_hz);
  const auto all_on =
      propagation::first_layers_active(chamber.layer_count(), chamber.layer_count());
  Scene scene = point_target_scene(10.0);
  scene.centres[0].rcs_m2 = 0.0;  // clutter only
  const std::size_t cols = p.samples_per_chirp;
  const double bin_m = reference_range_bin_m(p);
  const auto w = make_window(p.window, cols);
  const double enbw = static_cast<double>(cols) * sum_of_squares(w) / (sum_of(w) * sum_of(w));
  const double gain = sum_of(w) * sum_of(make_window(p.window, p.chirps_per_frame));
  const double eta = chamber.layer(0).optics.volume_backscatter_m2_per_m3;
  const double omega = std::numbers::pi *
                       std::pow(p.azimuth_beamwidth_deg * std::numbers::pi / 180.0, 2) /
                       (8.0 * std::log(2.0));  // Probert-Jones, 10 deg x 10 deg
  const double fog_start_m = chamber.layer(0).start_m,
               fog_end_m = chamber.layer(chamber.layer_count() - 1).end_m;

  std::vector<std::size_t> cells;
  for (std::size_t k = 0; k < cols; ++k) {
    const double r = static_cast<double>(k) * bin_m;
    if (r >= fog_start_m + 3.0 * bin_m && r <= fog_end_m - 3.0 * bin_m) cells.push_back(k);
  }
  MeasurementWorkspace ws = chain.make_workspace();
  constexpr int kFrames = 400;
  double ratio_sum = 0.0;
  for (int f = 0; f < kFrames; ++f) {
    RandomStream rng(31, static_cast<std::uint64_t>(f));
    chain.synthesize_and_process(scene, chamber, all_on, rng, ws);
    for (const std::size_t k : cells) {
      const double r = static_cast<double>(k) * bin_m;
      const double one_way_db =
          1e-3 * chamber.layer(0).optics.specific_attenuation_db_per_km * (r - fog_start_m);
      const double expected_w = enbw *
                                reference_received_power_w(p, eta * omega * r * r * bin_m, r) *
                                std::pow(10.0, -2.0 * one_way_db / 10.0);
      ratio_sum += ws.power[k] / (gain * gain) / expected_w;  // Doppler bin 0 is row 0
    }
  }
  const double ratio = ratio_sum / static_cast<double>(kFrames * cells.size());
  std::printf(
      "[ measured ] fog clutter %s (eta %.3e m^-1, ENBW %.3f): mean cell / (ENBW eta V radar eq.) "
      "= %.4f "
      "over %zu cells x %d frames\n",
      std::string(to_string(p.window)).c_str(), eta, enbw, ratio, cells.size(), kFrames);
  fogradar::testing::validate(
      {.id = "radar.chain.fog_clutter." + std::string(to_string(p.window)) + ".mean_cell_power",
       .group = "radar: SNR",
       .quantity = "mean clutter cell power / (ENBW eta V radar equation T)",
       .unit = "1",
       .conditions = "LWC 100 g/m^3, 100 um droplets, four layers, " +
                     std::string(to_string(p.window)) + " window, 4 x 512, 400 frames",
       .reference = 1.0,
       .source = "ENBW x volume radar equation (Skolnik eq. 2.1, Probert-Jones Omega, "
                 "docs/radar.md)",
       .value = ratio,
       .tolerance = 0.10,
       .kind = Tolerance::relative});
}

INSTANTIATE_TEST_SUITE_P(Windows, FogClutter,
                         ::testing::Values(WindowType::rectangular, WindowType::hann,
                                           WindowType::blackman_harris),
                         window_name);

// --- Target fluctuation and motion ------------------------------------------------------------

// Swerling 1 [Sk sec. 2.8]: the RCS is exponential from frame to frame. Noise off, 600 frames
// (4 x 128 samples: the property does not depend on size): the measured RCS (m^2) over the set
// mean is unit exponential by a chi-square GoF (10 equiprobable cells, df 9, significance 1e-3),
// and the sample mean lies in the 99.9 % interval of Gamma(600, mean/600).
TEST(Fluctuation, SwerlingOneMeasuredRcsIsExponentialWithTheSetMean) {
  RadarParams p = noise_free(RadarParams{});
  p.chirps_per_frame = 4;
  p.samples_per_chirp = 128;
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  Scene scene = point_target_scene(10.0);
  scene.centres[0].swerling = Swerling::one;
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement m;
  constexpr int kFrames = 600;
  std::vector<double> normalised;
  double sum = 0.0;
  for (int f = 0; f < kFrames; ++f) {
    RandomStream rng(41, static_cast<std::uint64_t>(f));
    chain.measure(scene, chamber, no_fog, rng, ws, m);
    ASSERT_TRUE(m.target.has_value());
    normalised.push_back(m.target->rcs_m2 / 10.0);
    sum += m.target->rcs_m2;
  }
  const double mean = sum / kFrames;
  const boost::math::gamma_distribution<double> mean_dist(kFrames, 10.0 / kFrames);
  const double low = boost::math::quantile(mean_dist, 0.0005);
  const double high = boost::math::quantile(boost::math::complement(mean_dist, 0.0005));
  const double p_value = exponential_chi_square_p_value(normalised, 10);
  std::printf(
      "[ measured ] Swerling 1: mean RCS %.3f m^2 (set 10, accept [%.3f, %.3f]); chi-square p = "
      "%.3f\n",
      mean, low, high, p_value);
  const std::string conditions = "Swerling 1, set mean 10 m^2 at 10 m, noise off, 600 frames";
  fogradar::testing::validate({.id = "radar.chain.swerling1.mean_rcs",
                               .group = "radar: RCS",
                               .quantity = "mean measured RCS",
                               .unit = "m^2",
                               .conditions = conditions,
                               .reference = 10.0,
                               .source = "the set mean RCS [Sk sec. 2.8]",
                               .value = mean,
                               .tolerance = 0.0,
                               .kind = Tolerance::statistical,
                               .samples = kFrames,
                               .interval_low = low,
                               .interval_high = high,
                               .confidence = "99.9 % two-sided interval of Gamma(600, 10/600)"});
  fogradar::testing::validate({.id = "radar.chain.swerling1.exponential_gof_p_value",
                               .group = "radar: RCS",
                               .quantity = "chi-square goodness-of-fit p-value of RCS / set mean",
                               .unit = "1",
                               .conditions = conditions + ", 10 equiprobable cells, df 9",
                               .reference = 1e-3,
                               .source = "unit exponential (Swerling 1) [Sk sec. 2.8]",
                               .value = p_value,
                               .tolerance = 0.0,
                               .kind = Tolerance::at_least});
}

// A moving point target, noise off, paper frame (64 x 512), every window, up- and down-chirp: the
// velocity estimate within 0.01 velocity bin of the set value, the range corrected for
// range-Doppler coupling within 2 mm of the true range (the uncorrected beat-frequency range would
// be off by 2 v / lambda * c / (2 S), 1.6-4.9 cm here, with opposite signs for the two directions:
// asserted larger than 5 mm so the check has teeth), RCS within 0.2 dB. The Doppler bin is the
// echo phase step from chirp to chirp: the path grows by 2 v T_i, so the phase eps 2 pi f_c tau at
// the window centre (docs/radar.md §3.2) steps by eps 4 pi v T_i / lambda, lambda = c / f_c, i.e.
// bin eps 2 v N_c T_i / lambda; within 0.01 bin (lambda at a sweep end, f_c -+ B/2, would be off
// by 0.65 %: 0.13 bin at 12.3 m/s).
class Motion : public ::testing::TestWithParam<WindowType> {};

TEST_P(Motion, MovingTargetVelocityAndCouplingCorrectedRange) {
  for (const SweepDirection direction : {SweepDirection::up, SweepDirection::down}) {
    RadarParams p = noise_free(RadarParams{});
    p.window = GetParam();
    p.sweep_direction = direction;
    const double eps = direction == SweepDirection::up ? 1.0 : -1.0;
    const RadarChain chain(p);
    const RadarDerived& d = chain.derived();
    const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
    const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
    const double lambda_m = kC / p.centre_frequency_hz;
    const double v_bin =
        lambda_m / (2.0 * static_cast<double>(p.chirps_per_frame) * p.chirp_interval_s);
    const double slope = p.sweep_bandwidth_hz / p.chirp_duration_s;
    const std::string motion =
        std::string(to_string(p.window)) + "." + std::string(to_string(direction));
    const std::string frame = "paper frame 64 x 512, " + std::string(to_string(p.window)) + ", " +
                              std::string(to_string(direction)) + "-chirp, noise off";
    fogradar::testing::validate({.id = "radar.chain.motion." + motion + ".velocity_resolution",
                                 .group = "radar: Doppler",
                                 .quantity = "velocity resolution",
                                 .unit = "m/s",
                                 .conditions = frame,
                                 .reference = v_bin,
                                 .source = "lambda / (2 N_c T_i), lambda = c / f_c [Ri14]",
                                 .value = d.velocity_resolution_m_per_s,
                                 .tolerance = 1e-12,
                                 .kind = Tolerance::relative});
    MeasurementWorkspace ws = chain.make_workspace();
    Measurement m;
    for (const double v : {7.3, -4.1, 12.345}) {
      Scene scene = point_target_scene(10.0);
      scene.centres[0].radial_velocity_m_per_s = v;
      RandomStream rng(3);
      chain.measure(scene, chamber, no_fog, rng, ws, m);
      ASSERT_TRUE(m.target.has_value()) << v;
      const double coupling_m = 2.0 * std::abs(v) / lambda_m * kC / (2.0 * slope);
      const double expected_bin = eps * v / v_bin;
      std::printf(
          "[ measured ] moving target %s %s-chirp v = %+.3f m/s: v error %.2e bin, Doppler bin "
          "%+.4f "
          "(expected %+.4f), range error %.2e m (uncorrected coupling %.4f m), RCS error %.2e dB\n",
          std::string(to_string(p.window)).c_str(), std::string(to_string(direction)).c_str(), v,
          (m.target->radial_velocity_m_per_s - v) / v_bin, m.target->doppler_bin, expected_bin,
          m.target->range_m - 10.0, coupling_m, m.target->rcs_dbsm - 10.0);
      const std::string id = "radar.chain.motion." + motion + ".v" + id_number(v);
      const std::string conditions = frame + ", 10 dBsm at 10 m, v = " + id_number(v) + " m/s";
      fogradar::testing::validate(
          {.id = id + ".doppler_bin",
           .group = "radar: Doppler",
           .quantity = "Doppler bin of the target",
           .unit = "bins",
           .conditions = conditions,
           .reference = expected_bin,
           .source = "chirp-to-chirp echo phase step: bin eps 2 v N_c T_i / lambda (docs/radar.md "
                     "§3.2)",
           .value = m.target->doppler_bin,
           .tolerance = 0.01,
           .kind = Tolerance::absolute});
      validate_set_velocity(id, conditions, "m/s", v, m.target->radial_velocity_m_per_s,
                            0.01 * v_bin);
      fogradar::testing::validate({.id = id + ".range",
                                   .group = "radar: Doppler",
                                   .quantity = "range read back, corrected for range-Doppler "
                                               "coupling",
                                   .unit = "m",
                                   .conditions = conditions,
                                   .reference = 10.0,
                                   .source = "the set range",
                                   .value = m.target->range_m,
                                   .tolerance = 0.002,
                                   .kind = Tolerance::absolute});
      EXPECT_GT(coupling_m, 0.005);
      validate_set_rcs(id, conditions, 10.0, m.target->rcs_dbsm, 0.2);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllWindows, Motion, ::testing::ValuesIn(kAllWindows), window_name);

// The Newton polish of both peak searches (docs/radar.md §5): Brent's bracket alone leaves
// read-back errors of ~1e-8 (4.5e-8 dB, 1.4e-8 m, 2e-8 velocity bin with Brent to 2^-30 bin,
// docs/radar.md), since |X|^2 is flat to second order at its maximum; the Newton steps on
// dP/df = 0 from the time signal reach rounding level (the calibration and motion tests print
// <= 6.5e-13 dB, 1.5e-14 m, 4.5e-15 bin). A noise-free point target, paper frame (64 x 512,
// Hann), at three velocities (0 and two moving, so the Doppler search is off-bin) and four sub-bin
// range offsets: RCS within 1e-10 dB, range within 1e-11 m and velocity within 1e-10 bin of the set
// values, 100-1000 x below what Brent alone reaches, so a wrong or skipped Newton step fails.
TEST(Estimation, NewtonPolishReadsBackToRoundingLevel) {
  const RadarParams p = noise_free(RadarParams{});
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const double v_bin = chain.derived().velocity_resolution_m_per_s;
  const double bin_m = reference_range_bin_m(p);
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement m;
  double worst_db = 0.0, worst_m = 0.0, worst_bin = 0.0;
  for (const double v : {0.0, 7.3, -4.1}) {
    for (const double offset_bins : {0.05, 0.3, 0.55, 0.8}) {
      const double range_m = (std::round(12.0 / bin_m) + offset_bins) * bin_m;
      Scene scene = point_target_scene(10.0);
      scene.centres[0].range_offset_m = range_m - chamber.target_range_m();
      scene.centres[0].radial_velocity_m_per_s = v;
      RandomStream rng(5);
      chain.measure(scene, chamber, no_fog, rng, ws, m);
      const Detection* det = strongest(m.detections);
      ASSERT_NE(det, nullptr) << v << " m/s, offset " << offset_bins;
      const std::string id =
          "radar.chain.newton_polish.v" + id_number(v) + ".offset" + id_number(offset_bins);
      const std::string conditions = "paper frame 64 x 512, Hann, noise off, 10 dBsm at " +
                                     id_number(range_m) + " m (" + id_number(offset_bins) +
                                     " bin offset), v = " + id_number(v) + " m/s";
      validate_set_rcs(id, conditions, 10.0, det->rcs_dbsm, 1e-10);
      validate_set_range(id, conditions, range_m, det->range_m, 1e-11);
      validate_set_velocity(id, conditions, "velocity bins", v / v_bin,
                            det->radial_velocity_m_per_s / v_bin, 1e-10);
      worst_db = std::max(worst_db, std::abs(det->rcs_dbsm - 10.0));
      worst_m = std::max(worst_m, std::abs(det->range_m - range_m));
      worst_bin = std::max(worst_bin, std::abs(det->radial_velocity_m_per_s - v) / v_bin);
    }
  }
  std::printf(
      "[ measured ] Newton polish, 64 x 512 Hann, 3 velocities x 4 offsets: worst |RCS error| %.1e "
      "dB, "
      "|range error| %.1e m, |velocity error| %.1e bin\n",
      worst_db, worst_m, worst_bin);
}

// Nine point targets in one frame (more than one batch of the row interpolation, which serves up to
// four objects per pass over the map), at 6-14 m and -6..+6 m/s, noise off, Blackman-Harris (side
// lobes -92 dB, so the targets do not bias each other): each is found as its own detection with
// its set RCS, range and velocity (tolerances as the single-target tests: 0.2 dB... here 0.01 dB,
// 2 mm, 0.01 velocity bin), and the batched result equals measuring each target alone.
TEST(Estimation, ManyObjectsInOneFrameEachReadBack) {
  RadarParams p = noise_free(RadarParams{});
  p.window = WindowType::blackman_harris;
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const double v_bin = chain.derived().velocity_resolution_m_per_s;
  Scene scene = point_target_scene(10.0);
  const ScatteringCentre prototype = scene.centres[0];
  scene.centres.clear();
  for (int i = 0; i < 9; ++i) {
    ScatteringCentre centre = prototype;
    centre.range_offset_m = -4.0 + 1.0 * i;
    centre.radial_velocity_m_per_s = 1.5 * (i % 5) - 3.0 + (i % 2 == 0 ? 0.0 : 0.37);
    scene.centres.push_back(centre);
  }
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement all;
  RandomStream rng(4);
  chain.measure(scene, chamber, no_fog, rng, ws, all);
  for (const ScatteringCentre& centre : scene.centres) {
    const double range_m = chamber.target_range_m() + centre.range_offset_m;
    const Detection* match = nullptr;
    for (const Detection& det :
         all.detections) {  // the strongest within 5 cm (noise-free side lobes
      const bool near = std::abs(det.range_m - range_m) < 0.05;  // are detected too, ~90 dB down)
      if (near && (match == nullptr || det.received_power_w > match->received_power_w))
        match = &det;
    }
    ASSERT_NE(match, nullptr) << "target at " << range_m << " m";
    const std::string id = "radar.chain.many_objects.R" + id_number(range_m) + "m";
    const std::string conditions =
        "nine targets in one paper frame, Blackman-Harris, noise off, target at " +
        id_number(range_m) + " m, " + id_number(centre.radial_velocity_m_per_s) + " m/s";
    validate_set_rcs(id, conditions, 10.0, match->rcs_dbsm, 0.01);
    validate_set_range(id, conditions, range_m, match->range_m, 0.002);
    validate_set_velocity(id, conditions, "m/s", centre.radial_velocity_m_per_s,
                          match->radial_velocity_m_per_s, 0.01 * v_bin);

    Scene alone = scene;
    alone.centres = {centre};
    Measurement single;
    RandomStream single_rng(4);
    chain.measure(alone, chamber, no_fog, single_rng, ws, single);
    const Detection* lone = strongest(single.detections);
    ASSERT_NE(lone, nullptr);
    EXPECT_NEAR(match->rcs_dbsm, lone->rcs_dbsm, 0.01) << range_m;
  }
  std::printf("[ measured ] %zu targets in one frame: %zu detections\n", scene.centres.size(),
              all.detections.size());
}

// --- Receiver impairments ---------------------------------------------------------------------

// ADC quantiser alone [W]: a complex Gaussian of rail standard deviation sigma = 4 q, far inside
// full scale (A = 2^(b-1) q = 128 q for 8 bits), quantised mid-rise: the error per rail has mean
// 0 and variance q^2/12 within 2 % (200'000 samples: 1-sigma 0.2 %; Widrow's condition sigma >= q
// makes the uniform-error model exact to < 1e-6). Nothing clips.
TEST(Adc, QuantisationErrorIsUniformQSquaredOverTwelvePerRail) {
  constexpr unsigned kBits = 8;
  constexpr double kFullScale = 1.0;
  const double q = 2.0 * kFullScale / 256.0;
  std::vector<std::complex<double>> x(200'000);
  RandomStream rng(17);
  for (auto& v : x) v = rng.complex_normal(2.0 * 16.0 * q * q);  // sigma per rail = 4 q
  std::vector<std::complex<double>> y = x;
  EXPECT_EQ(quantize(y, kBits, kFullScale), 0u);
  double mean_re = 0, mean_im = 0, var_re = 0, var_im = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::complex<double> e = y[i] - x[i];
    mean_re += e.real();
    mean_im += e.imag();
    var_re += e.real() * e.real();
    var_im += e.imag() * e.imag();
  }
  const double n = static_cast<double>(x.size());
  std::printf(
      "[ measured ] ADC 8 bit, sigma = 4 q: error variance / (q^2/12) I %.4f Q %.4f, mean / q I "
      "%.1e Q %.1e\n",
      var_re / n / (q * q / 12.0), var_im / n / (q * q / 12.0), mean_re / n / q, mean_im / n / q);
  const std::string conditions = "8 bits, rail sigma 4 q, 200000 samples, no clipping";
  for (const auto& [rail, var, mean] :
       {std::tuple<const char*, double, double>{"I", var_re, mean_re}, {"Q", var_im, mean_im}}) {
    fogradar::testing::validate({.id = "radar.chain.adc.error_variance." + std::string(rail),
                                 .group = "radar: SNR",
                                 .quantity = std::string("quantisation error variance, ") + rail,
                                 .unit = "q^2/12",
                                 .conditions = conditions,
                                 .reference = 1.0,
                                 .source = "uniform error q^2/12 per rail [W]",
                                 .value = var / n / (q * q / 12.0),
                                 .tolerance = 0.02,
                                 .kind = Tolerance::relative});
    fogradar::testing::validate({.id = "radar.chain.adc.error_mean." + std::string(rail),
                                 .group = "radar: SNR",
                                 .quantity = std::string("|quantisation error mean|, ") + rail,
                                 .unit = "q",
                                 .conditions = conditions,
                                 .reference = 0.01,
                                 .source = "zero-mean uniform error [W] (bound 0.01 q)",
                                 .value = std::abs(mean / n / q),
                                 .tolerance = 0.0,
                                 .kind = Tolerance::at_most});
  }
  // Every output is a mid-rise level q (m + 1/2).
  for (std::size_t i = 0; i < 100; ++i) {
    const double level = y[i].real() / q - 0.5;
    EXPECT_NEAR(level, std::round(level), 1e-9);
  }
}

// synthesize_frame given the processor's window returns exactly the frame it returns without one,
// multiplied by apply_frame_window afterwards (reference; tolerance: identical bits), on every
// path: the window inside the noise pass (static scene, thermal noise, no phase noise, no ADC) and
// after everything else (a moving path, phase noise, an ADC, no thermal noise).
TEST(Synthesis, WindowInTheNoisePassEqualsTheWindowAfterwards) {
  RadarParams base;
  base.chirps_per_frame = 16;
  base.samples_per_chirp = 250;  // not a multiple of 4: the generator's tail
  const double amplitude = 30.0 * std::sqrt(reference_noise_power_w(base));
  const std::vector<Tone> static_tones{
      {20.0, {amplitude, -0.5 * amplitude}, 0.0, Origin::target},
      {31.3, {0.2 * amplitude, 0.7 * amplitude}, 0.0, Origin::fog}};
  std::vector<Tone> with_moving = static_tones;
  with_moving.push_back({25.0, {0.0, amplitude}, 2.5, Origin::target});
  struct Case {
    const char* name;
    std::vector<Tone> tones;
    void (*edit)(RadarParams&);
  };
  const Case cases[] = {
      {"static scene, thermal noise", static_tones, [](RadarParams&) {}},
      {"moving path", with_moving, [](RadarParams&) {}},
      {"phase noise", static_tones, [](RadarParams& p) { p.phase_noise_rms_rad = 0.01; }},
      {"ADC", static_tones, [](RadarParams& p) { p.adc_bits = 10; }},
      {"no thermal noise", static_tones, [](RadarParams& p) { p.thermal_noise = false; }},
  };
  for (const Case& c : cases) {
    RadarParams p = base;
    c.edit(p);
    const RadarDerived d = derive(p);
    const RangeDopplerProcessor processor(p);
    const FrameWindow window = processor.window();
    ComplexVector windowed(p.chirps_per_frame * p.samples_per_chirp), afterwards(windowed.size());
    RandomStream rng_windowed(41), rng_afterwards(41);
    const SynthesisReport report = synthesize_frame(c.tones, p, d, rng_windowed, windowed, &window);
    const SynthesisReport report_afterwards =
        synthesize_frame(c.tones, p, d, rng_afterwards, afterwards);
    apply_frame_window(window, afterwards);
    EXPECT_EQ(report.clipped_samples, report_afterwards.clipped_samples) << c.name;
    EXPECT_EQ(std::memcmp(windowed.data(), afterwards.data(), windowed.size() * sizeof windowed[0]),
              0)
        << c.name;
    EXPECT_EQ(rng_windowed(), rng_afterwards()) << c.name;  // the same draws
  }
}

// The range FFT chirp by chirp inside the noise pass (ChirpTransform, out of place from a one-chirp
// buffer) followed by doppler_transform gives the frame of the other path bit for bit: synthesis
// into the frame, then transform_windowed (the same one-chirp plan from a copy of each row). The
// two paths write the chirp's noise and window through different buffers, so this pins that the
// noise pass hands the FFT the values it would have left in the frame. With the transform given on
// a path other than the noise pass (no thermal noise), the frame is left untransformed and equals
// the frame synthesised without it.
TEST(Synthesis, RangeFftChirpByChirpEqualsTheBatchBitForBit) {
  const std::pair<std::size_t, std::size_t> sizes[] = {
      {64, 512}, {128, 1024}, {16, 250}, {8, 1000}, {5, 96}};
  for (const auto& [chirps, samples] : sizes) {
    RadarParams p;
    p.chirps_per_frame = chirps;
    p.samples_per_chirp = samples;
    p.sample_rate_hz = 20e6;  // up to 1024 samples fit the 51.2 us chirp
    const RadarDerived d = derive(p);
    const RangeDopplerProcessor processor(p);
    const FrameWindow window = processor.window();
    const double amplitude = 30.0 * std::sqrt(reference_noise_power_w(p));
    const std::vector<Tone> tones{{20.0, {amplitude, -0.5 * amplitude}, 0.0, Origin::target},
                                  {31.3, {0.2 * amplitude, 0.7 * amplitude}, 0.0, Origin::fog}};
    for (const bool thermal_noise : {true, false}) {
      p.thermal_noise = thermal_noise;
      ComplexVector by_chirp(chirps * samples), batch(by_chirp.size()), chirp(samples);
      const ChirpTransform transform{.fft = &processor.range_chirp_fft(), .chirp = chirp};
      RandomStream rng_by_chirp(5), rng_batch(5);
      const SynthesisReport report =
          synthesize_frame(tones, p, d, rng_by_chirp, by_chirp, &window, &transform);
      synthesize_frame(tones, p, d, rng_batch, batch, &window);
      ASSERT_EQ(report.range_transformed, thermal_noise) << chirps << " x " << samples;
      if (report.range_transformed) {
        processor.doppler_transform(by_chirp);
        processor.transform_windowed(batch);
      }
      EXPECT_EQ(std::memcmp(by_chirp.data(), batch.data(), batch.size() * sizeof batch[0]), 0)
          << chirps << " x " << samples << (thermal_noise ? ", noise pass" : ", no thermal noise");
    }
  }
}

// Static tones, summed up to four per pass over the chirp: every sample of every chirp equals the
// direct sum of a_t exp(i 2 pi f_t n / fs) over the tones, f_t = S L_t / c (reference: std::polar
// in long double per sample and tone). 1 to 9 tones cover passes of one to four tones and a last
// short pass; 1000 samples leave a tail of 8 after the blocks of 16. Tolerance 4 (N/16 + 16) eps
// sum |a_t|: the block recurrence and the 16 powers each carry about one rounding per step.
TEST(Synthesis, StaticTonesAreTheDirectSumOfTheirExponentials) {
  RadarParams p;
  p.chirps_per_frame = 3;
  p.samples_per_chirp = 1000;
  p.sample_rate_hz = 20e6;  // 1000 samples fit the 51.2 us chirp
  p.thermal_noise = false;
  const RadarDerived d = derive(p);
  const std::size_t columns = p.samples_per_chirp;
  for (std::size_t count = 1; count <= 9; ++count) {
    std::vector<Tone> tones;
    double amplitude_sum = 0.0;
    for (std::size_t t = 0; t < count; ++t) {
      const std::complex<double> a =
          std::polar(1.0 + 0.37 * static_cast<double>(t), 0.9 * static_cast<double>(t));
      tones.push_back({4.0 + 3.71 * static_cast<double>(t), a, 0.0, Origin::fog});
      amplitude_sum += std::abs(a);
    }
    ComplexVector frame(p.chirps_per_frame * columns);
    RandomStream rng(3);
    synthesize_frame(tones, p, d, rng, frame);
    const double tolerance = 4.0 * (static_cast<double>(columns) / 16.0 + 16.0) *
                             std::numeric_limits<double>::epsilon() * amplitude_sum;
    for (std::size_t n = 0; n < columns; ++n) {
      std::complex<long double> expected = 0.0L;
      for (const Tone& tone : tones) {
        const long double f = beat_frequency_hz(tone.path_length_m, d.chirp_slope_hz_per_s);
        const long double phase = 2.0L * std::numbers::pi_v<long double> * f *
                                  static_cast<long double>(n) /
                                  static_cast<long double>(p.sample_rate_hz);
        expected += std::complex<long double>(tone.amplitude) * std::polar(1.0L, phase);
      }
      for (std::size_t c = 0; c < p.chirps_per_frame; ++c) {
        ASSERT_LE(std::abs(std::complex<long double>(frame[c * columns + n]) - expected), tolerance)
            << count << " tones, chirp " << c << ", sample " << n;
      }
    }
  }
}

// Clipping is counted: with the full scale set to the thermal noise power (rail amplitude
// A = sqrt(k T0 F fs), about 1.41 rail sigmas) the count reported by synthesize_frame equals the
// number of samples with a rail at |x| >= A, counted here from the unquantised frame drawn with
// the same seed (mid-rise: x >= A or x < -A). With full scale 40 dB above the noise, none clip.
TEST(Adc, ClippingIsCountedExactly) {
  RadarParams p;
  p.chirps_per_frame = 8;
  p.adc_bits = 10;
  const RadarDerived d = derive(p);
  const double noise_dbm = 10.0 * std::log10(reference_noise_power_w(p) / 1e-3);
  p.adc_full_scale_dbm = noise_dbm;
  const double a = std::sqrt(reference_noise_power_w(p));
  ComplexVector frame(p.chirps_per_frame * p.samples_per_chirp), raw(frame.size());
  RandomStream rng_q(23);
  const SynthesisReport report = synthesize_frame({}, p, d, rng_q, frame);
  RadarParams ideal = p;
  ideal.adc_bits = 0;
  RandomStream rng_raw(23);
  synthesize_frame({}, ideal, d, rng_raw, raw);
  std::size_t expected = 0;
  for (const auto& v : raw) {
    const auto out = [a](double x) { return x >= a || x < -a; };
    expected += (out(v.real()) || out(v.imag())) ? 1 : 0;
  }
  // Gaussian rails: P(clip) = 1 - (1 - 2 Q(sqrt 2))^2 = 0.29.
  std::printf(
      "[ measured ] ADC clipping at full scale = noise power: %zu of %zu samples (expected %zu)\n",
      report.clipped_samples, frame.size(), expected);
  EXPECT_EQ(report.clipped_samples, expected);
  EXPECT_GT(expected, frame.size() / 5);
  p.adc_full_scale_dbm = noise_dbm + 40.0;
  RandomStream rng_high(23);
  EXPECT_EQ(synthesize_frame({}, p, d, rng_high, frame).clipped_samples, 0u);
}

// Clipping reaches the summary: with the full scale at -90 dBm, far below the paper target's echo,
// two measured frames' records sum to a step whose adc_clipped_fraction is exactly the counts
// quantize returns on the same frames drawn without an ADC (the same stream: the chain's beat
// before the ADC), over their samples; the CSV's last column carries it. The paper default (an
// ideal ADC) and a full scale far above the echo report 0.
TEST(Adc, ClippedFractionReachesTheSummaryExactly) {
  RadarParams p;
  p.adc_bits = 12;
  p.adc_full_scale_dbm = -90.0;
  RadarParams ideal = p;
  ideal.adc_bits = 0;
  const RadarChain chain(p), ideal_chain(ideal);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto clear = propagation::first_layers_active(0, chamber.layer_count());
  const Scene scene = evt_rear_scene();
  chain.check_compatible(scene, chamber);
  MeasurementWorkspace ws = chain.make_workspace(), ideal_ws = ideal_chain.make_workspace();
  const double a = std::sqrt(dbm_to_watt(p.adc_full_scale_dbm));
  ComplexVector raw;
  FrameTaps taps;
  taps.beat = [&raw](std::span<const std::complex<double>> beat) {
    raw.assign(beat.begin(), beat.end());
  };
  StepResult step;
  std::size_t expected = 0, samples = 0;
  for (std::uint64_t index = 0; index < 2; ++index) {
    Measurement m, ideal_m;
    RandomStream rng(5, 0, index), ideal_rng(5, 0, index);
    chain.measure(scene, chamber, clear, rng, ws, m);
    ideal_chain.measure(scene, chamber, clear, ideal_rng, ideal_ws, ideal_m, taps);
    ASSERT_EQ(raw.size(), p.chirps_per_frame * p.samples_per_chirp);
    const std::size_t count = quantize(raw, p.adc_bits, a);
    EXPECT_EQ(m.synthesis.clipped_samples, count);
    EXPECT_EQ(m.synthesis.samples, raw.size());
    expected += count;
    samples += raw.size();
    step.records.push_back(record_of(m, chamber.target_range_m(), p.association_gate_m));
  }
  EXPECT_GT(expected, 0u);
  EXPECT_LT(expected, samples);
  const RadarSummary summary = summarize({step}, 0.0, 0.0);
  ASSERT_EQ(summary.steps.size(), 1u);
  const double fraction = static_cast<double>(expected) / static_cast<double>(samples);
  std::printf("[ measured ] ADC full scale -90 dBm, paper target: %zu of %zu samples clipped\n",
              expected, samples);
  EXPECT_EQ(summary.steps[0].adc_clipped_fraction, fraction);

  const std::string csv = step_table(summary).csv();
  const std::string header = csv.substr(0, csv.find('\n'));
  const std::string last =
      ",adc_clipped_fraction,clipping_detections_per_frame,sidelobe_detections_per_frame,"
      "multipath_detections_per_frame,room_detections_per_frame";
  ASSERT_GE(header.size(), last.size());
  EXPECT_EQ(header.substr(header.size() - last.size()), last) << header;
  EXPECT_EQ(csv.find("adc_clipped_fraction"), header.size() - last.size() + 1);
  std::string row = csv.substr(header.size() + 1, csv.size() - header.size() - 2);
  row.erase(row.rfind(','));  // the room detections
  row.erase(row.rfind(','));  // the multipath detections
  row.erase(row.rfind(','));  // the sidelobe detections
  row.erase(row.rfind(','));  // the clipping detections
  EXPECT_EQ(std::stod(row.substr(row.rfind(',') + 1)), fraction) << row;
  EXPECT_EQ(summary_json(summary)["steps"][0]["adc_clipped_fraction"].get<double>(), fraction);

  // The paper default: an ideal ADC, nothing clipped.
  const RadarChain paper_chain{RadarParams{}};
  MeasurementWorkspace paper_ws = paper_chain.make_workspace();
  Measurement paper_m;
  RandomStream paper_rng(5, 0, 0);
  paper_chain.measure(scene, chamber, clear, paper_rng, paper_ws, paper_m);
  EXPECT_EQ(paper_m.synthesis.clipped_samples, 0u);
  const StepResult paper_step{
      .active_layers = 0,
      .two_way_attenuation_db = 0.0,
      .records = {record_of(paper_m, chamber.target_range_m(), p.association_gate_m)}};
  EXPECT_EQ(summarize({paper_step}, 0.0, 0.0).steps[0].adc_clipped_fraction, 0.0);
  // A 12-bit ADC with its full scale 60 dB above the clipping one: nothing clipped either.
  RadarParams high = p;
  high.adc_full_scale_dbm = -30.0;
  const RadarChain high_chain(high);
  Measurement high_m;
  RandomStream high_rng(5, 0, 0);
  high_chain.measure(scene, chamber, clear, high_rng, paper_ws, high_m);
  EXPECT_EQ(high_m.synthesis.clipped_samples, 0u);
  EXPECT_EQ(high_m.synthesis.samples, raw.size());
}

// ADC through the chain: with q = rail sigma of the thermal noise (8 bits, no clipping), the
// noise floor of the processed map rises by the quantisation noise 2 q^2 / 12 (both rails):
// mean cell power / ((k T0 F fs + q^2/6) sum w_r^2 sum w_d^2) within 2 % (the increase is 8.3 %).
TEST(Adc, QuantisationNoiseAddsToTheNoiseFloor) {
  RadarParams p;
  p.adc_bits = 8;
  const double sigma_rail = std::sqrt(reference_noise_power_w(p) / 2.0);
  const double q = sigma_rail;
  const double a = 128.0 * q;  // 2^(b-1) q
  p.adc_full_scale_dbm = 10.0 * std::log10(a * a / 1e-3);
  const RadarDerived d = derive(p);
  const RangeDopplerProcessor processor(p);
  ComplexVector frame(p.chirps_per_frame * p.samples_per_chirp);
  std::vector<double> power(frame.size());
  double sum = 0.0;
  constexpr int kFrames = 4;
  for (int f = 0; f < kFrames; ++f) {
    RandomStream rng(29, static_cast<std::uint64_t>(f));
    EXPECT_EQ(synthesize_frame({}, p, d, rng, frame).clipped_samples, 0u);
    processor.process(frame, power);
    for (const double v : power) sum += v;
  }
  const double gains = window_noise_gain(p.window, p.samples_per_chirp) *
                       window_noise_gain(p.window, p.chirps_per_frame);
  const double mean = sum / static_cast<double>(kFrames * frame.size());
  const double expected = (reference_noise_power_w(p) + q * q / 6.0) * gains;
  std::printf(
      "[ measured ] ADC 8 bit, q = sigma: mean cell / ((kT0Ffs + q^2/6) gains) = %.4f, / (kT0Ffs "
      "gains) = %.4f\n",
      mean / expected, mean / (reference_noise_power_w(p) * gains));
  fogradar::testing::validate({.id = "radar.chain.adc.noise_floor",
                               .group = "radar: SNR",
                               .quantity = "mean cell power of the noise-only map with an ADC",
                               .unit = "W",
                               .conditions = "paper radar, Hann, 8 bits, q = rail sigma, 4 frames",
                               .reference = expected,
                               .source = "(k T0 F fs + q^2/6) sum w_r^2 sum w_d^2 [W; H78]",
                               .value = mean,
                               .tolerance = 0.02,
                               .kind = Tolerance::relative});
}

// Phase noise: off by default (and so is the ADC). On: white Gaussian phase noise of rms s
// multiplies each sample by exp(i phi), E[exp(i phi)] = exp(-s^2/2), so the coherent peak power
// drops by exp(-s^2); the rest spreads into a floor. Noise off, s = 0.5 rad, paper frame: the mean
// over 8 frames of the RCS power ratio (noisy / clean) is exp(-0.25) = -1.086 dB within 0.04 dB.
// Per frame the ratio fluctuates by 2 (1 - e^{-s^2}) e^{s^2} ENBW_r ENBW_d / (N N_c) = 3.9e-5 in
// variance (0.027 dB rms), so the 8-frame mean has 1-sigma 0.0095 dB.
TEST(PhaseNoise, OffByDefaultAndCoherentLossIsExpMinusSigmaSquared) {
  EXPECT_EQ(RadarParams{}.phase_noise_rms_rad, 0.0);
  EXPECT_EQ(RadarParams{}.adc_bits, 0u);
  RadarParams p = noise_free(RadarParams{});
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
  const Scene scene = point_target_scene(10.0);
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement m;
  RandomStream rng(1);
  chain.measure(scene, chamber, no_fog, rng, ws, m);
  ASSERT_TRUE(m.target.has_value());
  const double clean_m2 = m.target->rcs_m2;

  p.phase_noise_rms_rad = 0.5;
  const RadarChain noisy(p);
  constexpr int kFrames = 8;
  double ratio_sum = 0.0;
  for (int f = 0; f < kFrames; ++f) {
    RandomStream rng2(51, static_cast<std::uint64_t>(f));
    noisy.measure(scene, chamber, no_fog, rng2, ws, m);
    ASSERT_TRUE(m.target.has_value());
    ratio_sum += m.target->rcs_m2 / clean_m2;
  }
  const double change_db = 10.0 * std::log10(ratio_sum / kFrames);
  const double expected_db = 10.0 * std::log10(std::exp(-0.25));
  std::printf(
      "[ measured ] phase noise 0.5 rad rms: mean RCS change %.4f dB over %d frames (expected %.4f "
      "dB)\n",
      change_db, kFrames, expected_db);
  fogradar::testing::validate({.id = "radar.chain.phase_noise.coherent_loss",
                               .group = "radar: SNR",
                               .quantity = "mean RCS change (8-frame mean of noisy / clean)",
                               .unit = "dB",
                               .conditions = "phase noise 0.5 rad rms, paper frame, noise off",
                               .reference = expected_db,
                               .source = "coherent loss exp(-s^2) of white Gaussian phase noise",
                               .value = change_db,
                               .tolerance = 0.04,
                               .kind = Tolerance::absolute});
}

// --- Floor multipath --------------------------------------------------------------------------

// Two-ray floor reflection [Sk; Radar Handbook ch. 26]: with direct legs r_d, floor legs r_f (via
// the image below the floor), one-way amplitude patterns g_d, g_f (Gaussian beam) and a real
// floor coefficient Gamma, the monostatic field is (g_d e^{-jk r_d}/r_d + Gamma g_f e^{-jk
// r_f}/r_f)^2, so the RCS read back (eq. 7 at the estimated range R) is
//   sigma * g_d^4 |1 + Gamma (g_f/g_d)(r_d/r_f) e^{-jk(r_f - r_d)}|^4 (R / r_d)^4.
// Computed here from the geometry. k = 2 pi f_c / c: the processed peak holds each path's phase at
// the window centre, where the sweep passes its centre frequency f_c (the Hann window is symmetric
// about sample N/2, and the N samples fill the chirp), for either sweep direction (the up-chirp
// conjugates the phases, which leaves |.| unchanged). The residual video phase pi S tau^2 differs
// between the paths by < 3e-4 rad here and is left out of the reference. A 150 MHz sweep keeps
// the three delays within 0.01 bin of each other, so the window's response is flat across them.
// Tolerance 0.1 dB, at 18 geometries (heights 0.2 and 0.65 m, ranges 20-35 m, Gamma in {-0.5,
// -0.9, 0.4}) x 2 directions; expected factors between -8 and +11 dB. (For information the test
// also prints the worst error had k been taken at either end of the sweep, f_c -+ B/2.)
TEST(FloorMultipath, TwoRayFactorFromGeometry) {
  for (const SweepDirection direction : {SweepDirection::up, SweepDirection::down}) {
    RadarParams p = noise_free(RadarParams{});
    p.sweep_bandwidth_hz = 150e6;
    p.chirps_per_frame = 4;
    p.sweep_direction = direction;
    const RadarChain chain(p);
    const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
    const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
    const double k = 2.0 * std::numbers::pi * p.centre_frequency_hz / kC;
    const double beam_rad = p.elevation_beamwidth_deg * std::numbers::pi / 180.0;
    const auto amplitude_pattern = [&](double angle_rad) {
      return std::sqrt(std::exp(-4.0 * std::log(2.0) * std::pow(angle_rad / beam_rad, 2)));
    };
    MeasurementWorkspace ws = chain.make_workspace();
    Measurement m;
    const double sensor_h = 0.5;
    double worst_db = 0.0, lowest_db = 1e9, highest_db = -1e9;
    double worst_other_db[2] = {0.0, 0.0};
    int count = 0;
    for (const double gamma : {-0.5, -0.9, 0.4}) {
      for (const double target_h : {0.2, 0.65}) {
        for (const double horizontal_m : {20.0, 27.3, 35.0}) {
          ++count;
          Scene scene = point_target_scene(10.0);
          scene.sensor_height_m = sensor_h;
          scene.centres[0].height_m = target_h;
          scene.centres[0].range_offset_m = horizontal_m - chamber.target_range_m();
          scene.surfaces = {coefficient_floor(gamma)};
          RandomStream rng(count);
          chain.measure(scene, chamber, no_fog, rng, ws, m);
          const Detection* det = strongest(m.detections);
          ASSERT_NE(det, nullptr);
          const double r_d = std::hypot(horizontal_m, target_h - sensor_h);
          const double r_f = std::hypot(horizontal_m, target_h + sensor_h);
          const double g_d = amplitude_pattern(std::atan2(target_h - sensor_h, horizontal_m));
          const double g_f = amplitude_pattern(std::atan2(target_h + sensor_h, horizontal_m));
          const auto expected_for = [&](double wavenumber) {
            const std::complex<double> two_ray =
                1.0 +
                gamma * (g_f / g_d) * (r_d / r_f) * std::polar(1.0, -wavenumber * (r_f - r_d));
            return 10.0 * std::pow(g_d, 4) * std::pow(std::abs(two_ray), 4) *
                   std::pow(det->range_m / r_d, 4);
          };
          const double expected_m2 = expected_for(k);
          const double k_low =
              2.0 * std::numbers::pi * (p.centre_frequency_hz - 0.5 * p.sweep_bandwidth_hz) / kC;
          const double k_high =
              2.0 * std::numbers::pi * (p.centre_frequency_hz + 0.5 * p.sweep_bandwidth_hz) / kC;
          worst_other_db[0] = std::max(
              worst_other_db[0], std::abs(det->rcs_dbsm - 10.0 * std::log10(expected_for(k_low))));
          worst_other_db[1] = std::max(
              worst_other_db[1], std::abs(det->rcs_dbsm - 10.0 * std::log10(expected_for(k_high))));
          const double error_db = det->rcs_dbsm - 10.0 * std::log10(expected_m2);
          worst_db = std::max(worst_db, std::abs(error_db));
          lowest_db = std::min(lowest_db, 10.0 * std::log10(expected_m2 / 10.0));
          highest_db = std::max(highest_db, 10.0 * std::log10(expected_m2 / 10.0));
          fogradar::testing::validate(
              {.id = "radar.chain.floor_two_ray." + std::string(to_string(direction)) + ".gamma" +
                     id_number(gamma) + ".h" + id_number(target_h) + ".D" + id_number(horizontal_m),
               .group = "radar: RCS",
               .quantity = "RCS read back with a floor reflection",
               .unit = "dBsm",
               .conditions = "10 dBsm, sensor 0.5 m, target " + id_number(target_h) +
                             " m high at " + id_number(horizontal_m) + " m, Gamma " +
                             id_number(gamma) + ", 150 MHz sweep, " +
                             std::string(to_string(direction)) + "-chirp",
               .reference = 10.0 * std::log10(expected_m2),
               .source = "two-ray factor from the geometry [Sk; Radar Handbook ch. 26] (this test)",
               .value = det->rcs_dbsm,
               .tolerance = 0.1,
               .kind = Tolerance::absolute});
        }
      }
    }
    std::printf(
        "[ measured ] floor two-ray %s-chirp: %d geometries, expected factors %.1f..%.1f dB, worst "
        "error %.3f dB (with k at f_c - B/2: %.2f dB, at f_c + B/2: %.2f dB)\n",
        std::string(to_string(direction)).c_str(), count, lowest_db, highest_db, worst_db,
        worst_other_db[0], worst_other_db[1]);
  }
}

// --- Chirp: centre frequency and sweep direction -------------------------------------------------

// Phase of the dechirped echo of delay tau at the centre t_m = T/2 of a chirp whose N samples fill
// it, written out from the transmit phase 2 pi (f_0 t + s t^2 / 2), s = eps B / T,
// f_0 = f_c - eps B / 2: the receiver forms rx conj(tx) for a down-chirp and tx conj(rx) for an
// up-chirp (the product whose beat frequency |s| tau is positive), phase
// eps 2 pi (f_0 tau + s tau t - s tau^2 / 2), which at t = T/2 is eps 2 pi f_c tau - pi |s| tau^2.
double echo_phase_at_chirp_centre_rad(const RadarParams& p, double delay_s) {
  const double eps = p.sweep_direction == SweepDirection::up ? 1.0 : -1.0;
  const double slope = p.sweep_bandwidth_hz / p.chirp_duration_s;
  return eps * 2.0 * std::numbers::pi * p.centre_frequency_hz * delay_s -
         std::numbers::pi * slope * delay_s * delay_s;
}

double wrapped(double phase) { return std::remainder(phase, 2.0 * std::numbers::pi); }

// The phase of a point echo at its peak cell: for the periodic Hann window (symmetric about
// sample N/2) the range DFT of a tone at any offset u within the main lobe is a e^{i pi u} times a
// positive real number, so Y[0][k] (-1)^k has the phase of the tone at t_m = N / (2 fs) = T/2
// (the paper radar's samples fill the chirp). Reference: echo_phase_at_chirp_centre_rad above,
// i.e. -2 pi f_c tau - pi S tau^2 for a down-chirp and +2 pi f_c tau - pi S tau^2 for an up-chirp
// (the residual video phase pi S tau^2 is 0.27 rad at 10 m). Static point target, noise off,
// 8 chirps, 3-40 m at sub-bin offsets 0..0.9; tolerance 1e-6 rad (the phases are ~1e4-1e5 rad,
// rounding ~1e-11). Printed for information: the worst error had the phase been taken at the
// sweep's start frequency f_0 = f_c - eps B/2 (hundreds of rad) or without the residual term.
TEST(Chirp, PointEchoPhaseAtThePeakCellIsTheCentreFrequencyPhase) {
  for (const SweepDirection direction : {SweepDirection::up, SweepDirection::down}) {
    RadarParams p = noise_free(RadarParams{});
    p.chirps_per_frame = 8;
    p.sweep_direction = direction;
    const double eps = direction == SweepDirection::up ? 1.0 : -1.0;
    const RadarDerived d = derive(p);
    const RangeDopplerProcessor processor(p);
    const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
    const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
    const double bin_m = reference_range_bin_m(p);
    const std::size_t columns = p.samples_per_chirp;
    ComplexVector frame(p.chirps_per_frame * columns);
    std::vector<Tone> tones;
    double worst = 0.0, worst_start = 0.0, worst_no_residual = 0.0;
    for (const double nominal_m : {3.0, 10.0, 23.7, 40.0}) {
      for (const double offset_bins : {0.0, 0.3, 0.5, 0.9}) {
        const double range_m = (std::round(nominal_m / bin_m) + offset_bins) * bin_m;
        Scene scene = point_target_scene(10.0);
        scene.centres[0].range_offset_m = range_m - chamber.target_range_m();
        RandomStream rng(2);
        scene_tones(scene, chamber, no_fog, p, d, rng, tones);
        synthesize_frame(tones, p, d, rng, frame);
        processor.transform(frame);
        std::size_t peak = 0;
        for (std::size_t k = 1; k < columns; ++k) {
          if (std::abs(frame[k]) > std::abs(frame[peak])) peak = k;
        }
        const double measured = std::arg(frame[peak] * (peak % 2 == 0 ? 1.0 : -1.0));
        const double tau = 2.0 * range_m / kC;
        const double expected = echo_phase_at_chirp_centre_rad(p, tau);
        const double error = std::abs(wrapped(measured - expected));
        fogradar::testing::validate(
            {.id = "radar.chain.peak_cell_phase." + std::string(to_string(direction)) + ".R" +
                   id_number(nominal_m) + "m.offset" + id_number(offset_bins),
             .group = "radar: signal processing",
             .quantity = "|peak-cell phase error| (wrapped)",
             .unit = "rad",
             .conditions = "static point target at " + id_number(range_m) + " m, " +
                           std::string(to_string(direction)) + "-chirp, Hann, noise off",
             .reference = 1e-6,
             .source = "echo phase at the chirp centre eps 2 pi f_c tau - pi S tau^2 (this test)",
             .value = error,
             .tolerance = 0.0,
             .kind = Tolerance::at_most});
        worst = std::max(worst, error);
        worst_start = std::max(
            worst_start, std::abs(wrapped(measured - (expected - std::numbers::pi *
                                                                     p.sweep_bandwidth_hz * tau))));
        worst_no_residual = std::max(worst_no_residual,
                                     std::abs(wrapped(measured - eps * 2.0 * std::numbers::pi *
                                                                     p.centre_frequency_hz * tau)));
      }
    }
    std::printf(
        "[ measured ] peak-cell phase, %s-chirp, 16 positions 3-40 m: worst error %.1e rad (phase "
        "at "
        "f_0: %.2f rad; without the residual video phase: %.2f rad)\n",
        std::string(to_string(direction)).c_str(), worst, worst_start, worst_no_residual);
  }
}

// Two equal scatterers in one range cell, on boresight at R_1 and R_2 = R_1 + dR (dR = 1-7 cm,
// 0.07-0.47 bin), the second with RCS sigma (R_2/R_1)^4 so that both echoes have the same
// amplitude a. Two tones of equal amplitude and phase difference dphi through a symmetric window
// with real response H(u) (bins): the DTFT magnitude |H(x - delta/2) + e^{i dphi} H(x + delta/2)|
// is even in x, so the interpolated peak (docs/radar.md §5) is at the midpoint, where it is
// 2 |a| |cos(dphi/2)| H(delta/2). Eq. 7 at the read-back range R^ then gives
//   sigma^ = sigma (R^/R_1)^4 4 cos^2(dphi/2) (H(delta/2) / H(0))^2,
// dphi = eps 2 pi f_c (tau_2 - tau_1) - pi S (tau_2^2 - tau_1^2) (lambda = c / f_c) and H summed
// here from the Hann definition. Noise off, 8 chirps, both directions, two ranges; the cases are
// away from the nulls (cos^2 >= 0.29), where the midpoint is the maximum. Tolerance 1e-3 dB; the
// range within 1 mm of the midpoint. Printed: the worst error had lambda been c / f_0.
TEST(Chirp, TwoScatterersInOneCellInterfereAtTheCentreWavelength) {
  for (const SweepDirection direction : {SweepDirection::up, SweepDirection::down}) {
    RadarParams p = noise_free(RadarParams{});
    p.chirps_per_frame = 8;
    p.sweep_direction = direction;
    const double eps = direction == SweepDirection::up ? 1.0 : -1.0;
    const RadarChain chain(p);
    const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
    const auto no_fog = propagation::first_layers_active(0, chamber.layer_count());
    const double bin_m = reference_range_bin_m(p);
    const double slope = p.sweep_bandwidth_hz / p.chirp_duration_s;
    const std::size_t n = p.samples_per_chirp;
    const auto hann_response = [&](double u) {
      double sum = 0.0;
      for (std::size_t j = 0; j < n; ++j) {
        const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(j) /
                                              static_cast<double>(n));
        sum += w * std::cos(2.0 * std::numbers::pi * u *
                            (static_cast<double>(j) - 0.5 * static_cast<double>(n)) /
                            static_cast<double>(n));
      }
      return sum;
    };
    MeasurementWorkspace ws = chain.make_workspace();
    Measurement m;
    double worst_db = 0.0, worst_start_db = 0.0;
    for (const double r1 : {7.3, 12.3}) {
      for (const double dr : {0.01, 0.02, 0.05, 0.06, 0.07}) {
        const double r2 = r1 + dr;
        Scene scene = point_target_scene(10.0);
        scene.centres.push_back(scene.centres[0]);
        scene.centres[0].range_offset_m = r1 - chamber.target_range_m();
        scene.centres[1].range_offset_m = r2 - chamber.target_range_m();
        scene.centres[1].rcs_m2 = 10.0 * std::pow(r2 / r1, 4);
        RandomStream rng(4);
        chain.measure(scene, chamber, no_fog, rng, ws, m);
        const Detection* det = strongest(m.detections);
        ASSERT_NE(det, nullptr);
        const double tau1 = 2.0 * r1 / kC, tau2 = 2.0 * r2 / kC;
        const double residual = std::numbers::pi * slope * (tau2 * tau2 - tau1 * tau1);
        const double response = hann_response(0.5 * dr / bin_m) / hann_response(0.0);
        const auto expected_db = [&](double frequency_hz) {
          const double dphi =
              eps * 2.0 * std::numbers::pi * frequency_hz * (tau2 - tau1) - residual;
          const double cos_half = std::cos(0.5 * dphi);
          return 10.0 * std::log10(10.0 * std::pow(det->range_m / r1, 4) * 4.0 * cos_half *
                                   cos_half * response * response);
        };
        const double expected = expected_db(p.centre_frequency_hz);
        EXPECT_GT(expected, 10.0 + 10.0 * std::log10(4.0 * 0.29 * 0.5));  // away from a null
        const std::string id = "radar.chain.two_scatterers." + std::string(to_string(direction)) +
                               ".R" + id_number(r1) + "m.dR" + id_number(dr) + "m";
        const std::string conditions = "two equal echoes at " + id_number(r1) + " m and +" +
                                       id_number(dr) + " m, Hann, " +
                                       std::string(to_string(direction)) + "-chirp, noise off";
        fogradar::testing::validate(
            {.id = id + ".rcs",
             .group = "radar: RCS",
             .quantity = "RCS read back",
             .unit = "dBsm",
             .conditions = conditions,
             .reference = expected,
             .source = "sigma (R^/R_1)^4 4 cos^2(dphi/2) (H(delta/2) / H(0))^2 at lambda = c / f_c "
                       "(this test)",
             .value = det->rcs_dbsm,
             .tolerance = 1e-3,
             .kind = Tolerance::absolute});
        fogradar::testing::validate({.id = id + ".range",
                                     .group = "radar: signal processing",
                                     .quantity = "range read back",
                                     .unit = "m",
                                     .conditions = conditions,
                                     .reference = 0.5 * (r1 + r2),
                                     .source = "midpoint of the two scatterers (symmetric window)",
                                     .value = det->range_m,
                                     .tolerance = 1e-3,
                                     .kind = Tolerance::absolute});
        worst_db = std::max(worst_db, std::abs(det->rcs_dbsm - expected));
        worst_start_db = std::max(
            worst_start_db,
            std::abs(det->rcs_dbsm -
                     expected_db(p.centre_frequency_hz - eps * 0.5 * p.sweep_bandwidth_hz)));
      }
    }
    std::printf(
        "[ measured ] two scatterers in one cell, %s-chirp, 10 cases: worst error %.1e dB (lambda "
        "at "
        "the start frequency: %.2f dB)\n",
        std::string(to_string(direction)).c_str(), worst_db, worst_start_db);
  }
}

// --- Determinism ------------------------------------------------------------------------------

bool same_detections(const std::vector<Detection>& a, const std::vector<Detection>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].range_m != b[i].range_m || a[i].rcs_m2 != b[i].rcs_m2 || a[i].snr_db != b[i].snr_db ||
        a[i].radial_velocity_m_per_s != b[i].radial_velocity_m_per_s || a[i].cells != b[i].cells ||
        a[i].received_power_w != b[i].received_power_w) {
      return false;
    }
  }
  return true;
}

// Same RandomStream seed -> identical Measurement (every detection field bit for bit, the
// target, the synthesis report), with everything random switched on: EVT with floor, all four
// layers of the default fog, thermal noise, phase noise and an ADC. A different stream changes it.
TEST(Determinism, SameSeedGivesIdenticalMeasurement) {
  RadarParams p;
  p.phase_noise_rms_rad = 0.01;
  p.adc_bits = 14;
  const RadarChain chain(p);
  const propagation::Chamber chamber = make_chamber(paper_chamber_spec(), p.centre_frequency_hz);
  const auto all_on =
      propagation::first_layers_active(chamber.layer_count(), chamber.layer_count());
  Scene scene = evt_rear_scene();
  scene.surfaces = {coefficient_floor(-0.7)};
  chain.check_compatible(scene, chamber);
  MeasurementWorkspace ws1 = chain.make_workspace(), ws2 = chain.make_workspace();
  Measurement m1, m2, m3;
  RandomStream a(1, 3, 17), b(1, 3, 17), c(1, 3, 18);
  chain.measure(scene, chamber, all_on, a, ws1, m1);
  chain.measure(scene, chamber, all_on, b, ws2, m2);
  ASSERT_TRUE(m1.target.has_value());
  EXPECT_TRUE(same_detections(m1.detections, m2.detections));
  ASSERT_TRUE(m2.target.has_value());
  EXPECT_EQ(m1.target->rcs_m2, m2.target->rcs_m2);
  EXPECT_EQ(m1.synthesis.clipped_samples, m2.synthesis.clipped_samples);
  // Reusing a workspace gives the same result as a fresh one.
  RandomStream a2(1, 3, 17);
  chain.measure(scene, chamber, all_on, a2, ws2, m3);
  EXPECT_TRUE(same_detections(m1.detections, m3.detections));
  chain.measure(scene, chamber, all_on, c, ws1, m3);
  ASSERT_TRUE(m3.target.has_value());
  EXPECT_NE(m1.target->rcs_m2, m3.target->rcs_m2);
}

}  // namespace
}  // namespace fogradar::radar
