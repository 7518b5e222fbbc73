#include "fogradar/radar/estimation.hpp"

#include <boost/math/tools/minima.hpp>
#include <cmath>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::radar {
namespace {

// Bits of precision for Brent's search of the peak: 2^-30 bins is far below any physical effect.
constexpr int peak_search_bits = 30;
// The true maximum of a tone lies within half a bin of the largest cell; a little margin lets
// Brent's method find it when two cells are nearly equal.
constexpr double peak_search_half_width_bins = 0.75;

std::complex<double> interpolate(std::span<const std::complex<double>> values,
                                 std::span<const std::complex<double>> kernel) {
  std::complex<double> sum{};
  for (std::size_t m = 0; m < values.size(); ++m) sum += values[m] * kernel[m];
  return sum;
}

// Fractional offset in [-w, w] around bin `centre` that maximises |X(centre + offset)|.
double peak_offset(std::span<const std::complex<double>> values, std::size_t centre,
                   std::span<std::complex<double>> kernel) {
  const std::size_t n = values.size();
  if (n == 1) return 0.0;
  const auto negative_magnitude = [&](double offset) {
    dirichlet_kernel(static_cast<double>(centre) + offset, n, kernel);
    return -std::norm(interpolate(values, kernel));
  };
  return boost::math::tools::brent_find_minima(negative_magnitude, -peak_search_half_width_bins,
                                               peak_search_half_width_bins, peak_search_bits)
      .first;
}

// Doppler bin in [-N/2, N/2).
double signed_bin(double bin, std::size_t n) {
  const double half = 0.5 * static_cast<double>(n);
  double wrapped = std::fmod(bin, static_cast<double>(n));
  if (wrapped < 0.0) wrapped += static_cast<double>(n);
  return wrapped >= half ? wrapped - static_cast<double>(n) : wrapped;
}

// Marks each CFAR detection in the mask, row by row.
void run_cfar(std::span<const double> power, std::size_t rows, std::size_t columns, const CfarDetector& cfar,
              EstimationWorkspace& ws) {
  ws.detected.assign(rows * columns, 0);
  for (std::size_t d = 0; d < rows; ++d) {
    cfar.detect(power.subspan(d * columns, columns), ws.cfar);
    for (std::size_t k : ws.cfar.detections) ws.detected[d * columns + k] = 1;
  }
}

// Flood fill of the 8-connected object containing `seed` (Doppler wraps); clears its cells from the
// mask and returns the index of its strongest cell and its size.
std::pair<std::size_t, std::size_t> take_object(std::size_t seed, std::span<const double> power,
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
    if (power[cell] > power[peak]) peak = cell;
    const std::size_t d = cell / columns, k = cell % columns;
    for (int dd = -1; dd <= 1; ++dd) {
      const std::size_t nd = (d + rows + static_cast<std::size_t>(dd + 1) - 1) % rows;
      for (int dk = -1; dk <= 1; ++dk) {
        if ((dk < 0 && k == 0) || (dk > 0 && k + 1 == columns)) continue;
        const std::size_t neighbour = nd * columns + static_cast<std::size_t>(static_cast<long>(k) + dk);
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

void dirichlet_kernel(double nu, std::size_t n, std::span<std::complex<double>> kernel) {
  FOGRADAR_CHECK(kernel.size() >= n);
  const double nd = static_cast<double>(n);
  for (std::size_t m = 0; m < n; ++m) {
    const double u = nu - static_cast<double>(m);
    // Integer u: the kernel is 1 at multiples of N (aliases of bin m) and 0 elsewhere.
    const double s = std::sin(pi * u / nd);
    const double magnitude = std::abs(s) < 1e-12 ? (std::abs(std::remainder(u, nd)) < 1e-9 ? 1.0 : 0.0)
                                                 : std::sin(pi * u) / (nd * s);
    // X(nu) = sum_m X[m] (1/N) sum_n exp(-i 2 pi (nu - m) n / N): the geometric sum has phase
    // exp(-i pi u (N-1)/N) for FFTW's forward sign exp(-i 2 pi n k / N).
    kernel[m] = std::polar(magnitude, -pi * u * (nd - 1.0) / nd);
  }
}

void estimate_detections(std::span<const std::complex<double>> map, std::span<const double> power,
                         const RangeDopplerProcessor& processor, const CfarDetector& cfar,
                         const RadarParams& params, const RadarDerived& derived,
                         EstimationWorkspace& ws, std::vector<Detection>& detections) {
  const std::size_t rows = processor.chirps(), columns = processor.samples();
  FOGRADAR_CHECK(map.size() == rows * columns && power.size() == map.size());
  detections.clear();
  run_cfar(power, rows, columns, cfar, ws);
  ws.kernel.resize(std::max(rows, columns));
  ws.doppler.resize(rows);
  const double noise_per_cell_w = derived.noise_power_w * processor.noise_power_gain();
  const double gain = processor.coherent_amplitude_gain();

  for (std::size_t seed = 0; seed < ws.detected.size(); ++seed) {
    if (!ws.detected[seed]) continue;
    const auto [peak, cells] = take_object(seed, power, rows, columns, ws);
    const std::size_t d = peak / columns, k = peak % columns;

    // Range: the DTFT maximum along the peak's Doppler row.
    const std::span<std::complex<double>> range_kernel(ws.kernel.data(), columns);
    const double range_offset = peak_offset(map.subspan(d * columns, columns), k, range_kernel);
    // Doppler: interpolate every row to that range, then find the maximum across Doppler.
    dirichlet_kernel(static_cast<double>(k) + range_offset, columns, range_kernel);
    for (std::size_t row = 0; row < rows; ++row) {
      ws.doppler[row] = interpolate(map.subspan(row * columns, columns), range_kernel);
    }
    const std::span<std::complex<double>> doppler_kernel(ws.kernel.data(), rows);
    const double doppler_offset = peak_offset(ws.doppler, d, doppler_kernel);
    dirichlet_kernel(static_cast<double>(d) + doppler_offset, rows, doppler_kernel);
    const double peak_power = std::norm(interpolate(ws.doppler, doppler_kernel));

    Detection det;
    det.range_bin = static_cast<double>(k) + range_offset;
    det.doppler_bin = signed_bin(static_cast<double>(d) + doppler_offset, rows);
    det.radial_velocity_m_per_s = -det.doppler_bin * derived.velocity_resolution_m_per_s;
    // The beat frequency holds the Doppler shift too (range-Doppler coupling): remove it.
    const double beat_hz = det.range_bin * params.sample_rate_hz / static_cast<double>(columns);
    const double doppler_hz = -2.0 * det.radial_velocity_m_per_s / derived.wavelength_m;
    det.range_m = (beat_hz - doppler_hz) * speed_of_light_m_per_s / (2.0 * derived.chirp_slope_hz_per_s);
    det.received_power_w = peak_power / (gain * gain);
    det.snr_db = power_ratio_to_db(peak_power / noise_per_cell_w);
    det.rcs_m2 = rcs_from_received_power_m2(det.received_power_w, derived.tx_power_w, derived.tx_gain,
                                            derived.rx_gain, derived.wavelength_m, det.range_m);
    det.rcs_dbsm = power_ratio_to_db(det.rcs_m2);
    det.cells = cells;
    detections.push_back(det);
  }
}

}  // namespace fogradar::radar
