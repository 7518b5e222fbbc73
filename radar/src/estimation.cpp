#include "fogradar/radar/estimation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstring>
#include <limits>

#include "estimation_peak.hpp"
#include "fogradar/core/constants.hpp"
#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::radar {
namespace {

using detail::f64x4;
using estimation_peak::dirichlet_weights;
using estimation_peak::find_peak;

// Objects whose rows are interpolated in one pass over the map.
constexpr std::size_t interpolation_batch = 4;

// An object's strongest cell and its range offset, between the range and the Doppler search.
struct ObjectPeak {
  std::size_t doppler_cell = 0, range_cell = 0, cells = 0;
  double range_offset = 0.0;
};

// Eight doubles: one AVX-512 register, for the x86-64-v4 body of rows_times_kernels only (GCC
// splits it badly into AVX2 register pairs, so the other bodies keep f64x4). The helpers below are
// unused, hence maybe_unused, in builds without that body (the baseline-only and clang builds).
using f64x8 = double __attribute__((vector_size(64)));

[[maybe_unused, gnu::always_inline]] inline f64x8 load8(const double* from) {
  f64x8 v;
  std::memcpy(&v, from, sizeof v);
  return v;
}

// The low and high four lanes of v.
[[maybe_unused, gnu::always_inline]] inline void split8(f64x8 v, f64x4& low, f64x4& high) {
  double lanes[8];
  std::memcpy(lanes, &v, sizeof v);
  low = detail::load4(lanes);
  high = detail::load4(lanes + 4);
}

// x, as a value the compiler cannot fuse with its uses: GCC 12 turned the odd last value's (re, im)
// products and the add/subtract pair of add_row_stretch into one vfmaddsub where FMA exists, in
// spite of -ffp-contract=off, so that the x86-64-v4 version rounded differently from the others
// for odd column counts.
[[gnu::always_inline]] inline double rounded(double x) {
  asm("" : "+m"(x));
  return x;
}

// out[o] += sum_m x[m] K_o[m] over the interleaved (re, im) values [begin, end) of one row
// (begin a multiple of 4), for the `objects` kernels at k_re/k_im + o * stride (stored as at
// rows_times_kernels). Each load of x serves every kernel, and `groups` consecutive steps go to
// separate partial sums so that at least 4 sums are in flight (one would make every step wait for
// the previous addition, 4 cycles, instead of for its loads). With width 8, one eight-lane sum
// holds two consecutive four-lane partial sums (lanes 0-3 group g, lanes 4-7 group g + 1): the same
// products added in the same order as with width 4, so the same bits, in half the instructions.
template <std::size_t objects, std::size_t width>
[[gnu::always_inline]] inline void add_row_stretch(const double* x, const double* k_re,
                                                   const double* k_im, std::size_t stride,
                                                   std::size_t begin, std::size_t end,
                                                   std::complex<double>* out) {
  constexpr std::size_t groups = objects == 1 ? 4 : 2;
  static_assert(width == 4 || width == 8, "four or eight lanes");
  // by_re: (x_re K_re, x_im K_re, ...), by_im: (x_re K_im, x_im K_im, ...); value i of the stretch
  // in partial sum (i - begin) / 4 % groups (sum 0 past the last whole group).
  f64x4 by_re[objects][groups] = {}, by_im[objects][groups] = {};
  std::size_t i = begin;
  if constexpr (width == 8) {
    constexpr std::size_t pairs = groups / 2;
    f64x8 wide_re[objects][pairs] = {}, wide_im[objects][pairs] = {};
    for (; i + 4 * groups <= end; i += 4 * groups) {
      for (std::size_t p = 0; p < pairs; ++p) {
        const f64x8 v = load8(x + i + 8 * p);
        for (std::size_t o = 0; o < objects; ++o) {
          wide_re[o][p] += v * load8(k_re + o * stride + i + 8 * p);
          wide_im[o][p] += v * load8(k_im + o * stride + i + 8 * p);
        }
      }
    }
    for (std::size_t o = 0; o < objects; ++o) {
      for (std::size_t p = 0; p < pairs; ++p) {
        split8(wide_re[o][p], by_re[o][2 * p], by_re[o][2 * p + 1]);
        split8(wide_im[o][p], by_im[o][2 * p], by_im[o][2 * p + 1]);
      }
    }
  } else {
    for (; i + 4 * groups <= end; i += 4 * groups) {
      for (std::size_t g = 0; g < groups; ++g) {
        const f64x4 v = detail::load4(x + i + 4 * g);
        for (std::size_t o = 0; o < objects; ++o) {
          by_re[o][g] += v * detail::load4(k_re + o * stride + i + 4 * g);
          by_im[o][g] += v * detail::load4(k_im + o * stride + i + 4 * g);
        }
      }
    }
  }
  for (; i + 4 <= end; i += 4) {
    const f64x4 v = detail::load4(x + i);
    for (std::size_t o = 0; o < objects; ++o) {
      by_re[o][0] += v * detail::load4(k_re + o * stride + i);
      by_im[o][0] += v * detail::load4(k_im + o * stride + i);
    }
  }
  for (std::size_t o = 0; o < objects; ++o) {
    f64x4 all_re = by_re[o][0], all_im = by_im[o][0];
    for (std::size_t g = 1; g < groups; ++g) {
      all_re += by_re[o][g];
      all_im += by_im[o][g];
    }
    double re = (all_re[0] + all_re[2]) - (all_im[1] + all_im[3]);
    double im = (all_re[1] + all_re[3]) + (all_im[0] + all_im[2]);
    if (i < end) {  // odd column count: one complex value left
      const double* kr = k_re + o * stride;
      const double* ki = k_im + o * stride;
      re += rounded(x[i] * kr[i]) - rounded(x[i + 1] * ki[i]);
      im += rounded(x[i] * ki[i]) + rounded(x[i + 1] * kr[i]);
    }
    out[o] += std::complex<double>(re, im);
  }
}

// out[o][r] = sum_m map[r][m] K_o[m] for every row r and each of `objects` kernels, kernel o at
// kernel_re/kernel_im + o * 2 columns with each value stored twice (kernel_re[2m] = kernel_re[2m+1]
// = Re K[m], likewise Im) to multiply interleaved (re, im) pairs; out[o][r] at out[o * rows + r].
// The map is read once for all kernels, in stripes of columns narrow enough that every kernel's
// stripe stays in the L1 cache while all rows pass (two or more whole kernels, 32 KiB each for
// 1024 columns, would come from L2 for every row, and that bounded the loop).
template <std::size_t objects, std::size_t width>
[[gnu::always_inline]] inline void rows_times_kernels_of(const double* map, std::size_t rows,
                                                         std::size_t columns,
                                                         const double* kernel_re,
                                                         const double* kernel_im,
                                                         std::complex<double>* out) {
  // The kernels' stripes together 32 KiB (2 x 8 bytes per value per kernel), a multiple of 16
  // values: a whole row of 1024 columns for one object. Fewer, longer stripes read the map in
  // longer runs, which the prefetchers follow: with the map out of cache, fixed 2 KiB stripes were
  // 10-20 % slower.
  constexpr std::size_t stripe_values = 2048 / objects / 16 * 16;
  const std::size_t values = 2 * columns;
  std::fill(out, out + objects * rows, std::complex<double>{});
  std::complex<double> row_sums[objects];
  for (std::size_t begin = 0; begin < values; begin += stripe_values) {
    const std::size_t end = std::min(values, begin + stripe_values);
    for (std::size_t r = 0; r < rows; ++r) {
      std::fill(row_sums, row_sums + objects, std::complex<double>{});
      add_row_stretch<objects, width>(map + r * values, kernel_re, kernel_im, values, begin, end,
                                      row_sums);
      for (std::size_t o = 0; o < objects; ++o) out[o * rows + r] += row_sums[o];
    }
  }
}

template <std::size_t width>
[[gnu::always_inline]] inline void rows_times_kernels_body(
    const double* map, std::size_t rows, std::size_t columns, const double* kernel_re,
    const double* kernel_im, std::size_t objects, std::complex<double>* out) {
  switch (objects) {
    case 1:
      return rows_times_kernels_of<1, width>(map, rows, columns, kernel_re, kernel_im, out);
    case 2:
      return rows_times_kernels_of<2, width>(map, rows, columns, kernel_re, kernel_im, out);
    case 3:
      return rows_times_kernels_of<3, width>(map, rows, columns, kernel_re, kernel_im, out);
    case 4:
      return rows_times_kernels_of<4, width>(map, rows, columns, kernel_re, kernel_im, out);
    default:
      FOGRADAR_CHECK(objects == 0);
  }
  static_assert(interpolation_batch == 4, "one case per batch size");
}

// One body per instruction set, differing only in the vector width, as GCC's function
// multiversioning: the loader picks the version as it picks the clones of detail/simd.hpp.
#define FOGRADAR_ROWS_TIMES_KERNELS(attributes, width)                                         \
  attributes void rows_times_kernels(const double* map, std::size_t rows, std::size_t columns, \
                                     const double* kernel_re, const double* kernel_im,         \
                                     std::size_t objects, std::complex<double>* out) {         \
    rows_times_kernels_body<width>(map, rows, columns, kernel_re, kernel_im, objects, out);    \
  }

#if defined(FOGRADAR_SIMD_AVX2)
FOGRADAR_ROWS_TIMES_KERNELS(__attribute__((target("default"))), 4)
FOGRADAR_ROWS_TIMES_KERNELS(__attribute__((target("avx2"))), 4)
#if defined(FOGRADAR_SIMD_AVX512)
FOGRADAR_ROWS_TIMES_KERNELS(__attribute__((target("arch=x86-64-v4"))), 8)
#endif
#else
FOGRADAR_ROWS_TIMES_KERNELS(, 4)
#endif
#undef FOGRADAR_ROWS_TIMES_KERNELS

// ws.doppler[o * rows + r] = X_r(nu_o): every row of the map interpolated to the fractional range
// bins nu_o of up to interpolation_batch objects, in one pass over the map.
void interpolate_rows(std::span<const std::complex<double>> map, std::size_t rows,
                      std::size_t columns, std::span<const double> nu, EstimationWorkspace& ws) {
  const std::size_t values = 2 * columns;
  for (std::size_t o = 0; o < nu.size(); ++o) {
    double* k_re = ws.kernel_re.data() + o * values;
    double* k_im = ws.kernel_im.data() + o * values;
    dirichlet_weights(nu[o], ws.range_table,
                      [k_re, k_im](std::size_t m, std::complex<double> weight) {
                        k_re[2 * m] = k_re[2 * m + 1] = weight.real();
                        k_im[2 * m] = k_im[2 * m + 1] = weight.imag();
                      });
  }
  // std::complex<double> is layout-compatible with double[2] ([complex.numbers.general]).
  rows_times_kernels(reinterpret_cast<const double*>(map.data()), rows, columns,
                     ws.kernel_re.data(), ws.kernel_im.data(), nu.size(), ws.doppler.data());
}

// Doppler bin in [-N/2, N/2).
double signed_bin(double bin, std::size_t n) {
  const double half = 0.5 * static_cast<double>(n);
  double wrapped = std::fmod(bin, static_cast<double>(n));
  if (wrapped < 0.0) wrapped += static_cast<double>(n);
  return wrapped >= half ? wrapped - static_cast<double>(n) : wrapped;
}

// Marks each CFAR detection in the mask and lists it, row by row (ascending cell index). The mask
// is all zero between frames: every listed cell is cleared again by take_object, so it is never
// swept in full. The Doppler rows' |X|^2 is formed four rows at a time, interleaved, just before
// their CFAR (CfarDetector::detect_four: the same bits as row by row, the edge cells a quarter of
// the cost), in buffers that stay in the L1 or L2 cache: a whole power map would be written out and
// read back (1 MiB each for a bench frame) and push the map itself out of the cache before the row
// interpolation reads it. The last rows % 4 rows run one at a time.
void run_cfar(std::span<const std::complex<double>> map, std::size_t rows, std::size_t columns,
              const CfarDetector& cfar, EstimationWorkspace& ws) {
  constexpr std::size_t four = CfarFourWorkspace::profiles;
  if (ws.detected.size() != rows * columns) ws.detected.assign(rows * columns, 0);
  ws.detected_cells.clear();
  const auto mark = [&ws, columns](std::size_t d, std::span<const std::size_t> cells) {
    for (std::size_t k : cells) {
      ws.detected[d * columns + k] = 1;
      ws.detected_cells.push_back(d * columns + k);
    }
  };
  if (cfar.config().shape == CfarShape::range_doppler) {
    ws.map_power.resize(rows * columns);
    squared_magnitudes(map, ws.map_power);
    cfar.detect_map(ws.map_power, rows, ws.cfar_map);
    for (std::size_t cell : ws.cfar_map.detections) {
      ws.detected[cell] = 1;
      ws.detected_cells.push_back(cell);
    }
    return;
  }
  std::size_t d = 0;
  for (; d + four <= rows; d += four) {
    cfar.detect_four(map.subspan(d * columns, four * columns), ws.cfar_four);
    for (std::size_t r = 0; r < four; ++r) mark(d + r, ws.cfar_four.detections[r]);
  }
  ws.row_power.resize(columns);
  for (; d < rows; ++d) {
    squared_magnitudes(map.subspan(d * columns, columns), ws.row_power);
    cfar.detect(ws.row_power, ws.cfar);
    mark(d, ws.cfar.detections);
  }
}

// Flood fill of the 8-connected object containing `seed` (Doppler wraps); clears its cells from the
// mask and returns the index of its strongest cell and its size.
std::pair<std::size_t, std::size_t> take_object(std::size_t seed,
                                                std::span<const std::complex<double>> map,
                                                std::size_t rows, std::size_t columns,
                                                EstimationWorkspace& ws) {
  std::size_t peak = seed, cells = 0;
  ws.stack.clear();
  ws.stack.push_back(seed);
  ws.detected[seed] = 0;
  while (!ws.stack.empty()) {
    const std::size_t cell = ws.stack.back();
    ws.stack.pop_back();
    ++cells;
    if (std::norm(map[cell]) > std::norm(map[peak])) peak = cell;
    const std::size_t d = cell / columns, k = cell % columns;
    for (int dd = -1; dd <= 1; ++dd) {
      const std::size_t nd = (d + rows + static_cast<std::size_t>(dd + 1) - 1) % rows;
      for (int dk = -1; dk <= 1; ++dk) {
        if ((dk < 0 && k == 0) || (dk > 0 && k + 1 == columns)) continue;
        const std::size_t neighbour =
            nd * columns + static_cast<std::size_t>(static_cast<long>(k) + dk);
        if (ws.detected[neighbour]) {
          ws.detected[neighbour] = 0;
          ws.stack.push_back(neighbour);
        }
      }
    }
  }
  return {peak, cells};
}

}  // namespace

