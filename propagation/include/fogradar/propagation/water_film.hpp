// A water film on a radome or target surface (the study's l_s = 0 / l_t = 0 case): reflection and
// transmission of a stack of plane homogeneous layers at normal incidence by the characteristic
// (transfer) matrix method (Born & Wolf, Principles of Optics, 7th ed., sec. 1.6; Hecht, Optics,
// sec. 9.7). Indices use m = n + i k, k >= 0.
#pragma once

#include <complex>
#include <span>
#include <string_view>

namespace fogradar::propagation {

struct SlabLayer {
  std::complex<double> refractive_index{1.0, 0.0};
  double thickness_m = 0.0;
};

struct SlabResponse {
  std::complex<double> reflection_amplitude;    // r
  std::complex<double> transmission_amplitude;  // t
  double reflectance = 0.0;                     // R = |r|^2
  double transmittance = 0.0;                   // T = Re(n_out)/Re(n_in) |t|^2
  double absorptance = 0.0;                     // A = 1 - R - T
};

// Normal incidence from a medium of index n_in through `layers` (in order of incidence) into n_out.
// Throws InvalidParameter for negative or non-finite thickness, Im(index) < 0, Re(index) <= 0, or
// wavelength <= 0.
SlabResponse slab_response(std::span<const SlabLayer> layers, double wavelength_m,
                           std::complex<double> n_in = {1.0, 0.0},
                           std::complex<double> n_out = {1.0, 0.0});

// Two-way power loss (dB) of a radar wave through a water film of given thickness in air on a
// radome of given index and thickness: -10 log10(T^2), T the one-way transmittance.
double film_two_way_loss_db(double film_thickness_m, std::complex<double> water_index,
                            std::complex<double> radome_index, double radome_thickness_m,
                            double wavelength_m);

// Reflection amplitude at normal incidence, from n_in, of `layers` on a perfect electric conductor
// (tangential E = 0 behind the last layer): r = (m12 n_in - m22) / (m12 n_in + m22), the
// n_out -> infinity limit of slab_response (Born & Wolf sec. 1.6); -1 with no layer. Throws as
// slab_response.
std::complex<double> conductor_backed_reflection(std::span<const SlabLayer> layers,
                                                 double wavelength_m,
                                                 std::complex<double> n_in = {1.0, 0.0});

// Power loss (dB) of the echo of a metal surface under a water film in air, against the dry
// metal: -10 log10 |r|^2, r = conductor_backed_reflection of the film. The film is crossed twice
// (in and out), with the standing wave between the metal and the film's face.
double conductor_film_loss_db(double film_thickness_m, std::complex<double> water_index,
                              double wavelength_m);

// Index of the optical sensors' window: crown or fused silica glass, 1.45-1.52 in the visible and
// near infrared (polycarbonate's 1.58 changes window_film_transmittance by under 0.5 %).
inline constexpr double optical_window_index = 1.5;

// One-way power transmittance of a water film on the outer face of a window of index n_g, against
// the dry face; the film's fringes averaged out (incoherent sum, Harbecke 1986, Appl. Phys. B 39,
// 165, eq. 9), since a real film varies in thickness by more than lambda / (2 n) over a beam:
//   T = (1 - R_af)(1 - R_fg) tau / (1 - R_af R_fg tau^2) / (1 - R_ag),
//   tau = exp(-4 pi k t / lambda),
//   R_xy = |(m_x - m_y) / (m_x + m_y)|^2 (Fresnel, normal incidence).
// Above 1 for a thin clear film, which index-matches the window better than air. For films of a
// few wavelengths and more (a thinner film is coherent); 0 gives 1. A flat film only: the
// scattering of droplets on a wet window is not modelled. Throws InvalidParameter for a
// negative thickness, an index as slab_response refuses, or wavelength <= 0.
double window_film_transmittance(double film_thickness_m, std::complex<double> water_index,
                                 double wavelength_m, double window_index = optical_window_index);

// A window film is 0 (dry) or in [min_window_film_m, max_window_film_m]: from 1 um (1.5 optical
// wavelengths in water at 905 nm) window_film_transmittance's incoherent sum holds; 10 mm is far
// beyond the film a vertical window holds.
inline constexpr double min_window_film_m = 1e-6;
inline constexpr double max_window_film_m = 0.01;
// Throws InvalidParameter naming `field` otherwise.
void require_window_film(std::string_view field, double film_thickness_m);

}  // namespace fogradar::propagation
