// Ground truth per detection: which of the frame's ingredients (target paths, ghosts, the room's
// echoes, fog clutter, their sidelobes, noise) dominates the detection's peak cell of the
// range-Doppler map (docs/radar.md sec. 5.1).
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
  // The main lobe's half width in bins: the offset of the first minimum of |W(u)| from u = 0 on
  // the table's grid (1 / oversampling), found from the window itself: 1 for the rectangular
  // window, 2 for Hann and Hamming, 4 for the 4-term Blackman-Harris (Harris 1978, Table 1), and
  // wherever a Chebyshev window's first null falls; N / 2 when |W| has no minimum within half a
  // period.
  double main_lobe_half_width_bins() const noexcept { return main_lobe_half_width_bins_; }

 private:
  std::size_t n_;
  std::vector<std::complex<double>>
      table_;  // W(j / oversampling), j = 0 .. N oversampling (first repeated)
  double main_lobe_half_width_bins_;
};

// The complex contributions of the frame's tones to one cell of the range-Doppler map, split by
// where the cell lies in each tone's window response, and the expected power of the noise there
// (map units: |Y|^2). A tone's main lobe covers the cells within the main-lobe half width of its
// peak in range and in Doppler (both, offsets circular); everywhere else it leaks (sidelobes).
struct CellContributions {
  std::complex<double> target;       // the target paths (Origin::target) whose main lobe covers it
  std::complex<double> multipath;    // the ghosts (Origin::multipath) whose main lobe covers it
  std::complex<double> room;         // the room's own echoes whose main lobe covers it
  std::complex<double> fog;          // the fog clutter tones whose main lobe covers it
  std::complex<double> target_leak;  // the other target paths and ghosts (their sidelobes)
  std::complex<double> room_leak;    // the room's other echoes
  std::complex<double> fog_leak;     // the other fog tones
  double noise_power = 0.0;          // thermal, ADC quantisation and phase noise (noise_power)
  // The chamber layer (Tone::layer) whose main-lobe fog tones sum to the most power here; -1
  // without main-lobe fog.
  std::int16_t fog_layer = -1;

  // All tones' leakage, summed coherently: what a sidelobe false alarm is made of.
  std::complex<double> sidelobe() const { return target_leak + room_leak + fog_leak; }
};

// A cell's ground truth: its origin and, for fog, the layer that dominates the fog there (the
// index in chamber.layers, 0-based from the sensor); -1 when the origin is not fog.
struct Attribution {
  Origin origin = Origin::noise;
  std::int16_t layer = -1;
};

// Attributes detections to their origin. A tone of amplitude a, beat frequency f (Doppler shift
// included) and Doppler frequency f_D = -2 v / lambda adds to cell (d, k) of the map
//   Y_p[d][k] = a g W_r(k - f N / fs) W_d(d - f_D T_i N_c)
// (the windowed 2-D DFT of the tone synthesize_frame makes; W_r, W_d the range and Doppler windows'
// DTFTs; g = exp(-sigma^2 / 2) the coherent part left by white phase noise of rms sigma). The cell
// goes to the largest of |T|^2 (target main lobes), |M|^2 (ghosts' main lobes), |R|^2 (the room's
// echoes' main lobes), |F|^2 (fog main lobes), |S|^2 (every tone's leakage outside its main lobe,
// summed coherently: a sidelobe false alarm) and the noise power (dominant_origin's ties). In a
// frame whose ADC clipped, a cell that none of the tones explains (noise would dominate) is the
// clipping's: a rail clipped at +-A is an odd nonlinearity of the sum of tones, whose harmonics and
// intermodulation products (f = sum of n_i f_i, Blachman, IEEE Trans. Inf. Theory 17 (1971) 398)
// land in cells no tone reaches, strong as the clipped tones and far above the noise. Immutable:
// one classifier serves every thread.
class OriginClassifier {
 public:
  OriginClassifier(const RangeDopplerProcessor& processor, const RadarParams& params,
                   const RadarDerived& derived);

  // The expected noise power per cell of a frame of these tones, the sum of three white noises
  // through the windowed 2-D DFT (each times sum(w_r^2) sum(w_d^2)):
  // - thermal: k T0 F fs per sample (zero without thermal noise);
  // - ADC quantisation: q^2 / 12 per rail, q^2 / 6 per complex sample, q = 2 A / 2^bits the
  //   mid-rise step (Widrow, Kollar, Quantization Noise (2008) ch. 4); valid while the input
  //   spans many steps (thermal noise or signal rms >> q per rail) and does not clip;
  // - phase noise: a sample s e^{i phi}, phi ~ N(0, sigma^2) white, has the coherent part
  //   s e^{-sigma^2/2} and white power |s|^2 (1 - e^{-sigma^2}) (E e^{i phi} = e^{-sigma^2/2},
  //   the characteristic function of the normal); |s|^2 averaged over the frame is sum_t |a_t|^2
  //   when the tones' cross terms average out (tones more than a bin apart).
  double noise_power(std::span<const Tone> tones) const;
  CellContributions contributions(std::span<const Tone> tones, std::size_t doppler_cell,
                                  std::size_t range_cell) const;
  // The origin and layer of the contributions at the cell; noise becomes clipping when `clipped`.
  Attribution attribution(std::span<const Tone> tones, std::size_t doppler_cell,
                          std::size_t range_cell, bool clipped = false) const;
  Origin classify(std::span<const Tone> tones, std::size_t doppler_cell, std::size_t range_cell,
                  bool clipped = false) const {
    return attribution(tones, doppler_cell, range_cell, clipped).origin;
  }
  // Sets every detection's origin and layer from its peak cell; `clipped`: the frame's ADC clipped.
  void attribute(std::span<const Tone> tones, std::span<Detection> detections,
                 bool clipped = false) const;
  // The origin a detection peaking in each cell would be given (classify), Doppler rows in FFT
  // order x range columns as the map: the frame's ground truth everywhere; and, when `layers` is
  // not empty, each cell's fog layer (Attribution::layer). The tones are summed in groups of equal
  // Doppler shift (the window's DTFT along Doppler is common to a group), so a cell whose powers
  // tie to rounding may differ from classify.
  void origin_map(std::span<const Tone> tones, bool clipped, std::span<std::uint8_t> map,
                  std::span<std::int16_t> layers = {}) const;

  double range_main_lobe_half_width_bins() const noexcept {
    return range_spectrum_.main_lobe_half_width_bins();
  }
  double doppler_main_lobe_half_width_bins() const noexcept {
    return doppler_spectrum_.main_lobe_half_width_bins();
  }

 private:
  // A tone's part in the cell, and whether the cell lies in its main lobe.
  std::complex<double> tone_at(const Tone& tone, double doppler_cell, double range_cell,
                               bool& main_lobe) const;

  WindowSpectrum range_spectrum_;
  WindowSpectrum doppler_spectrum_;
  double range_bins_per_hz_;    // N / fs
  double doppler_bins_per_hz_;  // T_i N_c
  RadarDerived derived_;        // the beat and Doppler frequencies synthesize_frame gives each tone
  double noise_gain_;           // sum(w_r^2) sum(w_d^2)
  double thermal_and_quantisation_w_;  // per sample, before the window gains
  double phase_noise_incoherent_;      // 1 - e^{-sigma^2}
  double phase_noise_coherent_;        // e^{-sigma^2 / 2}
  std::size_t chirps_;
  std::size_t samples_;
};

}  // namespace fogradar::radar
