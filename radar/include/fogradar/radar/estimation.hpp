// From the range-Doppler map to detections: CFAR along range in every Doppler bin, detected cells
// grouped into objects (8-connected, Doppler wrapping), each object's peak interpolated to the exact
// DTFT maximum, received power calibrated for every processing gain, RCS by paper eq. 7.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/processing.hpp"

namespace fogradar::radar {

struct Detection {
  double range_m = 0.0;
  double radial_velocity_m_per_s = 0.0;   // + receding
  double range_bin = 0.0;                 // interpolated
  double doppler_bin = 0.0;               // interpolated, signed (in [-N_c/2, N_c/2))
  double received_power_w = 0.0;          // at the receiver input, all processing gains removed
  double rcs_m2 = 0.0;                    // eq. 7 with the estimated range
  double rcs_dbsm = 0.0;
  double snr_db = 0.0;                    // peak power over the chain's thermal-noise power per cell
  std::size_t cells = 0;                  // detected cells in the object
};

// Reusable buffers, one per thread.
struct EstimationWorkspace {
  CfarWorkspace cfar;
  std::vector<std::uint8_t> detected;   // chirps x samples mask
  std::vector<std::size_t> stack;       // flood fill
  std::vector<std::complex<double>> kernel;   // Dirichlet weights along range
  std::vector<std::complex<double>> doppler;  // range-interpolated value per Doppler bin
};

// Exact interpolation of a DFT to a fractional bin nu: the DTFT of the (windowed) time signal,
// X(nu) = sum_m X[m] K(nu - m), K(u) = exp(-i pi u (N-1)/N) sin(pi u) / (N sin(pi u / N)) (the
// periodic sinc / Dirichlet kernel; e.g. Oppenheim & Schafer, Discrete-Time Signal Processing,
// 3rd ed., sec. 8.4). Fills `kernel` with K(nu - m), m = 0..N-1.
void dirichlet_kernel(double nu, std::size_t n, std::span<std::complex<double>> kernel);

// Detections of one processed frame (map = complex range-Doppler map, power = |map|^2).
// `detections` is cleared and refilled.
void estimate_detections(std::span<const std::complex<double>> map, std::span<const double> power,
                         const RangeDopplerProcessor& processor, const CfarDetector& cfar,
                         const RadarParams& params, const RadarDerived& derived,
                         EstimationWorkspace& workspace, std::vector<Detection>& detections);

}  // namespace fogradar::radar
