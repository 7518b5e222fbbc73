#include "fogradar/propagation/materials.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::propagation {

namespace {

using complex = std::complex<double>;

// ITU-R P.2040-3 (08/2023) Table 3, the first frequency range of each row; the 220-450 GHz rows of
// glass and ceiling board are left out (no sensor of this project works there).
ItuP2040Fit p2040_row(Material material) {
  switch (material) {
    case Material::concrete:
      return {5.24, 0.0, 0.0462, 0.7822, 1.0, 100.0};
    case Material::brick:
      return {3.91, 0.0, 0.0238, 0.16, 1.0, 40.0};
    case Material::plasterboard:
      return {2.73, 0.0, 0.0085, 0.9395, 1.0, 100.0};
    case Material::wood:
      return {1.99, 0.0, 0.0047, 1.0718, 0.001, 100.0};
    case Material::glass:
      return {6.31, 0.0, 0.0036, 1.3394, 0.1, 100.0};
    case Material::ceiling_board:
      return {1.48, 0.0, 0.0011, 1.0750, 1.0, 100.0};
    case Material::chipboard:
      return {2.58, 0.0, 0.0217, 0.7800, 1.0, 100.0};
    case Material::plywood:
      return {2.71, 0.0, 0.33, 0.0, 1.0, 40.0};
    case Material::marble:
      return {7.074, 0.0, 0.0055, 0.9262, 1.0, 60.0};
    case Material::floorboard:
      return {3.66, 0.0, 0.0044, 1.3515, 50.0, 100.0};
    case Material::metal:
      return {1.0, 0.0, 1e7, 0.0, 1.0, 100.0};
    case Material::very_dry_ground:
      return {3.0, 0.0, 0.00015, 2.52, 1.0, 10.0};
    case Material::medium_dry_ground:
      return {15.0, -0.1, 0.035, 1.63, 1.0, 10.0};
    case Material::wet_ground:
      return {30.0, -0.4, 0.15, 1.30, 1.0, 10.0};
    case Material::water:
    case Material::plastic:
      break;
  }
  FOGRADAR_CHECK(false);
  return {};
}

// Liebe's fit holds to 1 THz (water.hpp); 1 MHz is P.2040's own lower limit.
constexpr FrequencyRangeGhz water_range{0.001, 1000.0};
constexpr FrequencyRangeGhz plastic_range{10.0, 300.0};

constexpr std::array<Material, 3> with_optical_data = {Material::water, Material::glass,
                                                       Material::metal};
constexpr WavelengthRangeNm malitson_range{210.0, 3710.0};
// A window around the lidar bands (905, 1550 nm) inside Rakic's fitted spectrum.
constexpr WavelengthRangeNm rakic_window{400.0, 2000.0};

std::string range_text(double low, double high, std::string_view unit) {
  return "in [" + message_number(low) + ", " + message_number(high) + "] " + std::string(unit);
}

}  // namespace

std::optional<ItuP2040Fit> itu_p2040_fit(Material material) {
  if (material == Material::water || material == Material::plastic) return std::nullopt;
  return p2040_row(material);
}

double itu_p2040_conductivity_s_per_m(const ItuP2040Fit& fit, double frequency_ghz) {
  return fit.c * std::pow(frequency_ghz, fit.d);
}

complex itu_p2040_permittivity(const ItuP2040Fit& fit, double frequency_ghz) {
  const double real = fit.a * std::pow(frequency_ghz, fit.b);
  return {real, 17.98 * itu_p2040_conductivity_s_per_m(fit, frequency_ghz) / frequency_ghz};
}

FrequencyRangeGhz radio_frequency_range(Material material) {
  if (material == Material::water) return water_range;
  if (material == Material::plastic) return plastic_range;
  const ItuP2040Fit fit = p2040_row(material);
  return {fit.min_frequency_ghz, fit.max_frequency_ghz};
}

std::string_view radio_permittivity_source(Material material) {
  if (material == Material::water) return "Liebe et al. 1991 (ITU-R P.840 form), water at 20 C";
  if (material == Material::plastic)
    return "assumption: HDPE, n = 1.526, tan delta = 3e-4 (as quoted from Lamb 1996)";
  return "ITU-R P.2040-3 Table 3";
}

complex radio_permittivity(Material material, double frequency_hz, std::string_view field) {
  const FrequencyRangeGhz range = radio_frequency_range(material);
  const double frequency_ghz = frequency_hz / 1e9;
  if (!(frequency_ghz >= range.min_ghz && frequency_ghz <= range.max_ghz)) {
    throw_invalid(field, frequency_hz,
                  range_text(range.min_ghz * 1e9, range.max_ghz * 1e9, "Hz") + " for material '" +
                      std::string(to_string(material)) + "' (" +
                      std::string(radio_permittivity_source(material)) + ")");
  }
  if (material == Material::water) {
    return liebe1991_permittivity(frequency_hz, material_water_temperature_k);
  }
  if (material == Material::plastic) {
    const double real = plastic_refractive_index * plastic_refractive_index;
    return {real, real * plastic_loss_tangent};
  }
  return itu_p2040_permittivity(p2040_row(material), frequency_ghz);
}

