// Transfer-matrix slab response. References: closed forms for lossless half- and quarter-wave
// slabs and for a single interface (Fresnel; Born & Wolf, 7th ed., sec. 1.5.2 and 1.6; Hecht,
// Optics, sec. 4.6 and 9.7); the thick-film limit of the Airy sum with Beer-Lambert decay
// exp(-4 pi k t / lambda) (B&W sec. 14.1); energy balance and reciprocity on random stacks.
#include <gtest/gtest.h>

#include "rejected_field.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/propagation/water_film.hpp"

namespace fogradar::propagation {
namespace {

using complex = std::complex<double>;

constexpr double kTol = 1e-12;            // closed forms and energy balance of lossless stacks
constexpr double kBeerLambertTol = 1e-3;  // thick film against its single-pass limit
const double kWavelength77Ghz_m = wavelength_from_frequency_m(77e9);
// Water at 77 GHz, m = n + i k (the ITU-R P.840 double-Debye model gives 3.67 + 2.16i at 20 C and
// 3.83 + 2.27i at 25 C); the tests only need a strongly absorbing index.
constexpr complex kWater77Ghz{3.76, 2.32};

// Expects `call` to throw InvalidParameter naming `field`.
void expect_invalid(const std::function<void()>& call, const std::string& field) {
  EXPECT_EQ(test_support::rejected_field(call), field);
}

// Fresnel amplitude coefficients at normal incidence from a into b.
complex fresnel_r(complex a, complex b) { return (a - b) / (a + b); }
complex fresnel_t(complex a, complex b) { return 2.0 * a / (a + b); }

// ---- Lossless slabs ----------------------------------------------------------------------------

TEST(Slab, LosslessHalfWaveSlabTransmitsFully) {
  const double lambda = 3.9e-3;
  const std::vector<SlabLayer> slab = {{{2.0, 0.0}, lambda / (2.0 * 2.0)}};
  const SlabResponse response = slab_response(slab, lambda);
  EXPECT_NEAR(response.transmittance, 1.0, kTol);
  EXPECT_NEAR(response.reflectance, 0.0, kTol);
  EXPECT_NEAR(response.absorptance, 0.0, kTol);
}

TEST(Slab, LosslessQuarterWaveSlabReflectanceMatchesClosedForm) {
  const double lambda = 3.9e-3;
  for (double n : {1.5, 2.0, 3.3}) {
    const std::vector<SlabLayer> slab = {{{n, 0.0}, lambda / (4.0 * n)}};
    const double expected = std::pow((1.0 - n * n) / (1.0 + n * n), 2);
    const SlabResponse response = slab_response(slab, lambda);
    EXPECT_NEAR(response.reflectance, expected, kTol * expected) << "n = " << n;
    EXPECT_NEAR(response.transmittance, 1.0 - expected, kTol) << "n = " << n;
  }
}

// ---- Single interface -------------------------------------------------------------------------

TEST(Slab, SingleInterfaceGivesFresnelCoefficients) {
  const double lambda = kWavelength77Ghz_m;
  for (complex n_out : {complex{1.5, 0.0}, kWater77Ghz}) {
    const std::vector<SlabLayer> no_layer;
    const std::vector<SlabLayer> zero_thickness = {{{2.7, 0.4}, 0.0}};
    for (const auto& layers : {no_layer, zero_thickness}) {
      const SlabResponse response = slab_response(layers, lambda, 1.0, n_out);
      EXPECT_NEAR(std::abs(response.reflection_amplitude - fresnel_r(1.0, n_out)), 0.0, kTol);
      EXPECT_NEAR(std::abs(response.transmission_amplitude - fresnel_t(1.0, n_out)), 0.0, kTol);
      // Into a semi-infinite medium all power that is not reflected is transmitted, lossy or not.
      EXPECT_NEAR(response.absorptance, 0.0, kTol);
    }
  }
  // From glass into air (n_in > n_out): r changes sign, T carries Re(n_out)/Re(n_in).
  const SlabResponse inside = slab_response({}, lambda, 1.5, 1.0);
  EXPECT_NEAR(inside.reflection_amplitude.real(), 0.2, kTol);
  EXPECT_NEAR(inside.transmittance, 1.0 / 1.5 * std::norm(fresnel_t(1.5, 1.0)), kTol);
  EXPECT_NEAR(inside.transmittance, 0.96, kTol);
}

// ---- Thick absorbing film: Beer-Lambert ------------------------------------------------------

// Thick-film limit of the Airy sum: T = |t_12 t_21|^2 exp(-4 pi k t / lambda), the multiple
// reflection term |r_21 r_23| exp(-4 pi k t / lambda) being negligible. (For an absorbing film,
// |t_12 t_21|^2 = 16|m|^2/|1+m|^4, not (1-R_1)(1-R_2) = 16 Re(m)^2/|1+m|^4.)
double single_pass_transmittance(complex m, double thickness_m, double wavelength_m) {
  const double alpha_per_m = 4.0 * pi * m.imag() / wavelength_m;
  return std::norm(fresnel_t(1.0, m) * fresnel_t(m, 1.0)) * std::exp(-alpha_per_m * thickness_m);
}

TEST(Film, ThickWaterFilmFollowsBeerLambert) {
  const double lambda = kWavelength77Ghz_m;
  const double skin_depth_m = lambda / (4.0 * pi * kWater77Ghz.imag());  // power 1/e depth
  for (double depths : {8.0, 12.0, 20.0}) {
    const double t = depths * skin_depth_m;
    const std::vector<SlabLayer> film = {{kWater77Ghz, t}};
    const double expected = single_pass_transmittance(kWater77Ghz, t, lambda);
    const double transmittance = slab_response(film, lambda).transmittance;
    EXPECT_NEAR(transmittance / expected, 1.0, kBeerLambertTol) << depths << " skin depths";
  }
  // Log-slope d ln T / dt = -4 pi k / lambda, by a finite difference deep in the film.
  const double t1 = 8.0 * skin_depth_m;
  const double t2 = 12.0 * skin_depth_m;
  const std::vector<SlabLayer> film1 = {{kWater77Ghz, t1}};
  const std::vector<SlabLayer> film2 = {{kWater77Ghz, t2}};
  const double slope = (std::log(slab_response(film2, lambda).transmittance) -
                        std::log(slab_response(film1, lambda).transmittance)) /
                       (t2 - t1);
  const double expected_slope = -4.0 * pi * kWater77Ghz.imag() / lambda;
  EXPECT_NEAR(slope / expected_slope, 1.0, kBeerLambertTol);
}

// ---- Energy balance and reciprocity on random stacks ------------------------------------------

std::vector<SlabLayer> random_stack(std::mt19937_64& rng, bool lossy) {
  std::uniform_int_distribution<int> count(1, 6);
  std::uniform_real_distribution<double> real_part(1.0, 4.0);
  std::uniform_real_distribution<double> imag_part(0.0, 2.5);
  std::uniform_real_distribution<double> thickness(0.0, 3e-3);
  std::vector<SlabLayer> layers(static_cast<std::size_t>(count(rng)));
  for (SlabLayer& layer : layers) {
    layer.refractive_index = {real_part(rng), lossy ? imag_part(rng) : 0.0};
    layer.thickness_m = thickness(rng);
  }
  return layers;
}

TEST(Slab, LossyStacksAbsorbNonNegativePower) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> out_index(1.0, 4.0);
  for (int trial = 0; trial < 500; ++trial) {
    const auto layers = random_stack(rng, true);
    const complex n_out = out_index(rng);
    const SlabResponse response = slab_response(layers, kWavelength77Ghz_m, 1.0, n_out);
    // A passive stack cannot create power (a sign error in the exp(-i omega t) convention would).
    EXPECT_GE(response.absorptance, -kTol) << "trial " << trial;
    EXPECT_LE(response.absorptance, 1.0 + kTol) << "trial " << trial;
    EXPECT_GE(response.reflectance, 0.0);
    EXPECT_GE(response.transmittance, 0.0);
    EXPECT_NEAR(std::norm(response.reflection_amplitude) +
                    n_out.real() * std::norm(response.transmission_amplitude) +
                    response.absorptance,
                1.0, kTol);
  }
}

TEST(Slab, LosslessStacksConserveEnergy) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> out_index(1.0, 4.0);
  for (int trial = 0; trial < 500; ++trial) {
    const auto layers = random_stack(rng, false);
    const complex n_out = out_index(rng);
    const SlabResponse response = slab_response(layers, kWavelength77Ghz_m, 1.0, n_out);
    EXPECT_NEAR(response.absorptance, 0.0, kTol) << "trial " << trial;
    EXPECT_NEAR(response.reflectance + n_out.real() * std::norm(response.transmission_amplitude),
                1.0, kTol);
  }
}

