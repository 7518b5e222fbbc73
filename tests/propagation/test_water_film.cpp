// Transfer-matrix slab response. References: closed forms for lossless half- and quarter-wave
// slabs and for a single interface (Fresnel; Born & Wolf, 7th ed., sec. 1.5.2 and 1.6; Hecht,
// Optics, sec. 4.6 and 9.7); the thick-film limit of the Airy sum with Beer-Lambert decay
// exp(-4 pi k t / lambda) (B&W sec. 14.1); energy balance and reciprocity on random stacks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/propagation/water_film.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::propagation {
namespace {

using complex = std::complex<double>;
using fogradar::testing::Tolerance;
using fogradar::testing::validate;

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

// A number as written in a check's id and conditions: "1.5", "3.76".
std::string num(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Records one check of the slab response against its reference.
void check(const std::string& id, const std::string& quantity, const std::string& unit,
           const std::string& conditions, double value, double reference, const std::string& source,
           double tolerance, Tolerance kind) {
  validate({.id = "propagation.water_film." + id,
            .group = "physics: water",
            .quantity = quantity,
            .unit = unit,
            .conditions = conditions,
            .reference = reference,
            .source = source,
            .value = value,
            .tolerance = tolerance,
            .kind = kind});
}

// Fresnel amplitude coefficients at normal incidence from a into b.
complex fresnel_r(complex a, complex b) { return (a - b) / (a + b); }
complex fresnel_t(complex a, complex b) { return 2.0 * a / (a + b); }

// ---- Lossless slabs ----------------------------------------------------------------------------

TEST(Slab, LosslessHalfWaveSlabTransmitsFully) {
  const double lambda = 3.9e-3;
  const std::vector<SlabLayer> slab = {{{2.0, 0.0}, lambda / (2.0 * 2.0)}};
  const SlabResponse response = slab_response(slab, lambda);
  const std::string conditions = "lossless slab n = 2, half-wave thick, lambda = 3.9 mm";
  const std::string source =
      "closed form: lossless half-wave slab is transparent (Born & Wolf "
      "sec. 1.6; Hecht sec. 9.7)";
  check("half_wave.transmittance", "transmittance T", "1", conditions, response.transmittance, 1.0,
        source, kTol, Tolerance::absolute);
  check("half_wave.reflectance", "reflectance R", "1", conditions, response.reflectance, 0.0,
        source, kTol, Tolerance::absolute);
  check("half_wave.absorptance", "absorptance A", "1", conditions, response.absorptance, 0.0,
        source, kTol, Tolerance::absolute);
}

TEST(Slab, LosslessQuarterWaveSlabReflectanceMatchesClosedForm) {
  const double lambda = 3.9e-3;
  for (double n : {1.5, 2.0, 3.3}) {
    const std::vector<SlabLayer> slab = {{{n, 0.0}, lambda / (4.0 * n)}};
    const double expected = std::pow((1.0 - n * n) / (1.0 + n * n), 2);
    const SlabResponse response = slab_response(slab, lambda);
    const std::string conditions = "lossless slab n = " + num(n) +
                                   ", quarter-wave thick, "
                                   "lambda = 3.9 mm";
    const std::string source =
        "closed form: quarter-wave slab R = ((1 - n^2)/(1 + n^2))^2 "
        "(Born & Wolf sec. 1.6; Hecht sec. 9.7)";
    check("quarter_wave.reflectance.n" + num(n), "reflectance R", "1", conditions,
          response.reflectance, expected, source, kTol, Tolerance::relative);
    check("quarter_wave.transmittance.n" + num(n), "transmittance T", "1", conditions,
          response.transmittance, 1.0 - expected, source + ", T = 1 - R", kTol,
          Tolerance::absolute);
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
      const std::string id = "interface.n_out" + num(n_out.real()) + "+" + num(n_out.imag()) +
                             "i." + (layers.empty() ? "no_layer" : "zero_thickness_layer") + ".";
      const std::string conditions = "air into n = " + num(n_out.real()) + " + " +
                                     num(n_out.imag()) + "i, 77 GHz, " +
                                     (layers.empty() ? "no layer" : "a zero-thickness layer");
      const std::string fresnel =
          "Fresnel coefficients at normal incidence (Born & Wolf sec. "
          "1.5.2; Hecht sec. 4.6)";
      check(id + "r", "|r - r_Fresnel|", "1", conditions,
            std::abs(response.reflection_amplitude - fresnel_r(1.0, n_out)), 0.0, fresnel, kTol,
            Tolerance::absolute);
      check(id + "t", "|t - t_Fresnel|", "1", conditions,
            std::abs(response.transmission_amplitude - fresnel_t(1.0, n_out)), 0.0, fresnel, kTol,
            Tolerance::absolute);
      // Into a semi-infinite medium all power that is not reflected is transmitted, lossy or not.
      check(id + "absorptance", "absorptance A", "1", conditions, response.absorptance, 0.0,
            "closed form: a single interface absorbs nothing", kTol, Tolerance::absolute);
    }
  }
  // From glass into air (n_in > n_out): r changes sign, T carries Re(n_out)/Re(n_in).
  const SlabResponse inside = slab_response({}, lambda, 1.5, 1.0);
  const std::string glass_air = "glass n = 1.5 into air, 77 GHz";
  check("interface.glass_to_air.r", "Re r", "1", glass_air, inside.reflection_amplitude.real(), 0.2,
        "Fresnel: r = (1.5 - 1)/(1.5 + 1)", kTol, Tolerance::absolute);
  check("interface.glass_to_air.transmittance", "transmittance T", "1", glass_air,
        inside.transmittance, 1.0 / 1.5 * std::norm(fresnel_t(1.5, 1.0)),
        "Fresnel: T = Re(n_out)/Re(n_in) |t|^2", kTol, Tolerance::absolute);
  check("interface.glass_to_air.transmittance.by_hand", "transmittance T", "1", glass_air,
        inside.transmittance, 0.96, "Fresnel: T = 1 - R = 1 - 0.2^2", kTol, Tolerance::absolute);
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
    check("thick_film.transmittance." + num(depths) + "skin_depths", "transmittance T", "1",
          "water film m = 3.76 + 2.32i, " + num(depths) + " skin depths, 77 GHz", transmittance,
          expected,
          "thick-film limit of the Airy sum: |t_12 t_21|^2 exp(-4 pi k t / lambda) (Born & Wolf "
          "sec. 14.1)",
          kBeerLambertTol, Tolerance::relative);
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
  check("thick_film.log_slope", "d ln T / dt", "1/m",
        "water film m = 3.76 + 2.32i, 8 to 12 skin depths, 77 GHz", slope, expected_slope,
        "Beer-Lambert: d ln T / dt = -4 pi k / lambda", kBeerLambertTol, Tolerance::relative);
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
  check("radome.dry_half_wave.two_way_loss", "two-way loss", "dB",
        "no water, lossless radome n = 1.7, half-wave thick, 77 GHz",
        film_two_way_loss_db(0.0, kWater77Ghz, 1.7, lambda / (2.0 * 1.7), lambda), 0.0,
        "closed form: lossless half-wave slab is transparent", 1e-10, Tolerance::absolute);
}

TEST(Film, ThickFilmLossGrowsAtTheBeerLambertRate) {
  // Deep in the film each extra millimetre adds 2 * 10 log10(e) * 4 pi k / lambda dB (two-way).
  const double lambda = kWavelength77Ghz_m;
  const double extra_db = film_two_way_loss_db(2e-3, kWater77Ghz, 1.7, 3e-3, lambda) -
                          film_two_way_loss_db(1e-3, kWater77Ghz, 1.7, 3e-3, lambda);
  const double expected_db =
      2.0 * db_per_neper_power * 4.0 * pi * kWater77Ghz.imag() / lambda * 1e-3;
  check("radome.thick_film.loss_per_mm", "two-way loss of the 2nd millimetre of water", "dB",
        "water m = 3.76 + 2.32i on radome n = 1.7, 3 mm, 77 GHz", extra_db, expected_db,
        "Beer-Lambert: 2 x 10 log10(e) x 4 pi k / lambda per metre", kBeerLambertTol,
        Tolerance::relative);
}

// ---- Single film in air: Airy's closed form --------------------------------------------------

// Airy's single-film amplitudes at normal incidence, exp(-i omega t) convention (Born & Wolf sec.
// 7.6.1; Orfanidis, Electromagnetic Waves and Antennas, sec. 5.4): with delta = 2 pi m t / lambda,
//   r = (r01 + r12 e^{2 i delta}) / (1 + r01 r12 e^{2 i delta}),
//   t = t01 t12 e^{i delta} / (1 + r01 r12 e^{2 i delta}).
// A perfect conductor behind the film is r12 = -1 (Orfanidis sec. 5.4, a PEC-backed slab).
complex airy_r(complex m, double thickness_m, double wavelength_m, complex r12) {
  const complex r01 = fresnel_r(1.0, m);
  const complex round_trip =
      std::exp(complex{0.0, 2.0} * 2.0 * pi * m * thickness_m / wavelength_m);
  return (r01 + r12 * round_trip) / (1.0 + r01 * r12 * round_trip);
}

double airy_film_in_air_transmittance(complex m, double thickness_m, double wavelength_m) {
  const complex phase = complex{0.0, 1.0} * 2.0 * pi * m * thickness_m / wavelength_m;
  const complex r01 = fresnel_r(1.0, m), r12 = fresnel_r(m, 1.0);
  const complex t = fresnel_t(1.0, m) * fresnel_t(m, 1.0) * std::exp(phase) /
                    (1.0 + r01 * r12 * std::exp(2.0 * phase));
  return std::norm(t);
}

// The radome's film without a radome: the transfer matrix's two-way loss against Airy's T, to
// rounding (1e-9 dB).
TEST(Film, FilmInAirMatchesAiry) {
  const double lambda = kWavelength77Ghz_m;
  for (double t_m : {0.02e-3, 0.1e-3, 0.26e-3, 0.5e-3}) {
    const double expected_db =
        -20.0 * std::log10(airy_film_in_air_transmittance(kWater77Ghz, t_m, lambda));
    check("film_in_air.two_way_loss." + num(t_m * 1e3) + "mm", "two-way loss", "dB",
          "water film m = 3.76 + 2.32i, " + num(t_m * 1e3) + " mm, no radome, 77 GHz",
          film_two_way_loss_db(t_m, kWater77Ghz, 1.0, 0.0, lambda), expected_db,
          "Airy single film: t = t01 t12 e^{i delta} / (1 + r01 r12 e^{2 i delta}) (Born & Wolf "
          "sec. 7.6.1)",
          1e-9, Tolerance::absolute);
  }
}

// A film on a perfect conductor: the transfer matrix's PEC limit against Airy with r12 = -1, to
// rounding; bare metal reflects r = -1 (0 dB); a lossless film keeps |r| = 1; a film many skin
// depths thick reflects as the water surface, r01.
TEST(Film, ConductorBackedFilmMatchesAiryWithR12MinusOne) {
  const double lambda = kWavelength77Ghz_m;
  EXPECT_NEAR(std::abs(conductor_backed_reflection({}, lambda) - complex{-1.0, 0.0}), 0.0, kTol);
  EXPECT_EQ(conductor_film_loss_db(0.0, kWater77Ghz, lambda), 0.0);
  const double quarter_wave_m = lambda / (4.0 * kWater77Ghz.real());
  for (double t_m : {0.05e-3, 0.1e-3, quarter_wave_m, 0.5e-3, 1e-3}) {
    const std::vector<SlabLayer> film = {{kWater77Ghz, t_m}};
    const complex expected = airy_r(kWater77Ghz, t_m, lambda, -1.0);
    const std::string conditions =
        "water film m = 3.76 + 2.32i, " + num(t_m * 1e3) + " mm, on a perfect conductor, 77 GHz";
    const std::string source =
        "Airy with r12 = -1: r = (r01 - e^{2 i delta}) / (1 - r01 e^{2 i delta}) (Orfanidis, EWA "
        "sec. 5.4; Born & Wolf sec. 7.6.1)";
    check("on_conductor.r." + num(t_m * 1e3) + "mm", "|r - r_Airy|", "1", conditions,
          std::abs(conductor_backed_reflection(film, lambda) - expected), 0.0, source, kTol,
          Tolerance::absolute);
    check("on_conductor.loss." + num(t_m * 1e3) + "mm", "echo loss against bare metal", "dB",
          conditions, conductor_film_loss_db(t_m, kWater77Ghz, lambda),
          -10.0 * std::log10(std::norm(expected)), source, 1e-9, Tolerance::absolute);
  }
  const std::vector<SlabLayer> lossless = {{{1.7, 0.0}, 0.7e-3}};
  EXPECT_NEAR(std::abs(conductor_backed_reflection(lossless, lambda)), 1.0, kTol);
  const std::vector<SlabLayer> thick = {{kWater77Ghz, 20.0 * lambda}};
  EXPECT_NEAR(std::abs(conductor_backed_reflection(thick, lambda) - fresnel_r(1.0, kWater77Ghz)),
              0.0, 1e-12);
  // The n_out -> infinity limit of slab_response.
  const std::vector<SlabLayer> film = {{kWater77Ghz, 0.1e-3}};
  EXPECT_NEAR(std::abs(conductor_backed_reflection(film, lambda) -
                       slab_response(film, lambda, 1.0, complex{1e9, 0.0}).reflection_amplitude),
              0.0, 1e-8);
}

// ---- Window film at optical wavelengths -------------------------------------------------------

// Water at 905 nm (Segelstein 1981, 1.3235 + 5.15e-7i at 905.7 nm): absorption
// exp(-4 pi k t / lambda) is 0.07 % over 0.1 mm, so the film's Fresnel terms dominate.
constexpr complex kWater905Nm{1.3235, 5.15e-7};

// The incoherent sum written out here (Harbecke 1986, Appl. Phys. B 39, 165; Heavens, Optical
// Properties of Thin Solid Films, sec. 4.10): a film's multiple reflections added in power,
//   T_wet = (1 - R_af)(1 - R_fg) tau / (1 - R_af R_fg tau^2),  T_dry = 1 - R_ag.
double incoherent_wet_over_dry(complex m, double n_glass, double thickness_m, double lambda_m) {
  const double r_af = std::norm(fresnel_r(1.0, m));
  const double r_fg = std::norm(fresnel_r(m, n_glass));
  const double r_ag = std::norm(fresnel_r(1.0, n_glass));
  const double tau = std::exp(-4.0 * pi * m.imag() * thickness_m / lambda_m);
  return (1.0 - r_af) * (1.0 - r_fg) * tau / (1.0 - r_af * r_fg * tau * tau) / (1.0 - r_ag);
}

// The window film against the closed form (to rounding), and against the coherent transfer matrix
// of the film on glass averaged over one fringe period lambda / (2 n) of thickness, over the dry
// face's transfer-matrix transmittance: the average of Airy's T over the round-trip phase is the
// incoherent sum (Harbecke 1986, sec. 3), up to the absorption across one period (3e-6 here);
// tolerance 1e-5 relative.
TEST(WindowFilm, IncoherentSumMatchesTheFringeAveragedTransferMatrix) {
  const double lambda = 905e-9;
  const double glass = optical_window_index;
  const double period_m = lambda / (2.0 * kWater905Nm.real());
  const double dry = slab_response({}, lambda, 1.0, glass).transmittance;
  for (double t_m : {2e-6, 0.1e-3, 1e-3}) {
    const double closed = incoherent_wet_over_dry(kWater905Nm, glass, t_m, lambda);
    EXPECT_NEAR(window_film_transmittance(t_m, kWater905Nm, lambda), closed, 1e-14) << t_m;
    constexpr int samples = 256;  // the midpoint rule on a periodic integrand converges fast
    double sum = 0.0;
    for (int i = 0; i < samples; ++i) {
      const std::vector<SlabLayer> film = {{kWater905Nm, t_m + (i + 0.5) / samples * period_m}};
      sum += slab_response(film, lambda, 1.0, glass).transmittance;
    }
    check("window.fringe_average." + num(t_m * 1e3) + "mm", "wet over dry window transmittance",
          "1", "water m = 1.3235 + 5.15e-7i on glass n = 1.5, " + num(t_m * 1e3) + " mm, 905 nm",
          window_film_transmittance(t_m, kWater905Nm, lambda), sum / samples / dry,
          "transfer matrix (Born & Wolf sec. 1.6) averaged over one fringe period (Harbecke 1986)",
          1e-5, Tolerance::relative);
  }
  // A clear film index-matches the window: the wet face transmits more than the dry one.
  EXPECT_GT(window_film_transmittance(0.1e-3, kWater905Nm, lambda), 1.0);
  EXPECT_EQ(window_film_transmittance(0.0, kWater905Nm, lambda), 1.0);
  // Beer-Lambert: each extra millimetre multiplies by exp(-4 pi k / lambda 1 mm), to the 1e-6 by
  // which it moves the multiple-reflection term R_af R_fg tau^2 (7e-5).
  const double ratio = window_film_transmittance(3e-3, kWater905Nm, lambda) /
                       window_film_transmittance(2e-3, kWater905Nm, lambda);
  EXPECT_NEAR(ratio, std::exp(-4.0 * pi * kWater905Nm.imag() / lambda * 1e-3), 1e-5);
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

  expect_invalid([&] { conductor_film_loss_db(-1e-4, kWater77Ghz, lambda); }, "film_thickness_m");
  expect_invalid([&] { conductor_film_loss_db(1e-4, {3.76, -2.32}, lambda); }, "water_index");
  expect_invalid([&] { conductor_film_loss_db(1e-4, kWater77Ghz, 0.0); }, "wavelength_m");
  expect_invalid([&] { conductor_backed_reflection(negative_thickness, lambda); }, "thickness_m");
  expect_invalid([&] { conductor_backed_reflection(good, lambda, {1.0, -0.1}); }, "n_in");
  expect_invalid([&] { window_film_transmittance(-1e-4, kWater905Nm, 905e-9); },
                 "film_thickness_m");
  expect_invalid([&] { window_film_transmittance(1e-4, {0.0, 0.0}, 905e-9); }, "water_index");
  expect_invalid([&] { window_film_transmittance(1e-4, kWater905Nm, 905e-9, 0.0); },
                 "window_index");
  expect_invalid([&] { window_film_transmittance(1e-4, kWater905Nm, -905e-9); }, "wavelength_m");
  for (double bad : {-1e-6, 0.5e-6, 0.011, std::nan("")}) {
    expect_invalid([&] { require_window_film("lidar.window_water_film_m", bad); },
                   "lidar.window_water_film_m");
  }
  for (double fine : {0.0, min_window_film_m, 1e-4, max_window_film_m}) {
    EXPECT_NO_THROW(require_window_film("camera.window_water_film_m", fine)) << fine;
  }
}

}  // namespace
}  // namespace fogradar::propagation
