// Drop size distributions. References: closed-form moments (lognormal: Aitchison & Brown 1957;
// modified gamma: Deirmendjian 1969) checked against independent adaptive quadrature (Boost
// Gauss-Kronrod, not the library's Gauss-Legendre nodes), and the published Shettle & Fenn presets
// (Al Naboulsi et al. 2004, Table 1: a, alpha, b, N).
#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <variant>

#include "fogradar/core/error.hpp"
#include "fogradar/propagation/dsd.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::propagation {
namespace {

using fogradar::testing::Tolerance;

constexpr double rho_water_g_per_m3 = 1e6;

// A number as written in a check's id and conditions: "0.01", "50".
std::string num(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// A distribution as written in a check's id and conditions: its family and parameters.
std::string dsd_label(const DropSizeDistribution& dsd) {
  if (const auto* l = std::get_if<Lognormal>(&dsd)) {
    return "lognormal_" + num(l->median_diameter_m * 1e6) + "um_sg" + num(l->geometric_std);
  }
  if (const auto* g = std::get_if<ModifiedGamma>(&dsd)) {
    return "modified_gamma_a" + num(g->alpha) + "_g" + num(g->gamma) + "_b" +
           num(g->b_per_um_gamma);
  }
  return std::string(distribution_name(dsd));
}

// Records one drop size distribution check (fogradar::testing::validate, qualified: validate(dsd)
// is the library's).
void validate_dsd(const std::string& id, const std::string& quantity, const std::string& unit,
                  const std::string& conditions, double value, double reference,
                  const std::string& source, double tolerance, Tolerance kind) {
  fogradar::testing::validate({.id = "propagation.dsd." + id,
                               .group = "physics: droplets",
                               .quantity = quantity,
                               .unit = unit,
                               .conditions = conditions,
                               .reference = reference,
                               .source = source,
                               .value = value,
                               .tolerance = tolerance,
                               .kind = kind});
}

// Independent integral of f(D) p(D) dD in ln D over a generous range, adaptive G-K, tol 1e-12.
template <class F>
double adaptive_integral(const DropSizeDistribution& dsd, F f) {
  const DiameterRange r = quadrature_range(dsd);
  const auto integrand = [&](double log_d) {
    const double d = std::exp(log_d);
    return f(d) * diameter_pdf(dsd, d) * d;
  };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      integrand, std::log(r.min_m) - 1.0, std::log(r.max_m) + 1.0, 20, 1e-12);
}

std::vector<DropSizeDistribution> continuous_distributions() {
  return {Lognormal{1e-6, 1.5}, Lognormal{8e-6, 1.5}, advection_fog(), radiation_fog(),
          ModifiedGamma{.alpha = 6.0, .gamma = 2.0, .b_per_um_gamma = 0.2}};
}

TEST(Dsd, PdfIntegratesToOneAndMomentsMatchClosedForms) {
  for (const auto& dsd : continuous_distributions()) {
    const std::string name = dsd_label(dsd);
    validate_dsd("pdf_normalisation." + name, "integral of p(D) dD", "1", name,
                 adaptive_integral(dsd, [](double) { return 1.0; }), 1.0,
                 "closed form: a pdf integrates to 1 (Boost adaptive Gauss-Kronrod quadrature)",
                 1e-9, Tolerance::absolute);
    for (int k = 1; k <= 6; ++k) {
      const double closed = diameter_moment(dsd, k);
      const double numeric = adaptive_integral(dsd, [k](double d) { return std::pow(d, k); });
      validate_dsd("moment." + name + ".k" + std::to_string(k),
                   "diameter moment <D^" + std::to_string(k) + ">", "m^" + std::to_string(k),
                   name + ", k = " + std::to_string(k), closed, numeric,
                   "independent adaptive Gauss-Kronrod integral (Boost) of the pdf; closed forms "
                   "Aitchison & Brown 1957 (lognormal), Deirmendjian 1969 (modified gamma)",
                   1e-9, Tolerance::relative);
    }
  }
}

// Issue criterion: the distribution holds the requested LWC within 1e-6 (relative), here checked
// by integrating rho_w (pi/6) D^3 N p(D) independently of the normalisation formula's moment.
TEST(Dsd, HoldsTheRequestedLiquidWaterContent) {
  for (const auto& dsd : continuous_distributions()) {
    for (double lwc : {0.01, 0.3, 50.0}) {
      const double n = number_concentration_per_m3(dsd, lwc);
      const double held = n * adaptive_integral(dsd, [](double d) {
                            return rho_water_g_per_m3 * std::numbers::pi / 6.0 * d * d * d;
                          });
      const std::string name = dsd_label(dsd);
      validate_dsd("lwc_held." + name + ".lwc" + num(lwc), "liquid water content held", "g/m^3",
                   name + ", " + num(lwc) + " g/m^3", held, lwc,
                   "the requested LWC; rho_w (pi/6) D^3 N p(D) integrated by Boost adaptive "
                   "Gauss-Kronrod",
                   1e-6, Tolerance::relative);
    }
  }
  // Monodisperse: N = LWC / (rho pi D^3 / 6) exactly; 1 g/m^3 of 10 um drops is 1.9099e9 per m^3.
  validate_dsd("number_concentration.monodisperse10um", "number concentration N", "1/m^3",
               "monodisperse D = 10 um, 1 g/m^3",
               number_concentration_per_m3(Monodisperse{10e-6}, 1.0),
               1.0 / (1e6 * std::numbers::pi / 6.0 * 1e-15),
               "closed form: N = LWC / (rho_w pi D^3 / 6)", 1e-3, Tolerance::absolute);
}

TEST(Dsd, QuadratureNodesReproduceMoments) {
  for (const auto& dsd : continuous_distributions()) {
    double w0 = 0.0, w3 = 0.0, w6 = 0.0;
    for (const QuadratureNode& node : quadrature_nodes(dsd)) {
      w0 += node.weight;
      w3 += node.weight * std::pow(node.diameter_m, 3);
      w6 += node.weight * std::pow(node.diameter_m, 6);
    }
    validate_dsd("quadrature_weights_sum." + dsd_label(dsd), "sum of quadrature weights", "1",
                 dsd_label(dsd), w0, 1.0, "closed form: a pdf integrates to 1", 1e-9,
                 Tolerance::absolute);
    EXPECT_NEAR(w3 / diameter_moment(dsd, 3), 1.0, 1e-9) << distribution_name(dsd);
    EXPECT_NEAR(w6 / diameter_moment(dsd, 6), 1.0, 1e-9) << distribution_name(dsd);
  }
  const auto mono = quadrature_nodes(Monodisperse{3e-6});
  ASSERT_EQ(mono.size(), 1u);
  EXPECT_EQ(mono[0].diameter_m, 3e-6);
  EXPECT_EQ(mono[0].weight, 1.0);
}

// Shettle & Fenn presets as tabulated by Al Naboulsi et al. 2004: with their scale a, the number
// concentration a Gamma(alpha+1) / b^(alpha+1) is 20 cm^-3 (advection, a = 0.027) and 100 cm^-3
// (radiation, a = 2.37305); mode radii alpha / b are 10 um and 4 um.
// A broad distribution is truncated at the largest accepted droplet (1 mm) and renormalised; the
// truncated distribution still holds exactly the requested LWC (independent adaptive integral of
// the pdf over the truncated range, normalised by its own integral).
TEST(Dsd, BroadDistributionsAreTruncatedAtOneMillimetre) {
  const DropSizeDistribution broad = Lognormal{20e-6, 2.5};
  const DiameterRange r = quadrature_range(broad);
  EXPECT_EQ(r.max_m, 1e-3);
  const auto truncated = [&](auto f) {
    const auto integrand = [&](double log_d) {
      const double d = std::exp(log_d);
      return f(d) * diameter_pdf(broad, d) * d;
    };
    return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        integrand, std::log(r.min_m), std::log(r.max_m), 20, 1e-12);
  };
  const double mass_fraction_kept =
      truncated([](double d) { return d * d * d; }) / diameter_moment(broad, 3);
  EXPECT_LT(mass_fraction_kept, 0.99);  // the cap really cuts this one
  const double lwc = 0.5;
  const double held = number_concentration_per_m3(broad, lwc) * rho_water_g_per_m3 *
                      std::numbers::pi / 6.0 * truncated([](double d) { return d * d * d; }) /
                      truncated([](double) { return 1.0; });
  validate_dsd("lwc_held.truncated_lognormal20um_2.5.lwc0.5", "liquid water content held", "g/m^3",
               "lognormal median 20 um, sigma_g 2.5, truncated at 1 mm, 0.5 g/m^3", held, lwc,
               "the requested LWC; truncated pdf integrated by Boost adaptive Gauss-Kronrod, "
               "normalised by its own integral",
               1e-6, Tolerance::relative);
}

