// The range_doppler CFAR (a ring of reference cells over the range-Doppler map, cfar.hpp), tested
// against independent references: the ring counted cell by cell, its limiting case (no Doppler
// rows: the range CFAR of every row), the realised false-alarm rate of noise-only frames through
// the real chain with a Hann window in both dimensions against the design value (Clopper-Pearson
// interval, Boost.Math), and a slow target beside a zero-Doppler clutter ridge.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <boost/math/distributions/binomial.hpp>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/radar/cfar_design.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/processing.hpp"
#include "fogradar/radar/synthesis.hpp"
#include "validation.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;

CfarConfig ring_config(CfarKind kind, unsigned guard, unsigned training, unsigned doppler_guard,
                       unsigned doppler_training) {
  CfarConfig c;
  c.kind = kind;
  c.guard_cells = guard;
  c.training_cells = training;
  c.shape = CfarShape::range_doppler;
  c.doppler_guard_cells = doppler_guard;
  c.doppler_training_cells = doppler_training;
  return c;
}

// The interior ring counted cell by cell: the window's rectangle less the guard rectangle.
TEST(CfarRing, InteriorRingIsTheRectangleLessTheGuardRectangle) {
  for (const auto& [g, n, gd, nd] : std::vector<std::array<unsigned, 4>>{
           {2, 8, 1, 2}, {0, 3, 0, 1}, {1, 4, 2, 0}, {3, 2, 0, 3}}) {
    const CfarConfig c = ring_config(CfarKind::ca, g, n, gd, nd);
    const std::vector<CfarCellOffset> ring = cfar_ring_offsets(c, g + n);
    std::set<std::pair<long, long>> expected;
    const long a = g + n, b = gd + nd;
    for (long dk = -a; dk <= a; ++dk) {
      for (long dd = -b; dd <= b; ++dd) {
        if (std::abs(dk) <= static_cast<long>(g) && std::abs(dd) <= static_cast<long>(gd)) continue;
        expected.insert({dk, dd});
      }
    }
    std::set<std::pair<long, long>> got;
    for (const CfarCellOffset& o : ring) got.insert({o.range, o.doppler});
    EXPECT_EQ(got.size(), ring.size()) << "no cell twice";
    EXPECT_EQ(got, expected);
    EXPECT_EQ(ring.size(), c.shape_reference_cells());
    // The halves: the cells before the cell under test (its own column's lower rows) and after.
    for (std::size_t j = 0; j < ring.size(); ++j) {
      const bool before = ring[j].range < 0 || (ring[j].range == 0 && ring[j].doppler < 0);
      EXPECT_EQ(before, j < ring.size() / 2) << "cell " << j;
    }
  }
}

// No Doppler rows (doppler guard = training = 0): the ring is the range CFAR's reference cells, and
// the map's thresholds and detections are the range CFAR's in every row, for every kind, with the
// correlated design for a Hann range window (the same geometries, the same solved factors).
TEST(CfarRing, WithoutDopplerRowsItIsTheRangeCfarOfEveryRow) {
  const std::size_t rows = 6, columns = 96;
  const std::vector<double> hann = make_window(WindowType::hann, columns);
  const NoiseCorrelation range_noise = window_noise_correlation(hann, 40);
  const NoiseCorrelation doppler_noise =
      window_noise_correlation(make_window(WindowType::hann, rows), rows - 1);
  RandomStream rng(77);
  std::vector<double> power(rows * columns);
  for (double& x : power) x = std::norm(rng.complex_normal(1.0));
  power[3 * columns + 40] = 300.0;  // a target and a strong cell near an edge
  power[1 * columns + 2] = 80.0;
  for (const CfarKind kind : {CfarKind::ca, CfarKind::go, CfarKind::so, CfarKind::os}) {
    CfarConfig one_row = ring_config(kind, 2, 8, 0, 0);
    const CfarDetector ring(one_row, range_noise, doppler_noise);
    one_row.shape = CfarShape::range;
    const CfarDetector range(one_row, range_noise);
    EXPECT_EQ(ring.threshold_factor(), range.threshold_factor()) << to_string(kind);
    for (std::size_t i = 0; i < 10; ++i)
      EXPECT_EQ(ring.edge_threshold_factor(i), range.edge_threshold_factor(i)) << i;
    CfarMapWorkspace map_ws;
    ring.detect_map(power, rows, map_ws);
    CfarWorkspace ws;
    std::vector<std::size_t> detections;
    for (std::size_t d = 0; d < rows; ++d) {
      range.detect(std::span<const double>(power).subspan(d * columns, columns), ws);
      for (std::size_t k = 0; k < columns; ++k) {
        // The sums are added in another order: equal to rounding.
        EXPECT_NEAR(map_ws.threshold[d * columns + k], ws.threshold[k], 1e-12 * ws.threshold[k])
            << to_string(kind) << " row " << d << " cell " << k;
      }
      for (const std::size_t k : ws.detections) detections.push_back(d * columns + k);
    }
    EXPECT_EQ(map_ws.detections, detections) << to_string(kind);
  }
}

