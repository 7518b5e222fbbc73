#include "fogradar/radar/processing.hpp"

#include <numeric>

#include "fogradar/core/error.hpp"

namespace fogradar::radar {
namespace {

double sum_of_squares(std::span<const double> w) {
  return std::inner_product(w.begin(), w.end(), w.begin(), 0.0);
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
  for (std::size_t c = 0; c < chirps_; ++c) {
    std::complex<double>* row = frame.data() + c * samples_;
    const double wd = doppler_window_[c];
    for (std::size_t n = 0; n < samples_; ++n) row[n] *= wd * range_window_[n];
  }
  range_fft_.execute(frame);
  doppler_fft_.execute(frame);
  for (std::size_t i = 0; i < frame.size(); ++i) power[i] = std::norm(frame[i]);
}

}  // namespace fogradar::radar
