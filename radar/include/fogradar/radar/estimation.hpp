// From the range-Doppler map to detections: CFAR along range in every Doppler bin, detected cells
// grouped into objects (8-connected, Doppler wrapping), each object's peak interpolated to the
// exact DTFT maximum, received power calibrated for every processing gain, RCS by paper eq. 7.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "fogradar/core/stop.hpp"
#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/fft.hpp"
#include "fogradar/radar/origin.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/processing.hpp"

namespace fogradar::radar {

struct Detection {
  double range_m = 0.0;
  double radial_velocity_m_per_s = 0.0;  // + receding
  double range_bin = 0.0;                // interpolated
  double doppler_bin = 0.0;              // interpolated, signed (in [-N_c/2, N_c/2))
  double received_power_w = 0.0;         // at the receiver input, all processing gains removed
  double rcs_m2 = 0.0;                   // eq. 7 with the estimated range
  double rcs_dbsm = 0.0;
  double snr_db = 0.0;           // peak power over the chain's thermal-noise power per cell
  std::size_t cells = 0;         // detected cells in the object
  std::size_t range_cell = 0;    // the object's strongest cell: range bin in [0, N)
  std::size_t doppler_cell = 0;  // and Doppler bin in [0, N_c) (unsigned, as in the map)
  // What dominates the strongest cell (OriginClassifier, attribution.hpp); estimate_detections
  // leaves noise, RadarChain::measure sets it.
  Origin origin = Origin::noise;
  // For a fog origin, the chamber layer that dominates the fog in the cell (Attribution::layer);
  // -1 otherwise.
  std::int16_t layer = -1;
};

// cos(pi j / N) and sin(pi j / N) for j = 0 .. 2N-1, the rotations from which the Dirichlet
// kernel is assembled without per-bin trigonometry (see dirichlet_kernel).
class DirichletTable {
 public:
  explicit DirichletTable(std::size_t n = 0) { prepare(n); }
  // Makes the table for length n; nothing happens if it is already made for n.
  void prepare(std::size_t n);
  std::size_t length() const noexcept { return n_; }
  double cos_pi_j_over_n(std::size_t j) const { return cos_[j]; }  // j < 2N
  double sin_pi_j_over_n(std::size_t j) const { return sin_[j]; }

 private:
  std::size_t n_ = 0;
  std::vector<double> cos_, sin_;
};

// Inverse DFT of one row or column (the peak's time signal), planned on first use for its length.
struct InverseDft {
  std::optional<FftPlan> plan;
  ComplexVector signal;
  void prepare(std::size_t n);
};

// Reusable buffers, one per thread.
struct EstimationWorkspace {
  CfarFourWorkspace cfar_four;  // |X|^2 of four Doppler rows under CFAR, and its results
  CfarWorkspace cfar;
  std::vector<double> map_power;  // range_doppler: |X|^2 of the whole map
  CfarMapWorkspace cfar_map;
  std::vector<double> row_power;            // |X|^2 of a Doppler row under CFAR (the last rows % 4)
  std::vector<std::uint8_t> detected;       // chirps x samples mask, all zero between frames
  std::vector<std::size_t> detected_cells;  // the cells set in the mask, ascending
  std::vector<std::size_t> stack;           // flood fill
  DirichletTable range_table, doppler_table;
  std::vector<double> rotated_re, rotated_im, sin_j, cos_j;  // one peak search (see estimation.cpp)
  InverseDft range_inverse, doppler_inverse;  // the peak's time signal for the final Newton steps
  std::vector<double> kernel_re,
      kernel_im;  // Dirichlet weights along range, each value twice, per object
  std::vector<std::complex<double>>
      doppler;  // range-interpolated value per Doppler bin, per object
};

// Exact interpolation of a DFT to a fractional bin nu: the DTFT of the (windowed) time signal,
// X(nu) = sum_m X[m] K(nu - m), K(u) = exp(-i pi u (N-1)/N) sin(pi u) / (N sin(pi u / N)) (the
// periodic sinc / Dirichlet kernel; e.g. Oppenheim & Schafer, Discrete-Time Signal Processing,
// 3rd ed., sec. 8.4). Fills `kernel` with K(nu - m), m = 0..N-1. Evaluated as
//   K(nu - m) = A(f) e^{i pi j/N} / sin(pi (j + f) / N),  A(f) = sin(pi f) e^{-i pi f (N-1)/N} / N,
// with nu = k + f (k the nearest integer) and j = k - m: the sines and rotations of pi j / N come
// from `table` (made for n), sin(pi (j + f)/N) = sin(pi j/N) cos(pi f/N) + cos(pi j/N) sin(pi f/N),
// so one call costs three sines and N divisions (derivation in docs/radar.md sec. 5).
void dirichlet_kernel(double nu, std::size_t n, std::span<std::complex<double>> kernel);
void dirichlet_kernel(double nu, const DirichletTable& table,
                      std::span<std::complex<double>> kernel);

// The row interpolation inside estimate_detections, declared for its test: out[o * rows + r] =
// sum_m map[r][m] K_o[m] for the `objects` (at most 4) kernels K_o, map the rows x columns complex
// values as interleaved (re, im) doubles, kernel o at kernel_re/kernel_im + o * 2 columns with each
// value stored twice (kernel_re[2m] = kernel_re[2m+1] = Re K_o[m], likewise Im). The sums are
// formed in a fixed order (estimation.cpp), the same in every instruction-set version.
void rows_times_interleaved_kernels(const double* map, std::size_t rows, std::size_t columns,
                                    const double* kernel_re, const double* kernel_im,
                                    std::size_t objects, std::complex<double>* out);

// Detections of one processed frame (map = the complex range-Doppler map of
// RangeDopplerProcessor; the CFAR runs on |map|^2, formed one Doppler row at a time).
// `detections` is cleared and refilled. Throws Stopped, before a batch of objects, when
// `stop` says stop: each batch is a pass over the whole map, and a large noisy frame has hundreds
// of false alarms (65536 x 4096 cells: about 270, 45 s).
void estimate_detections(std::span<const std::complex<double>> map,
                         const RangeDopplerProcessor& processor, const CfarDetector& cfar,
                         const RadarParams& params, const RadarDerived& derived,
                         EstimationWorkspace& workspace, std::vector<Detection>& detections,
                         const StopToken& stop = {});

}  // namespace fogradar::radar