// The keys: the Doppler rows fit the map (distinct around the circular Doppler axis), the ring at
// most kCfarRingMaxCells, each refused naming its key; the Doppler keys only with the ring.
TEST(CfarRing, KeysRefuseWhatDoesNotFit) {
  RadarParams p;
  p.chirps_per_frame = 8;
  p.cfar = ring_config(CfarKind::ca, 2, 8, 1, 3);  // 2 (1 + 3) + 1 = 9 rows > 8
  try {
    p.validate();
    FAIL() << "accepted 9 Doppler rows in a map of 8";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("radar.processing.cfar.doppler_training_cells"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("[0, 2]"), std::string::npos) << e.what();
  }
  p.cfar.doppler_training_cells = 2;
  EXPECT_NO_THROW(p.validate());
  p.chirps_per_frame = 64;
  p.cfar = ring_config(CfarKind::ca, 2, 8, 1, 10);  // 16 x 23 + 20 x 5 = 468 cells
  EXPECT_NO_THROW(p.validate());
  p.cfar.doppler_training_cells = 11;  // 16 x 25 + 22 x 5 = 510
  EXPECT_NO_THROW(p.validate());
  p.cfar.doppler_training_cells = 12;  // 16 x 27 + 24 x 5 = 552 > 512
  EXPECT_THROW(p.validate(), InvalidParameter);
  // The OS rank's bound is the ring's N.
  p.cfar = ring_config(CfarKind::os, 2, 8, 1, 2);  // N = 16 x 7 + 4 x 5 = 132
  p.cfar.os_rank = 132;
  EXPECT_NO_THROW(p.validate());
  p.cfar.os_rank = 133;
  EXPECT_THROW(p.validate(), InvalidParameter);
}

// Noise-only frames of `rows` x 256 through the chain (synthesis with thermal noise, the Hann
// frame window in both dimensions, range and Doppler FFTs, |X|^2), every map through the ring; the
// interior (range) and edge alarms counted per frame.
struct MapRate {
  double interior = 0, edges = 0, interior_cells = 0, edge_cells = 0;
  double interior_squares = 0, edge_squares = 0, frames = 0;
};

MapRate realised_map_rate(const RadarParams& p, const CfarDetector& detector, std::size_t frames,
                          std::uint64_t stream) {
  const RadarDerived d = derive(p);
  const RangeDopplerProcessor processor(p);
  const std::size_t rows = p.chirps_per_frame, cols = p.samples_per_chirp;
  const std::size_t edge = p.cfar.guard_cells + p.cfar.training_cells;
  ComplexVector frame(rows * cols);
  std::vector<double> power(rows * cols);
  CfarMapWorkspace ws;
  MapRate rate;
  const FrameWindow window = processor.window();
  for (std::size_t f = 0; f < frames; ++f) {
    RandomStream rng(2026, stream, f);
    synthesize_frame({}, p, d, rng, frame, &window);
    processor.transform_windowed(frame);
    squared_magnitudes(frame, power);
    detector.detect_map(power, rows, ws);
    double interior = 0, edges = 0;
    for (const std::size_t cell : ws.detections) {
      const std::size_t k = cell % cols;
      (k < edge || k >= cols - edge ? edges : interior) += 1;
    }
    rate.interior += interior;
    rate.edges += edges;
    rate.interior_squares += interior * interior;
    rate.edge_squares += edges * edges;
    rate.frames += 1;
    rate.interior_cells += static_cast<double>(rows * (cols - 2 * edge));
    rate.edge_cells += static_cast<double>(rows * 2 * edge);
  }
  return rate;
}

