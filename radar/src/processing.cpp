#include "fogradar/radar/processing.hpp"

#include <numeric>

#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::radar {
namespace {

double sum_of_squares(std::span<const double> w) {
  return std::inner_product(w.begin(), w.end(), w.begin(), 0.0);
}

// The two element-wise passes over a frame, as plain loops over interleaved (re, im) doubles so
// that each instruction-set clone vectorises them; element-wise IEEE products and sums give the
// same bits in every clone.

// row[n] *= row_weight w[n] for the n complex samples of one chirp.
FOGRADAR_SIMD_CLONES
void apply_window(double* row, const double* window, double row_weight, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k) {
    const double weight = row_weight * window[k];
    row[2 * k] *= weight;
    row[2 * k + 1] *= weight;
  }
}

// power[i] = |X_i|^2 = re^2 + im^2 (as std::norm).
FOGRADAR_SIMD_CLONES
void squared_magnitudes(const double* spectrum, double* power, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    const double re = spectrum[2 * i];
    const double im = spectrum[2 * i + 1];
    power[i] = re * re + im * im;
  }
}

}  // namespace

RangeDopplerProcessor::RangeDopplerProcessor(const RadarParams& params, FftPlanner planner)
    : chirps_(params.chirps_per_frame),
      samples_(params.samples_per_chirp),
      range_window_(make_window(params.window, samples_)),
      doppler_window_(make_window(params.window, chirps_)),
      range_fft_(FftPlan::along_rows(chirps_, samples_, FftDirection::forward,
                                     {.planner = planner, .placement = FftPlacement::in_place})),
      doppler_fft_(FftPlan::along_columns(chirps_, samples_, FftDirection::forward,
                                          {.planner = planner, .placement = FftPlacement::in_place})),
      coherent_amplitude_gain_(static_cast<double>(samples_) * coherent_gain(range_window_) *
                               static_cast<double>(chirps_) * coherent_gain(doppler_window_)),
      noise_power_gain_(sum_of_squares(range_window_) * sum_of_squares(doppler_window_)) {}

void RangeDopplerProcessor::process(std::span<std::complex<double>> frame, std::span<double> power) const {
  FOGRADAR_CHECK(frame.size() == chirps_ * samples_ && power.size() == frame.size());
  // Both windows at once: the 2-D window is separable and the transforms are linear.
  // std::complex<double> is layout-compatible with double[2] ([complex.numbers.general]).
  double* samples = reinterpret_cast<double*>(frame.data());
  for (std::size_t c = 0; c < chirps_; ++c) {
    apply_window(samples + 2 * c * samples_, range_window_.data(), doppler_window_[c], samples_);
  }
  range_fft_.execute(frame);
  doppler_fft_.execute(frame);
  squared_magnitudes(samples, power.data(), frame.size());
}

}  // namespace fogradar::radar
