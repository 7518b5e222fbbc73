// Range-Doppler processing of one frame: window -> range FFT along each chirp -> Doppler FFT across
// chirps -> power map. Plans and windows are made once; one processor may be shared by many
// threads, each processing its own frame buffer in place.
#pragma once

#include <complex>
#include <span>
#include <vector>

#include "fogradar/radar/fft.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/window.hpp"

namespace fogradar::radar {

// power[i] = |values[i]|^2 (re^2 + im^2, the one formula every stage uses).
void squared_magnitudes(std::span<const std::complex<double>> values, std::span<double> power);

// The gains of range window w_r (N samples) and Doppler window w_d (N_c chirps) through the 2-D
// DFT: a tone of amplitude a centred on a cell peaks at |Y| = a N CG_r N_c CG_d; white noise of
// variance s^2 per sample gives E|Y|^2 = s^2 (sum w_r^2)(sum w_d^2).
double coherent_amplitude_gain(std::span<const double> range_window,
                               std::span<const double> doppler_window);
double noise_power_gain(std::span<const double> range_window,
                        std::span<const double> doppler_window);

class RangeDopplerProcessor {
 public:
  // The chain plans with the shipped FFTW wisdom (FftPlanner::shipped_wisdom).
  explicit RangeDopplerProcessor(const RadarParams& params,
                                 FftPlanner planner = FftPlanner::shipped_wisdom);

  std::size_t chirps() const { return chirps_; }
  std::size_t samples() const { return samples_; }

  // In place: frame (chirps x samples, chirp-major, FFTW-aligned) becomes the range-Doppler map
  // Y[d][k] = sum_c sum_n w_d[c] w_r[n] x_c[n] exp(-i 2 pi (n k / N + c d / N_c)). Row d < N_c/2
  // is Doppler bin d, d >= N_c/2 is d - N_c; velocity is eps (RadarDerived::sweep_sign) times the
  // bin times the velocity resolution.
  void transform(std::span<std::complex<double>> frame) const;
  // The range and Doppler FFTs of transform, for a frame that already carries window() (as
  // synthesize_frame leaves it when given the window).
  void transform_windowed(std::span<std::complex<double>> frame) const;
  // The same with a caller's one-chirp buffer (FFTW-aligned, samples() long) for the range FFT's
  // copy of each chirp, so that a workspace's frames allocate nothing.
  void transform_windowed(std::span<std::complex<double>> frame,
                          std::span<std::complex<double>> chirp) const;
  // The Doppler FFT of transform_windowed alone, for a frame whose chirps are already range
  // transformed (by range_chirp_fft, as synthesize_frame does given it); throws Stopped part way
  // when `stop` says stop (ColumnBlockFft::execute).
  void doppler_transform(std::span<std::complex<double>> frame, const StopToken& stop = {}) const;
  // The range FFT of one chirp, out of place (from a one-chirp buffer into the frame's row; both
  // FFTW-aligned): transform_windowed applies it to every chirp, the synthesis to each chirp as it
  // finishes it, so both paths give the same bits.
  const FftPlan& range_chirp_fft() const { return range_fft_; }
  // transform, and `power` receives |Y|^2 (same layout).
  void process(std::span<std::complex<double>> frame, std::span<double> power) const;

  // Amplitude gain of the whole chain for a tone centred on a range and a Doppler bin:
  // N CG_r N_c CG_d, so a tone of amplitude a peaks at |Y| = a * coherent_amplitude_gain().
  double coherent_amplitude_gain() const { return coherent_amplitude_gain_; }
  // Noise power gain: white noise of variance s^2 per sample gives E|Y|^2 = s^2 * this
  // = s^2 (sum w_r^2)(sum w_d^2).
  double noise_power_gain() const { return noise_power_gain_; }

  std::span<const double> range_window() const { return range_window_; }
  std::span<const double> doppler_window() const { return doppler_window_; }
  // Both windows, as transform applies them.
  FrameWindow window() const { return {doppler_window_, range_window_pairs_}; }

 private:
  std::size_t chirps_;
  std::size_t samples_;
  std::vector<double> range_window_;
  std::vector<double> doppler_window_;
  std::vector<double> range_window_pairs_;  // w_r[n] at 2n and 2n + 1
  FftPlan range_fft_;                       // one chirp, out of place: see range_chirp_fft()
  ColumnBlockFft doppler_fft_;  // down the columns in cache-sized blocks: same bits, no cache cliff
  double coherent_amplitude_gain_;
  double noise_power_gain_;
};

}  // namespace fogradar::radar
