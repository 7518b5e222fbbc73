// Physical constants, exact where the SI defines them exactly (BIPM, SI Brochure 9th ed., 2019).
#pragma once

#include <numbers>

namespace fogradar {

inline constexpr double pi = std::numbers::pi;

// Speed of light in vacuum, exact (SI 2019).
inline constexpr double speed_of_light_m_per_s = 299'792'458.0;

// Boltzmann constant, exact (SI 2019).
inline constexpr double boltzmann_j_per_k = 1.380'649e-23;

// Reference noise temperature T0 of the noise figure definition (IEEE Std 100, 290 K).
inline constexpr double reference_noise_temperature_k = 290.0;

// Offset between the Celsius and Kelvin scales, exact.
inline constexpr double zero_celsius_k = 273.15;

// Density of liquid water used to turn volume into liquid water content: 1 g/cm^3 = 1e6 g/m^3
// (ITU-R P.840 and fog literature use this value; the 0.2 % change over 0-30 C is neglected).
inline constexpr double water_density_g_per_m3 = 1.0e6;

}  // namespace fogradar