// The 99.9 % bounds of a realised rate of `alarms` in `cells` cells against the design rate p:
// neighbouring cells share reference cells (one small noise estimate raises several alarms), so the
// per-frame counts vary by deff = their variance over the binomial one (at least 1; Kish 1965,
// Survey Sampling, the design effect), and the binomial bounds are taken on the effective sample
// cells / deff. `accept`: the rates an exact equal-tailed binomial test at p accepts (Boost.Math
// quantiles at 0.0005 and 0.9995); `clopper_pearson`: the realised rate's two-sided 99.9 %
// Clopper-Pearson interval, its dual (p inside it exactly when the rate is accepted, up to the
// count's rounding).
struct RateBounds {
  std::pair<double, double> accept, clopper_pearson;
};

RateBounds rate_bounds(double alarms, double cells, double squares, double frames, double p) {
  const double mean = alarms / frames;
  const double seen = (squares / frames - mean * mean) * frames / (frames - 1.0);
  const double binomial = cells / frames * p * (1.0 - p);
  const double deff = std::max(1.0, seen / binomial);
  using boost::math::binomial_distribution;
  const double trials = std::floor(cells / deff), successes = std::round(alarms / deff);
  const binomial_distribution<> design(trials, p);
  return {{boost::math::quantile(design, 0.0005) / trials,
           boost::math::quantile(design, 0.9995) / trials},
          {binomial_distribution<>::find_lower_bound_on_p(trials, successes, 0.0005),
           binomial_distribution<>::find_upper_bound_on_p(trials, successes, 0.0005)}};
}

class RingRealisedPfa : public ::testing::TestWithParam<CfarKind> {};

#ifdef FOGRADAR_SANITIZE_BUILD
constexpr std::size_t kFrames = 40;
#else
constexpr std::size_t kFrames = 400;
#endif

