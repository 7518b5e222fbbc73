// The CFAR's sliding window sums and detection scans, cloned per instruction set with the same
// bits.
#include "cfar_kernels.hpp"

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
#include "fogradar/radar/cfar.hpp"

namespace fogradar::radar::cfar_kernels {

namespace {

// The passes of window_sums, cloned so that AVX2 adds four cells per instruction (element-wise
// sums: the same bits in every clone). Only `a` and `b` may overlap (both are read).
FOGRADAR_SIMD_CLONES
void add_cells(const double* __restrict a, const double* __restrict b, double* __restrict out,
               std::size_t count) {
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
[[gnu::always_inline]] inline void scan_cells_above(const double* power, const double* threshold,
                                                    std::size_t begin, std::size_t end,
                                                    std::vector<std::size_t>& cells,
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
  [[gnu::always_inline]] detail::f64x4 four_from(std::size_t k) const {
    return detail::load4(threshold + k);
  }
  [[gnu::always_inline]] double one_at(std::size_t i) const { return threshold[i]; }
};

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
void interior_thresholds_and_detect(HalfSums rule, const double* lead, const double* lag,
                                    const double* power, double scale, double* threshold,
                                    std::size_t begin, std::size_t end,
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

}  // namespace

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

FOGRADAR_SIMD_CLONES
void append_cells_above(const double* power, const double* threshold, std::size_t length,
                        std::vector<std::size_t>& cells) {
  scan_cells_above(power, threshold, 0, length, cells, StoredThresholds{threshold});
}

std::span<const double> window_sums(std::span<const double> power, std::size_t n,
                                    std::vector<double>& sums, std::vector<double>& blocks) {
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

HalfSums half_sums_rule(CfarKind kind) {
  return kind == CfarKind::ca   ? HalfSums::add
         : kind == CfarKind::go ? HalfSums::greater
                                : HalfSums::smaller;
}

void two_sided_detect(std::span<const double> power, std::size_t guard, std::size_t n, double scale,
                      std::span<const double> edge_scale, std::span<const double> sums,
                      HalfSums rule, std::vector<double>& threshold,
                      std::vector<std::size_t>& cells) {
  const std::size_t length = power.size();
  const auto edge_cell = [&](std::size_t i) {
    const auto [first, second] = edge_halves<double>(i, length, guard, n, CellsOf{power.data()});
    threshold[i] = edge_scale[std::min(i, length - 1 - i)] * combine(rule, first, second);
    if (power[i] > threshold[i]) cells.push_back(i);
  };
  const std::size_t interior_begin = guard + n;
  const std::size_t interior_end = length - guard - n;  // > interior_begin (validated)
  for (std::size_t i = 0; i < interior_begin; ++i) edge_cell(i);
  const double* lead = sums.data();                     // S_lead of cell i = sums[i - guard - n]
  const double* lag = sums.data() + 2 * guard + n + 1;  // S_lag of cell i = sums[i + guard + 1]
  interior_thresholds_and_detect(rule, lead, lag, power.data(), scale, threshold.data(),
                                 interior_begin, interior_end, cells);
  for (std::size_t i = interior_end; i < length; ++i) edge_cell(i);
}

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
    const detail::f64x4 norms01 = __builtin_shufflevector(squares[0], squares[1], 0, 4, 2, 6) +
                                  __builtin_shufflevector(squares[0], squares[1], 1, 5, 3, 7);
    const detail::f64x4 norms23 = __builtin_shufflevector(squares[2], squares[3], 0, 4, 2, 6) +
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

}  // namespace fogradar::radar::cfar_kernels
