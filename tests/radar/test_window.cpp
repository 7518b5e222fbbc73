// Window tests. Reference: [H78] F. J. Harris, "On the use of windows for harmonic analysis
// with the discrete Fourier transform", Proc. IEEE 66(1), 51-83, 1978, Table 1 (coherent gain,
// equivalent noise bandwidth, highest sidelobe level) and eqs. 30-33, 44-45.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/radar/fft.hpp"
#include "fogradar/radar/window.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;

// A number as check ids and conditions show it ("512", "0.005", "1e-12").
std::string id_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

const WindowType kAllWindows[] = {WindowType::rectangular, WindowType::hann, WindowType::hamming,
                                  WindowType::blackman_harris, WindowType::chebyshev};

// |DTFT| of the window on a grid of `pad` points per DFT bin over [0, pi] (zero-padded FFT),
// normalised to the main-lobe peak at frequency 0.
std::vector<double> normalised_spectrum(const std::vector<double>& w, std::size_t pad) {
  const std::size_t size = w.size() * pad;
  ComplexVector buffer(size, {0.0, 0.0});
  std::copy(w.begin(), w.end(), buffer.begin());
  const FftPlan plan(size, FftDirection::forward, {.placement = FftPlacement::in_place});
  plan.execute(buffer);
  std::vector<double> magnitude(size / 2 + 1);
  for (std::size_t k = 0; k < magnitude.size(); ++k) magnitude[k] = std::abs(buffer[k]);
  const double peak = magnitude[0];
  for (double& value : magnitude) value /= peak;
  return magnitude;
}

// Sidelobe peaks (local maxima beyond the first null) of a normalised spectrum, in dB.
std::vector<double> sidelobe_peaks_db(const std::vector<double>& spectrum) {
  std::size_t k = 1;
  while (k + 1 < spectrum.size() && spectrum[k + 1] < spectrum[k]) ++k;  // walk down the main lobe
  std::vector<double> peaks;
  for (; k + 1 < spectrum.size(); ++k) {
    if (spectrum[k] > spectrum[k - 1] && spectrum[k] >= spectrum[k + 1]) {
      peaks.push_back(20.0 * std::log10(spectrum[k]));
    }
  }
  return peaks;
}

double highest_sidelobe_db(const std::vector<double>& w) {
  const std::vector<double> peaks = sidelobe_peaks_db(normalised_spectrum(w, 64));
  return *std::max_element(peaks.begin(), peaks.end());
}

// --- Harris 1978 Table 1 ----------------------------------------------------------------------

struct HarrisRow {
  WindowType type;
  double coherent_gain;  // [H78] Table 1, two decimals
  double enbw_bins;      // [H78] Table 1, two decimals
  double exact_cg;       // a0 of the cosine sum
  double exact_enbw;     // (a0^2 + sum_{m>0} a_m^2 / 2) / a0^2
};

class HarrisTable : public ::testing::TestWithParam<HarrisRow> {};

std::string harris_row_name(const ::testing::TestParamInfo<HarrisRow>& info) {
  return std::string(to_string(info.param.type));
}

std::string window_name(const ::testing::TestParamInfo<WindowType>& info) {
  return std::string(to_string(info.param));
}