// Design P_fa 1e-3, Hann in range and Doppler, g = 1, n = 4, g_d = 1, n_d = 2 (N = 68), maps of
// 32 x 256 through the chain's detector (RadarChain builds it the same way): 400 frames, 2.6e6
// interior and 2.6e5 edge cells. Acceptance: the design value inside the 99.9 % Clopper-Pearson
// interval of the realised rate (clopper_pearson). The same frames with the independent-cell
// factor (threshold_design = independent) are printed beside it.
TEST_P(RingRealisedPfa, DesignValueAtOneInAThousandWithHannInBothDimensions) {
  const CfarKind kind = GetParam();
  RadarParams p;
  p.window = WindowType::hann;
  p.samples_per_chirp = 256;
  p.chirps_per_frame = 32;
  p.cfar = ring_config(kind, 1, 4, 1, 2);
  p.cfar.false_alarm_probability = 1e-3;
  const RangeDopplerProcessor processor(p);
  const NoiseCorrelation range_noise =
      window_noise_correlation(processor.range_window(), cfar_correlation_lags(p.cfar));
  const NoiseCorrelation doppler_noise =
      window_noise_correlation(processor.doppler_window(), cfar_doppler_correlation_lags(p.cfar));
  const CfarDetector detector(p.cfar, range_noise, doppler_noise);
  const MapRate rate = realised_map_rate(p, detector, kFrames, 40 + static_cast<int>(kind));
  CfarConfig iid = p.cfar;
  iid.threshold_design = CfarThresholdDesign::independent;
  const MapRate iid_rate = realised_map_rate(p, CfarDetector(iid, range_noise, doppler_noise),
                                             kFrames, 40 + static_cast<int>(kind));
  const RateBounds interior =
      rate_bounds(rate.interior, rate.interior_cells, rate.interior_squares, rate.frames, 1e-3);
  const RateBounds edge =
      rate_bounds(rate.edges, rate.edge_cells, rate.edge_squares, rate.frames, 1e-3);
  std::printf(
      "[ measured ] ring %s: interior %.4e (accept [%.4e, %.4e], Clopper-Pearson [%.4e, %.4e]), "
      "edge %.4e (accept [%.4e, %.4e]); independent factor: interior %.4e, edge %.4e\n",
      std::string(to_string(kind)).c_str(), rate.interior / rate.interior_cells,
      interior.accept.first, interior.accept.second, interior.clopper_pearson.first,
      interior.clopper_pearson.second, rate.edges / rate.edge_cells, edge.accept.first,
      edge.accept.second, iid_rate.interior / iid_rate.interior_cells,
      iid_rate.edges / iid_rate.edge_cells);
  const std::string conditions = "range_doppler " + std::string(to_string(kind)) +
                                 ", g = 1, n = 4, g_d = 1, n_d = 2 (68 cells), Hann in range and "
                                 "Doppler, " +
                                 std::to_string(kFrames) + " noise-only maps of 32 x 256";
  const std::string confidence =
      "99.9 % exact binomial acceptance interval of the design P_fa (dual of Clopper-Pearson; "
      "Boost.Math) on the effective sample, cells / design effect of the per-frame counts";
  for (const auto& [part, alarms, cells, bounds] :
       {std::tuple{"interior", rate.interior, rate.interior_cells, interior},
        std::tuple{"edge", rate.edges, rate.edge_cells, edge}}) {
    fogradar::testing::validate({.id = "radar.cfar_ring.chain." + std::string(to_string(kind)) +
                                       ".hann." + part + ".pfa1e-3",
                                 .group = "radar: CFAR",
                                 .quantity = std::string("realised P_fa of the range-Doppler "
                                                         "ring, ") +
                                             part + " cells",
                                 .unit = "1",
                                 .conditions = conditions,
                                 .reference = 1e-3,
                                 .source = "design P_fa (noise-only frames through the chain)",
                                 .value = alarms / cells,
                                 .tolerance = 0.0,
                                 .kind = Tolerance::statistical,
                                 .samples = static_cast<std::size_t>(cells),
                                 .interval_low = bounds.accept.first,
                                 .interval_high = bounds.accept.second,
                                 .confidence = confidence,
                                 .plot = "cfar_pfa",
                                 .x = 1e-3,
                                 .x_label = "design P_fa"});
    EXPECT_LE(bounds.clopper_pearson.first, 1e-3) << part;
    EXPECT_GE(bounds.clopper_pearson.second, 1e-3) << part;
  }
  // The bounds are narrow enough to see the independent-cell factor's excess (1.35-2.9 x).
  EXPECT_GT(iid_rate.interior / iid_rate.interior_cells, interior.accept.second);
}

INSTANTIATE_TEST_SUITE_P(EveryKind, RingRealisedPfa,
                         ::testing::Values(CfarKind::ca, CfarKind::go, CfarKind::so, CfarKind::os),
                         [](const auto& kind_info) {
                           return std::string(to_string(kind_info.param));
                         });

// A frame of white noise (unit variance per sample) and tones centred on range cell k and Doppler
// bin d, each of `snr_db` per cell after the chain's gains, through the chain's windows and FFTs.
std::vector<double> clutter_map(const RangeDopplerProcessor& processor,
                                const std::vector<std::array<double, 3>>& tones,  // k, d, snr_db
                                std::uint64_t seed) {
  const std::size_t rows = processor.chirps(), columns = processor.samples();
  ComplexVector frame(rows * columns);
  RandomStream rng(seed);
  for (auto& x : frame) x = rng.complex_normal(1.0);
  for (const auto& [k, d, snr_db] : tones) {
    const double a = std::sqrt(std::pow(10.0, snr_db / 10.0) * processor.noise_power_gain()) /
                     processor.coherent_amplitude_gain();
    const double phase0 = 2.0 * std::numbers::pi * rng.uniform();
    for (std::size_t c = 0; c < rows; ++c)
      for (std::size_t n = 0; n < columns; ++n)
        frame[c * columns + n] +=
            std::polar(a, phase0 + 2.0 * std::numbers::pi *
                                       (k * static_cast<double>(n) / static_cast<double>(columns) +
                                        d * static_cast<double>(c) / static_cast<double>(rows)));
  }
  std::vector<double> power(rows * columns);
  processor.process(frame, power);
  return power;
}

