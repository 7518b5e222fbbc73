// The fog return (fog_return.hpp: the pulse convolved with the fog's range profile on a node grid
// of the waveform's samples) against a straightforward numerical integral written out here, for
// several fogs, pulse widths, sample intervals and layer layouts, and against the erf closed forms
// of a uniform slab.
//
// The reference integrates the model the code computes, the lidar equation's fog term
// integral p(t - 2r/c) beta_pi T^2(r) O(r) / r^2 dr with the pulse cut 2 FWHM from its centre, by
// composite 20-point Gauss-Legendre (Boost.Math) in panels of at most 1 cm, broken at the layer's
// edges, the overlap kink and the cut (where the integrand jumps): its own error is below 1e-12.
//
// Tolerance: 3e-6 of the largest sample of the reference. The rule's corrected end weights are
// exact for polynomials of degree 7 over 8 node steps of at most sigma / 4 (fog_return.hpp), which
// the worst cases below meet to 2e-6; the pulse's cut, a jump of p(2 fwhm) = 1.5e-5 that the
// trapezoidal sum puts at most half a node step off, costs at most 1.5e-5 h / (2 tau_e) = 4e-7 of a
// plateau at h = sigma / 4 (tau_e = 1.064 fwhm the pulse's energy width).
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/lidar/fog_return.hpp"
#include "fogradar/lidar/waveform.hpp"
#include "validation.hpp"

