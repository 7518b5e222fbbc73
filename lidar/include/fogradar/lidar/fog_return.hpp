// The fog's volume return in a beam's waveform (the integral term of waveform.hpp's lidar
// equation), computed as the pulse convolved with the fog's range profile on a grid of the
// waveform's samples.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "fogradar/lidar/waveform.hpp"

namespace fogradar::lidar {

// A homogeneous stretch of fog along the beam, [start_m, end_m] in range, with extinction alpha
// and volume backscatter beta_pi = sigma_b / (4 pi) per metre per steradian, entered with two-way
// transmittance `transmittance_at_start`.
struct FogStretch {
  double start_m = 0.0;
  double end_m = 0.0;
  double extinction_per_m = 0.0;
  double backscatter_per_m_sr = 0.0;
  double transmittance_at_start = 1.0;
};

// The tables of one waveform grid (made once per grid, read-only after: shared by threads).
//
// add() computes waveform[k] += integral_start^end p(k dt - 2r/c) beta_pi T^2(r) / r^2 O(r) dr,
// T^2(r) = T^2(start) exp(-2 alpha (r - start)), split at the overlap function's kink, as a sum
// over nodes tau_m = m h on a grid of round-trip times of step h = M dt or dt / S (M, S integers;
// h <= sigma / 4, sigma = fwhm / sqrt(8 ln 2) the pulse's time standard deviation, and small enough
// that the profile is near a polynomial over the edge rule's 8 nodes, below), each node's
// pulse p(k dt - tau_m) read from a table of p at multiples of dt / S: no exp per node or sample.
// The rule is the trapezoidal one with corrected end weights: a stretch [tau_a, tau_b] gets weight
// 1 on its nodes and, at either edge, weights on the 8 nodes around it (4 outside, where the
// profile is continued by its formula) that make the rule exact for every polynomial of degree 7:
// the partial cell up to the edge plus the Euler-Maclaurin (midpoint form) corrections of the
// grid's end (Davis & Rabinowitz 1984, Methods of Numerical Integration, ch. 2). Away from
// the edges the trapezoidal sum of p(t - tau) g(tau) is spectrally accurate (aliasing error ~
// exp(-2 pi^2 sigma^2 / h^2) < 1e-130 at h = sigma / 4). The pulse is cut 2 fwhm from each node,
// and a call writes only the samples from 2 fwhm before its nearest stretch to 2 fwhm beyond its
// farthest. With `first_sample`, waveform[0] is sample first_sample: a part of the record gets
// exactly the values the whole record would (the same sums in the same order).
class FogReturn {
 public:
  explicit FogReturn(const WaveformGrid& grid);

  // The stretches' return, one profile on one node grid (the finest any of them needs).
  void add(std::span<double> waveform, std::span<const FogStretch> stretches,
           std::size_t first_sample = 0) const;
  void add(std::span<double> waveform, const FogStretch& fog, std::size_t first_sample = 0) const {
    add(waveform, std::span<const FogStretch>(&fog, 1), first_sample);
  }

 private:
  // Nodes of the edge rule: offsets -4..3 from the first node inside the stretch.
  static constexpr std::size_t edge_nodes = 8;

  WaveformGrid grid_;
  double sigma_s_ = 0.0;
  // pulse_[i][n + half_[i]] = p(n dt / 2^i), |n dt / 2^i| <= 2 fwhm.
  std::vector<std::vector<double>> pulse_;
  std::vector<long> half_;
  // Edge weights w_l(theta) = edge_constant_[l] + sum_j edge_theta_[l][j] theta^(j+1), for the edge
  // theta node steps before the first node inside.
  std::array<double, edge_nodes> edge_constant_{};
  std::array<std::array<double, edge_nodes>, edge_nodes> edge_theta_{};
};

}  // namespace fogradar::lidar