// Zero-Doppler clutter in a synthetic frame (bench/cfar_clutter's; the room's own table is
// scripts/cfar-room.sh's, docs/radar.md §7.1): a band of static scatterers in range cells 200-259
// at +25 dB per cell and two barrels at cells 300 and 310 at +40 dB, Hann in both dimensions, 512 x
// 64, design P_fa 1e-6, g = 2, n = 8 (ring: g_d = 1, n_d = 2). What happens, over 4 noise draws
// each: a slow target of +20 dB at (230, Doppler 3), inside the wall's range extent, is kept by the
// range CA-CFAR (its row holds no clutter: static tones leak only into Doppler bins 0 and +-1
// through Hann) and masked by the ring's CA (its Doppler training rows reach the wall's rows); a
// target at zero Doppler between the barrels (305, 0) is masked by the range OS-CFAR (6 of its 16
// cells are barrel) and kept by the ring's OS (18 of 132).
TEST(CfarRing, ZeroDopplerClutterBesideASlowTarget) {
  RadarParams p;
  const RangeDopplerProcessor processor(p);
  const std::size_t rows = p.chirps_per_frame, columns = p.samples_per_chirp;
  std::vector<std::array<double, 3>> clutter;
  for (int k = 200; k < 260; ++k) clutter.push_back({static_cast<double>(k), 0.0, 25.0});
  clutter.push_back({300.0, 0.0, 40.0});
  clutter.push_back({310.0, 0.0, 40.0});
  const auto detector = [&](CfarKind kind, CfarShape shape) {
    CfarConfig c = p.cfar;
    c.kind = kind;
    c.shape = shape;
    return CfarDetector(
        c, window_noise_correlation(processor.range_window(), cfar_correlation_lags(c)),
        window_noise_correlation(processor.doppler_window(), cfar_doppler_correlation_lags(c)));
  };
  const CfarDetector range_ca = detector(CfarKind::ca, CfarShape::range);
  const CfarDetector ring_ca = detector(CfarKind::ca, CfarShape::range_doppler);
  const CfarDetector range_os = detector(CfarKind::os, CfarShape::range);
  const CfarDetector ring_os = detector(CfarKind::os, CfarShape::range_doppler);
  const auto kept = [&](const CfarDetector& cfar, double k, double d, std::uint64_t seed) {
    const CfarShape shape = cfar.config().shape;
    std::vector<std::array<double, 3>> tones = clutter;
    tones.push_back({k, d, 20.0});
    const std::vector<double> power = clutter_map(processor, tones, seed);
    const std::size_t cell = static_cast<std::size_t>(d) * columns + static_cast<std::size_t>(k);
    if (shape == CfarShape::range_doppler) {
      CfarMapWorkspace ws;
      cfar.detect_map(power, rows, ws);
      return std::binary_search(ws.detections.begin(), ws.detections.end(), cell);
    }
    CfarWorkspace ws;
    cfar.detect(
        std::span<const double>(power).subspan(static_cast<std::size_t>(d) * columns, columns), ws);
    return std::binary_search(ws.detections.begin(), ws.detections.end(),
                              static_cast<std::size_t>(k));
  };
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    EXPECT_TRUE(kept(range_ca, 230, 3, seed)) << seed;
    EXPECT_FALSE(kept(ring_ca, 230, 3, seed)) << seed;
    EXPECT_FALSE(kept(range_os, 305, 0, seed)) << seed;
    EXPECT_TRUE(kept(ring_os, 305, 0, seed)) << seed;
  }
}

}  // namespace
}  // namespace fogradar::radar
