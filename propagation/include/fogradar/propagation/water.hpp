// Complex refractive index of liquid water: the Segelstein (1981) table and the Liebe et al. (1991)
// double-Debye permittivity model used by ITU-R P.840. Convention: m = n + i k with k >= 0 and
// eps = eps' + i eps'' with eps'' >= 0 (time dependence exp(-i w t), as Bohren & Huffman 1983).
#pragma once

#include <complex>
#include <span>
#include <string_view>
#include <vector>

#include "fogradar/core/enum_names.hpp"

namespace fogradar::propagation {

enum class WaterModel { segelstein, liebe };

// The Segelstein table is for room temperature, about 25 C (data/PROVENANCE.md), with no
// temperature dependence: a water temperature is accepted with it only at this value.
inline constexpr double segelstein_table_temperature_c = 25.0;

inline constexpr auto water_model_names =
    enum_names<WaterModel>({{WaterModel::liebe, "liebe"}, {WaterModel::segelstein, "segelstein"}});
constexpr std::string_view to_string(WaterModel model) noexcept {
  return water_model_names.name(model);
}

// The Segelstein 1981 table (data/segelstein81_index.txt, compiled into the library), interpolated
// monotonically (PCHIP) in log(lambda) -> log(n), log(k). Immutable after construction; safe to
// share between threads. Wavelengths outside the table throw InvalidParameter.
class SegelsteinTable {
 public:
  SegelsteinTable();
  ~SegelsteinTable();
  SegelsteinTable(const SegelsteinTable&) = delete;
  SegelsteinTable& operator=(const SegelsteinTable&) = delete;

  std::complex<double> refractive_index(double wavelength_m) const;
  double min_wavelength_m() const;
  double max_wavelength_m() const;
  // The tabulated rows, as parsed (wavelength in metres).
  std::span<const double> wavelengths_m() const;
  std::span<const double> real_index() const;
  std::span<const double> imag_index() const;

 private:
  struct Impl;
  Impl* impl_;
};

// Liebe, Hufford & Manabe 1991 (Int. J. IR mm Waves 12, 659) double-Debye relative permittivity of
// liquid water, in the form ITU-R P.840 uses (eq. (4)-(11) in the numbering of P.840-7), which
// keeps the high-frequency permittivity eps2 = 3.52 constant as Liebe et al. 1993 do. Valid 0-1000
// GHz, temperature_k in [253.15, 323.15] (-20..50 C, supercooled water included as P.840 does);
// outside throws.
std::complex<double> liebe1991_permittivity(double frequency_hz, double temperature_k);

// m = sqrt(eps) on the branch with Im(m) >= 0.
std::complex<double> refractive_index_from_permittivity(std::complex<double> permittivity);

// ITU-R P.840 eq. (2)-(3) (P.840-7 numbering): Rayleigh specific attenuation coefficient of
// cloud/fog liquid water, K_l = 0.819 f / (eps'' (1 + eta^2)), eta = (2 + eps') / eps'', in
// (dB/km)/(g/m^3), f in GHz.
double itu_p840_specific_attenuation_coefficient(double frequency_hz, double temperature_k);

// The refractive index of water under a chosen model at one temperature. The Segelstein table takes
// only its own temperature (segelstein_table_temperature_c); Liebe takes -20..50 C and is valid
// only up to 1 THz (wavelength >= 0.2998 mm). Any other temperature throws InvalidParameter
// ("temperature_k"), so that no temperature is accepted that the index does not use.
class WaterOptics {
 public:
  WaterOptics(WaterModel model, double temperature_k, const SegelsteinTable& table);
  std::complex<double> refractive_index(double wavelength_m) const;
  WaterModel model() const { return model_; }
  double temperature_k() const { return temperature_k_; }

 private:
  WaterModel model_;
  double temperature_k_;
  const SegelsteinTable* table_;
};

}  // namespace fogradar::propagation
