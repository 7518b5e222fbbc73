// Ground truth per detection: which of the frame's ingredients (target paths, fog clutter, thermal
// noise) dominates the detection's peak cell of the range-Doppler map (docs/radar.md sec. 6).
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fogradar/radar/estimation.hpp"
#include "fogradar/radar/origin.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/processing.hpp"
#include "fogradar/radar/scene.hpp"

namespace fogradar::radar {

// The DTFT of a window, W(u) = sum_n w[n] exp(-i 2 pi n u / N), at fractional bin offsets u (period
// N), interpolated linearly in a table of W(j / oversampling) over one period (a zero-padded FFT of
// length N oversampling). Linear interpolation errs by at most h^2 max|W''| / 8 with h = 1 /
// oversampling and |W''| <= 4 pi^2 sum |w[n]|: 0.019 sum |w[n]|, and in practice about 0.5 % of the
// local value (the phase turns by pi / oversampling from one entry to the next).
// Immutable after construction: one table serves every thread.
class WindowSpectrum {
 public:
  static constexpr std::size_t oversampling = 16;

  explicit WindowSpectrum(std::span<const double> window);

  std::size_t length() const noexcept { return n_; }
  std::complex<double> at(double offset_bins) const noexcept;

 private:
  std::size_t n_;
  std::vector<std::complex<double>>
      table_;  // W(j / oversampling), j = 0 .. N oversampling (first repeated)
};

// Noise-free complex contributions of the target paths and of the fog clutter to one cell of the
// range-Doppler map, and the thermal noise's expected power there (map units: |Y|^2).
struct CellContributions {
  std::complex<double> target;
  std::complex<double> fog;
  double noise_power = 0.0;
};

// Attributes detections to their origin. A tone of amplitude a, beat frequency f (Doppler shift
// included) and Doppler frequency f_D = -2 v / lambda adds to cell (d, k) of the map
//   Y_p[d][k] = a W_r(k - f N / fs) W_d(d - f_D T_i N_c)
// (the windowed 2-D DFT of the tone synthesize_frame makes; W_r, W_d the range and Doppler windows'
// DTFTs); T and F sum this over the target and the fog tones; the noise's expected power is
// k T0 F fs sum(w_r^2) sum(w_d^2) (zero without thermal noise). Phase noise and ADC quantisation
// are not counted. In a frame whose ADC clipped, a cell that neither T nor F explains (noise would
// dominate) is the clipping's: a rail clipped at +-A is an odd nonlinearity of the sum of tones,
// whose harmonics and intermodulation products (f = sum of n_i f_i, Blachman, IEEE Trans. Inf.
// Theory 17 (1971) 398) land in cells no tone reaches, strong as the clipped tones and far above
// the thermal noise. Immutable: one classifier serves every thread.
class OriginClassifier {
 public:
  OriginClassifier(const RangeDopplerProcessor& processor, const RadarParams& params,
                   const RadarDerived& derived);

  CellContributions contributions(std::span<const Tone> tones, std::size_t doppler_cell,
                                  std::size_t range_cell) const;
  // dominant_origin of the contributions at the cell; noise becomes clipping when `clipped`.
  Origin classify(std::span<const Tone> tones, std::size_t doppler_cell, std::size_t range_cell,
                  bool clipped = false) const;
  // Sets every detection's origin from its peak cell; `clipped`: the frame's ADC clipped.
  void attribute(std::span<const Tone> tones, std::span<Detection> detections,
                 bool clipped = false) const;
  // The origin a detection peaking in each cell would be given (classify), Doppler rows in FFT
  // order x range columns as the map: the frame's ground truth everywhere. The tones are summed
  // in groups of equal Doppler shift (the window's DTFT along Doppler is common to a group), so a
  // cell whose powers tie to rounding may differ from classify.
  void origin_map(std::span<const Tone> tones, bool clipped, std::span<std::uint8_t> map) const;

 private:
  WindowSpectrum range_spectrum_;
  WindowSpectrum doppler_spectrum_;
  double range_bins_per_hz_;    // N / fs
  double doppler_bins_per_hz_;  // T_i N_c
  RadarDerived derived_;  // the beat and Doppler frequencies synthesize_frame gives each tone
  double noise_power_;
  std::size_t chirps_;
  std::size_t samples_;
};

}  // namespace fogradar::radar
