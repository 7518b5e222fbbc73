// Data windows (tapers) for the range and Doppler FFTs, their processing-gain figures, and the
// separable 2-D window applied to a frame.
//
// Reference: F. J. Harris, "On the use of windows for harmonic analysis with the discrete
// Fourier transform", Proc. IEEE 66(1), 51-83, 1978 (Table 1 for the figures of merit).
#pragma once

#include <complex>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "fogradar/core/enum_names.hpp"

namespace fogradar::radar {

enum class WindowType { rectangular, hann, hamming, blackman_harris, chebyshev };

// Periodic ("DFT-even") or symmetric samples.
//   periodic:  w[j] = f(2 pi j / N), j = 0..N-1: the first N samples of the symmetric window of
//              length N+1 (Chebyshev: see make_window). Harris 1978 §II recommends this form for
//              spectral analysis with an N-point DFT: the window is then exactly periodic on the
//              DFT grid, so e.g. the Hann window has exactly three non-zero DFT bins, and its
//              coherent gain and noise bandwidth equal the tabulated asymptotic values for every N.
//   symmetric: w[j] = w[N-1-j] (filter-design form, e.g. MATLAB hann(N)/scipy sym=True).
// Default: periodic, used by the radar chain.
enum class WindowSymmetry { periodic, symmetric };

inline constexpr auto window_type_names = enum_names<WindowType>({
    {WindowType::rectangular, "rectangular"},
    {WindowType::hann, "hann"},
    {WindowType::hamming, "hamming"},
    {WindowType::blackman_harris, "blackman_harris"},
    {WindowType::chebyshev, "chebyshev"},
});
constexpr std::string_view to_string(WindowType type) noexcept {
  return window_type_names.name(type);
}

// N samples of a window with the published coefficients (cosine windows are not renormalised:
// their peak is 1 where a sample falls on the window centre, i.e. periodic with even N or
// symmetric with odd N, slightly less otherwise; Chebyshev is normalised to a peak of 1).
//   rectangular      w = 1
//   (x = 2 pi j / N periodic, x = 2 pi j / (N-1) symmetric, j = 0..N-1)
//   hann             w = 0.5 - 0.5 cos(x)
//   hamming          w = 0.54 - 0.46 cos(x)
//   blackman_harris  4-term, -92 dB: 0.35875 - 0.48829 cos x + 0.14128 cos 2x - 0.01168 cos 3x
//   chebyshev        Dolph-Chebyshev, every sidelobe at -chebyshev_sidelobe_db relative to the
//                    main-lobe peak: for a symmetric window of length M, the inverse DFT of the
//                    Chebyshev polynomial W(k) = T_{M-1}(beta cos(pi k / M)),
//                    beta = cosh(acosh(10^(A/20)) / (M-1)) (Harris 1978 eqs. 44-45; the
//                    algorithm of scipy.signal.windows.chebwin). symmetric: M = N. periodic:
//                    w = [0, symmetric design of M = N-1], DFT-even (w[j] = w[N-j]) like the
//                    periodic Hann window [0, ...] and still exactly equiripple. (Truncating a
//                    length N+1 design, scipy's sym=False, would raise the highest sidelobe by
//                    up to 6 dB, so it is not used.)
// n >= 1 (n = 1 gives {1}); chebyshev_sidelobe_db in [13, 300] (only read for chebyshev).
// Throws InvalidParameter naming "window.n" or "window.chebyshev_sidelobe_db".
std::vector<double> make_window(WindowType type, std::size_t n, double chebyshev_sidelobe_db = 80.0,
                                WindowSymmetry symmetry = WindowSymmetry::periodic);

// Coherent gain CG = sum(w) / N: amplitude gain of a tone at a bin centre relative to the
// rectangular window (Harris 1978 Table 1). The power loss of the window is CG^2.
double coherent_gain(std::span<const double> window);

// Equivalent noise bandwidth in bins ENBW = N sum(w^2) / (sum w)^2 (Harris 1978 eq. 13,
// Table 1): white-noise power through the window relative to a rectangular window.
double noise_equivalent_bandwidth_bins(std::span<const double> window);

// The separable window of a frame, w[c][n] = doppler[c] range[n] (chirp c, sample n), with each
// range weight stored twice (range_pairs[2n] = range_pairs[2n + 1] = range[n]) to scale the
// interleaved (re, im) values of a chirp.
struct FrameWindow {
  std::span<const double> doppler;
  std::span<const double> range_pairs;
};

// frame[c][n] *= doppler[c] range[n] for a doppler.size() x range_pairs.size() / 2 frame
// (chirp-major).
void apply_frame_window(const FrameWindow& window, std::span<std::complex<double>> frame);

}  // namespace fogradar::radar
