// Closed-form physical-optics (PO) radar cross sections of the simple static objects of a room: a
// flat rectangular plate and a right circular cylinder, perfectly conducting, in the far field,
// monostatic. PO keeps the specular lobe and its sidelobes; edge diffraction, creeping waves and
// the cylinder's end caps are left out, so the values hold for sizes of many wavelengths (ka >> 1)
// and near the specular direction (Knott, Shaeffer & Tuley, Radar Cross Section, 2nd ed., 1993,
// ch. 5 and Table 5.1; Ross 1966, IEEE Trans. AP-14, 329).
#pragma once

namespace fogradar::radar {

// sin(x) / x, 1 at x = 0.
double sinc(double x);

// A flat plate width_m x height_m. The direction to the radar is given by its angle from the
// plate's normal (off_normal_rad, in [0, pi/2)) and the azimuth of that tilt measured from the
// width side (tilt_azimuth_rad): 0 tilts across the width, pi/2 across the height.
struct RectangularPlate {
  double width_m = 1.0;
  double height_m = 1.0;
  void validate() const;
};

// sigma = 4 pi A^2 / lambda^2 cos^2(theta) sinc^2(k w u) sinc^2(k h v), A = w h,
// u = sin(theta) cos(phi), v = sin(theta) sin(phi) (Knott Table 5.1; Ross 1966).
double plate_rcs_m2(const RectangularPlate& plate, double wavelength_m, double off_normal_rad,
                    double tilt_azimuth_rad);

// A right circular cylinder. off_broadside_rad is the angle between the direction to the radar
// and the cylinder's broadside plane (the tilt in the plane that holds the axis), in (-pi/2, pi/2).
struct Cylinder {
  double radius_m = 0.3;
  double length_m = 0.9;
  void validate() const;
};

// sigma = k a L^2 cos(theta) sinc^2(k L sin(theta)), k = 2 pi / lambda; broadside (theta = 0)
// 2 pi a L^2 / lambda (Knott Table 5.1; the PO integral over the lit half by stationary phase
// around the circumference).
double cylinder_rcs_m2(const Cylinder& cylinder, double wavelength_m, double off_broadside_rad);

}  // namespace fogradar::radar
