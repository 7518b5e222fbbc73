// The diffuse (Lambertian) reflectance of a room's materials at optical wavelengths, for the
// lidar's walls and objects and the camera's background: published laboratory spectra of one sample
// per material (USGS Spectral Library Version 7, Kokaly et al. 2017, U.S. Geological Survey Data
// Series 1035, doi:10.3133/ds1035; its splib07a records, absolute reflectance), read at the
// spectrum's channel at 550, 905 and 1550 nm. A sample is one specimen of its material: real walls
// of the same name differ (the library's seven bricks span 0.08-0.23 at 905 nm), so a value is a
// representative one, not a property of every surface of that name. Materials the library has no
// sample of are refused by name.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "fogradar/propagation/materials.hpp"

namespace fogradar::propagation {

// One material's published sample: its reflectance at the table's wavelengths
// (diffuse_reflectance_wavelengths_nm(), in that order) and where it comes from.
struct DiffuseReflectanceSample {
  double at_550_nm;
  double at_905_nm;
  double at_1550_nm;
  // "USGS splib07a record 18568: Concrete GDS375 Lt Gry Road (ASD, absolute reflectance)"
  std::string_view source;
};

// The wavelengths with a value: 550 nm (the camera's default and the middle of the visible band),
// 905 and 1550 nm (the automotive lidar bands).
std::span<const double> diffuse_reflectance_wavelengths_nm();
// A wavelength within this distance of a table wavelength takes its value: over +-10 nm the
// samples' spectra depart from it by at most 2.2 % at 905 nm and 3.9 % at 1550 nm (the white
// HDPE), but by up to 15 % at 550 nm (the red brick's steep visible edge).
inline constexpr double diffuse_reflectance_tolerance_nm = 10.0;

// The materials with a published sample, in Material's order, and their names ("concrete, brick,
// ...") for messages.
std::span<const Material> diffuse_materials();
std::string diffuse_material_names();
// The material's sample; none for a material without one.
std::optional<DiffuseReflectanceSample> diffuse_reflectance_sample(Material material);

// The material's diffuse reflectance (0-1, the fraction of the incident power a Lambertian surface
// sends back into the hemisphere) at `wavelength_m`. A material without a sample throws
// InvalidParameter naming `material_field` and the materials with one; a wavelength farther than
// diffuse_reflectance_tolerance_nm from every table wavelength throws naming `wavelength_field`
// and the table's wavelengths.
double diffuse_reflectance(Material material, double wavelength_m,
                           std::string_view material_field = "material",
                           std::string_view wavelength_field = "wavelength_m");

}  // namespace fogradar::propagation
