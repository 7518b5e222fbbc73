#include "fogradar/propagation/water_film.hpp"

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <span>
#include <sstream>
#include <string_view>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::propagation {
namespace {

using complex = std::complex<double>;
constexpr complex imaginary_unit{0.0, 1.0};

// Passive medium in the exp(-i omega t) convention: Re(m) > 0, Im(m) >= 0 (absorbing or lossless).
void require_passive_index(std::string_view field, complex index) {
  if (!(std::isfinite(index.real()) && std::isfinite(index.imag()) && index.real() > 0.0 &&
        index.imag() >= 0.0)) {
    std::ostringstream value;
    value.precision(10);
    value << index;
    throw_invalid(field, value.str(), "finite with Re > 0 and Im >= 0 (m = n + i k, k >= 0)");
  }
}

// Characteristic matrix of a homogeneous layer at normal incidence, p = m (Born & Wolf, 7th ed.,
// sec. 1.6): [[cos d, -i sin d / m], [-i m sin d, cos d]], d = 2 pi m t / lambda. B&W use
// exp(-i omega t), in which the forward wave exp(i d) decays when Im(m) > 0.
Eigen::Matrix2cd characteristic_matrix(const SlabLayer& layer, double wavelength_m) {
  const complex m = layer.refractive_index;
  const complex phase = 2.0 * pi * m * layer.thickness_m / wavelength_m;
  const complex c = std::cos(phase);
  const complex s = std::sin(phase);
  Eigen::Matrix2cd matrix;
  matrix << c, -imaginary_unit * s / m, -imaginary_unit * m * s, c;
  return matrix;
}

}  // namespace

// Total matrix M = M_1 ... M_N (order of incidence); with p_1 = n_in, p_l = n_out (B&W sec. 1.6)
//   r = ((m11 + m12 p_l) p_1 - (m21 + m22 p_l)) / D,  t = 2 p_1 / D,
//   D = (m11 + m12 p_l) p_1 + (m21 + m22 p_l).
// R = |r|^2 and T = Re(n_out)/Re(n_in) |t|^2 are power fractions of the incident Poynting flux;
// they assume a lossless incidence medium (with Im(n_in) > 0 the incident and reflected waves
// exchange power and R, T lose their meaning).
SlabResponse slab_response(std::span<const SlabLayer> layers, double wavelength_m, complex n_in,
                           complex n_out) {
  require_positive("wavelength_m", wavelength_m);
  require_passive_index("n_in", n_in);
  require_passive_index("n_out", n_out);
  Eigen::Matrix2cd total = Eigen::Matrix2cd::Identity();
  for (const SlabLayer& layer : layers) {
    require_non_negative("thickness_m", layer.thickness_m);
    require_passive_index("refractive_index", layer.refractive_index);
    total = total * characteristic_matrix(layer, wavelength_m);
  }

  const complex toward_in = (total(0, 0) + total(0, 1) * n_out) * n_in;
  const complex toward_out = total(1, 0) + total(1, 1) * n_out;
  const complex denominator = toward_in + toward_out;
  SlabResponse response;
  response.reflection_amplitude = (toward_in - toward_out) / denominator;
  response.transmission_amplitude = 2.0 * n_in / denominator;
  response.reflectance = std::norm(response.reflection_amplitude);
  response.transmittance = n_out.real() / n_in.real() * std::norm(response.transmission_amplitude);
  response.absorptance = 1.0 - response.reflectance - response.transmittance;
  return response;
}

// -10 log10(T^2) for the stack [radome, film] in air: the wave leaves the radar through the
// radome, then crosses the water film on its outer face; the echo crosses them in reverse, with
// the same T (reciprocity, equal media on both sides). Multiple reflections between the radome
// and the antenna or target are left out.
double film_two_way_loss_db(double film_thickness_m, complex water_index, complex radome_index,
                            double radome_thickness_m, double wavelength_m) {
  require_non_negative("film_thickness_m", film_thickness_m);
  require_passive_index("water_index", water_index);
  require_passive_index("radome_index", radome_index);
  require_non_negative("radome_thickness_m", radome_thickness_m);
  const SlabLayer stack[] = {{radome_index, radome_thickness_m}, {water_index, film_thickness_m}};
  const double one_way = slab_response(stack, wavelength_m).transmittance;
  // 10 log10(1 / T^2) rather than -10 log10(T^2): no radome and no film give +0, not -0.
  return power_ratio_to_db(1.0 / (one_way * one_way));
}

// Behind a perfect conductor U_l = E = 0 while V_l = H is free: [U_1, V_1] = M [0, V_l], and with
// U_1 = 1 + r, V_1 = n_in (1 - r) (B&W sec. 1.6) r = (m12 n_in - m22) / (m12 n_in + m22).
complex conductor_backed_reflection(std::span<const SlabLayer> layers, double wavelength_m,
                                    complex n_in) {
  require_positive("wavelength_m", wavelength_m);
  require_passive_index("n_in", n_in);
  Eigen::Matrix2cd total = Eigen::Matrix2cd::Identity();
  for (const SlabLayer& layer : layers) {
    require_non_negative("thickness_m", layer.thickness_m);
    require_passive_index("refractive_index", layer.refractive_index);
    total = total * characteristic_matrix(layer, wavelength_m);
  }
  return (total(0, 1) * n_in - total(1, 1)) / (total(0, 1) * n_in + total(1, 1));
}

double conductor_film_loss_db(double film_thickness_m, complex water_index, double wavelength_m) {
  require_non_negative("film_thickness_m", film_thickness_m);
  require_passive_index("water_index", water_index);
  const SlabLayer film[] = {{water_index, film_thickness_m}};
  return power_ratio_to_db(1.0 / std::norm(conductor_backed_reflection(film, wavelength_m)));
}

double window_film_transmittance(double film_thickness_m, complex water_index, double wavelength_m,
                                 double window_index) {
  require_non_negative("film_thickness_m", film_thickness_m);
  require_passive_index("water_index", water_index);
  require_passive_index("window_index", window_index);
  require_positive("wavelength_m", wavelength_m);
  // No film: the dry face itself (the incoherent sum holds for films of a few wavelengths only).
  if (film_thickness_m == 0.0) return 1.0;
  const auto reflectance = [](complex a, complex b) { return std::norm((a - b) / (a + b)); };
  const double r_air_film = reflectance(1.0, water_index);
  const double r_film_window = reflectance(water_index, window_index);
  const double r_air_window = reflectance(1.0, window_index);
  const double tau = std::exp(-4.0 * pi * water_index.imag() * film_thickness_m / wavelength_m);
  return (1.0 - r_air_film) * (1.0 - r_film_window) * tau /
         (1.0 - r_air_film * r_film_window * tau * tau) / (1.0 - r_air_window);
}

void require_window_film(std::string_view field, double film_thickness_m) {
  if (film_thickness_m == 0.0 ||
      (film_thickness_m >= min_window_film_m && film_thickness_m <= max_window_film_m)) {
    return;
  }
  std::ostringstream constraint;
  constraint << "0 (dry) or in [" << min_window_film_m << ", " << max_window_film_m
             << "] (the window's film model averages out the interference of films of 1 um "
                "and more)";
  throw_invalid(field, film_thickness_m, constraint.str());
}

}  // namespace fogradar::propagation
