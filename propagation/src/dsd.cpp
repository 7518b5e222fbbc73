#include "fogradar/propagation/dsd.hpp"

#include <algorithm>
#include <boost/math/distributions/gamma.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::propagation {
namespace {

constexpr double metres_per_um = 1e-6;
// Droplet sizes fogradar accepts: 10 nm (below, water is no continuum droplet) to 1 mm (drizzle;
// fog droplets are < 100 um, paper sec. I). Distributions are truncated to this interval.
constexpr double min_droplet_diameter_m = 1e-8;
constexpr double max_droplet_diameter_m = 1e-3;
// Tail mass left outside the quadrature range on each side.
constexpr double tail_fraction = 1e-12;
// Composite Gauss-Legendre: panels x points per panel in ln D. 20-point rules are exact for
// polynomials of degree 39 per panel; 48 panels resolve the Mie interference structure of optical
// wavelengths over a fog distribution (checked in test_dsd against adaptive Gauss-Kronrod).
constexpr int points_per_panel = 20;
constexpr int panel_count = 48;

// ln sigma_g of a lognormal.
double log_std(const Lognormal& d) { return std::log(d.geometric_std); }

// Shape parameter of the gamma law that u = b r^gamma follows under the r^k-weighted modified gamma
// distribution: n(r) r^k dr ~ u^((alpha+1+k)/gamma - 1) e^-u du (Deirmendjian 1969).
double gamma_shape(const ModifiedGamma& d, int k) { return (d.alpha + 1.0 + k) / d.gamma; }

// Radius (um) from u = b r^gamma.
double radius_um_from_u(const ModifiedGamma& d, double u) {
  return std::pow(u / d.b_per_um_gamma, 1.0 / d.gamma);
}

}  // namespace

ModifiedGamma advection_fog() { return {.alpha = 3.0, .gamma = 1.0, .b_per_um_gamma = 0.3}; }
ModifiedGamma radiation_fog() { return {.alpha = 6.0, .gamma = 1.0, .b_per_um_gamma = 1.5}; }

double mode_radius_um(const ModifiedGamma& d) {
  return std::pow(d.alpha / (d.b_per_um_gamma * d.gamma), 1.0 / d.gamma);
}

double mean_radius_um(const ModifiedGamma& d) {
  return boost::math::tgamma_ratio(gamma_shape(d, 1), gamma_shape(d, 0)) /
         std::pow(d.b_per_um_gamma, 1.0 / d.gamma);
}

std::string mean_radius_rule() {
  return "the mean radius Gamma((alpha + 2)/gamma) / (b^(1/gamma) Gamma((alpha + 1)/gamma)) <= " +
         message_number(max_mean_radius_um) + " um";
}

DropSizeDistribution default_fog_droplets() {
  return Lognormal{.median_diameter_m = 1e-6, .geometric_std = 1.5};
}

std::string_view distribution_name(const DropSizeDistribution& dsd) {
  struct Name {
    std::string_view operator()(const Monodisperse&) const { return "monodisperse"; }
    std::string_view operator()(const Lognormal&) const { return "lognormal"; }
    std::string_view operator()(const ModifiedGamma&) const { return "modified_gamma"; }
  };
  return std::visit(Name{}, dsd);
}