void rows_times_interleaved_kernels(const double* map, std::size_t rows, std::size_t columns,
                                    const double* kernel_re, const double* kernel_im,
                                    std::size_t objects, std::complex<double>* out) {
  FOGRADAR_CHECK(objects <= interpolation_batch);
  rows_times_kernels(map, rows, columns, kernel_re, kernel_im, objects, out);
}

void estimate_detections(std::span<const std::complex<double>> map,
                         const RangeDopplerProcessor& processor, const CfarDetector& cfar,
                         const RadarParams& params, const RadarDerived& derived,
                         EstimationWorkspace& ws, std::vector<Detection>& detections,
                         const StopToken& stop) {
  const std::size_t rows = processor.chirps(), columns = processor.samples();
  FOGRADAR_CHECK(map.size() == rows * columns);
  detections.clear();
  run_cfar(map, rows, columns, cfar, ws);
  ws.range_table.prepare(columns);
  ws.doppler_table.prepare(rows);
  ws.kernel_re.resize(interpolation_batch * 2 * columns);
  ws.kernel_im.resize(interpolation_batch * 2 * columns);
  ws.doppler.resize(interpolation_batch * rows);
  const double noise_per_cell_w = derived.noise_power_w * processor.noise_power_gain();
  const double gain = processor.coherent_amplitude_gain();

  // Objects in seed order, in batches: range peaks first, then one pass over the map interpolates
  // every row to each object's range, then each object's Doppler peak.
  std::array<ObjectPeak, interpolation_batch> batch{};
  std::array<double, interpolation_batch> range_bins{};
  std::size_t next_seed = 0;
  while (true) {
    stop.check();
    std::size_t count = 0;
    for (; count < interpolation_batch && next_seed < ws.detected_cells.size(); ++next_seed) {
      const std::size_t seed = ws.detected_cells[next_seed];
      if (!ws.detected[seed]) continue;  // already taken with an earlier cell of its object
      const auto [peak, cells] = take_object(seed, map, rows, columns, ws);
      ObjectPeak& object = batch[count];
      object.doppler_cell = peak / columns;
      object.range_cell = peak % columns;
      object.cells = cells;
      // Range: the DTFT maximum along the peak's Doppler row.
      object.range_offset = find_peak(map.subspan(object.doppler_cell * columns, columns),
                                      object.range_cell, ws.range_table, ws.range_inverse, ws)
                                .offset;
      range_bins[count] = static_cast<double>(object.range_cell) + object.range_offset;
      ++count;
    }
    if (count == 0) break;
    // Doppler: every row interpolated to the object's range, then the maximum across Doppler.
    interpolate_rows(map, rows, columns, std::span<const double>(range_bins.data(), count), ws);
    for (std::size_t o = 0; o < count; ++o) {
      const ObjectPeak& object = batch[o];
      const std::span<const std::complex<double>> profile(ws.doppler.data() + o * rows, rows);
      const auto [doppler_offset, peak_power] =
          find_peak(profile, object.doppler_cell, ws.doppler_table, ws.doppler_inverse, ws);

      Detection det;
      det.range_bin = range_bins[o];
      det.doppler_bin = signed_bin(static_cast<double>(object.doppler_cell) + doppler_offset, rows);
      // The Doppler bin is f_D N_c T_i with f_D = eps 2 v / lambda.
      det.radial_velocity_m_per_s =
          derived.sweep_sign * det.doppler_bin * derived.velocity_resolution_m_per_s;
      // The beat frequency holds the Doppler shift too (range-Doppler coupling): remove it.
      const double beat_hz = det.range_bin * params.sample_rate_hz / static_cast<double>(columns);
      const double doppler_hz = doppler_shift_hz(det.radial_velocity_m_per_s, derived);
      det.range_m =
          (beat_hz - doppler_hz) * speed_of_light_m_per_s / (2.0 * derived.chirp_slope_hz_per_s);
      det.received_power_w = peak_power / (gain * gain);
      det.snr_db = power_ratio_to_db(peak_power / noise_per_cell_w);
      det.rcs_m2 =
          rcs_from_received_power_m2(det.received_power_w, derived.tx_power_w, derived.tx_gain,
                                     derived.rx_gain, derived.wavelength_m, det.range_m);
      det.rcs_dbsm = power_ratio_to_db(det.rcs_m2);
      det.cells = object.cells;
      det.range_cell = object.range_cell;
      det.doppler_cell = object.doppler_cell;
      detections.push_back(det);
    }
  }
}

}  // namespace fogradar::radar