TEST(Slab, TransmittanceIsReciprocalForLossyStacks) {
  std::mt19937_64 rng(905);
  for (int trial = 0; trial < 200; ++trial) {
    const auto layers = random_stack(rng, true);
    const std::vector<SlabLayer> reversed(layers.rbegin(), layers.rend());
    const double forward = slab_response(layers, kWavelength77Ghz_m).transmittance;
    const double backward = slab_response(reversed, kWavelength77Ghz_m).transmittance;
    EXPECT_NEAR(backward, forward, kTol * std::max(forward, std::numeric_limits<double>::min()));
  }
}

// ---- Radome with water film --------------------------------------------------------------------

TEST(Film, TwoWayLossIsTwiceTheOneWayTransmittanceInDb) {
  const double lambda = kWavelength77Ghz_m;
  const complex radome{1.7, 0.01};
  const std::vector<SlabLayer> stack = {{radome, 3e-3}, {kWater77Ghz, 0.2e-3}};
  const double one_way = slab_response(stack, lambda).transmittance;
  EXPECT_NEAR(film_two_way_loss_db(0.2e-3, kWater77Ghz, radome, 3e-3, lambda),
              -20.0 * std::log10(one_way), kTol);
  // A dry lossless half-wave radome is transparent.
  EXPECT_NEAR(film_two_way_loss_db(0.0, kWater77Ghz, 1.7, lambda / (2.0 * 1.7), lambda), 0.0,
              1e-10);
}

