// Named unit conversions. SI inside the code, dB and engineering units only at the edges.
#pragma once

#include <cmath>

#include "fogradar/core/constants.hpp"

namespace fogradar {

// Power ratio from decibels: r = 10^(dB/10).
inline double db_to_power_ratio(double db) { return std::pow(10.0, db / 10.0); }

// Decibels from a power ratio: dB = 10 log10(r).
inline double power_ratio_to_db(double ratio) { return 10.0 * std::log10(ratio); }

// Watts from dBm: P = 1 mW * 10^(dBm/10).
inline double dbm_to_watt(double dbm) { return 1e-3 * db_to_power_ratio(dbm); }

// dBm from watts.
inline double watt_to_dbm(double watt) { return power_ratio_to_db(watt / 1e-3); }

// Decibels of a power loss factor exp(-x) (x in nepers of power): dB = 10 log10(e) x  (paper eq.
// 5).
inline constexpr double db_per_neper_power = 4.342944819032518;  // 10 / ln(10)

constexpr double celsius_to_kelvin(double celsius) { return celsius + zero_celsius_k; }

// Free-space wavelength: lambda = c / f.
inline double wavelength_from_frequency_m(double frequency_hz) {
  return speed_of_light_m_per_s / frequency_hz;
}

inline double frequency_from_wavelength_hz(double wavelength_m) {
  return speed_of_light_m_per_s / wavelength_m;
}

inline constexpr double per_km_to_per_m(double per_km) { return per_km * 1e-3; }
inline constexpr double per_m_to_per_km(double per_m) { return per_m * 1e3; }

}  // namespace fogradar