std::span<const Material> optical_materials() { return with_optical_data; }

std::string optical_material_names() {
  std::string text;
  for (const Material material : with_optical_data) {
    text += text.empty() ? "" : ", ";
    text += to_string(material);
  }
  return text;
}

std::optional<WavelengthRangeNm> optical_wavelength_range(Material material,
                                                          const SegelsteinTable& table) {
  switch (material) {
    case Material::water:
      return WavelengthRangeNm{table.min_wavelength_m() * 1e9, table.max_wavelength_m() * 1e9};
    case Material::glass:
      return malitson_range;
    case Material::metal:
      return rakic_window;
    default:
      return std::nullopt;
  }
}

std::string_view optical_index_source(Material material) {
  switch (material) {
    case Material::water:
      return "Segelstein 1981 table";
    case Material::glass:
      return "fused silica, Malitson 1965 Sellmeier fit, absorption neglected";
    case Material::metal:
      return "aluminium, Rakic et al. 1998 Lorentz-Drude fit";
    default:
      return "";
  }
}

double malitson_fused_silica_index(double wavelength_m) {
  const double l2 = std::pow(wavelength_m * 1e6, 2);
  constexpr std::array<double, 3> b = {0.6961663, 0.4079426, 0.8974794};
  constexpr std::array<double, 3> c = {0.0684043, 0.1162414, 9.896161};
  double n2 = 1.0;
  for (std::size_t j = 0; j < b.size(); ++j) n2 += b[j] * l2 / (l2 - c[j] * c[j]);
  return std::sqrt(n2);
}

complex rakic_aluminium_permittivity(double wavelength_m) {
  // Photon energy in eV: hc / e = 1.239841984e-6 eV m (CODATA 2018, exact in the 2019 SI).
  const double w = 1.239841984e-6 / wavelength_m;
  constexpr double plasma_ev = 14.98;
  constexpr double f0 = 0.523;
  constexpr double gamma0_ev = 0.047;
  struct Oscillator {
    double strength;
    double gamma_ev;
    double resonance_ev;
  };
  constexpr std::array<Oscillator, 4> oscillators = {
      {{0.227, 0.333, 0.162}, {0.050, 0.312, 1.544}, {0.166, 1.351, 1.808}, {0.030, 3.382, 3.473}}};
  const double wp2 = plasma_ev * plasma_ev;
  complex eps = 1.0 - f0 * wp2 / (w * complex(w, gamma0_ev));
  for (const Oscillator& o : oscillators) {
    eps += o.strength * wp2 / complex(o.resonance_ev * o.resonance_ev - w * w, -w * o.gamma_ev);
  }
  return eps;
}

complex optical_refractive_index(Material material, double wavelength_m,
                                 const SegelsteinTable& table, std::string_view field) {
  const std::optional<WavelengthRangeNm> range = optical_wavelength_range(material, table);
  if (!range) {
    throw InvalidParameter(std::string(field),
                           "material '" + std::string(to_string(material)) +
                               "' has no optical data: the materials with optical data are " +
                               optical_material_names());
  }
  const double wavelength_nm = wavelength_m * 1e9;
  if (!(wavelength_nm >= range->min_nm && wavelength_nm <= range->max_nm)) {
    throw_invalid(field, wavelength_m,
                  range_text(range->min_nm * 1e-9, range->max_nm * 1e-9, "m") + " for material '" +
                      std::string(to_string(material)) + "' (" +
                      std::string(optical_index_source(material)) + ")");
  }
  switch (material) {
    case Material::water:
      return table.refractive_index(wavelength_m);
    case Material::glass:
      return {malitson_fused_silica_index(wavelength_m), 0.0};
    case Material::metal:
      return refractive_index_from_permittivity(rakic_aluminium_permittivity(wavelength_m));
    default:
      break;
  }
  FOGRADAR_CHECK(false);
  return {};
}

FresnelCoefficients fresnel_reflection(complex permittivity, double grazing_rad) {
  const double sin_psi = std::sin(grazing_rad);
  const double cos_psi = std::cos(grazing_rad);
  const complex root = std::sqrt(permittivity - cos_psi * cos_psi);
  return {(sin_psi - root) / (sin_psi + root),
          (permittivity * sin_psi - root) / (permittivity * sin_psi + root)};
}

}  // namespace fogradar::propagation
