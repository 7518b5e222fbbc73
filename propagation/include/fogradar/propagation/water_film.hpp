// A water film on a radome or target surface (the study's l_s = 0 / l_t = 0 case): reflection and
// transmission of a stack of plane homogeneous layers at normal incidence by the characteristic
// (transfer) matrix method (Born & Wolf, Principles of Optics, 7th ed., sec. 1.6; Hecht, Optics,
// sec. 9.7). Indices use m = n + i k, k >= 0.
#pragma once

#include <complex>
#include <span>

namespace fogradar::propagation {

struct SlabLayer {
  std::complex<double> refractive_index{1.0, 0.0};
  double thickness_m = 0.0;
};

struct SlabResponse {
  std::complex<double> reflection_amplitude;    // r
  std::complex<double> transmission_amplitude;  // t
  double reflectance = 0.0;    // R = |r|^2
  double transmittance = 0.0;  // T = Re(n_out)/Re(n_in) |t|^2
  double absorptance = 0.0;    // A = 1 - R - T
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

}  // namespace fogradar::propagation