KeyTable<DropSizeDistribution> droplet_keys(std::string prefix) {
  KeyTable<DropSizeDistribution> keys(prefix);
  const std::string family = prefix + "distribution";
  const auto is = [](auto alternative) {
    return [](const DropSizeDistribution& d) {
      return std::holds_alternative<decltype(alternative)>(d);
    };
  };
  const auto only_with = [&family](std::string_view name) {
    return "with " + family + " = \"" + std::string(name) + "\"";
  };
  // A family given by name keeps the values already set for it (a file's keys over the paper's);
  // a preset starts from its published values.
  keys.choice(
      "distribution",
      [](const DropSizeDistribution& d) { return std::string(distribution_name(d)); },
      [family](DropSizeDistribution& d, std::string_view name) {
        if (name == "lognormal") {
          if (!std::holds_alternative<Lognormal>(d)) d = Lognormal{};
        } else if (name == "monodisperse") {
          if (!std::holds_alternative<Monodisperse>(d)) d = Monodisperse{};
        } else if (name == "advection") {
          d = advection_fog();
        } else if (name == "radiation") {
          d = radiation_fog();
        } else if (name == "modified_gamma") {
          if (!std::holds_alternative<ModifiedGamma>(d)) d = ModifiedGamma{};
        } else {
          throw_invalid(family, name,
                        "one of 'lognormal', 'monodisperse', 'advection', 'radiation', "
                        "'modified_gamma'");
        }
      },
      {"lognormal", "monodisperse", "advection", "radiation", "modified_gamma"},
      "drop size distribution; `advection` and `radiation` are the modified-gamma presets of "
      "Shettle & Fenn (Al Naboulsi et al. 2004, Table 1), written back as `modified_gamma`");
  keys.number(
          "median_diameter_m",
          [](const DropSizeDistribution& d) { return std::get<Lognormal>(d).median_diameter_m; },
          [](DropSizeDistribution& d, double v) { std::get<Lognormal>(d).median_diameter_m = v; },
          closed(min_droplet_diameter_m, max_droplet_diameter_m), "lognormal median diameter")
      .when(is(Lognormal{}), only_with("lognormal"));
  keys.number(
          "geometric_std",
          [](const DropSizeDistribution& d) { return std::get<Lognormal>(d).geometric_std; },
          [](DropSizeDistribution& d, double v) { std::get<Lognormal>(d).geometric_std = v; },
          closed(1.01, 3.0), "lognormal geometric standard deviation σ_g")
      .when(is(Lognormal{}), only_with("lognormal"));
  keys.number(
          "diameter_m",
          [](const DropSizeDistribution& d) { return std::get<Monodisperse>(d).diameter_m; },
          [](DropSizeDistribution& d, double v) { std::get<Monodisperse>(d).diameter_m = v; },
          closed(min_droplet_diameter_m, max_droplet_diameter_m), "monodisperse diameter")
      .when(is(Monodisperse{}), only_with("monodisperse"));
  const std::string gamma_text = "with " + family + " = \"modified_gamma\" (or a preset)";
  keys.number(
          "alpha", [](const DropSizeDistribution& d) { return std::get<ModifiedGamma>(d).alpha; },
          [](DropSizeDistribution& d, double v) { std::get<ModifiedGamma>(d).alpha = v; },
          closed(0.0, 20.0), "modified gamma n(r) = a r^α exp(−b r^γ): α")
      .when(is(ModifiedGamma{}), gamma_text);
  keys.number(
          "gamma", [](const DropSizeDistribution& d) { return std::get<ModifiedGamma>(d).gamma; },
          [](DropSizeDistribution& d, double v) { std::get<ModifiedGamma>(d).gamma = v; },
          closed(0.25, 4.0), "modified gamma: γ")
      .when(is(ModifiedGamma{}), gamma_text);
  const std::string b_key = prefix + "b_per_um_gamma";
  keys.number(
          "b_per_um_gamma",
          [](const DropSizeDistribution& d) { return std::get<ModifiedGamma>(d).b_per_um_gamma; },
          [](DropSizeDistribution& d, double v) { std::get<ModifiedGamma>(d).b_per_um_gamma = v; },
          positive(),
          "modified gamma: b in µm^−γ, with the mean radius Γ((α+2)/γ) / (b^(1/γ) Γ((α+1)/γ)) ≤ "
          "500 µm")
      .when(is(ModifiedGamma{}), gamma_text)
      .with_check([b_key](const DropSizeDistribution& dsd) {
        const ModifiedGamma& d = std::get<ModifiedGamma>(dsd);
        if (!(mean_radius_um(d) <= max_mean_radius_um)) {
          throw_invalid(b_key, d.b_per_um_gamma, "large enough that " + mean_radius_rule());
        }
      })
      .documented_as("> 0, mean radius ≤ 500 µm");
  return keys;
}

void validate(const DropSizeDistribution& dsd) { droplet_keys("fog.droplets.").check(dsd); }

double diameter_moment(const DropSizeDistribution& dsd, int k) {
  struct Moment {
    int k;
    // <D^k> = D^k.
    double operator()(const Monodisperse& d) const { return std::pow(d.diameter_m, k); }
    // <D^k> = D_med^k exp(k^2 s^2 / 2) (Aitchison & Brown 1957, lognormal moments).
    double operator()(const Lognormal& d) const {
      const double s = log_std(d);
      return std::pow(d.median_diameter_m, k) * std::exp(0.5 * k * k * s * s);
    }
    // <r^k> = Gamma((alpha+1+k)/gamma) / (b^(k/gamma) Gamma((alpha+1)/gamma)), <D^k> = 2^k <r^k>.
    double operator()(const ModifiedGamma& d) const {
      const double r_moment_um = boost::math::tgamma_ratio(gamma_shape(d, k), gamma_shape(d, 0)) /
                                 std::pow(d.b_per_um_gamma, k / d.gamma);
      return std::pow(2.0 * metres_per_um, k) * r_moment_um;
    }
  };
  return std::visit(Moment{k}, dsd);
}

// LWC = rho_w N (pi/6) <D^3>  =>  N = LWC / (rho_w (pi/6) <D^3>), with <D^3> of the truncated
// distribution the optics integrate over, so that N and the bulk sums hold exactly that LWC.
double number_concentration_per_m3(const DropSizeDistribution& dsd, double lwc_g_per_m3) {
  double mean_volume_m3 = 0.0;
  for (const QuadratureNode& node : quadrature_nodes(dsd)) {
    mean_volume_m3 += node.weight * pi / 6.0 * node.diameter_m * node.diameter_m * node.diameter_m;
  }
  return lwc_g_per_m3 / (water_density_g_per_m3 * mean_volume_m3);
}

