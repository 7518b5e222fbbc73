// Drop size distributions of fog, normalised to a liquid water content (LWC).
// Shapes are number densities over droplet diameter; the scale (number concentration N) follows
// from LWC = rho_w N (pi/6) <D^3>.
#pragma once

#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "fogradar/core/keys.hpp"

namespace fogradar::propagation {

// Every droplet has the same diameter.
struct Monodisperse {
  double diameter_m = 1e-6;
  bool operator==(const Monodisperse&) const = default;
};

// ln D ~ Normal(ln median, ln geometric_std^2).
struct Lognormal {
  double median_diameter_m = 1e-6;
  double geometric_std = 1.5;  // sigma_g > 1
  bool operator==(const Lognormal&) const = default;
};

// Modified gamma distribution in radius r (Deirmendjian 1969):
//   n(r) = a r^alpha exp(-b r^gamma),  r in micrometres, b in um^-gamma.
// The scale a is not stored: the LWC normalisation sets it.
struct ModifiedGamma {
  double alpha = 3.0;
  double gamma = 1.0;
  double b_per_um_gamma = 0.3;
  bool operator==(const ModifiedGamma&) const = default;
};

using DropSizeDistribution = std::variant<Monodisperse, Lognormal, ModifiedGamma>;

// Advection fog: alpha = 3, gamma = 1, b = 0.3 um^-1 (mode radius 10 um, N = 20 cm^-3,
// LWC about 0.37 g/m^3 with a = 0.027). Radiation fog: alpha = 6, gamma = 1, b = 1.5 um^-1
// (mode radius 4 um, N = 100 cm^-3, LWC about 0.06 g/m^3 with a = 2.37305). Both as tabulated by
// Al Naboulsi, Sizun & de Fornel, Opt. Eng. 43(2), 319-329 (2004), Table 1, after Shettle & Fenn
// 1979.
ModifiedGamma advection_fog();
ModifiedGamma radiation_fog();

// Mode radius of a modified gamma, where n(r) peaks: r_c = (alpha / (b gamma))^(1/gamma) in um
// (dn/dr = 0; Deirmendjian 1969).
double mode_radius_um(const ModifiedGamma& d);
// Mean radius of a modified gamma: <r> = Gamma((alpha + 2)/gamma) / (b^(1/gamma)
// Gamma((alpha + 1)/gamma)) in um (the k = 1 moment, Deirmendjian 1969). It bounds the droplets'
// scale for every alpha, where the mode radius is 0 at alpha = 0 whatever b is.
double mean_radius_um(const ModifiedGamma& d);
// The largest mean radius accepted: half the largest droplet diameter fogradar takes (1 mm).
inline constexpr double max_mean_radius_um = 500.0;
// That bound as a message states it: "the mean radius Gamma((alpha + 2)/gamma) / (b^(1/gamma)
// Gamma((alpha + 1)/gamma)) <= 500 um".
std::string mean_radius_rule();

// The distribution fogradar uses when none is given: the study's ultrasonic fogger makes droplets
// of "diameter about 1 um" (paper sec. III-B); lognormal, median 1 um, sigma_g = 1.5 (an assumption
// typical of ultrasonic atomiser spectra; documented in docs/physics.md).
DropSizeDistribution default_fog_droplets();

// Short name of the distribution family: "monodisperse", "lognormal" or "modified_gamma".
std::string_view distribution_name(const DropSizeDistribution& dsd);

// The scenario keys of a distribution under `prefix` ("fog.droplets."): `distribution` chooses the
// family (the modified-gamma presets `advection` and `radiation` by name), and each family's own
// keys take effect only with it.
KeyTable<DropSizeDistribution> droplet_keys(std::string prefix);

// Throws InvalidParameter naming the key under "fog.droplets." (e.g. "fog.droplets.geometric_std")
// if out of range (droplet_keys).
void validate(const DropSizeDistribution& dsd);

// k-th raw moment <D^k> of the normalised, untruncated distribution (m^k), closed form.
double diameter_moment(const DropSizeDistribution& dsd, int k);

// Number concentration N (1/m^3) that holds `lwc_g_per_m3` of liquid water:
//   N = LWC / (rho_w (pi/6) <D^3>), <D^3> of the distribution truncated to the quadrature range.
double number_concentration_per_m3(const DropSizeDistribution& dsd, double lwc_g_per_m3);

// Normalised probability density of diameter, p(D) (1/m), integrating to 1. Zero for monodisperse
// (a delta; quadrature_nodes handles it exactly).
double diameter_pdf(const DropSizeDistribution& dsd, double diameter_m);

// Diameter interval outside which each tail holds less than 1e-12 of the number (lower end) and of
// the D^6 moment (upper end), clipped to the droplet sizes fogradar accepts (10 nm .. 1 mm): the
// quadrature range. A broad distribution (e.g. lognormal, median 20 um, sigma_g 2.5) is truncated
// at 1 mm: its drops beyond are drizzle, not fog. Both ends equal the diameter for monodisperse.
struct DiameterRange {
  double min_m;
  double max_m;
};
DiameterRange quadrature_range(const DropSizeDistribution& dsd);

// Nodes and weights with sum_j weight_j f(D_j) ~ integral f(D) p(D) dD over the truncated and
// renormalised distribution: composite Gauss-Legendre in ln D over quadrature_range (a single node
// of weight 1 for monodisperse). Bulk fog optics are sums of per-droplet cross sections over these
// nodes.
struct QuadratureNode {
  double diameter_m;
  double weight;
};
std::vector<QuadratureNode> quadrature_nodes(const DropSizeDistribution& dsd);

}  // namespace fogradar::propagation
