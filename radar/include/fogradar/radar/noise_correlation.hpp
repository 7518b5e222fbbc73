// Correlation of the noise between the cells of a CFAR profile. A range profile is the DFT of the
// windowed samples of a chirp: white noise of variance s^2 per sample gives cells Y[k] that are
// circular complex Gaussian with
//   E[Y[k] conj(Y[k+m])] = s^2 sum_n w[n]^2 e^{-i 2 pi m n / N},
// so the correlation coefficient rho(m) = sum_n w[n]^2 e^{-i 2 pi m n / N} / sum_n w[n]^2 depends
// on the range window w alone (the Doppler window, applied across chirps, only scales the variance
// of every cell of a Doppler row alike). For a DFT-even window (w[n] = w[N-n], the periodic windows
// the chain uses) rho is real and even. The rectangular window gives rho(m) = 0 for m != 0: white
// cells.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace fogradar::radar {

struct NoiseCorrelation {
  // rho(0) = 1, rho(1), ..., rho(L); rho(-m) = rho(m) and rho(m) = 0 beyond L.
  std::vector<double> coefficients{1.0};

  double at(std::ptrdiff_t lag) const noexcept;
  // True when every coefficient beyond lag 0 is exactly zero (independent cells).
  bool white() const noexcept;
  // Throws InvalidParameter naming "noise_correlation.coefficients" unless rho(0) = 1 and
  // every coefficient is finite with |rho(m)| <= 1.
  void validate() const;
};

// rho(m), m = 0..max_lag (at most N - 1), of the cells of the DFT of white noise through the
// window, rho(m) = sum_n w[n]^2 cos(2 pi m n / N) / sum_n w[n]^2. The window must be DFT-even
// (w[n] = w[N-n], so that the sine sums vanish and rho is real): throws InvalidParameter naming
// "window" otherwise, or when it is empty or all zero.
NoiseCorrelation window_noise_correlation(std::span<const double> window, std::size_t max_lag);

}  // namespace fogradar::radar
