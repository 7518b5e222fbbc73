// The camera's spectral band: the CIE 1931 2-degree colour matching functions (data/
// cie1931_2deg_xyz.txt, compiled into the library; y_bar is the CIE 1924 photopic V(lambda)) and
// the quadrature weights with which per-wavelength transmittances are averaged over a channel.
#pragma once

#include <cstddef>
#include <vector>

#include "fogradar/camera/params.hpp"

namespace fogradar::camera {

// The tabulated CIE 1931 2-degree observer, 360-830 nm in 5 nm steps.
struct ColourMatchingTable {
  std::vector<double> wavelength_nm;
  std::vector<double> x_bar;
  std::vector<double> y_bar;  // V(lambda)
  std::vector<double> z_bar;
};
ColourMatchingTable cie1931_table();

// Nodes and weights of a band average: mean_c f = sum_k weight[c][k] f(lambda_k), the weights of
// channel c summing to 1 (trapezoid rule over the table's 5 nm nodes times the channel's
// sensitivity). Photopic: one channel, V(lambda). Rgb: the sRGB primaries' colour matching
// functions (IEC 61966-2-1 XYZ -> linear RGB matrix applied to x_bar, y_bar, z_bar), negative lobes
// set to 0. Monochromatic: one node at wavelength_nm, weight 1.
struct BandQuadrature {
  std::vector<double> wavelength_m;
  std::vector<std::vector<double>> weight;  // [channel][node]
};
BandQuadrature band_quadrature(Band band, double wavelength_nm, const ColourMatchingTable& table);

// Wavelengths at which Mie is evaluated: 400, 400 + step, ..., and 720 nm for the photopic and rgb
// bands (V(lambda) holds 99.99 % of its integral there); {wavelength_nm} for monochromatic.
std::vector<double> mie_wavelengths_m(Band band, double wavelength_nm, double step_nm);

// Piecewise-quadratic interpolation of the points (x, y), x ascending: at each of `at`, the
// Lagrange parabola through the three nodes nearest to it (linear with two nodes, constant with
// one); constant beyond the ends.
std::vector<double> interpolate_quadratic(const std::vector<double>& x,
                                          const std::vector<double>& y,
                                          const std::vector<double>& at);

}  // namespace fogradar::camera
