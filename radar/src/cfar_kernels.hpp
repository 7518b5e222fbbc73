// The CFAR's sliding-sum and detection kernels (cfar_kernels.cpp), shared by the detector and the
// configuration's reference offsets. The definitions carry the instruction-set clones; the
// declarations must not (a cloned declaration makes every caller build a resolver of its own).
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <span>
#include <vector>

#include "fogradar/radar/cfar.hpp"

namespace fogradar::radar::cfar_kernels {

// Reference cells of cell i as two contiguous ranges [lb, le) and [rb, re) (edge policy in
// cfar.hpp): the guard cells stay centred on i, the training window slides inward.
struct ReferenceCells {
  std::size_t lb, le, rb, re;
};

ReferenceCells reference_cells(std::size_t i, std::size_t length, std::size_t guard, std::size_t n);

// The detection scan of OS.
void append_cells_above(const double* power, const double* threshold, std::size_t length,
                        std::vector<std::size_t>& cells);

// Sums of every n consecutive cells, sums[j] = power[j] + ... + power[j + n - 1] for j in
// [0, length - n], by doubling: blocks of 1, 2, 4, ... cells are added pairwise and the blocks of
// n's binary digits collected. O(length log n), and every sum adds non-negative values only, so
// its relative error is below (2 log2 n + 1) eps however strong a target sits in the profile
// (a running sum, add one cell and subtract another, would carry an absolute error of the
// strongest cell that ever passed through it).
std::span<const double> window_sums(std::span<const double> power, std::size_t n,
                                    std::vector<double>& sums, std::vector<double>& blocks);

// window_sums for four interleaved profiles (cell j of profile r at 4 j + r, CfarFourWorkspace):
// the same blocks and the same additions per profile, every index scaled by four. `pairs` holds the
// first pass's blocks of two cells (formed with |X|^2) and takes the longer blocks in place, two
// passes in one where the block between is not one of n's binary digits, so that the buffers of
// four profiles stay in the L1 cache; `sums` collects n's binary digits (unused when n is a power
// of two).
std::span<const double> window_sums_four(std::span<const double> power, std::size_t n,
                                         std::vector<double>& pairs, std::vector<double>& sums);

// How the two half sums of the reference cells make the noise estimate: CA adds them, GO takes
// the greater, SO the smaller. One form for scalars and vectors (std::max is (a < b) ? b : a).
enum class HalfSums { add, greater, smaller };

HalfSums half_sums_rule(CfarKind kind);

// CA/GO/SO thresholds, scale * combine(S_lead, S_lag) with S the sums of the two halves of the
// reference cells (scale = alpha / N for CA, alpha / n for GO/SO), and the cells above them in
// ascending order. Interior cells read the two window sums; the 2 (guard + n) edge cells add their
// reference ranges directly, with the scale of their position (edge_scale[i] for the cells i and
// L-1-i).
void two_sided_detect(std::span<const double> power, std::size_t guard, std::size_t n, double scale,
                      std::span<const double> edge_scale, std::span<const double> sums,
                      HalfSums rule, std::vector<double>& threshold,
                      std::vector<std::size_t>& cells);

// two_sided_detect for four interleaved profiles of `length` cells (CfarFourWorkspace's layout),
// one per vector lane: each lane makes the operations two_sided_detect makes for its profile, in
// the same order (the edge cells' sums included), so the same bits.
void two_sided_detect_four(const double* power, std::size_t length, std::size_t guard,
                           std::size_t n, double scale, const double* edge_scale,
                           const double* sums, HalfSums rule, double* threshold,
                           std::array<std::vector<std::size_t>, 4>& cells);

// |X|^2 of four rows of `length` values, interleaved: two cells of the four rows per step, squared
// and their real and imaginary squares added (re^2 + im^2, as std::norm), then transposed into two
// vectors of the four rows. While they are in registers, the sums of every two adjacent cells
// (pairs[4 j + r] = power[4 j + r] + power[4 (j + 1) + r], window_sums' first pass) are formed too.
void interleave_norms(const std::complex<double>* rows, std::size_t length, double* power,
                      double* pairs);

}  // namespace fogradar::radar::cfar_kernels
