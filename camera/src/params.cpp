#include "fogradar/camera/params.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "fogradar/core/error.hpp"

namespace fogradar::camera {
namespace {

constexpr std::array<std::pair<Band, std::string_view>, 3> kBandNames{{
    {Band::photopic, "photopic"},
    {Band::rgb, "rgb"},
    {Band::monochromatic, "monochromatic"},
}};
constexpr std::array<std::pair<ExposureMode, std::string_view>, 2> kExposureNames{{
    {ExposureMode::fixed, "fixed"},
    {ExposureMode::automatic, "auto"},
}};
constexpr std::array<std::pair<TransferCurve, std::string_view>, 2> kTransferNames{{
    {TransferCurve::srgb, "srgb"},
    {TransferCurve::gamma, "gamma"},
}};

template <class Enum, std::size_t N>
std::string_view name_of(const std::array<std::pair<Enum, std::string_view>, N>& names,
                         Enum value) {
  for (const auto& [candidate, name] : names) {
    if (candidate == value) return name;
  }
  return "?";
}

template <class Enum, std::size_t N>
Enum parse_name(const std::array<std::pair<Enum, std::string_view>, N>& names,
                std::string_view text, std::string_view field, std::string_view allowed) {
  for (const auto& [value, name] : names) {
    if (name == text) return value;
  }
  throw_invalid(field, text, allowed);
}

void require_count(const char* field, std::size_t value, std::size_t low, std::size_t high) {
  require_in_range(field, static_cast<double>(value), static_cast<double>(low),
                   static_cast<double>(high));
}

void validate_region(const RegionParams& region, const char* median_field,
                     const char* sigma_field) {
  // Reflectance factors of real surfaces under diffuse light: (0, 1.5] leaves room for retro-
  // reflective or glossy patches; ln-spread up to 3 (a factor 20 per sigma).
  require_in_range(median_field, region.median_reflectance, 1e-4, 1.5);
  require_in_range(sigma_field, region.log_sigma, 0.0, 3.0);
}

}  // namespace

std::string_view to_string(Band band) noexcept { return name_of(kBandNames, band); }
std::string_view to_string(ExposureMode mode) noexcept { return name_of(kExposureNames, mode); }
std::string_view to_string(TransferCurve curve) noexcept { return name_of(kTransferNames, curve); }

Band parse_band(std::string_view text, std::string_view field) {
  return parse_name(kBandNames, text, field, "one of photopic, rgb, monochromatic");
}
ExposureMode parse_exposure_mode(std::string_view text, std::string_view field) {
  return parse_name(kExposureNames, text, field, "one of fixed, auto");
}
TransferCurve parse_transfer_curve(std::string_view text, std::string_view field) {
  return parse_name(kTransferNames, text, field, "one of srgb, gamma");
}

void CameraParams::validate() const {
  // The Segelstein table and the Mie sums cover it; a camera sees 380-780 nm, silicon to ~1100 nm.
  require_in_range("camera.wavelength_nm", wavelength_nm, 300.0, 1100.0);
  // 5 nm is the CIE table's own spacing; 160 nm leaves 3 nodes over 400-720 nm.
  require_in_range("camera.mie_step_nm", mie_step_nm, 5.0, 160.0);
  // Above 1 every pixel of a white surface clips; 1e-4 is 0.03 grey levels of linear signal.
  require_in_range("camera.exposure.ambient_level", exposure.ambient_level, 1e-4, 1.0);
  require_in_range("camera.exposure.auto_target_grey", exposure.auto_target_grey, 1.0, 254.0);
  require_in_range("camera.gamma", gamma, 1.0, 4.0);
  require_in_range("camera.noise.full_well_electrons", noise.full_well_electrons, 100.0, 1e7);
  require_in_range("camera.noise.read_noise_electrons", noise.read_noise_electrons, 0.0, 1000.0);
  require_count("camera.roi.width_px", roi.width_px, 8, 4096);
  require_count("camera.roi.height_px", roi.height_px, 8, 4096);
  if (!(roi.cell_px >= 2 && roi.cell_px <= roi.width_px / 2 && roi.cell_px <= roi.height_px / 2)) {
    throw_invalid("camera.roi.cell_px", static_cast<double>(roi.cell_px),
                  "in [2, " + std::to_string(std::min(roi.width_px, roi.height_px) / 2) +
                      "] (half of min(camera.roi.width_px, camera.roi.height_px))");
  }
  require_in_range("camera.roi.target_fraction", roi.target_fraction, 0.05, 0.95);
  validate_region(roi.target, "camera.roi.target.median_reflectance",
                  "camera.roi.target.log_sigma");
  validate_region(roi.background, "camera.roi.background.median_reflectance",
                  "camera.roi.background.log_sigma");
  require_count("camera.frames_per_step", frames_per_step, 1, 100000);
  require_in_range("camera.contrast_threshold", contrast_threshold, 1e-3, 0.5);
}

}  // namespace fogradar::camera