TEST(Dsd, ShettleFennPresets) {
  const auto check = [](const ModifiedGamma& d, double a_per_cm3_um, double n_per_cm3,
                        double mode_um) {
    validate_dsd("shettle_fenn.number_concentration.a" + num(a_per_cm3_um),
                 "number concentration a Gamma(alpha+1) / b^(alpha+1)", "1/cm^3",
                 "modified gamma preset, a = " + num(a_per_cm3_um) + " cm^-3 um^-1",
                 a_per_cm3_um * boost::math::tgamma(d.alpha + 1.0) /
                     std::pow(d.b_per_um_gamma, d.alpha + 1.0),
                 n_per_cm3, "Shettle & Fenn presets, Al Naboulsi et al. 2004 Table 1", 1e-3,
                 Tolerance::relative);
    // Mode of p(D) at D = 2 r_mode: the pdf is lower half a micrometre either side.
    const double mode_d = 2e-6 * mode_um;
    EXPECT_GT(diameter_pdf(d, mode_d), diameter_pdf(d, mode_d - 1e-6));
    EXPECT_GT(diameter_pdf(d, mode_d), diameter_pdf(d, mode_d + 1e-6));
  };
  check(advection_fog(), 0.027, 20.0, 10.0);
  check(radiation_fog(), 2.37305, 100.0, 4.0);
  // The mode radii the same table gives: 10 um (advection) and 4 um (radiation).
  validate_dsd("shettle_fenn.mode_radius.advection", "mode radius (alpha / (b gamma))^(1/gamma)",
               "um", "advection preset", mode_radius_um(advection_fog()), 10.0,
               "Al Naboulsi et al. 2004 Table 1", 1e-12, Tolerance::relative);
  validate_dsd("shettle_fenn.mode_radius.radiation", "mode radius (alpha / (b gamma))^(1/gamma)",
               "um", "radiation preset", mode_radius_um(radiation_fog()), 4.0,
               "Al Naboulsi et al. 2004 Table 1", 1e-12, Tolerance::relative);
}

