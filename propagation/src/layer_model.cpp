#include "fogradar/propagation/layer_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string_view>
#include <vector>

#include "fogradar/core/error.hpp"

namespace fogradar::propagation {
namespace {

constexpr std::uint64_t uint64_max = std::numeric_limits<std::uint64_t>::max();

// Product a b, throwing InvalidParameter on field "n" if it exceeds uint64.
std::uint64_t checked_product(std::uint64_t a, std::uint64_t b, unsigned n) {
  if (b != 0 && a > uint64_max / b) {
    throw_invalid("n", static_cast<double>(n), "small enough for the result to fit in uint64");
  }
  return a * b;
}

// Exact a b / c for an integer result: cancelling gcd(a, c) first leaves c' | b, so the only
// product formed is the (checked) result itself, never a larger intermediate.
std::uint64_t exact_product_quotient(std::uint64_t a, std::uint64_t b, std::uint64_t c,
                                     unsigned n) {
  const std::uint64_t g = std::gcd(a, c);
  return checked_product(a / g, b / (c / g), n);
}

// binom(n, k) by binom(m, j) = binom(m-1, j-1) m / j; every intermediate is a smaller binomial
// coefficient, so an overflow means binom(n, k) itself does not fit.
std::uint64_t binomial(unsigned n, unsigned k) {
  if (k > n) return 0;
  const unsigned j_max = std::min(k, n - k);
  std::uint64_t value = 1;
  for (unsigned j = 1; j <= j_max; ++j) value = exact_product_quotient(value, n - j_max + j, j, n);
  return value;
}

void require_probability_pair(std::string_view tau_field, double tau, std::string_view rho_field,
                              double rho) {
  require_in_range(tau_field, tau, 0.0, 1.0);
  require_in_range(rho_field, rho, 0.0, 1.0);
  if (tau + rho > 1.0) throw_invalid(rho_field, rho, "<= 1 - transmittance (energy conservation)");
}

void require_odd_kappa(unsigned kappa) {
  if (kappa % 2 == 0) throw_invalid("kappa", static_cast<double>(kappa), "odd (kappa = 2n - 1)");
}

// ln[N(m, i+1) / N(m, i)] = ln[(m-i)(m-i+1) / (i(i+1))], from N = binom(m, k) binom(m, k-1) / m.
double log_narayana_ratio(unsigned m, unsigned i) {
  const double mi = static_cast<double>(m - i);
  const double di = static_cast<double>(i);
  return std::log(mi * (mi + 1.0) / (di * (di + 1.0)));
}

// Eq. 3 sum for m = (kappa-1)/2 >= 1 and tau, rho > 0, in log space: p_i overflows uint64 from
// m = 38 on and tau^(2m) underflows double for deep bins whose total is still significant.
double eq3_sum_log_space(unsigned m, double tau, double rho) {
  const double log_x = 2.0 * std::log(rho / tau);  // term_{i+1} / term_i = N ratio * (rho/tau)^2
  std::vector<double> log_terms;
  log_terms.reserve(m);
  double log_term = std::log(rho) + 2.0 * static_cast<double>(m) * std::log(tau);  // i = 1, N = 1
  for (unsigned i = 1; i <= m; ++i) {
    log_terms.push_back(log_term);
    if (i < m) log_term += log_narayana_ratio(m, i) + log_x;
  }
  const double log_max = *std::max_element(log_terms.begin(), log_terms.end());
  double scaled_sum = 0.0;
  for (double t : log_terms) scaled_sum += std::exp(t - log_max);
  return std::exp(log_max) * scaled_sum;
}

// Weights of the partial paths that have just arrived at each height, split by the direction of
// the last step. Height h in 1..L is virtual layer h, height L+1 the object, height 0 the sensor.
struct PathFront {
  std::vector<double> rising;
  std::vector<double> falling;
};

// Reflectance that turns a path at height h (object above the last layer).
double turn_weight(std::span<const VirtualLayer> layers, double rho_object, std::size_t h) {
  return h <= layers.size() ? layers[h - 1].reflectance : rho_object;
}

// One step of every partial path. At an interior vertex at height h the wave meets layer h: it
// crosses it (tau_h) when the path keeps its direction and is reflected (rho_h) when it turns. A
// valley at h is the wave travelling toward the sensor in layer h+1 sent back up by layer h, so
// it also takes rho_h. The object (h = L+1) only reflects; the sensor (h = 0) absorbs.
PathFront advance(std::span<const VirtualLayer> layers, double rho_object, const PathFront& front) {
  const std::size_t top = front.rising.size() - 1;  // a path above it could not return in time
  PathFront next{std::vector<double>(top + 1, 0.0), std::vector<double>(top + 1, 0.0)};
  for (std::size_t h = 1; h <= top; ++h) {  // h = 0 is skipped: the sensor absorbs
    const double turn = turn_weight(layers, rho_object, h);
    const double cross = h <= layers.size() ? layers[h - 1].transmittance : 0.0;
    if (h < top) next.rising[h + 1] += front.rising[h] * cross;
    next.falling[h - 1] += front.rising[h] * turn;
    next.falling[h - 1] += front.falling[h] * cross;
    if (h < top) next.rising[h + 1] += front.falling[h] * turn;
  }
  return next;
}

}  // namespace

// C_n = binom(2n, n) / (n + 1) (OEIS A000108), by C_{j+1} = C_j 2(2j+1) / (j+2).
std::uint64_t catalan(unsigned n) {
  std::uint64_t value = 1;
  for (unsigned j = 0; j < n; ++j) value = exact_product_quotient(value, 2 * (2 * j + 1), j + 2, n);
  return value;
}

// N(n, k) = binom(n, k) binom(n, k-1) / n (OEIS A001263). N(0, 0) = 1 (the empty Dyck path), so
// sum_k N(n, k) = C_n holds for n = 0 too. For 2 <= k <= n-1 both binomials are <= N(n, k), so
// their own overflow already means N(n, k) does not fit.
std::uint64_t narayana(unsigned n, unsigned k) {
  if (n == 0) return k == 0 ? 1 : 0;
  if (k == 0 || k > n) return 0;
  return exact_product_quotient(binomial(n, k), binomial(n, k - 1), n, n);
}

// p_i of eq. 3: the Dyck paths of semilength (kappa+1)/2 touching 0 only at both ends are
// U (any Dyck path of semilength (kappa-1)/2) D, with the inner path's peaks.
std::uint64_t layer_path_count(unsigned kappa, unsigned i) {
  require_odd_kappa(kappa);
  const unsigned m = (kappa - 1) / 2;
  if (i < 1 || i > std::max(1U, m)) {
    throw_invalid("i", static_cast<double>(i), "in [1, max(1, (kappa - 1) / 2)]");
  }
  return m == 0 ? 1 : narayana(m, i);
}

// Eq. 3: I_kappa = I_0 sum_{i=1}^{(kappa-1)/2} p_i rho^(2i-1) tau^(kappa+1-2i); I_1 = I_0 rho.
double layer_model_intensity(unsigned kappa, double tau, double rho, double i0) {
  require_odd_kappa(kappa);
  require_probability_pair("tau", tau, "rho", rho);
  require_non_negative("i0", i0);
  const unsigned m = (kappa - 1) / 2;
  if (m == 0) return i0 * rho;
  if (tau == 0.0 || rho == 0.0) return 0.0;  // every term has rho^(>=1) tau^(>=2)
  return i0 * eq3_sum_log_space(m, tau, rho);
}

// Eq. 4: I_obj = I_0 rho_obj tau^(2 layers).
double object_intensity(unsigned layers, double tau, double rho_object, double i0) {
  require_in_range("tau", tau, 0.0, 1.0);
  require_in_range("rho_object", rho_object, 0.0, 1.0);
  require_non_negative("i0", i0);
  return i0 * rho_object * std::pow(tau, 2.0 * static_cast<double>(layers));
}

void VirtualLayer::validate() const {
  require_probability_pair("VirtualLayer.transmittance", transmittance, "VirtualLayer.reflectance",
                           reflectance);
}

// Sum over all paths of the virtual layer model, bin n = paths of 2n steps (see advance()).
std::vector<double> layer_stack_response(std::span<const VirtualLayer> layers, double rho_object,
                                         unsigned max_bin, double i0) {
  for (const VirtualLayer& layer : layers) layer.validate();
  require_in_range("rho_object", rho_object, 0.0, 1.0);
  require_non_negative("i0", i0);

  std::vector<double> response(max_bin, 0.0);
  if (max_bin == 0) return response;
  // A path of 2n steps rises at most n; nothing lies above the object at L+1.
  const std::size_t top = std::min<std::size_t>(layers.size() + 1, max_bin);
  PathFront front{std::vector<double>(top + 1, 0.0), std::vector<double>(top + 1, 0.0)};
  front.rising[1] = i0;  // first step: sensor -> layer 1, no interaction at the sensor
  for (unsigned step = 2; step <= 2 * max_bin; ++step) {
    front = advance(layers, rho_object, front);
    if (step % 2 == 0) response[step / 2 - 1] = front.falling[0];  // advance() drops it next
  }
  return response;
}

// tau = exp(-alpha d) (Beer-Lambert over the layer), rho = eta d (area reflectivity of a thin
// volume of backscatter coefficient eta).
VirtualLayer virtual_layer_from_fog(double extinction_per_m, double eta_m2_per_m3,
                                    double thickness_m) {
  require_non_negative("extinction_per_m", extinction_per_m);
  require_non_negative("eta_m2_per_m3", eta_m2_per_m3);
  require_positive("thickness_m", thickness_m);
  const VirtualLayer layer{std::exp(-extinction_per_m * thickness_m), eta_m2_per_m3 * thickness_m};
  if (layer.transmittance + layer.reflectance > 1.0) {
    throw_invalid("eta_m2_per_m3", eta_m2_per_m3,
                  "<= (1 - exp(-extinction_per_m thickness_m)) / thickness_m (tau + rho <= 1)");
  }
  return layer;
}

double longest_layer_m(double extinction_per_m, double eta_m2_per_m3) {
  require_positive("eta_m2_per_m3", eta_m2_per_m3);
  if (!(eta_m2_per_m3 < extinction_per_m)) {
    throw_invalid("eta_m2_per_m3", eta_m2_per_m3, "< extinction_per_m (some layer fits)");
  }
  double below = std::log(extinction_per_m / eta_m2_per_m3) / extinction_per_m;
  double above = 1.0 / eta_m2_per_m3;
  for (int step = 0; step < 200 && std::nextafter(below, above) < above; ++step) {
    const double middle = 0.5 * (below + above);
    const double sum = std::exp(-extinction_per_m * middle) + eta_m2_per_m3 * middle;
    (sum > 1.0 ? above : below) = middle;
  }
  return below;
}

std::vector<LayerModelRow> layer_model_table(const VirtualLayer& layer, unsigned max_layers,
                                             double object_reflectivity) {
  std::vector<LayerModelRow> rows;
  for (unsigned k = 0; k <= max_layers; ++k) {
    const unsigned kappa = 2 * k + 1;
    rows.push_back({k, kappa, layer_model_intensity(kappa, layer.transmittance, layer.reflectance),
                    object_intensity(k, layer.transmittance, object_reflectivity)});
  }
  return rows;
}

}  // namespace fogradar::propagation
