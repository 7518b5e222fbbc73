// What the correlated-cell CFAR design (cfar_design.cpp) takes from cfar_correlated.cpp.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fogradar/core/stop.hpp"
#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/cfar_design.hpp"
#include "fogradar/radar/noise_correlation.hpp"

namespace fogradar::radar {

// Samples of the reference vector per reference geometry.
inline constexpr std::size_t kSamples = std::size_t{1} << 14;

// kSamples draws of N independent CN(0, 1) values (sample-major) from the stream of `seed`: the
// same draws serve every geometry of a design (common random numbers).
std::vector<std::complex<double>> standard_draws(std::size_t big_n, std::uint64_t seed);

// Cells on each side of a structure point within which two geometries must agree to share a factor
// (cfar_design.cpp): the largest lag with |rho| >= 1e-2 up to lag 16, plus one; a correlation that
// has not decayed by then shares nothing (a reach no geometry meets).
std::size_t structure_cells(const NoiseCorrelation& noise);

// True when no two cells of a geometry spanning `span` cells are correlated.
bool white_within(const NoiseCorrelation& noise, std::size_t span);

// The threshold factor of one reference geometry (`offsets`) for the design P_fa: CA's exact, the
// other kinds' from the sampled P_fa over `draws` (standard_draws), tilted at a start near the
// root.
double correlated_factor(const CfarConfig& config, const NoiseCorrelation& noise,
                         std::span<const std::ptrdiff_t> offsets, double independent_factor,
                         std::span<const std::complex<double>> draws, const StopToken& stop);

// The noise correlation between two cells of a range-Doppler map: rho_r(dk) rho_d(dd). The 2-D
// DFT of white noise through the separable window w_d[c] w_r[n] gives E[Y Y'^*] proportional to
// sum_c sum_n w_d[c]^2 w_r[n]^2 e^{-i 2 pi (dk n / N + dd c / N_c)}, which factors into the two
// windows' coefficients (noise_correlation.hpp). One Doppler row: `doppler` white.
struct CellNoise {
  const NoiseCorrelation& range;
  const NoiseCorrelation& doppler;
  double at(const CfarCellOffset& a, const CfarCellOffset& b) const noexcept {
    return range.at(a.range - b.range) * doppler.at(a.doppler - b.doppler);
  }
};

// correlated_factor for reference cells anywhere on the map (the ring's, cfar_ring.cpp); `config`
// is the ring's equivalent config (cfar_ring_equivalent).
double correlated_factor(const CfarConfig& config, const CellNoise& noise,
                         std::span<const CfarCellOffset> offsets, double independent_factor,
                         std::span<const std::complex<double>> draws, const StopToken& stop);

}  // namespace fogradar::radar
