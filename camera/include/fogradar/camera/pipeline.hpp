// Small pure functions of the camera model: Koschmieder's law, contrast, and the sensor pipeline's
// transfer curves, quantisation and grey conversion (docs/camera.md).
#pragma once

#include <cstdint>

#include "fogradar/camera/params.hpp"

namespace fogradar::camera {

// Paper eq. 8 (Koschmieder): L = L0 t + Ls (1 - t), per wavelength, linear radiance.
double koschmieder_radiance(double intrinsic_radiance, double path_radiance, double transmittance);

// Path radiance of a fog slab lit by a uniform diffuse field of radiance L_a, in units of L_a:
// Ls = omega (single-scattering albedo; docs/camera.md §3 derives it and its limits).
double path_radiance_factor(double single_scattering_albedo);

// Weber contrast (L - L_b) / L_b (CIE; Koschmieder's contrast against the background).
double weber_contrast(double radiance, double background_radiance);

// IEC 61966-2-1 sRGB: v <= 0.0031308 -> 12.92 v, else 1.055 v^(1/2.4) - 0.055 (v, e in [0, 1]).
double srgb_encode(double linear);
double srgb_decode(double encoded);
// Pure power law e = v^(1/gamma).
double gamma_encode(double linear, double gamma);
double gamma_decode(double encoded, double gamma);
// The chosen curve (gamma used only by TransferCurve::gamma); the input is clipped to [0, 1].
double encode(TransferCurve curve, double gamma, double linear);
double decode(TransferCurve curve, double gamma, double encoded);

// 8-bit quantisation: round(255 e), e clipped to [0, 1].
std::uint8_t quantise_8bit(double encoded);

// ITU-R BT.601 luma Y' = 0.299 R' + 0.587 G' + 0.114 B' on encoded values (what OpenCV's
// cvtColor(..., COLOR_RGB2GRAY) computes).
double luma_bt601(double red, double green, double blue);

}  // namespace fogradar::camera
