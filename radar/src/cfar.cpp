#include "fogradar/radar/cfar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/radar/cfar_design.hpp"
#include "solve_factor.hpp"

namespace fogradar::radar {

namespace {

constexpr std::array<std::pair<CfarKind, std::string_view>, 4> kCfarNames{{
    {CfarKind::ca, "ca"},
    {CfarKind::go, "go"},
    {CfarKind::so, "so"},
    {CfarKind::os, "os"},
}};

constexpr std::array<std::pair<CfarThresholdDesign, std::string_view>, 2> kDesignNames{{
    {CfarThresholdDesign::correlated, "correlated"},
    {CfarThresholdDesign::independent, "independent"},
}};

// log Pfa of SO-CFAR, n cells per side, t = alpha / n (Gandhi & Kassam 1988):
//   Pfa_SO = 2 sum_{k=0}^{n-1} C(n-1+k, k) (2+t)^-(n+k).
double log_pfa_so(double n, double t) {
  const double log_base = std::log(2.0 + t);
  double log_term = -n * log_base;  // k = 0
  LogSum sum;
  for (double k = 0.0; k < n; k += 1.0) {
    sum.add(log_term);
    log_term += std::log((n + k) / (k + 1.0)) - log_base;
  }
  return std::log(2.0) + sum.log();
}

// log Pfa of GO-CFAR. The published form 2 (1+t)^-n - Pfa_SO cancels badly when Pfa is small
// (both terms ~ t^-n, the difference ~ t^-2n). Equivalent positive series, from
// Pfa_GO = E[exp(-t max(X, Y))] with X, Y ~ Gamma(n, 1) and P(max < m) = F(m)^2:
//   Pfa_GO = 2 sum_{j>=n} C(n-1+j, j) (2+t)^-(n+j).
// The term ratio r_j = (n+j) / ((j+1)(2+t)) is < 1 and decreasing for j >= n, so the tail after
// term j is bounded by term_j r_j / (1 - r_j).
double log_pfa_go(double n, double t) {
  const double log_base = std::log(2.0 + t);
  double log_term =
      std::lgamma(2.0 * n) - std::lgamma(n) - std::lgamma(n + 1.0) - 2.0 * n * log_base;  // j = n
  LogSum sum;
  for (double j = n;; j += 1.0) {
    sum.add(log_term);
    const double ratio = (n + j) / ((j + 1.0) * (2.0 + t));
    const double log_tail_bound = log_term + std::log(ratio / (1.0 - ratio));
    if (log_tail_bound < sum.log() - 45.0) break;  // tail < 3e-20 of the sum
    FOGRADAR_CHECK(j < n + 1e8);
    log_term += std::log(ratio);
  }
  return std::log(2.0) + sum.log();
}

// log Pfa of OS-CFAR, rank k of N (Rohling 1983): sum_{i<k} log((N-i) / (N-i+alpha)).
double log_pfa_os(double big_n, unsigned k, double alpha) {
  double result = 0.0;
  for (unsigned i = 0; i < k; ++i) result -= std::log1p(alpha / (big_n - i));
  return result;
}

double log_false_alarm_probability(const CfarConfig& config, double alpha) {
  const double n = config.training_cells;
  const double big_n = 2.0 * n;
  switch (config.kind) {
    case CfarKind::ca:
      return -big_n * std::log1p(alpha / big_n);
    case CfarKind::go:
      return log_pfa_go(n, alpha / n);
    case CfarKind::so:
      return log_pfa_so(n, alpha / n);
    case CfarKind::os:
      return log_pfa_os(big_n, config.effective_os_rank(), alpha);
  }
  FOGRADAR_CHECK(false && "unknown CfarKind");
  return 0.0;
}

// Reference cells of cell i as two contiguous ranges [lb, le) and [rb, re) (edge policy in
// cfar.hpp): the guard cells stay centred on i, the training window slides inward.
struct ReferenceCells {
  std::size_t lb, le, rb, re;
};

ReferenceCells reference_cells(std::size_t i, std::size_t length, std::size_t guard,
                               std::size_t n) {
  const std::size_t left_available = i >= guard ? std::min(n, i - guard) : 0;
  const std::size_t right_available =
      i + guard + 1 < length ? std::min(n, length - 1 - i - guard) : 0;
  std::size_t a = n;  // cells taken on the left
  std::size_t b = n;  // cells taken on the right
  if (left_available < n) {
    a = left_available;
    b = 2 * n - a;
  } else if (right_available < n) {
    b = right_available;
    a = 2 * n - b;
  }
  // Empty ranges stay inside [0, length]: a == 0 whenever i < guard (left range [0, 0)), and
  // b == 0 whenever the guard cells reach the end (right range [length, length)).
  const std::size_t left_end = i >= guard ? i - guard : 0;
  const std::size_t right_begin = std::min(i + guard + 1, length);
  return {left_end - a, left_end, right_begin, right_begin + b};
}

// The passes of window_sums, cloned so that AVX2 adds four cells per instruction (element-wise
// sums: the same bits in every clone). Only `a` and `b` may overlap (both are read).
FOGRADAR_SIMD_CLONES
void add_cells(const double* __restrict a, const double* __restrict b, double* __restrict out, std::size_t count) {
  for (std::size_t j = 0; j < count; ++j) out[j] = a[j] + b[j];
}

FOGRADAR_SIMD_CLONES
void accumulate_cells(double* __restrict sums, const double* __restrict terms, std::size_t count) {
  for (std::size_t j = 0; j < count; ++j) sums[j] += terms[j];
}

// Appends every i in [begin, end) with power[i] > threshold[i]. `thresholds.four_from(k)` gives
// the thresholds of cells k..k+3 and `thresholds.one_at(i)` that of cell i, storing them in
// `threshold` where it forms them (always-inlined members: no call with a vector argument or
// result crosses the clones' ABIs, docs/architecture.md). Detections are rare: a branch-free vector
// test of 16 cells at a time leaves the look at single cells to the few blocks that hold one.
template <class Thresholds>
[[gnu::always_inline]] inline void scan_cells_above(const double* power, const double* threshold, std::size_t begin,
                                                    std::size_t end, std::vector<std::size_t>& cells,
                                                    const Thresholds& thresholds) {
  constexpr std::size_t block = 16;
  std::size_t i = begin;
  for (; i + block <= end; i += block) {
    detail::u64x4 above{};
    for (std::size_t k = i; k < i + block; k += 4) {
      above |= detail::lanes_as<detail::u64x4>(detail::load4(power + k) > thresholds.four_from(k));
    }
    if ((above[0] | above[1] | above[2] | above[3]) == 0) continue;
    for (std::size_t k = i; k < i + block; ++k) {
      if (power[k] > threshold[k]) cells.push_back(k);
    }
  }
  for (; i < end; ++i) {
    if (power[i] > thresholds.one_at(i)) cells.push_back(i);
  }
}

// Thresholds formed beforehand (OS).
struct StoredThresholds {
  const double* threshold;
  [[gnu::always_inline]] detail::f64x4 four_from(std::size_t k) const { return detail::load4(threshold + k); }
  [[gnu::always_inline]] double one_at(std::size_t i) const { return threshold[i]; }
};

// The detection scan of OS.
FOGRADAR_SIMD_CLONES
void append_cells_above(const double* power, const double* threshold, std::size_t length,
                        std::vector<std::size_t>& cells) {
  scan_cells_above(power, threshold, 0, length, cells, StoredThresholds{threshold});
}

// Sums of every n consecutive cells, sums[j] = power[j] + ... + power[j + n - 1] for j in
// [0, length - n], by doubling: blocks of 1, 2, 4, ... cells are added pairwise and the blocks of
// n's binary digits collected. O(length log n), and every sum adds non-negative values only, so
// its relative error is below (2 log2 n + 1) eps however strong a target sits in the profile
// (a running sum, add one cell and subtract another, would carry an absolute error of the
// strongest cell that ever passed through it).
std::span<const double> window_sums(std::span<const double> power, std::size_t n, std::vector<double>& sums,
                                    std::vector<double>& blocks) {
  const std::size_t length = power.size();
  const std::size_t count = length - n + 1;
  sums.resize(count);
  blocks.resize(2 * length);  // two buffers, written in turn, so that no pass works in place
  const double* current = power.data();  // current[j] = power[j .. j + block)
  std::size_t covered = 0;               // sums[j] holds power[j .. j + covered)
  for (std::size_t block = 1; block <= n; block *= 2) {
    if ((n & block) != 0) {
      const double* from = current + covered;
      if (block == n) return {from, count};  // n a power of two: the blocks are the sums
      if (covered == 0) {
        std::copy(from, from + count, sums.begin());
      } else {
        accumulate_cells(sums.data(), from, count);
      }
      covered += block;
    }
    if (2 * block <= n) {  // next[j] = power[j .. j + 2 block) for j <= length - 2 block
      double* next = current == blocks.data() ? blocks.data() + length : blocks.data();
      add_cells(current, current + block, next, length + 1 - 2 * block);
      current = next;
    }
  }
  return sums;
}

// cells[j] += cells[j + offset] for j < count, in place (ascending, four at a time: offset >= 4, so
// every cell is read before it is written). Element-wise sums: the same bits in every clone.
FOGRADAR_SIMD_CLONES
void add_cells_ahead(double* cells, std::size_t offset, std::size_t count) {
  std::size_t j = 0;
  for (; j + 4 <= count; j += 4)
    detail::store4(cells + j, detail::load4(cells + j) + detail::load4(cells + j + offset));
  for (; j < count; ++j) cells[j] += cells[j + offset];
}

// cells[j] = (cells[j] + cells[j + offset]) + (cells[j + 2 offset] + cells[j + 3 offset]) for
// j < count, in place as add_cells_ahead: two doubling passes in one (the blocks of 2 b cells at j
// and j + 2 b added as the second pass would add them).
FOGRADAR_SIMD_CLONES
void add_cells_ahead_twice(double* cells, std::size_t offset, std::size_t count) {
  std::size_t j = 0;
  for (; j + 4 <= count; j += 4) {
    const detail::f64x4 near = detail::load4(cells + j) + detail::load4(cells + j + offset);
    const detail::f64x4 far =
        detail::load4(cells + j + 2 * offset) + detail::load4(cells + j + 3 * offset);
    detail::store4(cells + j, near + far);
  }
  for (; j < count; ++j) {
    cells[j] = (cells[j] + cells[j + offset]) + (cells[j + 2 * offset] + cells[j + 3 * offset]);
  }
}

// window_sums for four interleaved profiles (cell j of profile r at 4 j + r, CfarFourWorkspace):
// the same blocks and the same additions per profile, every index scaled by four. `pairs` holds the
// first pass's blocks of two cells (formed with |X|^2) and takes the longer blocks in place, two
// passes in one where the block between is not one of n's binary digits, so that the buffers of
// four profiles stay in the L1 cache; `sums` collects n's binary digits (unused when n is a power
// of two).
std::span<const double> window_sums_four(std::span<const double> power, std::size_t n,
                                         std::vector<double>& pairs, std::vector<double>& sums) {
  constexpr std::size_t lanes = 4;
  const std::size_t values = power.size();
  const std::size_t count = values - lanes * (n - 1);
  const double* current = power.data();  // current[j] = power[j .. j + block) (in cells)
  std::size_t covered = 0;               // sums[j] holds power[j .. j + covered)
  std::size_t block = 1;
  while (block <= n) {
    if ((n & block) != 0) {
      const double* from = current + lanes * covered;
      if (block == n) return {from, count};  // n a power of two: the blocks are the sums
      sums.resize(count);
      if (covered == 0) {
        std::copy(from, from + count, sums.begin());
      } else {
        accumulate_cells(sums.data(), from, count);
      }
      covered += block;
    }
    if (2 * block > n) break;
    // next[j] = power[j .. j + 2 block) for j <= length - 2 block (or 4 block)
    if (block == 1) {
      block = 2;
    } else if (4 * block <= n && (n & (2 * block)) == 0) {
      add_cells_ahead_twice(pairs.data(), lanes * block, values + lanes - 4 * lanes * block);
      block *= 4;
    } else {
      add_cells_ahead(pairs.data(), lanes * block, values + lanes - 2 * lanes * block);
      block *= 2;
    }
    current = pairs.data();
  }
  return sums;
}

// How the two half sums of the reference cells make the noise estimate: CA adds them, GO takes
// the greater, SO the smaller. One form for scalars and vectors (std::max is (a < b) ? b : a).
enum class HalfSums { add, greater, smaller };

HalfSums half_sums_rule(CfarKind kind) {
  return kind == CfarKind::ca   ? HalfSums::add
         : kind == CfarKind::go ? HalfSums::greater
                                : HalfSums::smaller;
}

template <class T>
[[gnu::always_inline]] inline T combine(HalfSums rule, T lead, T lag) {
  if (rule == HalfSums::add) return lead + lag;
  return rule == HalfSums::greater ? (lead < lag ? lag : lead) : (lag < lead ? lag : lead);
}

// The interior thresholds threshold[i] = scale * combine(lead[i - begin], lag[i - begin]), stored
// as they are formed.
template <HalfSums rule>
struct InteriorThresholds {
  const double* lead;
  const double* lag;
  double scale;
  double* threshold;
  std::size_t begin;
  [[gnu::always_inline]] detail::f64x4 four_from(std::size_t k) const {
    const detail::f64x4 four =
        scale * combine(rule, detail::load4(lead + (k - begin)), detail::load4(lag + (k - begin)));
    detail::store4(threshold + k, four);
    return four;
  }
  [[gnu::always_inline]] double one_at(std::size_t i) const {
    return threshold[i] = scale * combine(rule, lead[i - begin], lag[i - begin]);
  }
};

// The interior cells [begin, end) of two_sided_detect: thresholds and detections in one pass. The
// rule is fixed outside the loop so that each clone vectorises all three.
FOGRADAR_SIMD_CLONES
void interior_thresholds_and_detect(HalfSums rule, const double* lead, const double* lag, const double* power,
                                    double scale, double* threshold, std::size_t begin, std::size_t end,
                                    std::vector<std::size_t>& cells) {
  switch (rule) {
    case HalfSums::add:
      scan_cells_above(power, threshold, begin, end, cells,
                       InteriorThresholds<HalfSums::add>{lead, lag, scale, threshold, begin});
      break;
    case HalfSums::greater:
      scan_cells_above(power, threshold, begin, end, cells,
                       InteriorThresholds<HalfSums::greater>{lead, lag, scale, threshold, begin});
      break;
    case HalfSums::smaller:
      scan_cells_above(power, threshold, begin, end, cells,
                       InteriorThresholds<HalfSums::smaller>{lead, lag, scale, threshold, begin});
      break;
  }
}

// Cell j of one profile, and of four interleaved profiles as a vector (CfarFourWorkspace).
struct CellsOf {
  const double* power;
  [[gnu::always_inline]] double operator()(std::size_t j) const { return power[j]; }
};
struct FourCellsOf {
  const double* power;
  [[gnu::always_inline]] detail::f64x4 operator()(std::size_t j) const {
    return detail::load4(power + 4 * j);
  }
};

// cell(begin) + ... + cell(end - 1), added in range order from zero.
template <class T, class Cells>
[[gnu::always_inline]] inline T run_sum(const Cells& cell, std::size_t begin, std::size_t end) {
  T total{};
  for (std::size_t j = begin; j < end; ++j) total += cell(j);
  return total;
}

template <class T>
struct Halves {
  T first, second;
};

// The two half sums of edge cell i: the first n and the last n reference cells in range order,
// each contiguous run summed cell by cell in range order from zero and the runs' sums added in
// order. `cell(j)` gives cell j (a double, or four profiles' cells as a vector: each lane then
// makes the same additions as a single profile).
template <class T, class Cells>
[[gnu::always_inline]] inline Halves<T> edge_halves(std::size_t i, std::size_t length,
                                                    std::size_t guard, std::size_t n,
                                                    const Cells& cell) {
  const ReferenceCells r = reference_cells(i, length, guard, n);
  const std::size_t a = r.le - r.lb;
  if (a >= n) {
    return {run_sum<T>(cell, r.lb, r.lb + n),
            run_sum<T>(cell, r.lb + n, r.le) + run_sum<T>(cell, r.rb, r.re)};
  }
  return {run_sum<T>(cell, r.lb, r.le) + run_sum<T>(cell, r.rb, r.rb + (n - a)),
          run_sum<T>(cell, r.rb + (n - a), r.re)};
}

// CA/GO/SO thresholds, scale * combine(S_lead, S_lag) with S the sums of the two halves of the
// reference cells (scale = alpha / N for CA, alpha / n for GO/SO), and the cells above them in
// ascending order. Interior cells read the two window sums; the 2 (guard + n) edge cells add their
// reference ranges directly, with the scale of their position (edge_scale[i] for the cells i and
// L-1-i).
void two_sided_detect(std::span<const double> power, std::size_t guard, std::size_t n, double scale,
                      std::span<const double> edge_scale, std::span<const double> sums, HalfSums rule,
                      std::vector<double>& threshold, std::vector<std::size_t>& cells) {
  const std::size_t length = power.size();
  const auto edge_cell = [&](std::size_t i) {
    const auto [first, second] = edge_halves<double>(i, length, guard, n, CellsOf{power.data()});
    threshold[i] = edge_scale[std::min(i, length - 1 - i)] * combine(rule, first, second);
    if (power[i] > threshold[i]) cells.push_back(i);
  };
  const std::size_t interior_begin = guard + n;
  const std::size_t interior_end = length - guard - n;  // > interior_begin (validated)
  for (std::size_t i = 0; i < interior_begin; ++i) edge_cell(i);
  const double* lead = sums.data();                      // S_lead of cell i = sums[i - guard - n]
  const double* lag = sums.data() + 2 * guard + n + 1;  // S_lag of cell i = sums[i + guard + 1]
  interior_thresholds_and_detect(rule, lead, lag, power.data(), scale, threshold.data(), interior_begin, interior_end,
                                 cells);
  for (std::size_t i = interior_end; i < length; ++i) edge_cell(i);
}

// Appends i to cells[r] for each lane r with power > threshold.
[[gnu::always_inline]] inline void append_lanes_above(
    detail::f64x4 power, detail::f64x4 threshold, std::size_t i,
    std::array<std::vector<std::size_t>, 4>& cells) {
  const detail::u64x4 above = detail::lanes_as<detail::u64x4>(power > threshold);
  for (std::size_t r = 0; r < 4; ++r) {
    if (above[r] != 0) cells[r].push_back(i);
  }
}

// The interior cells [begin, end) of two_sided_detect_four, the rule fixed at compile time: per
// cell one vector of the four profiles' thresholds, stored and compared with their cells; blocks
// of 16 cells are tested together and only a block that holds a detection is looked at lane by
// lane (cells in ascending order within each profile).
template <HalfSums rule>
[[gnu::always_inline]] inline void interior_four(const double* power, const double* lead,
                                                 const double* lag, double scale, double* threshold,
                                                 std::size_t begin, std::size_t end,
                                                 std::array<std::vector<std::size_t>, 4>& cells) {
  constexpr std::size_t block = 16;
  std::size_t i = begin;
  for (; i + block <= end; i += block) {
    detail::u64x4 above{};
    for (std::size_t k = i; k < i + block; ++k) {
      const detail::f64x4 four = scale * combine(rule, detail::load4(lead + 4 * (k - begin)),
                                                 detail::load4(lag + 4 * (k - begin)));
      detail::store4(threshold + 4 * k, four);
      above |= detail::lanes_as<detail::u64x4>(detail::load4(power + 4 * k) > four);
    }
    if ((above[0] | above[1] | above[2] | above[3]) == 0) continue;
    for (std::size_t k = i; k < i + block; ++k) {
      append_lanes_above(detail::load4(power + 4 * k), detail::load4(threshold + 4 * k), k, cells);
    }
  }
  for (; i < end; ++i) {
    const detail::f64x4 four = scale * combine(rule, detail::load4(lead + 4 * (i - begin)),
                                               detail::load4(lag + 4 * (i - begin)));
    detail::store4(threshold + 4 * i, four);
    append_lanes_above(detail::load4(power + 4 * i), four, i, cells);
  }
}

// The edge cells [begin, end) of two_sided_detect_four.
[[gnu::always_inline]] inline void edges_four(const double* power, std::size_t length,
                                              std::size_t guard, std::size_t n,
                                              const double* edge_scale, HalfSums rule,
                                              double* threshold, std::size_t begin, std::size_t end,
                                              std::array<std::vector<std::size_t>, 4>& cells) {
  for (std::size_t i = begin; i < end; ++i) {
    const auto [first, second] =
        edge_halves<detail::f64x4>(i, length, guard, n, FourCellsOf{power});
    const detail::f64x4 four =
        edge_scale[std::min(i, length - 1 - i)] * combine(rule, first, second);
    detail::store4(threshold + 4 * i, four);
    append_lanes_above(detail::load4(power + 4 * i), four, i, cells);
  }
}

// two_sided_detect for four interleaved profiles of `length` cells (CfarFourWorkspace's layout),
// one per vector lane: each lane makes the operations two_sided_detect makes for its profile, in
// the same order (the edge cells' sums included), so the same bits.
FOGRADAR_SIMD_CLONES
void two_sided_detect_four(const double* power, std::size_t length, std::size_t guard,
                           std::size_t n, double scale, const double* edge_scale,
                           const double* sums, HalfSums rule, double* threshold,
                           std::array<std::vector<std::size_t>, 4>& cells) {
  const std::size_t interior_begin = guard + n;
  const std::size_t interior_end = length - guard - n;
  edges_four(power, length, guard, n, edge_scale, rule, threshold, 0, interior_begin, cells);
  const double* lead = sums;                           // S_lead of cell i at 4 (i - guard - n)
  const double* lag = sums + 4 * (2 * guard + n + 1);  // S_lag of cell i at 4 (i + guard + 1)
  switch (rule) {
    case HalfSums::add:
      interior_four<HalfSums::add>(power, lead, lag, scale, threshold, interior_begin, interior_end,
                                   cells);
      break;
    case HalfSums::greater:
      interior_four<HalfSums::greater>(power, lead, lag, scale, threshold, interior_begin,
                                       interior_end, cells);
      break;
    case HalfSums::smaller:
      interior_four<HalfSums::smaller>(power, lead, lag, scale, threshold, interior_begin,
                                       interior_end, cells);
      break;
  }
  edges_four(power, length, guard, n, edge_scale, rule, threshold, interior_end, length, cells);
}

// |X|^2 of four rows of `length` values, interleaved: two cells of the four rows per step, squared
// and their real and imaginary squares added (re^2 + im^2, as std::norm), then transposed into two
// vectors of the four rows. While they are in registers, the sums of every two adjacent cells
// (pairs[4 j + r] = power[4 j + r] + power[4 (j + 1) + r], window_sums' first pass) are formed too.
FOGRADAR_SIMD_CLONES
void interleave_norms(const std::complex<double>* rows, std::size_t length, double* power,
                      double* pairs) {
  const auto* values =
      reinterpret_cast<const double*>(rows);  // re, im of each value ([complex.numbers.general])
  std::size_t j = 0;
  detail::f64x4 previous{};  // cell j - 1
  for (; j + 2 <= length; j += 2) {
    std::array<detail::f64x4, 4> squares;  // row r: re_j^2, im_j^2, re_j+1^2, im_j+1^2
    for (std::size_t r = 0; r < 4; ++r) {
      const detail::f64x4 v = detail::load4(values + 2 * (r * length + j));
      squares[r] = v * v;
    }
    // Rows 0 and 1, 2 and 3: |x_j|^2 of both rows, then |x_j+1|^2 of both.
    const detail::f64x4 norms01 =
        __builtin_shufflevector(squares[0], squares[1], 0, 4, 2, 6) +
        __builtin_shufflevector(squares[0], squares[1], 1, 5, 3, 7);
    const detail::f64x4 norms23 =
        __builtin_shufflevector(squares[2], squares[3], 0, 4, 2, 6) +
        __builtin_shufflevector(squares[2], squares[3], 1, 5, 3, 7);
    const detail::f64x4 cell = __builtin_shufflevector(norms01, norms23, 0, 1, 4, 5);
    const detail::f64x4 next = __builtin_shufflevector(norms01, norms23, 2, 3, 6, 7);
    detail::store4(power + 4 * j, cell);
    detail::store4(power + 4 * (j + 1), next);
    if (j > 0) detail::store4(pairs + 4 * (j - 1), previous + cell);
    detail::store4(pairs + 4 * j, cell + next);
    previous = next;
  }
  if (j < length) {  // an odd length's last cell
    for (std::size_t r = 0; r < 4; ++r) {
      power[4 * j + r] = std::norm(rows[r * length + j]);
      if (j > 0) pairs[4 * (j - 1) + r] = power[4 * (j - 1) + r] + power[4 * j + r];
    }
  }
}

}  // namespace

std::string_view to_string(CfarKind kind) noexcept {
  for (const auto& [value, name] : kCfarNames) {
    if (value == kind) return name;
  }
  return "unknown";
}

CfarKind parse_cfar_kind(std::string_view text, std::string_view field) {
  for (const auto& [value, name] : kCfarNames) {
    if (name == text) return value;
  }
  throw_invalid(field, text, "one of ca, go, so, os");
}

std::string_view to_string(CfarThresholdDesign design) noexcept {
  for (const auto& [value, name] : kDesignNames) {
    if (value == design) return name;
  }
  return "unknown";
}

CfarThresholdDesign parse_cfar_threshold_design(std::string_view text, std::string_view field) {
  for (const auto& [value, name] : kDesignNames) {
    if (name == text) return value;
  }
  throw_invalid(field, text, "one of correlated, independent");
}

std::vector<std::ptrdiff_t> cfar_reference_offsets(const CfarConfig& config, std::size_t cells_from_end) {
  config.validate();
  const std::size_t guard = config.guard_cells;
  const std::size_t n = config.training_cells;
  const std::size_t i = std::min(cells_from_end, guard + n);
  // A profile long enough that cell i has its full window on the right.
  const ReferenceCells r = reference_cells(i, i + guard + 2 * n + 1, guard, n);
  std::vector<std::ptrdiff_t> offsets;
  const auto cell = static_cast<std::ptrdiff_t>(i);
  for (std::size_t j = r.lb; j < r.le; ++j) offsets.push_back(static_cast<std::ptrdiff_t>(j) - cell);
  for (std::size_t j = r.rb; j < r.re; ++j) offsets.push_back(static_cast<std::ptrdiff_t>(j) - cell);
  return offsets;
}

unsigned CfarConfig::effective_os_rank() const noexcept {
  if (os_rank != 0) return os_rank;
  // round(3N/4), N = 2 n: (3N + 2) / 4 in integers, at least 1.
  const std::uint64_t big_n = 2ULL * training_cells;
  return static_cast<unsigned>(std::max<std::uint64_t>(1, (3 * big_n + 2) / 4));
}

KeyTable<CfarConfig> cfar_keys(std::string prefix) {
  KeyTable<CfarConfig> keys(prefix);
  keys.choice(
      "kind", FOGRADAR_KEY_FIELD(kind), {"ca", "go", "so", "os"}, parse_cfar_kind,
      [](CfarKind k) { return to_string(k); }, "CFAR detector");
  keys.integer("guard_cells", FOGRADAR_KEY_FIELD(guard_cells), 0, 32766, "per side");
  keys.integer("training_cells", FOGRADAR_KEY_FIELD(training_cells), 1, 32767, "per side");
  keys.number("false_alarm_probability", FOGRADAR_KEY_FIELD(false_alarm_probability),
              open(0.0, 1.0), "design P_fa");
  const std::string rank_key = prefix + "os_rank", training_key = prefix + "training_cells";
  keys.integer("os_rank", FOGRADAR_KEY_FIELD(os_rank), 0, 65534,
               "OS rank k; 0 = round(3/4 · 2·training)")
      .also([training_key](const CfarConfig& c) {
        return "and 0 or at most 2 x " + training_key + " = " + std::to_string(c.reference_cells());
      })
      .with_check([rank_key, training_key](const CfarConfig& c) {
        const std::size_t big_n = c.reference_cells();
        if (c.os_rank > big_n) {
          throw_invalid(rank_key, c.os_rank,
                        "0 (default round(3N/4)) or in [1, " + std::to_string(big_n) +
                            "] (N = 2 x " + training_key + ")");
        }
      })
      .documented_as("integer 0 or [1, 2·training]")
      .when([](const CfarConfig& c) { return c.kind == CfarKind::os; },
            "with " + prefix + "kind = \"os\" (the other kinds average their cells)");
  keys.choice(
      "threshold_design", FOGRADAR_KEY_FIELD(threshold_design), {"correlated", "independent"},
      parse_cfar_threshold_design, [](CfarThresholdDesign d) { return to_string(d); },
      "threshold factors solved for the noise cells as the range window correlates them, "
      "so the realised P_fa is the design value (one factor for the interior cells and "
      "one per edge position; docs/radar.md §7); `independent` = the textbook iid factor, "
      "whose realised P_fa with a tapered window is higher (Hann: 2.2× at 1e-3, 10× at "
      "1e-6 for CA)");
  return keys;
}

void CfarConfig::validate() const { cfar_keys("cfar.").check(*this); }

void CfarConfig::validate_profile_length(std::size_t profile_length,
                                         std::string_view prefix) const {
  if (profile_length >= window_length()) return;
  const std::string guard_key = std::string(prefix) + "guard_cells",
                    training_key = std::string(prefix) + "training_cells";
  // Largest guard + n with 2 (guard + n) + 1 <= profile_length.
  const std::size_t usable = profile_length >= 1 ? (profile_length - 1) / 2 : 0;
  const std::string rule = " (2 (guard + training) + 1 <= profile length)";
  const std::string profile =
      "a profile of radar.samples_per_chirp = " + std::to_string(profile_length) + " cells";
  if (usable > guard_cells) {
    throw_invalid(training_key, training_cells,
                  "in [1, " + std::to_string(usable - guard_cells) + "] with " + guard_key + " = " +
                      std::to_string(guard_cells) + " and " + profile + rule);
  }
  // The guard cells alone fill the profile: they are what must shrink.
  const std::string constraint =
      usable > training_cells
          ? "in [0, " + std::to_string(usable - training_cells) + "] with " + training_key + " = " +
                std::to_string(training_cells) + " and " + profile + rule
          : "smaller: with " + training_key + " = " + std::to_string(training_cells) +
                " not even 0 guard cells fit in " + profile + rule;
  throw_invalid(guard_key, guard_cells, constraint);
}

double cfar_false_alarm_probability(const CfarConfig& config, double alpha) {
  config.validate();
  require_non_negative("cfar.threshold_factor", alpha);
  return std::exp(log_false_alarm_probability(config, alpha));
}

double cfar_threshold_factor(const CfarConfig& config) {
  config.validate();
  const double log_pfa = std::log(config.false_alarm_probability);
  const double big_n = static_cast<double>(config.reference_cells());
  if (config.kind == CfarKind::ca) {
    // Closed form: alpha = N (Pfa^(-1/N) - 1), written with expm1 for small -log(Pfa)/N.
    return big_n * std::expm1(-log_pfa / big_n);
  }

  // GO, SO, OS: log Pfa(alpha) is continuous and strictly decreasing from 0 at alpha = 0.
  return solve_threshold_factor(
      [&](double alpha) { return log_false_alarm_probability(config, alpha); },
      config.false_alarm_probability, 1.0);
}

CfarDetector::CfarDetector(const CfarConfig& config) : CfarDetector(config, NoiseCorrelation{}) {}

CfarDetector::CfarDetector(const CfarConfig& config, const NoiseCorrelation& noise,
                           const StopToken& stop)
    : config_(config) {
  CfarThresholdFactors factors = design_cfar_threshold_factors(config, noise, stop);
  alpha_ = factors.interior;
  edge_alpha_ = std::move(factors.edge);
  // The scale of the sums' thresholds: CA divides by N, GO/SO by n (the sums are of n cells).
  const double divisor = static_cast<double>(config.kind == CfarKind::ca ? config.reference_cells() : config.training_cells);
  edge_scale_.resize(edge_alpha_.size());
  for (std::size_t i = 0; i < edge_alpha_.size(); ++i) edge_scale_[i] = edge_alpha_[i] / divisor;
}

void CfarDetector::detect(std::span<const double> power, CfarWorkspace& workspace) const {
  config_.validate_profile_length(power.size());
  const std::size_t length = power.size();
  const std::size_t guard = config_.guard_cells;
  const std::size_t n = config_.training_cells;
  const std::size_t big_n = 2 * n;
  const double alpha = alpha_;
  const std::size_t reach = guard + n;  // cells i < reach and i >= length - reach are edge cells

  workspace.threshold.resize(length);
  workspace.detections.clear();
  workspace.detections.reserve(length);

  if (config_.kind == CfarKind::os) {
    // OS: the N reference cells are kept sorted while the cell under test slides; each step
    // replaces the cells that left the reference set by those that entered (two in the
    // interior, one at the edges), O(N) instead of a selection per cell.
    // Threshold = alpha * k-th smallest.
    const std::size_t k = config_.effective_os_rank();
    std::vector<double>& sorted = workspace.order_scratch;
    sorted.resize(big_n);
    ReferenceCells r = reference_cells(0, length, guard, n);
    const auto first_right = std::copy(power.begin() + r.lb, power.begin() + r.le, sorted.begin());
    std::copy(power.begin() + r.rb, power.begin() + r.re, first_right);
    std::sort(sorted.begin(), sorted.end());
    // Replace one value of the sorted buffer by another: locate both by a branch-free binary
    // search (conditional moves, no mispredictions on noise data) and shift only the values
    // between the two positions.
    double* const data = sorted.data();
    const auto count_below = [data, big_n](double value) {
      const double* base = data;
      std::size_t count = big_n;
      while (count > 1) {
        const std::size_t half = count / 2;
        base = base[half] < value ? base + half : base;
        count -= half;
      }
      return static_cast<std::size_t>(base - data) + (*base < value ? 1 : 0);
    };
    const auto replace = [data, big_n, &count_below](double leaving, double entering) {
      const std::size_t out = count_below(leaving);
      std::size_t in = count_below(entering);
      FOGRADAR_CHECK(out < big_n && data[out] == leaving);  // power must not be NaN
      if (in <= out) {
        for (std::size_t j = out; j > in; --j) data[j] = data[j - 1];
        data[in] = entering;
      } else {
        --in;  // `leaving` sat below the insertion point
        for (std::size_t j = out; j < in; ++j) data[j] = data[j + 1];
        data[in] = entering;
      }
    };
    // Cells that left / entered the reference set between two consecutive cells under test: set
    // differences of the left ranges and of the right ranges (a cell never moves between the
    // two). At most one per range end, and as many leave as enter (the set keeps N cells).
    std::array<std::size_t, 4> leaving{};
    std::array<std::size_t, 4> entering{};
    std::size_t leaving_count = 0;
    std::size_t entering_count = 0;
    const auto collect = [](std::array<std::size_t, 4>& into, std::size_t& count, std::size_t begin,
                            std::size_t end) {
      for (std::size_t j = begin; j < end; ++j) {
        FOGRADAR_CHECK(count < into.size());
        into[count++] = j;
      }
    };
    const auto alpha_at = [&](std::size_t i) {
      if (i < reach) return edge_alpha_[i];
      return i >= length - reach ? edge_alpha_[length - 1 - i] : alpha;
    };
    workspace.threshold[0] = alpha_at(0) * sorted[k - 1];
    for (std::size_t i = 1; i < length; ++i) {
      const ReferenceCells next = reference_cells(i, length, guard, n);
      leaving_count = 0;
      entering_count = 0;
      collect(leaving, leaving_count, r.lb, std::min(r.le, next.lb));
      collect(leaving, leaving_count, std::max(r.lb, next.le), r.le);
      collect(leaving, leaving_count, r.rb, std::min(r.re, next.rb));
      collect(leaving, leaving_count, std::max(r.rb, next.re), r.re);
      collect(entering, entering_count, next.lb, std::min(next.le, r.lb));
      collect(entering, entering_count, std::max(next.lb, r.le), next.le);
      collect(entering, entering_count, next.rb, std::min(next.re, r.rb));
      collect(entering, entering_count, std::max(next.rb, r.re), next.re);
      FOGRADAR_CHECK(leaving_count == entering_count);
      for (std::size_t m = 0; m < leaving_count; ++m) {
        replace(power[leaving[m]], power[entering[m]]);
      }
      workspace.threshold[i] = alpha_at(i) * sorted[k - 1];
      r = next;
    }
    append_cells_above(power.data(), workspace.threshold.data(), length, workspace.detections);
  } else {
    const std::span<const double> sums = window_sums(power, n, workspace.window_sums, workspace.sum_scratch);
    // CA divides by N, GO/SO by n (the sums are of n cells).
    const double scale = alpha / static_cast<double>(config_.kind == CfarKind::ca ? big_n : n);
    two_sided_detect(power, guard, n, scale, edge_scale_, sums, half_sums_rule(config_.kind),
                     workspace.threshold, workspace.detections);
  }
}

void CfarDetector::detect_four(std::span<const std::complex<double>> rows,
                               CfarFourWorkspace& workspace) const {
  constexpr std::size_t profiles = CfarFourWorkspace::profiles;
  FOGRADAR_CHECK(rows.size() % profiles == 0);
  const std::size_t length = rows.size() / profiles;
  config_.validate_profile_length(length);
  workspace.power.resize(profiles * length);
  workspace.pairs.resize(profiles * (length - 1));  // length >= 3 (validated)
  interleave_norms(rows.data(), length, workspace.power.data(), workspace.pairs.data());
  workspace.threshold.resize(profiles * length);
  for (std::vector<std::size_t>& cells : workspace.detections) {
    cells.clear();
    cells.reserve(length);
  }
  if (config_.kind == CfarKind::os) {
    // The sorted window moves differently in every profile: one at a time.
    std::vector<double>& profile = workspace.window_sums;
    profile.resize(length);
    for (std::size_t r = 0; r < profiles; ++r) {
      for (std::size_t j = 0; j < length; ++j) profile[j] = workspace.power[profiles * j + r];
      detect(profile, workspace.one);
      for (std::size_t j = 0; j < length; ++j)
        workspace.threshold[profiles * j + r] = workspace.one.threshold[j];
      workspace.detections[r] = workspace.one.detections;
    }
    return;
  }
  const std::size_t n = config_.training_cells;
  const std::span<const double> sums =
      window_sums_four(workspace.power, n, workspace.pairs, workspace.window_sums);
  const double scale = alpha_ / static_cast<double>(config_.kind == CfarKind::ca ? 2 * n : n);
  two_sided_detect_four(workspace.power.data(), length, config_.guard_cells, n, scale,
                        edge_scale_.data(), sums.data(), half_sums_rule(config_.kind),
                        workspace.threshold.data(), workspace.detections);
}

std::vector<std::size_t> cfar_detect(std::span<const double> power, const CfarConfig& config,
                                     std::vector<double>* threshold_out) {
  const CfarDetector detector(config);
  CfarWorkspace workspace;
  detector.detect(power, workspace);
  if (threshold_out != nullptr) *threshold_out = std::move(workspace.threshold);
  return std::move(workspace.detections);
}

}  // namespace fogradar::radar
