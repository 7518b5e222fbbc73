#include "fogradar/camera/pipeline.hpp"

#include <algorithm>
#include <cmath>

namespace fogradar::camera {
namespace {

double clip_unit(double v) { return std::clamp(v, 0.0, 1.0); }

}  // namespace

// Paper eq. 8.
double koschmieder_radiance(double intrinsic_radiance, double path_radiance, double transmittance) {
  return intrinsic_radiance * transmittance + path_radiance * (1.0 - transmittance);
}

// Single scattering of a uniform diffuse field: the source function is omega L_a (docs/camera.md
// §3).
double path_radiance_factor(double single_scattering_albedo) { return single_scattering_albedo; }

double weber_contrast(double radiance, double background_radiance) {
  return (radiance - background_radiance) / background_radiance;
}

// IEC 61966-2-1:1999, eq. for the sRGB transfer function.
double srgb_encode(double linear) {
  const double v = clip_unit(linear);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  const double e = clip_unit(encoded);
  return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

double gamma_encode(double linear, double gamma) {
  return std::pow(clip_unit(linear), 1.0 / gamma);
}
double gamma_decode(double encoded, double gamma) { return std::pow(clip_unit(encoded), gamma); }

double encode(TransferCurve curve, double gamma, double linear) {
  return curve == TransferCurve::srgb ? srgb_encode(linear) : gamma_encode(linear, gamma);
}
double decode(TransferCurve curve, double gamma, double encoded) {
  return curve == TransferCurve::srgb ? srgb_decode(encoded) : gamma_decode(encoded, gamma);
}

std::uint8_t quantise_8bit(double encoded) {
  return static_cast<std::uint8_t>(std::lround(255.0 * clip_unit(encoded)));
}

// ITU-R BT.601-7, luma coefficients of E'_Y.
double luma_bt601(double red, double green, double blue) {
  return 0.299 * red + 0.587 * green + 0.114 * blue;
}

}  // namespace fogradar::camera
