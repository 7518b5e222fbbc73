// Surfaces of a room: the complex relative permittivity of building materials at radio frequencies
// (ITU-R P.2040-3, 08/2023, Table 3 fits), of water and of a plastic; the complex refractive
// index of the few materials with published optical data at a wavelength; and the Fresnel amplitude
// reflection coefficients of a smooth half-space. Convention as water.hpp: eps = eps' + i eps''
// with eps'' >= 0 (time dependence exp(-i w t)); P.2040 writes eps' - j eps'' (exp(j w t)), so its
// reflection phases are the negatives of the ones here.
#pragma once

#include <complex>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/propagation/water.hpp"

namespace fogradar::propagation {

enum class Material {
  concrete,
  brick,
  plasterboard,
  wood,
  glass,
  ceiling_board,
  chipboard,
  plywood,
  marble,
  floorboard,
  metal,
  very_dry_ground,
  medium_dry_ground,
  wet_ground,
  water,
  plastic,
};

// Every material with the name a user types, in the order above.
inline constexpr auto material_names = enum_names<Material>({
    {Material::concrete, "concrete"},
    {Material::brick, "brick"},
    {Material::plasterboard, "plasterboard"},
    {Material::wood, "wood"},
    {Material::glass, "glass"},
    {Material::ceiling_board, "ceiling_board"},
    {Material::chipboard, "chipboard"},
    {Material::plywood, "plywood"},
    {Material::marble, "marble"},
    {Material::floorboard, "floorboard"},
    {Material::metal, "metal"},
    {Material::very_dry_ground, "very_dry_ground"},
    {Material::medium_dry_ground, "medium_dry_ground"},
    {Material::wet_ground, "wet_ground"},
    {Material::water, "water"},
    {Material::plastic, "plastic"},
});
constexpr std::string_view to_string(Material material) noexcept {
  return material_names.name(material);
}

// One row of ITU-R P.2040-3 Table 3: eps' = a f^b, sigma = c f^d (f in GHz, sigma in S/m), valid
// for min_frequency_ghz <= f <= max_frequency_ghz.
struct ItuP2040Fit {
  double a;
  double b;
  double c;
  double d;
  double min_frequency_ghz;
  double max_frequency_ghz;
};

// The material's P.2040 fit; none for water and plastic, which are not in P.2040's table.
std::optional<ItuP2040Fit> itu_p2040_fit(Material material);

// ITU-R P.2040-3, Table 3's model: sigma = c f^d, f in GHz (no range check).
double itu_p2040_conductivity_s_per_m(const ItuP2040Fit& fit, double frequency_ghz);
// ITU-R P.2040-3: eps' = a f^b and eps'' = sigma / (eps0 omega) = 17.98 sigma / f_GHz; returns
// eps' + i eps'' (no range check).
std::complex<double> itu_p2040_permittivity(const ItuP2040Fit& fit, double frequency_ghz);

struct FrequencyRangeGhz {
  double min_ghz;
  double max_ghz;
};

// The frequencies at which radio_permittivity() accepts the material.
FrequencyRangeGhz radio_frequency_range(Material material);
// Where the value comes from, for output ("ITU-R P.2040-3 Table 3", ...).
std::string_view radio_permittivity_source(Material material);

// Liquid water's permittivity here is Liebe et al. 1991 (water.hpp) at this temperature.
inline constexpr double material_water_temperature_k = 293.15;

// High-density polyethylene (the rain barrels' plastic), eps' = n^2 with n = 1.526 and
// tan(delta) = 3e-4: an assumption, the values quoted for HDPE from Lamb 1996 (Int. J. Infrared
// Millim. Waves 17, pp. 1997-2034), which this project has not checked against the paper; the
// far-infrared measurement 1.518-1.521 (Smith & Loewenstein 1975) puts n near 1.52. Constant over
// 10-300 GHz, where non-polar polyethylene has no dispersion of note.
inline constexpr double plastic_refractive_index = 1.526;
inline constexpr double plastic_loss_tangent = 3e-4;

// The material's complex relative permittivity at a radio frequency; a frequency outside
// radio_frequency_range() throws InvalidParameter naming `field`, the material and the range.
std::complex<double> radio_permittivity(Material material, double frequency_hz,
                                        std::string_view field = "frequency_hz");

struct WavelengthRangeNm {
  double min_nm;
  double max_nm;
};

// The materials with optical data: water (Segelstein 1981 table), glass (fused silica, Malitson
// 1965 Sellmeier fit, absorption neglected) and metal (aluminium, Rakic et al. 1998 Lorentz-Drude
// fit). The others have none.
std::span<const Material> optical_materials();
// Their names, "water, glass, metal", for messages.
std::string optical_material_names();
std::optional<WavelengthRangeNm> optical_wavelength_range(Material material,
                                                          const SegelsteinTable& table);
std::string_view optical_index_source(Material material);

// Malitson 1965 (JOSA 55, 1205) eq. for fused silica at 20 C: n^2 - 1 = sum_j B_j l^2 / (l^2 -
// C_j^2), l in um, valid 0.21-3.71 um.
double malitson_fused_silica_index(double wavelength_m);
// Rakic et al. 1998 (Appl. Opt. 37, 5271) Lorentz-Drude model of aluminium: eps = 1 - f0 wp^2 /
// (w (w + i G0)) + sum_j f_j wp^2 / (w_j^2 - w^2 - i w G_j), Table 1's parameters.
std::complex<double> rakic_aluminium_permittivity(double wavelength_m);

// The complex refractive index m = n + i k at a wavelength; a material without optical data or a
// wavelength outside its range throws InvalidParameter naming `field`.
std::complex<double> optical_refractive_index(Material material, double wavelength_m,
                                              const SegelsteinTable& table,
                                              std::string_view field = "wavelength_m");

// Amplitude reflection coefficients of a smooth half-space of relative permittivity eps, seen from
// vacuum at grazing angle psi (from the surface):
// TE (horizontal) = (sin psi - sqrt(eps - cos^2 psi)) / (sin psi + sqrt(eps - cos^2 psi)),
// TM (vertical) = (eps sin psi - sqrt(eps - cos^2 psi)) / (eps sin psi + sqrt(eps - cos^2 psi))
// (ITU-R P.2040-3's Fresnel coefficients with cos theta = sin psi; Born & Wolf, 7th ed.,
// sec. 1.5.2). Both tend to -1 at grazing incidence; at normal incidence TM = -TE, the
// ground-reflection sign convention (the TM field's reference direction turns with the ray).
struct FresnelCoefficients {
  std::complex<double> te;
  std::complex<double> tm;
};
FresnelCoefficients fresnel_reflection(std::complex<double> permittivity, double grazing_rad);

}  // namespace fogradar::propagation