double diameter_pdf(const DropSizeDistribution& dsd, double diameter_m) {
  struct Pdf {
    double diameter_m;
    double operator()(const Monodisperse&) const { return 0.0; }
    // p(D) = exp(-(ln D - ln D_med)^2 / (2 s^2)) / (D s sqrt(2 pi)).
    double operator()(const Lognormal& d) const {
      const boost::math::normal_distribution<double> log_law(std::log(d.median_diameter_m),
                                                             log_std(d));
      return boost::math::pdf(log_law, std::log(diameter_m)) / diameter_m;
    }
    // p_r(r) = gamma b^((alpha+1)/gamma) r^alpha exp(-b r^gamma) / Gamma((alpha+1)/gamma),
    // p(D) = p_r(D/2) / 2 with r in um, converted to 1/m.
    double operator()(const ModifiedGamma& d) const {
      const double r_um = 0.5 * diameter_m / metres_per_um;
      const double shape = gamma_shape(d, 0);
      const double log_pr = std::log(d.gamma) + shape * std::log(d.b_per_um_gamma) +
                            d.alpha * std::log(r_um) - d.b_per_um_gamma * std::pow(r_um, d.gamma) -
                            boost::math::lgamma(shape);
      return 0.5 * std::exp(log_pr) / metres_per_um;
    }
  };
  if (!(diameter_m > 0.0)) return 0.0;
  return std::visit(Pdf{diameter_m}, dsd);
}

DiameterRange quadrature_range(const DropSizeDistribution& dsd) {
  struct Range {
    DiameterRange operator()(const Monodisperse& d) const { return {d.diameter_m, d.diameter_m}; }
    // The D^k-weighted lognormal is lognormal with ln-median shifted by k s^2.
    DiameterRange operator()(const Lognormal& d) const {
      const double s = log_std(d);
      const double z =
          boost::math::quantile(boost::math::normal_distribution<double>(), 1.0 - tail_fraction);
      const double mu = std::log(d.median_diameter_m);
      return {std::exp(mu - z * s), std::exp(mu + 6.0 * s * s + z * s)};
    }
    // u = b r^gamma is Gamma((alpha+1+k)/gamma, 1) distributed under the r^k weight.
    DiameterRange operator()(const ModifiedGamma& d) const {
      const boost::math::gamma_distribution<double> number_law(gamma_shape(d, 0));
      const boost::math::gamma_distribution<double> d6_law(gamma_shape(d, 6));
      const double u_low = boost::math::quantile(number_law, tail_fraction);
      const double u_high = boost::math::quantile(boost::math::complement(d6_law, tail_fraction));
      return {2.0 * metres_per_um * radius_um_from_u(d, u_low),
              2.0 * metres_per_um * radius_um_from_u(d, u_high)};
    }
  };
  const DiameterRange tails = std::visit(Range{}, dsd);
  return {std::max(tails.min_m, min_droplet_diameter_m),
          std::min(tails.max_m, max_droplet_diameter_m)};
}

std::vector<QuadratureNode> quadrature_nodes(const DropSizeDistribution& dsd) {
  if (const auto* mono = std::get_if<Monodisperse>(&dsd)) {
    return {{mono->diameter_m, 1.0}};
  }
  using Rule = boost::math::quadrature::gauss<double, points_per_panel>;
  const DiameterRange range = quadrature_range(dsd);
  const double log_low = std::log(range.min_m);
  const double panel_width = (std::log(range.max_m) - log_low) / panel_count;
  std::vector<QuadratureNode> nodes;
  nodes.reserve(static_cast<std::size_t>(panel_count * points_per_panel));
  // Gauss-Legendre on [-1, 1] stores non-negative abscissae; each x > 0 stands for +x and -x.
  const auto add_node = [&](double panel_mid, double x, double w) {
    const double diameter = std::exp(panel_mid + 0.5 * panel_width * x);
    // dD = D d(ln D); the panel maps [-1, 1] onto a width of panel_width.
    nodes.push_back({diameter, 0.5 * panel_width * w * diameter * diameter_pdf(dsd, diameter)});
  };
  for (int panel = 0; panel < panel_count; ++panel) {
    const double mid = log_low + (panel + 0.5) * panel_width;
    for (std::size_t i = 0; i < Rule::abscissa().size(); ++i) {
      const double x = Rule::abscissa()[i];
      const double w = Rule::weights()[i];
      add_node(mid, x, w);
      if (x != 0.0) add_node(mid, -x, w);
    }
  }
  // Normalise to the truncated distribution (a no-op to ~1e-12 unless the 1 mm cap cut a tail).
  double total = 0.0;
  for (const QuadratureNode& node : nodes) total += node.weight;
  for (QuadratureNode& node : nodes) node.weight /= total;
  return nodes;
}

}  // namespace fogradar::propagation