namespace fogradar::lidar {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

constexpr double c = 299792458.0;
constexpr double ln2 = std::numbers::ln2;
constexpr double pi = std::numbers::pi;
constexpr double tolerance = 3e-6;

std::string str(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// One stretch's fog term at sample k, straight from its definition.
double reference_sample(const WaveformGrid& grid, const FogStretch& fog, std::size_t k) {
  using Rule = boost::math::quadrature::gauss<double, 20>;
  const double a = 4.0 * ln2 / (grid.pulse_fwhm_s * grid.pulse_fwhm_s);
  const double t = static_cast<double>(k) * grid.sample_interval_s;
  const double cut_m = c * 2.0 * grid.pulse_fwhm_s / 2.0;
  const double lo = std::max(fog.start_m, c * t / 2.0 - cut_m);
  const double hi = std::min(fog.end_m, c * t / 2.0 + cut_m);
  if (!(hi > lo)) return 0.0;
  std::vector<double> breaks{lo, hi};
  if (grid.full_overlap_range_m > lo && grid.full_overlap_range_m < hi) {
    breaks.push_back(grid.full_overlap_range_m);
  }
  std::sort(breaks.begin(), breaks.end());
  const auto integrand = [&](double r) {
    const double x = t - 2.0 * r / c;
    const double o =
        std::min(1.0, (r / grid.full_overlap_range_m) * (r / grid.full_overlap_range_m));
    return std::exp(-a * x * x) * fog.backscatter_per_m_sr * fog.transmittance_at_start *
           std::exp(-2.0 * fog.extinction_per_m * (r - fog.start_m)) * o / (r * r);
  };
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const auto panels = static_cast<std::size_t>(std::ceil((breaks[i + 1] - breaks[i]) / 0.01));
    const double width =
        (breaks[i + 1] - breaks[i]) / static_cast<double>(std::max<std::size_t>(1, panels));
    for (std::size_t p = 0; p < std::max<std::size_t>(1, panels); ++p) {
      const double from = breaks[i] + static_cast<double>(p) * width;
      sum += Rule::integrate(integrand, from, from + width);
    }
  }
  return sum;
}

struct Case {
  std::string name;
  WaveformGrid grid;
  // Layers as [start, end, alpha, beta]; each is entered with the two-way transmittance of those
  // before it, as the sensor's trace does.
  std::vector<std::array<double, 4>> layers;
};

std::vector<FogStretch> stretches_of(const Case& test) {
  std::vector<FogStretch> out;
  double transmittance = 1.0;
  for (const auto& [start, end, alpha, beta] : test.layers) {
    out.push_back({.start_m = start,
                   .end_m = end,
                   .extinction_per_m = alpha,
                   .backscatter_per_m_sr = beta,
                   .transmittance_at_start = transmittance});
    transmittance *= std::exp(-2.0 * alpha * (end - start));
  }
  return out;
}

void check_against_reference(const Case& test) {
  const std::vector<FogStretch> stretches = stretches_of(test);
  const double last_m = stretches.back().end_m;
  const auto samples = static_cast<std::size_t>(
      (2.0 * (last_m + 2.0) / c + 4.0 * test.grid.pulse_fwhm_s) / test.grid.sample_interval_s);
  std::vector<double> w(samples, 0.0);
  FogReturn(test.grid).add(w, stretches);
  std::vector<double> reference(samples, 0.0);
  for (const FogStretch& fog : stretches) {
    for (std::size_t k = 0; k < samples; ++k) reference[k] += reference_sample(test.grid, fog, k);
  }
  const double peak = *std::max_element(reference.begin(), reference.end());
  double worst = 0.0;
  for (std::size_t k = 0; k < samples; ++k) worst = std::max(worst, std::abs(w[k] - reference[k]));
  validate({.id = "lidar.fog_return." + test.name,
            .group = "lidar",
            .quantity = "fog return: largest difference from the reference over the record, "
                        "over the reference's peak",
            .unit = "1",
            .conditions = test.name + ": dt " + str(test.grid.sample_interval_s * 1e9) +
                          " ns, fwhm " + str(test.grid.pulse_fwhm_s * 1e9) + " ns, full overlap " +
                          str(test.grid.full_overlap_range_m) + " m, " +
                          std::to_string(test.layers.size()) + " layer(s)",
            .reference = 0.0,
            .source = "numerical integral written out in the test: composite 20-point "
                      "Gauss-Legendre (Boost.Math), 1 cm panels broken at the integrand's jumps",
            .value = worst / peak,
            .tolerance = tolerance,
            .kind = Tolerance::at_most});
}

constexpr WaveformGrid paper_grid{
    .sample_interval_s = 0.5e-9, .pulse_fwhm_s = 5e-9, .full_overlap_range_m = 0.5};

// The study's chamber: four 1 m layers from 2 m, the paper's fog (alpha 0.9 /m at 905 nm) with the
// scan-to-scan fluctuation's spread of factors.
TEST(LidarFogReturn, PaperChamberMatchesTheReference) {
  check_against_reference({"paper_chamber",
                           paper_grid,
                           {{2.0, 3.0, 0.9, 7.3e-3},
                            {3.0, 4.0, 1.3, 1.05e-2},
                            {4.0, 5.0, 0.6, 4.8e-3},
                            {5.0, 6.0, 0.9, 7.3e-3}}});
}

// A beam at 37 degrees through the same chamber: edges off the node grid, layers 1.25 m long.
TEST(LidarFogReturn, ObliqueBeamMatchesTheReference) {
  check_against_reference({"oblique_beam",
                           paper_grid,
                           {{2.5043, 3.7564, 0.9, 7.3e-3},
                            {3.7564, 5.0085, 0.9, 7.3e-3},
                            {5.0085, 6.2606, 0.9, 7.3e-3}}});
}

// A chamber unlike the paper's: a thin dense layer, an air gap, a long light layer, a 3 cm sliver
// of very dense fog (alpha 12 /m: the node step falls to dt / 4), and a layer straddling the
// overlap kink (full overlap at 1.5 m).
TEST(LidarFogReturn, UnevenChamberMatchesTheReference) {
  WaveformGrid grid = paper_grid;
  grid.full_overlap_range_m = 1.5;
  check_against_reference({"uneven_chamber",
                           grid,
                           {{0.8, 2.1, 0.9, 7.3e-3},
                            {2.37, 2.81, 3.5, 4.0e-2},
                            {4.1, 9.6, 0.2, 1.6e-3},
                            {9.6, 9.63, 12.0, 0.1}}});
}

// Other pulses and samplings: a short pulse sampled coarsely (dt = fwhm / 2: nodes at dt / 4),
// a long pulse sampled finely (nodes every 10 samples), a fog inside the overlap range from r = 0.
TEST(LidarFogReturn, OtherPulsesAndSamplingsMatchTheReference) {
  check_against_reference(
      {"short_pulse_coarse_sampling",
       {.sample_interval_s = 1e-9, .pulse_fwhm_s = 2e-9, .full_overlap_range_m = 0.5},
       {{2.0, 3.3, 0.9, 7.3e-3}, {3.3, 4.0, 2.5, 2.0e-2}}});
  check_against_reference(
      {"long_pulse_fine_sampling",
       {.sample_interval_s = 0.1e-9, .pulse_fwhm_s = 20e-9, .full_overlap_range_m = 0.5},
       {{2.0, 6.0, 0.9, 7.3e-3}, {7.0, 8.0, 0.3, 2.0e-3}}});
  check_against_reference(
      {"inside_overlap_from_zero",
       {.sample_interval_s = 0.5e-9, .pulse_fwhm_s = 5e-9, .full_overlap_range_m = 3.0},
       {{0.0, 1.7, 0.9, 7.3e-3}, {1.7, 4.5, 0.4, 3.0e-3}}});
}

// Inside the overlap range O / r^2 = 1 / r_full^2, so a uniform slab [a, b] has the profile
// beta T^2(a) exp(-alpha c (tau - tau_a)) / r_full^2 in round-trip time tau = 2r/c, and its return
// is the Gaussian convolved with a truncated exponential (completing the square):
//   (c/2) beta T^2(a) / r_full^2 exp(-lambda (t - tau_a) + lambda^2 / (4A)) sqrt(pi / A) / 2
//   [erf(sqrt(A) (tau_b - t')) - erf(sqrt(A) (tau_a - t'))],  t' = t - lambda / (2A),
// lambda = alpha c, A = 4 ln 2 / fwhm^2. The closed form is the uncut pulse's: the tolerance adds
// the cut tails' erfc(4 sqrt(ln 2)) / 2 = 1.5e-6 of the plateau per side to the rule's 3e-6.
// erf(x) - erf(y), x >= y, without the cancellation of two values near 1 (or -1).
double erf_difference(double x, double y) {
  if (y > 0.0) return std::erfc(y) - std::erfc(x);
  if (x < 0.0) return std::erfc(-x) - std::erfc(-y);
  return std::erf(x) - std::erf(y);
}

void check_closed_form(const std::string& name, double start_m, double end_m, double alpha) {
  const WaveformGrid grid{
      .sample_interval_s = 0.5e-9, .pulse_fwhm_s = 5e-9, .full_overlap_range_m = 40.0};
  const double beta = 2e-3, t0 = 0.7;
  const std::size_t samples = 300;  // 22.5 m: a slab ending beyond it is semi-infinite
  std::vector<double> w(samples, 0.0);
  FogReturn(grid).add(w, FogStretch{.start_m = start_m,
                                    .end_m = end_m,
                                    .extinction_per_m = alpha,
                                    .backscatter_per_m_sr = beta,
                                    .transmittance_at_start = t0});
  const double a = 4.0 * ln2 / (grid.pulse_fwhm_s * grid.pulse_fwhm_s);
  const double lambda = alpha * c;
  const double tau_a = 2.0 * start_m / c, tau_b = 2.0 * end_m / c;
  const double plateau = c / 2.0 * beta * t0 / (40.0 * 40.0) * std::sqrt(pi / a);
  double worst = 0.0;
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) * grid.sample_interval_s;
    const double shifted = t - lambda / (2.0 * a);
    const double expected =
        c / 2.0 * beta * t0 / (40.0 * 40.0) *
        std::exp(-lambda * (t - tau_a) + lambda * lambda / (4.0 * a)) * std::sqrt(pi / a) / 2.0 *
        erf_difference(std::sqrt(a) * (tau_b - shifted), std::sqrt(a) * (tau_a - shifted));
    worst = std::max(worst, std::abs(w[k] - expected));
  }
  validate({.id = "lidar.fog_return.closed_form." + name,
            .group = "lidar",
            .quantity = "fog return of a uniform slab: largest difference from the closed form, "
                        "over the uncut plateau",
            .unit = "1",
            .conditions = name + ": slab " + str(start_m) + "-" + str(end_m) + " m, alpha " +
                          str(alpha) + " /m, inside the overlap range, 5 ns FWHM, 0.5 ns samples",
            .reference = 0.0,
            .source = "closed form: Gaussian pulse convolved with a truncated exponential, erf",
            .value = worst / plateau,
            .tolerance = tolerance + 3e-6,
            .kind = Tolerance::at_most});
}

TEST(LidarFogReturn, UniformSlabsMatchTheirErfClosedForms) {
  check_closed_form("transparent_finite", 5.0, 8.37, 0.0);
  check_closed_form("absorbing_finite", 4.21, 6.02, 0.9);
  check_closed_form("dense_thin", 7.0, 7.2, 8.0);
  check_closed_form("semi_infinite", 3.33, 60.0, 0.15);
}

// A part of the record, from first_sample on, gets exactly the values the whole record would.
TEST(LidarFogReturn, PartOfTheRecordHasTheWholeRecordsValues) {
  const FogStretch fog{.start_m = 2.3,
                       .end_m = 3.4,
                       .extinction_per_m = 0.9,
                       .backscatter_per_m_sr = 7.3e-3,
                       .transmittance_at_start = 0.8};
  const FogReturn fog_return(paper_grid);
  std::vector<double> whole(80, 0.0), part(25, 0.0);
  fog_return.add(whole, fog);
  fog_return.add(part, fog, 20);
  for (std::size_t k = 0; k < part.size(); ++k) EXPECT_EQ(part[k], whole[20 + k]) << k;
  EXPECT_GT(part[10], 0.0);
}

}  // namespace
}  // namespace fogradar::lidar