// CG = sum(w)/N and ENBW = N sum(w^2) / sum(w)^2 of the periodic (DFT-even) windows:
//  * against [H78] Table 1 within +-0.005 (the table's rounding to two decimals);
//  * against the exact values of a periodic cosine sum within 1e-12 (over a full period the
//    cross terms of the cosines vanish, so CG = a0 and ENBW = (a0^2 + sum a_m^2/2)/a0^2 for
//    every N larger than the number of terms). Sizes include odd ones.
TEST_P(HarrisTable, CoherentGainAndNoiseBandwidth) {
  const HarrisRow& row = GetParam();
  for (const std::size_t n : {16u, 63u, 64u, 512u, 1023u}) {
    const std::vector<double> w = make_window(row.type, n);
    ASSERT_EQ(w.size(), n);
    const double cg = coherent_gain(w);
    const double enbw = noise_equivalent_bandwidth_bins(w);
    const std::string name(to_string(row.type));
    const std::string conditions = name + " window, periodic, N = " + std::to_string(n);
    const std::string id = "radar.window." + name + ".";
    const std::string size = ".N" + std::to_string(n);
    fogradar::testing::validate({.id = id + "coherent_gain.harris_table" + size,
                                 .group = "radar: signal processing",
                                 .quantity = "coherent gain sum(w)/N",
                                 .unit = "1",
                                 .conditions = conditions,
                                 .reference = row.coherent_gain,
                                 .source = "Harris 1978 Table 1 (two decimals)",
                                 .value = cg,
                                 .tolerance = 0.005,
                                 .kind = Tolerance::absolute});
    fogradar::testing::validate({.id = id + "enbw.harris_table" + size,
                                 .group = "radar: signal processing",
                                 .quantity = "equivalent noise bandwidth N sum(w^2)/sum(w)^2",
                                 .unit = "bins",
                                 .conditions = conditions,
                                 .reference = row.enbw_bins,
                                 .source = "Harris 1978 Table 1 (two decimals)",
                                 .value = enbw,
                                 .tolerance = 0.005,
                                 .kind = Tolerance::absolute});
    fogradar::testing::validate({.id = id + "coherent_gain.exact" + size,
                                 .group = "radar: signal processing",
                                 .quantity = "coherent gain sum(w)/N",
                                 .unit = "1",
                                 .conditions = conditions,
                                 .reference = row.exact_cg,
                                 .source = "closed form: a0 of the periodic cosine sum",
                                 .value = cg,
                                 .tolerance = 1e-12,
                                 .kind = Tolerance::absolute});
    fogradar::testing::validate(
        {.id = id + "enbw.exact" + size,
         .group = "radar: signal processing",
         .quantity = "equivalent noise bandwidth N sum(w^2)/sum(w)^2",
         .unit = "bins",
         .conditions = conditions,
         .reference = row.exact_enbw,
         .source = "closed form: (a0^2 + sum a_m^2 / 2) / a0^2 of the periodic cosine sum",
         .value = enbw,
         .tolerance = 1e-12,
         .kind = Tolerance::absolute});
  }
}

constexpr double kBh0 = 0.35875, kBh1 = 0.48829, kBh2 = 0.14128, kBh3 = 0.01168;
INSTANTIATE_TEST_SUITE_P(
    Harris1978, HarrisTable,
    ::testing::Values(HarrisRow{WindowType::rectangular, 1.00, 1.00, 1.0, 1.0},
                      HarrisRow{WindowType::hann, 0.50, 1.50, 0.5, 1.5},
                      HarrisRow{WindowType::hamming, 0.54, 1.36, 0.54,
                                (0.54 * 0.54 + 0.46 * 0.46 / 2) / (0.54 * 0.54)},
                      HarrisRow{WindowType::blackman_harris, 0.36, 2.00, kBh0,
                                (kBh0 * kBh0 + (kBh1 * kBh1 + kBh2 * kBh2 + kBh3 * kBh3) / 2) /
                                    (kBh0 * kBh0)}),
    harris_row_name);

// Highest sidelobe against [H78] Table 1 (rectangular -13.3 dB, Hann -31.5 dB, Hamming -43 dB,
// 4-term Blackman-Harris -92 dB), zero-padded DFT at 1/64-bin resolution, periodic, N = 512.
// Tolerance 0.5 dB: the table rounds to 0.5-1 dB steps (the exact level of the 0.54/0.46
// Hamming window is -42.7 dB); the DFT-even truncation of Hamming (end sample 0.08) adds
// < 0.05 dB at N = 512 (about 0.2 dB at N = 64).
TEST(Window, HighestSidelobeMatchesHarrisTable) {
  const struct {
    WindowType type;
    double sidelobe_db;
  } rows[] = {{WindowType::hann, -31.5},
              {WindowType::hamming, -43.0},
              {WindowType::blackman_harris, -92.0},
              {WindowType::rectangular, -13.3}};
  for (const auto& row : rows) {
    const double measured = highest_sidelobe_db(make_window(row.type, 512));
    std::printf("[ measured ] %s highest sidelobe %.2f dB (Harris %.1f dB)\n",
                std::string(to_string(row.type)).c_str(), measured, row.sidelobe_db);
    fogradar::testing::validate(
        {.id = "radar.window." + std::string(to_string(row.type)) + ".highest_sidelobe",
         .group = "radar: signal processing",
         .quantity = "highest sidelobe level",
         .unit = "dB",
         .conditions = std::string(to_string(row.type)) +
                       " window, periodic, N = 512, zero-padded DFT at 1/64 bin",
         .reference = row.sidelobe_db,
         .source = "Harris 1978 Table 1",
         .value = measured,
         .tolerance = 0.5,
         .kind = Tolerance::absolute});
  }
}

