// Beat-signal synthesis: complex baseband I/Q of one frame from the scene's paths, plus thermal
// noise, optional phase noise and ADC quantisation. Frame layout: chirps_per_frame rows of
// samples_per_chirp samples, row-major (chirp-major), in units of sqrt(W) at the receiver input.
#pragma once

#include <complex>
#include <cstddef>
#include <span>

#include "fogradar/core/random.hpp"
#include "fogradar/core/stop.hpp"
#include "fogradar/radar/fft.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/radar/window.hpp"

namespace fogradar::radar {

struct SynthesisReport {
  std::size_t clipped_samples = 0;  // I or Q rail beyond the ADC full scale
  std::size_t samples = 0;          // the frame's samples (chirps x samples per chirp)
  bool range_transformed = false;   // every chirp went through the ChirpTransform given
};

// The range FFT done chirp by chirp as synthesize_frame finishes each chirp: the chirp is written
// to `chirp` (one chirp long, FFTW-aligned) and transformed out of place into its row of the frame
// by `fft` (RangeDopplerProcessor::range_chirp_fft), while it is in the L1 cache.
struct ChirpTransform {
  const FftPlan* fft = nullptr;
  std::span<std::complex<double>> chirp;
};

// Per sample n of chirp c (t = n / fs, stop-and-hop between chirps, range rate kept within a
// chirp):
//   x_c[n] = sum_p a_p exp(i 2 pi (f_b,p - 2 v_p / lambda) t) exp(-i 4 pi v_p c T_i / lambda) +
//   w_c[n]
// with f_b,p = S L_p / c and w ~ CN(0, k T0 F fs) from a ComplexNormalGenerator seeded by `rng`.
// Tones without velocity (the static scene) are summed once, in blocks of 16 samples from
// precomputed phasor powers, and copied to every chirp, the thermal noise added during the copy
// when phase noise is off. `frame` must hold rows x columns samples; nothing is allocated.
// Given a window (rows Doppler weights, 2 columns range-pair weights), the frame comes out
// multiplied by it, with the values apply_frame_window would give afterwards: for a static scene
// with thermal noise and neither phase noise nor an ADC it is applied in the noise pass, which
// saves a pass over the frame; otherwise after everything else. Given a ChirpTransform as well, on
// that noise-pass path (and when the frame's chirps are FFTW-aligned) each chirp is range
// transformed as it is finished, and the report says so (range_transformed); on every other path
// the transform is not used and the frame comes out untransformed.
//
// `parts` (without a window only) keeps the frame's two parts apart as well, each chirps x samples
// or empty: `noise`, the thermal noise w_c[n] as drawn, and `signal`, everything else before it is
// added (the paths, the fog clutter and the phase noise). The frame is then the same bits as
// without them: signal + noise exactly where the noise is the last thing added (every path static
// or phase noise on), to rounding where moving paths are added after the noise; both are taken
// before the ADC.
struct FrameParts {
  std::span<std::complex<double>> signal;
  std::span<std::complex<double>> noise;
};
SynthesisReport synthesize_frame(std::span<const Tone> tones, const RadarParams& params,
                                 const RadarDerived& derived, RandomStream& rng,
                                 std::span<std::complex<double>> frame,
                                 const FrameWindow* window = nullptr,
                                 const ChirpTransform* transform = nullptr,
                                 const FrameParts* parts = nullptr, const StopToken& stop = {});

// ADC model: I and Q each quantised mid-rise with 2^bits levels over [-A, A], A = sqrt(P_fs) the
// amplitude of a full-scale complex tone; values beyond A clip to the outermost level. Returns the
// number of samples with a clipped rail.
std::size_t quantize(std::span<std::complex<double>> samples, unsigned bits,
                     double full_scale_amplitude);

}  // namespace fogradar::radar
