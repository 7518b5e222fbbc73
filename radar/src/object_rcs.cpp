#include "fogradar/radar/object_rcs.hpp"

#include <cmath>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::radar {

double sinc(double x) { return x == 0.0 ? 1.0 : std::sin(x) / x; }

void RectangularPlate::validate() const {
  require_positive("plate.width_m", width_m);
  require_finite("plate.width_m", width_m);
  require_positive("plate.height_m", height_m);
  require_finite("plate.height_m", height_m);
}

void Cylinder::validate() const {
  require_positive("cylinder.radius_m", radius_m);
  require_finite("cylinder.radius_m", radius_m);
  require_positive("cylinder.length_m", length_m);
  require_finite("cylinder.length_m", length_m);
}

double plate_rcs_m2(const RectangularPlate& plate, double wavelength_m, double off_normal_rad,
                    double tilt_azimuth_rad) {
  const double k = 2.0 * pi / wavelength_m;
  const double area_m2 = plate.width_m * plate.height_m;
  const double u = std::sin(off_normal_rad) * std::cos(tilt_azimuth_rad);
  const double v = std::sin(off_normal_rad) * std::sin(tilt_azimuth_rad);
  const double cos_theta = std::cos(off_normal_rad);
  const double pattern = sinc(k * plate.width_m * u) * sinc(k * plate.height_m * v);
  return 4.0 * pi * area_m2 * area_m2 / (wavelength_m * wavelength_m) * cos_theta * cos_theta *
         pattern * pattern;
}

double cylinder_rcs_m2(const Cylinder& cylinder, double wavelength_m, double off_broadside_rad) {
  const double k = 2.0 * pi / wavelength_m;
  const double pattern = sinc(k * cylinder.length_m * std::sin(off_broadside_rad));
  return k * cylinder.radius_m * cylinder.length_m * cylinder.length_m *
         std::cos(off_broadside_rad) * pattern * pattern;
}

}  // namespace fogradar::radar