TEST(Film, ThickFilmLossGrowsAtTheBeerLambertRate) {
  // Deep in the film each extra millimetre adds 2 * 10 log10(e) * 4 pi k / lambda dB (two-way).
  const double lambda = kWavelength77Ghz_m;
  const double extra_db = film_two_way_loss_db(2e-3, kWater77Ghz, 1.7, 3e-3, lambda) -
                          film_two_way_loss_db(1e-3, kWater77Ghz, 1.7, 3e-3, lambda);
  const double expected_db =
      2.0 * db_per_neper_power * 4.0 * pi * kWater77Ghz.imag() / lambda * 1e-3;
  EXPECT_NEAR(extra_db / expected_db, 1.0, kBeerLambertTol);
}

// ---- Rejected inputs --------------------------------------------------------------------------

TEST(FilmConfig, RejectsEveryInvalidField) {
  const double lambda = kWavelength77Ghz_m;
  const std::vector<SlabLayer> negative_thickness = {{{1.5, 0.0}, -1e-3}};
  const std::vector<SlabLayer> nan_thickness = {{{1.5, 0.0}, std::nan("")}};
  const std::vector<SlabLayer> gain_medium = {{{1.5, -0.1}, 1e-3}};
  const std::vector<SlabLayer> zero_index = {{{0.0, 1.0}, 1e-3}};
  const std::vector<SlabLayer> good = {{{1.5, 0.1}, 1e-3}};
  expect_invalid([&] { slab_response(negative_thickness, lambda); }, "thickness_m");
  expect_invalid([&] { slab_response(nan_thickness, lambda); }, "thickness_m");
  expect_invalid([&] { slab_response(gain_medium, lambda); }, "refractive_index");
  expect_invalid([&] { slab_response(zero_index, lambda); }, "refractive_index");
  expect_invalid([&] { slab_response(good, 0.0); }, "wavelength_m");
  expect_invalid([&] { slab_response(good, -lambda); }, "wavelength_m");
  expect_invalid([&] { slab_response(good, lambda, {1.0, -0.1}); }, "n_in");
  expect_invalid([&] { slab_response(good, lambda, 1.0, {-1.0, 0.0}); }, "n_out");

  expect_invalid([&] { film_two_way_loss_db(-1e-4, kWater77Ghz, 1.7, 3e-3, lambda); },
                 "film_thickness_m");
  expect_invalid(
      [&] {
        film_two_way_loss_db(1e-4, {3.76, -2.32}, 1.7, 3e-3, lambda);
      },
      "water_index");
  expect_invalid([&] { film_two_way_loss_db(1e-4, kWater77Ghz, 0.0, 3e-3, lambda); },
                 "radome_index");
  expect_invalid([&] { film_two_way_loss_db(1e-4, kWater77Ghz, 1.7, -3e-3, lambda); },
                 "radome_thickness_m");
  expect_invalid([&] { film_two_way_loss_db(1e-4, kWater77Ghz, 1.7, 3e-3, 0.0); }, "wavelength_m");
}

}  // namespace
}  // namespace fogradar::propagation
