#include "fogradar/propagation/diffuse_reflectance.hpp"

#include <array>
#include <cmath>
#include <string>

#include "fogradar/core/error.hpp"

namespace fogradar::propagation {

namespace {

constexpr std::array<double, 3> table_wavelengths_nm = {550.0, 905.0, 1550.0};

struct Row {
  Material material;
  DiffuseReflectanceSample sample;
};

// USGS splib07a (Kokaly et al. 2017), each record's value at its spectrometer's channel of 0.550,
// 0.905 and 1.550 um (ASD full range, 1 nm channels; the seawater's Beckman channels nearest them:
// 0.5493, 0.9040 and 1.5520 um), rounded to four figures.
constexpr std::array<Row, 8> rows = {{
    {Material::concrete,
     {0.2862, 0.3104, 0.3318,
      "USGS splib07a record 18568: Concrete GDS375 Lt Gry Road, road concrete (ASD, absolute "
      "reflectance)"}},
    {Material::brick,
     {0.0988, 0.2342, 0.2655,
      "USGS splib07a record 18359: Brick GDS353 Building MedRed, a wall brick (ASD, absolute "
      "reflectance)"}},
    {Material::wood,
     {0.3285, 0.6591, 0.4565,
      "USGS splib07a record 20779: Wood_Beam GDS363 Nw Pine 2X4, new pine (ASD, absolute "
      "reflectance)"}},
    {Material::chipboard,
     {0.3056, 0.6303, 0.4976,
      "USGS splib07a record 19527: Particle_Board GDS364 Fn Gr, particle board (ASD, absolute "
      "reflectance)"}},
    {Material::plywood,
     {0.3218, 0.8137, 0.5645,
      "USGS splib07a record 19883: Plywood GDS365 Fresh Pine (ASD, absolute reflectance)"}},
    // Measured off the glint: the diffuse part only; a metal's mirror reflection is not in it.
    {Material::metal,
     {0.0886, 0.0583, 0.1143,
      "USGS splib07a record 18773: GalvanizedSheetMetal GDS334, measured off its glint (ASD, "
      "absolute reflectance)"}},
    {Material::water,
     {0.0260, 0.0199, 0.0187,
      "USGS splib07a record 13635: Seawater_Open_Ocean SW2 (Beckman, absolute reflectance)"}},
    // The study does not say the barrels' colour: white opaque HDPE is an assumption (the
    // library's HDPE samples span 0.11, a black sheet, to 0.73, this one, at 905 nm).
    {Material::plastic,
     {0.7830, 0.7308, 0.5553,
      "USGS splib07a record 19604: Plastic_HDPE GDS384 Wht Opaq, white opaque HDPE (ASD, absolute "
      "reflectance); the colour an assumption"}},
}};

constexpr std::array<Material, rows.size()> materials_with_sample = [] {
  std::array<Material, rows.size()> out{};
  for (std::size_t i = 0; i < rows.size(); ++i) out[i] = rows[i].material;
  return out;
}();

}  // namespace

std::span<const double> diffuse_reflectance_wavelengths_nm() { return table_wavelengths_nm; }

std::span<const Material> diffuse_materials() { return materials_with_sample; }

std::string diffuse_material_names() {
  std::string text;
  for (const Row& row : rows) {
    text += text.empty() ? "" : ", ";
    text += to_string(row.material);
  }
  return text;
}

std::optional<DiffuseReflectanceSample> diffuse_reflectance_sample(Material material) {
  for (const Row& row : rows) {
    if (row.material == material) return row.sample;
  }
  return std::nullopt;
}

double diffuse_reflectance(Material material, double wavelength_m, std::string_view material_field,
                           std::string_view wavelength_field) {
  const std::optional<DiffuseReflectanceSample> sample = diffuse_reflectance_sample(material);
  if (!sample) {
    throw_invalid(material_field, to_string(material),
                  "a material with a published diffuse reflectance: " + diffuse_material_names());
  }
  const double wavelength_nm = wavelength_m * 1e9;
  const std::array<double, 3> values = {sample->at_550_nm, sample->at_905_nm, sample->at_1550_nm};
  for (std::size_t i = 0; i < table_wavelengths_nm.size(); ++i) {
    if (std::abs(wavelength_nm - table_wavelengths_nm[i]) <= diffuse_reflectance_tolerance_nm) {
      return values[i];
    }
  }
  throw_invalid(wavelength_field, wavelength_m,
                "within 10 nm of 550, 905 or 1550 nm (5.5e-07, 9.05e-07 or 1.55e-06 m), the "
                "wavelengths with a published diffuse reflectance of '" +
                    std::string(to_string(material)) + "'");
}

}  // namespace fogradar::propagation
