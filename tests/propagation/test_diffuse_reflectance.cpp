// Diffuse reflectance of the room's materials. Reference: the USGS Spectral Library Version 7
// (Kokaly et al. 2017, U.S. Geological Survey Data Series 1035, doi:10.3133/ds1035), splib07a ASCII
// records, the values below copied from each record at the line of its wavelength file that reads
// 0.550, 0.905 and 1.550 um (ASD), or the nearest (Beckman: 0.5493, 0.9040, 1.5520 um); the library
// rounds nothing, fogradar keeps four figures, hence the 5e-5 tolerance.
#include <gtest/gtest.h>

#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/propagation/diffuse_reflectance.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::propagation {
namespace {

using fogradar::test_support::rejected_field;
using fogradar::testing::Tolerance;
using fogradar::testing::validate;

struct Published {
  Material material;
  const char* record;
  double at_550_nm;
  double at_905_nm;
  double at_1550_nm;
};
constexpr Published published[] = {
    {Material::concrete, "18568 Concrete GDS375 Lt Gry Road", 2.8622860e-01, 3.1044638e-01,
     3.3177111e-01},
    {Material::brick, "18359 Brick GDS353 Building MedRed", 9.8841533e-02, 2.3423219e-01,
     2.6551875e-01},
    {Material::wood, "20779 Wood_Beam GDS363 Nw Pine 2X4", 3.2852462e-01, 6.5911061e-01,
     4.5650360e-01},
    {Material::chipboard, "19527 Particle_Board GDS364 Fn Gr", 3.0561912e-01, 6.3033968e-01,
     4.9759397e-01},
    {Material::plywood, "19883 Plywood GDS365 Fresh Pine", 3.2176146e-01, 8.1369668e-01,
     5.6451923e-01},
    {Material::metal, "18773 GalvanizedSheetMetal GDS334", 8.8618770e-02, 5.8301263e-02,
     1.1431958e-01},
    {Material::water, "13635 Seawater_Open_Ocean SW2", 2.5950529e-02, 1.9850032e-02, 1.8712146e-02},
    {Material::plastic, "19604 Plastic_HDPE GDS384 Wht Opaq", 7.8300363e-01, 7.3082012e-01,
     5.5534816e-01},
};

TEST(DiffuseReflectance, FollowsTheUsgsRecords) {
  for (const Published& row : published) {
    const std::string name(to_string(row.material));
    SCOPED_TRACE(name);
    const double wavelengths_nm[] = {550.0, 905.0, 1550.0};
    const double values[] = {row.at_550_nm, row.at_905_nm, row.at_1550_nm};
    for (int i = 0; i < 3; ++i) {
      const std::string nm = std::to_string(static_cast<int>(wavelengths_nm[i]));
      validate({.id = "propagation.materials.diffuse." + name + "." + nm + "nm",
                .group = "physics: materials",
                .quantity = "diffuse reflectance",
                .unit = "1",
                .conditions = name + ", " + nm + " nm",
                .reference = values[i],
                .source = std::string("USGS splib07a record ") + row.record,
                .value = diffuse_reflectance(row.material, wavelengths_nm[i] * 1e-9),
                .tolerance = 5e-5,
                .kind = Tolerance::absolute});
    }
  }
  EXPECT_EQ(diffuse_materials().size(), std::size(published));
}

TEST(DiffuseReflectance, EveryValueIsAFraction) {
  for (const Material material : diffuse_materials()) {
    for (const double nm : diffuse_reflectance_wavelengths_nm()) {
      const double rho = diffuse_reflectance(material, nm * 1e-9);
      EXPECT_GT(rho, 0.0) << to_string(material) << " " << nm;
      EXPECT_LT(rho, 1.0) << to_string(material) << " " << nm;
    }
  }
}

TEST(DiffuseReflectance, NearATableWavelengthTakesItsValue) {
  EXPECT_EQ(diffuse_reflectance(Material::concrete, 895e-9), 0.3104);
  EXPECT_EQ(diffuse_reflectance(Material::concrete, 915e-9), 0.3104);
  EXPECT_EQ(diffuse_reflectance(Material::plastic, 1560e-9), 0.5553);
  EXPECT_EQ(rejected_field([] { diffuse_reflectance(Material::concrete, 894e-9); }),
            "wavelength_m");
  EXPECT_EQ(rejected_field([] { diffuse_reflectance(Material::concrete, 1064e-9, "m", "w"); }),
            "w");
  EXPECT_EQ(rejected_field([] { diffuse_reflectance(Material::brick, 700e-9); }), "wavelength_m");
  try {
    diffuse_reflectance(Material::wood, 1064e-9, "material", "lidar.wavelength_m");
    ADD_FAILURE() << "accepted";
  } catch (const InvalidParameter& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("lidar.wavelength_m = 1.064e-06"), std::string::npos) << message;
    EXPECT_NE(message.find("550, 905 or 1550 nm"), std::string::npos) << message;
    EXPECT_NE(message.find("'wood'"), std::string::npos) << message;
  }
}

TEST(DiffuseReflectance, AMaterialWithoutASampleIsRefusedWithTheList) {
  for (const Material material : {Material::glass, Material::plasterboard, Material::floorboard,
                                  Material::ceiling_board, Material::marble}) {
    EXPECT_FALSE(diffuse_reflectance_sample(material)) << to_string(material);
    try {
      diffuse_reflectance(material, 905e-9, "chamber.room.left_wall.material");
      ADD_FAILURE() << to_string(material) << " accepted";
    } catch (const InvalidParameter& error) {
      EXPECT_EQ(error.field(), "chamber.room.left_wall.material");
      const std::string message = error.what();
      EXPECT_NE(message.find(std::string(to_string(material))), std::string::npos) << message;
      EXPECT_NE(message.find("concrete, brick, wood, chipboard, plywood, metal, water, plastic"),
                std::string::npos)
          << message;
    }
  }
}

}  // namespace
}  // namespace fogradar::propagation