// [H78] §II: the DFT-even Hann window has exactly three non-zero N-point DFT bins,
// W[0] = N/2 and W[1] = W[N-1] = -N/4. Tolerance 1e-12 N.
TEST(Window, PeriodicHannHasThreeDftBins) {
  for (const std::size_t n : {8u, 64u, 100u, 1024u}) {
    const std::vector<double> w = make_window(WindowType::hann, n);
    ComplexVector buffer(w.begin(), w.end());
    const FftPlan plan(n, FftDirection::forward, {.placement = FftPlacement::in_place});
    plan.execute(buffer);
    const double nd = static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double expected = k == 0 ? nd / 2 : (k == 1 || k == n - 1) ? -nd / 4 : 0.0;
      const std::string id =
          "radar.window.hann.dft_bin.N" + std::to_string(n) + ".k" + std::to_string(k);
      const std::string conditions =
          "periodic Hann, N = " + std::to_string(n) + ", bin k = " + std::to_string(k);
      fogradar::testing::validate({.id = id + ".real",
                                   .group = "radar: signal processing",
                                   .quantity = "real part of the window's N-point DFT bin",
                                   .unit = "1",
                                   .conditions = conditions,
                                   .reference = expected,
                                   .source = "Harris 1978 §II: W[0] = N/2, W[1] = W[N-1] = -N/4",
                                   .value = buffer[k].real(),
                                   .tolerance = 1e-12 * nd,
                                   .kind = Tolerance::absolute});
      fogradar::testing::validate({.id = id + ".imag",
                                   .group = "radar: signal processing",
                                   .quantity = "imaginary part of the window's N-point DFT bin",
                                   .unit = "1",
                                   .conditions = conditions,
                                   .reference = 0.0,
                                   .source = "Harris 1978 §II: real, even DFT of the Hann window",
                                   .value = buffer[k].imag(),
                                   .tolerance = 1e-12 * nd,
                                   .kind = Tolerance::absolute});
    }
  }
}

// --- Symmetry and shape -----------------------------------------------------------------------

// Symmetric windows: w[j] = w[N-1-j]. Periodic windows: DFT-even symmetry w[j] = w[N-j] for
// j = 1..N-1; the cosine windows are the first N samples of their symmetric window of length
// N+1 [H78 §II], periodic Chebyshev is [0, symmetric Chebyshev of length N-1].
// Values in [0, 1], peak exactly 1 where a sample sits on the centre (periodic even N,
// symmetric odd N, always for Chebyshev). Tolerance 1e-12 (Chebyshev goes through an FFT).
class WindowShape : public ::testing::TestWithParam<WindowType> {};

