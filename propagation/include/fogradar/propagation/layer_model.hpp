// The study's virtual layer model (paper eq. 3 and 4, after its ref. [17]): the range is cut into
// virtual layers as thick as the sensor's range resolution; each layer transmits a fraction tau of
// the power crossing it and reflects a fraction rho back. A wave that returns to the sensor after
// crossing 2n layer boundaries arrives in delay bin n. Its paths are Dyck paths of semilength n
// (heights = layer index) that touch height 0 (the sensor) only at both ends; a path with i peaks
// has 2i-1 reflections (i peaks, i-1 valleys) and 2n-2i transmissions, kappa = 2n-1 interactions
// in all, and is counted by the Narayana number N(n-1, i). That is eq. 3:
//   I_kappa = I_0 sum_{i=1}^{(kappa-1)/2} p_i rho^(2i-1) tau^(kappa+1-2i),  p_i = N((kappa-1)/2, i)
// and the total over i is the Catalan number C((kappa-1)/2). n = 1 (kappa = 1), the first layer's
// own echo, is the single path with one reflection: I_1 = I_0 rho.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace fogradar::propagation {

// Catalan number C_n = binom(2n, n) / (n + 1). Throws InvalidParameter if it overflows uint64.
std::uint64_t catalan(unsigned n);

// Narayana number N(n, k) = binom(n, k) binom(n, k-1) / n: Dyck paths of semilength n with k peaks.
// N(n, k) = 0 for k = 0 or k > n (n >= 1). Throws InvalidParameter on uint64 overflow.
std::uint64_t narayana(unsigned n, unsigned k);

// p_i of eq. 3 for odd kappa >= 1: N((kappa-1)/2, i) for kappa >= 3; for kappa = 1, p_1 = 1.
// Throws InvalidParameter for even kappa or i outside 1..max(1, (kappa-1)/2).
std::uint64_t layer_path_count(unsigned kappa, unsigned i);

// Eq. 3: fog-only received intensity in the delay bin of kappa = 2n-1 interactions, for an
// unbounded stack of identical layers. tau, rho in [0, 1] with tau + rho <= 1.
double layer_model_intensity(unsigned kappa, double tau, double rho, double i0 = 1.0);

// Eq. 4: the direct echo of an object behind `layers` layers: I_obj = I_0 rho_obj tau^(2 layers).
double object_intensity(unsigned layers, double tau, double rho_object, double i0 = 1.0);

// One virtual layer of a finite stack.
struct VirtualLayer {
  double transmittance = 1.0;  // tau, power fraction that crosses the layer
  double reflectance = 0.0;    // rho, power fraction sent back
  void validate() const;       // each in [0, 1], tau + rho <= 1
};

// Received intensity per delay bin n = 1..max_bin (index n-1 of the result) for a finite stack of
// virtual layers followed, one layer beyond the last, by an object of reflectance rho_object
// (0 for none). Sums every reflection path (with any number of multiple reflections, bounded by
// the stack) by dynamic programming over Dyck paths. With all rho = 0 it reduces to eq. 4 in bin
// layers.size() + 1; with identical layers and a stack deeper than max_bin it equals eq. 3.
std::vector<double> layer_stack_response(std::span<const VirtualLayer> layers, double rho_object,
                                         unsigned max_bin, double i0 = 1.0);

// Virtual layer from fog bulk optics: tau = exp(-alpha d) with alpha the power extinction
// coefficient (1/m) and d the layer thickness (m); rho = eta d, the layer's backscattering cross
// section per unit area (eta in m^2/m^3), i.e. its area reflectivity sigma^0.
VirtualLayer virtual_layer_from_fog(double extinction_per_m, double eta_m2_per_m3,
                                    double thickness_m);

// The longest layer d whose virtual layer keeps tau + rho = exp(-alpha d) + eta d <= 1, for
// 0 < eta < alpha: the sum falls from 1 at d = 0 to its minimum at ln(alpha / eta) / alpha and
// rises through 1 once more before d = 1 / eta (the root found to the last double).
double longest_layer_m(double extinction_per_m, double eta_m2_per_m3);

// One row of eq. 3, 4 for a stack of identical layers: an object behind `layers` layers (eq. 4),
// and the fog's own echo in its delay bin, kappa = 2 layers + 1 (eq. 3), both per I_0.
struct LayerModelRow {
  unsigned layers = 0;
  unsigned kappa = 1;
  double fog_intensity_per_i0 = 0.0;
  double object_intensity_per_i0 = 0.0;
};
// The rows for 0 .. max_layers layers of `layer` before an object of `object_reflectivity`.
std::vector<LayerModelRow> layer_model_table(const VirtualLayer& layer, unsigned max_layers,
                                             double object_reflectivity);

}  // namespace fogradar::propagation
