// What the correlated-cell CFAR design (cfar_design.cpp) takes from cfar_correlated.cpp.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fogradar/core/stop.hpp"
#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/noise_correlation.hpp"

namespace fogradar::radar {

// Samples of the reference vector per reference geometry.
inline constexpr std::size_t kSamples = std::size_t{1} << 14;

// kSamples draws of N independent CN(0, 1) values (sample-major) from the stream of `seed`: the
// same draws serve every geometry of a design (common random numbers).
std::vector<std::complex<double>> standard_draws(std::size_t big_n, std::uint64_t seed);

// True when no two cells of a geometry spanning `span` cells are correlated.
bool white_within(const NoiseCorrelation& noise, std::size_t span);

// The threshold factor of one reference geometry (`offsets`) for the design P_fa: CA's exact, the
// other kinds' from the sampled P_fa over `draws` (standard_draws), tilted at a start near the
// root.
double correlated_factor(const CfarConfig& config, const NoiseCorrelation& noise,
                         std::span<const std::ptrdiff_t> offsets, double independent_factor,
                         std::span<const std::complex<double>> draws, const StopToken& stop);

}  // namespace fogradar::radar