TEST_P(WindowShape, SymmetryAndPeak) {
  const WindowType type = GetParam();
  for (const std::size_t n : {2u, 3u, 16u, 31u, 64u, 257u}) {
    const std::vector<double> sym = make_window(type, n, 80.0, WindowSymmetry::symmetric);
    const std::vector<double> per = make_window(type, n, 80.0, WindowSymmetry::periodic);
    ASSERT_EQ(sym.size(), n);
    ASSERT_EQ(per.size(), n);
    std::vector<double> per_expected;
    if (type == WindowType::chebyshev) {
      per_expected = make_window(type, n - 1, 80.0, WindowSymmetry::symmetric);
      per_expected.insert(per_expected.begin(), 0.0);
    } else {
      per_expected = make_window(type, n + 1, 80.0, WindowSymmetry::symmetric);
      per_expected.pop_back();
    }
    for (std::size_t j = 0; j < n; ++j) {
      EXPECT_NEAR(sym[j], sym[n - 1 - j], 1e-12) << to_string(type) << " N=" << n << " j=" << j;
      if (j > 0) {
        EXPECT_NEAR(per[j], per[n - j], 1e-12) << to_string(type) << " N=" << n << " j=" << j;
      }
      EXPECT_NEAR(per[j], per_expected[j], 1e-12) << to_string(type) << " N=" << n << " j=" << j;
      for (const double value : {per[j], sym[j]}) {
        EXPECT_GE(value, -1e-15) << to_string(type) << " N=" << n;
        EXPECT_LE(value, 1.0 + 1e-15) << to_string(type) << " N=" << n;
      }
    }
    const bool centred_per = n % 2 == 0 || type == WindowType::chebyshev;
    const bool centred_sym =
        n % 2 == 1 || type == WindowType::chebyshev || type == WindowType::rectangular;
    const std::string name(to_string(type));
    const auto validate_peak = [&](const std::vector<double>& w, const std::string& symmetry) {
      fogradar::testing::validate(
          {.id = "radar.window." + name + ".peak." + symmetry + ".N" + std::to_string(n),
           .group = "radar: signal processing",
           .quantity = "window peak (a sample on the centre)",
           .unit = "1",
           .conditions = name + " window, " + symmetry + ", N = " + std::to_string(n),
           .reference = 1.0,
           .source = "closed form: the window's normalisation, peak 1 at the centre [H78 §II]",
           .value = *std::max_element(w.begin(), w.end()),
           .tolerance = 1e-15,
           .kind = Tolerance::absolute});
    };
    if (centred_per) validate_peak(per, "periodic");
    if (centred_sym) validate_peak(sym, "symmetric");
  }
  EXPECT_EQ(make_window(type, 1), std::vector<double>{1.0});
}

INSTANTIATE_TEST_SUITE_P(AllWindows, WindowShape, ::testing::ValuesIn(kAllWindows), window_name);

// --- Dolph-Chebyshev --------------------------------------------------------------------------

// Symmetric Dolph-Chebyshev: the highest sidelobe of the zero-padded DFT (1/64-bin grid) equals
// the design level within 0.1 dB, and the window is equiripple: every sidelobe peak is within
// 0.1 dB of the design level [H78 §V.D; Dolph 1946]. Odd and even lengths.
TEST(ChebyshevWindow, SymmetricSidelobesEqualDesignLevel) {
  for (const double design_db : {50.0, 80.0, 100.0}) {
    for (const std::size_t n : {31u, 64u, 127u, 256u}) {
      const std::vector<double> w =
          make_window(WindowType::chebyshev, n, design_db, WindowSymmetry::symmetric);
      const std::vector<double> peaks = sidelobe_peaks_db(normalised_spectrum(w, 64));
      ASSERT_FALSE(peaks.empty());
      const auto [lowest, highest] = std::minmax_element(peaks.begin(), peaks.end());
      for (const auto& [which, level] : {std::pair<const char*, double>{"highest", *highest},
                                         std::pair<const char*, double>{"lowest", *lowest}}) {
        fogradar::testing::validate(
            {.id = "radar.window.chebyshev.symmetric." + std::string(which) + "_sidelobe.design" +
                   id_number(design_db) + "dB.N" + std::to_string(n),
             .group = "radar: signal processing",
             .quantity = std::string(which) + " sidelobe peak",
             .unit = "dB",
             .conditions = "symmetric Dolph-Chebyshev, design -" + id_number(design_db) +
                           " dB, N = " + std::to_string(n) + ", zero-padded DFT at 1/64 bin",
             .reference = -design_db,
             .source = "equiripple design level [H78 §V.D; Dolph 1946]",
             .value = level,
             .tolerance = 0.1,
             .kind = Tolerance::absolute});
      }
    }
  }
}