TEST(Dsd, RejectsInvalidParameters) {
  const auto field_of = [](const DropSizeDistribution& dsd) {
    return test_support::rejected_field([&] { validate(dsd); });
  };
  EXPECT_EQ(field_of(Monodisperse{-1e-6}), "fog.droplets.diameter_m");
  EXPECT_EQ(field_of(Monodisperse{std::nan("")}), "fog.droplets.diameter_m");
  EXPECT_EQ(field_of(Monodisperse{2e-3}), "fog.droplets.diameter_m");
  EXPECT_EQ(field_of(Lognormal{0.0, 1.5}), "fog.droplets.median_diameter_m");
  EXPECT_EQ(field_of(Lognormal{1e-6, 1.0}), "fog.droplets.geometric_std");
  EXPECT_EQ(field_of(Lognormal{1e-6, INFINITY}), "fog.droplets.geometric_std");
  EXPECT_EQ(field_of(ModifiedGamma{.alpha = -1.0}), "fog.droplets.alpha");
  EXPECT_EQ(field_of(ModifiedGamma{.gamma = 0.0}), "fog.droplets.gamma");
  EXPECT_EQ(field_of(ModifiedGamma{.b_per_um_gamma = 0.0}), "fog.droplets.b_per_um_gamma");
  EXPECT_EQ(field_of(ModifiedGamma{.alpha = 3.0, .gamma = 1.0, .b_per_um_gamma = 1e-3}),
            "fog.droplets.b_per_um_gamma");
  // The mean radius bound itself: for gamma = 1 the mean radius is (alpha + 1) / b, 500 um at
  // alpha = 3, b = 8e-3 (accepted), beyond it just below.
  EXPECT_EQ(field_of(ModifiedGamma{.alpha = 3.0, .gamma = 1.0, .b_per_um_gamma = 8e-3}),
            "accepted");
  EXPECT_EQ(field_of(ModifiedGamma{.alpha = 3.0, .gamma = 1.0, .b_per_um_gamma = 7.99e-3}),
            "fog.droplets.b_per_um_gamma");
  // At alpha = 0 the mode radius is 0 for every b; the mean radius 1/b still bounds the droplets
  // (b = 1e-300 once passed the mode's bound and then asked for droplets of 1e300 um).
  EXPECT_EQ(field_of(ModifiedGamma{.alpha = 0.0, .gamma = 1.0, .b_per_um_gamma = 1e-300}),
            "fog.droplets.b_per_um_gamma");
  EXPECT_EQ(field_of(ModifiedGamma{.alpha = 0.0, .gamma = 1.0, .b_per_um_gamma = 2e-3}),
            "accepted");
  EXPECT_EQ(field_of(advection_fog()), "accepted");
  EXPECT_EQ(field_of(default_fog_droplets()), "accepted");
}

}  // namespace
}  // namespace fogradar::propagation