// Periodic (DFT-even) Chebyshev [0, symmetric N-1]: still equiripple at the design level
// within 0.1 dB (zero-padded DFT, 1/64-bin grid). The rejected alternative, truncating a length
// N+1 design, is printed for comparison: it is several dB worse.
TEST(ChebyshevWindow, PeriodicSidelobesEqualDesignLevel) {
  for (const double design_db : {60.0, 80.0}) {
    for (const std::size_t n : {64u, 128u, 512u}) {
      const std::vector<double> w = make_window(WindowType::chebyshev, n, design_db);
      const std::vector<double> peaks = sidelobe_peaks_db(normalised_spectrum(w, 64));
      const auto [lowest, highest] = std::minmax_element(peaks.begin(), peaks.end());
      std::vector<double> truncated =
          make_window(WindowType::chebyshev, n + 1, design_db, WindowSymmetry::symmetric);
      truncated.pop_back();
      std::printf(
          "[ measured ] Chebyshev N=%zu design -%.0f dB: periodic highest sidelobe "
          "%.2f dB; truncated N+1 design would give %.2f dB\n",
          n, design_db, *highest, highest_sidelobe_db(truncated));
      for (const auto& [which, level] : {std::pair<const char*, double>{"highest", *highest},
                                         std::pair<const char*, double>{"lowest", *lowest}}) {
        fogradar::testing::validate(
            {.id = "radar.window.chebyshev.periodic." + std::string(which) + "_sidelobe.design" +
                   id_number(design_db) + "dB.N" + std::to_string(n),
             .group = "radar: signal processing",
             .quantity = std::string(which) + " sidelobe peak",
             .unit = "dB",
             .conditions = "periodic Dolph-Chebyshev, design -" + id_number(design_db) +
                           " dB, N = " + std::to_string(n) + ", zero-padded DFT at 1/64 bin",
             .reference = -design_db,
             .source = "equiripple design level [H78 §V.D; Dolph 1946]",
             .value = level,
             .tolerance = 0.1,
             .kind = Tolerance::absolute});
      }
    }
  }
}

// --- Names and invalid input ------------------------------------------------------------------

TEST(FrameWindow, ScalesEachSampleByBothWeights) {
  // Reference: each complex sample times the real product w_d[c] w_r[n] in std::complex
  // arithmetic (both parts times the same double); tolerance: identical values. 5 x 7 samples,
  // an odd row length, with distinct weights.
  const std::vector<double> doppler = make_window(WindowType::hamming, 5);
  const std::vector<double> range =
      make_window(WindowType::blackman_harris, 7, 80.0, WindowSymmetry::symmetric);
  std::vector<double> range_pairs;
  for (const double w : range) range_pairs.insert(range_pairs.end(), {w, w});
  std::vector<std::complex<double>> frame, expected;
  for (std::size_t c = 0; c < doppler.size(); ++c) {
    for (std::size_t n = 0; n < range.size(); ++n) {
      frame.emplace_back(1.0 + 0.1 * static_cast<double>(c * 7 + n),
                         -2.0 + 0.3 * static_cast<double>(n));
      expected.push_back(frame.back() * (doppler[c] * range[n]));
    }
  }
  apply_frame_window({doppler, range_pairs}, frame);
  EXPECT_EQ(frame, expected);
}

TEST(Window, NamesRoundTrip) {
  for (const WindowType type : kAllWindows)
    EXPECT_EQ(window_type_names.parse(to_string(type), "window"), type);
  try {
    window_type_names.parse("Hanning", "processing.range_window");
    ADD_FAILURE() << "accepted an unknown window name";
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.field(), "processing.range_window");
    EXPECT_NE(std::string(error.what()).find("blackman_harris"), std::string::npos);
  }
}

TEST(Window, RejectsInvalidParameters) {
  const auto expect_field = [](auto&& call, const std::string& field) {
    EXPECT_EQ(test_support::rejected_field(call), field);
  };
  expect_field([] { make_window(WindowType::hann, 0); }, "window.n");
  for (const double level : {0.0, 12.0, 301.0, std::numeric_limits<double>::quiet_NaN()}) {
    expect_field([level] { make_window(WindowType::chebyshev, 64, level); },
                 "window.chebyshev_sidelobe_db");
  }
  // The sidelobe level is only read for Chebyshev.
  EXPECT_NO_THROW(make_window(WindowType::hann, 64, std::numeric_limits<double>::quiet_NaN()));
}

}  // namespace
}  // namespace fogradar::radar
