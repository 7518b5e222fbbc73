#include "fogradar/camera/params.hpp"

#include <algorithm>
#include <functional>
#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/propagation/water_film.hpp"

namespace fogradar::camera {

KeyTable<CameraParams> camera_keys() {
  KeyTable<CameraParams> keys("camera.");
  keys.choice("band", FOGRADAR_KEY_FIELD(band), band_names,
              "spectral weighting: CIE photopic V(λ) (one grey channel), sRGB primaries to grey, "
              "or one wavelength; the study's images are \"converted into gray scale\", and V(λ) "
              "is the luminance weighting of a grey image");
  // The Segelstein table and the Mie sums cover it; a camera sees 380-780 nm, silicon to ~1100 nm.
  // Keys a setting makes meaningless are refused there, not recorded and ignored.
  const auto monochromatic = [](const CameraParams& p) { return p.band == Band::monochromatic; };
  keys.number("wavelength_nm", FOGRADAR_KEY_FIELD(wavelength_nm), closed(300.0, 1100.0),
              "band = monochromatic only (default 550 nm: the visibility wavelength, paper sec. I)")
      .when(monochromatic,
            "with camera.band = \"monochromatic\" (the other bands weight "
            "their own wavelengths)");
  // 5 nm is the CIE table's own spacing; 160 nm leaves 3 nodes over 400-720 nm.
  keys.number("mie_step_nm", FOGRADAR_KEY_FIELD(mie_step_nm), closed(5.0, 160.0),
              "spacing of the Mie wavelengths over the band (docs/camera.md §2: 2.6e-3 error of t "
              "at 4 layers; Mie ≈ 4 ms per wavelength)")
      .when(std::not_fn(monochromatic),
            "with camera.band = \"photopic\" or \"rgb\" (one wavelength has no spacing)");
  keys.choice("transfer", FOGRADAR_KEY_FIELD(transfer), transfer_curve_names,
              "output encoding: IEC 61966-2-1 sRGB, the usual 8-bit encoding (assumption), or a "
              "power law");
  keys.number("gamma", FOGRADAR_KEY_FIELD(gamma), closed(1.0, 4.0),
              "transfer = gamma only (default 2.2)")
      .when([](const CameraParams& p) { return p.transfer == TransferCurve::gamma; },
            "with camera.transfer = \"gamma\" (sRGB has its own curve)");
  keys.integer("frames_per_step", FOGRADAR_KEY_FIELD(frames_per_step), 1, 100000,
               "the study records continuously; 10 × 19200 px fill the histograms");
  keys.number("contrast_threshold", FOGRADAR_KEY_FIELD(contrast_threshold), closed(1e-3, 0.5),
              "Weber contrast threshold of an edge and of the target: CIE 5 % (paper eq. 9)");
  keys.number(
      "window_water_film_m", FOGRADAR_KEY_FIELD(window_water_film_m), "0, or [1e-6, 0.01]",
      [](const CameraParams& p) {
        propagation::require_window_film("camera.window_water_film_m", p.window_water_film_m);
      },
      "flat water film on the lens window (the study's water-covered sensor): Fresnel and "
      "absorption, one way, against the dry window; droplets' scattering not modelled");
  keys.boolean("write_roi_images", FOGRADAR_KEY_FIELD(write_roi_images),
               "keep the first frame of each step as camera_roi_<step>.pgm (Fig. 8)");
  keys.choice("exposure.mode", FOGRADAR_KEY_FIELD(exposure.mode), exposure_mode_names,
              "fixed, or per step so that the noise-free ROI mean grey is auto_target_grey; the "
              "study's means rise with fog: no ROI auto-exposure");
  const auto automatic = [](const CameraParams& p) {
    return p.exposure.mode == ExposureMode::automatic;
  };
  // Above 1 every pixel of a white surface clips; 1e-4 is 0.03 grey levels of linear signal.
  keys.number("exposure.ambient_level", FOGRADAR_KEY_FIELD(exposure.ambient_level),
              closed(1e-4, 1.0),
              "linear signal (fraction of full scale) of a white surface in the hall's light; "
              "**calibrated** on the study's 0- and 2-layer means (docs/camera.md §6)")
      .when(std::not_fn(automatic),
            "with camera.exposure.mode = \"fixed\" (auto exposure scales the light away)");
  keys.number("exposure.auto_target_grey", FOGRADAR_KEY_FIELD(exposure.auto_target_grey),
              closed(1.0, 254.0), "auto mode only (default 46: the study's clear mean)")
      .when(automatic, "with camera.exposure.mode = \"auto\"");
  keys.boolean("noise.enabled", FOGRADAR_KEY_FIELD(noise.enabled), "shot and read noise");
  const auto noisy = [](const CameraParams& p) { return p.noise.enabled; };
  const std::string noisy_text = "with camera.noise.enabled = true";
  keys.number("noise.full_well_electrons", FOGRADAR_KEY_FIELD(noise.full_well_electrons),
              closed(100.0, 1e7),
              "electrons at full scale (shot noise √N_e); assumption, order of automotive CMOS "
              "pixels")
      .when(noisy, noisy_text);
  keys.number("noise.read_noise_electrons", FOGRADAR_KEY_FIELD(noise.read_noise_electrons),
              closed(0.0, 1000.0), "rms, Gaussian, per pixel and channel; assumption, same")
      .when(noisy, noisy_text);
  keys.integer("roi.width_px", FOGRADAR_KEY_FIELD(roi.width_px), 8, 4096,
               "assumption: the study gives no ROI size");
  keys.integer("roi.height_px", FOGRADAR_KEY_FIELD(roi.height_px), 8, 4096,
               "assumption: the study gives no ROI size");
  keys.integer("roi.cell_px", FOGRADAR_KEY_FIELD(roi.cell_px), 2, 2048,
               "square cells of one reflectance each: the scale of the scene's structure (edges)")
      .within([](const CameraParams& p) {
        const double half = static_cast<double>(std::min(p.roi.width_px, p.roi.height_px) / 2);
        return CrossBound{.range = closed(2.0, half),
                          .low_text = "2",
                          .high_text = message_number(half),
                          .integer = true,
                          .note = " (half of min(camera.roi.width_px, camera.roi.height_px))"};
      })
      .documented_as("integer [2, min(width_px, height_px)/2]");
  keys.number("roi.target_fraction", FOGRADAR_KEY_FIELD(roi.target_fraction), closed(0.05, 0.95),
              "the target (EVT) is the central rectangle of cells holding this fraction; ROI = "
              "\"area of the EVT\" with some background");
  // Reflectance factors of real surfaces under diffuse light: (0, 1.5] leaves room for retro-
  // reflective or glossy patches; ln-spread up to 3 (a factor 20 per sigma).
  keys.number("roi.target.median_reflectance", FOGRADAR_KEY_FIELD(roi.target.median_reflectance),
              closed(1e-4, 1.5),
              "reflectance factor L₀/L_a, lognormal over the cells; **calibrated** "
              "(docs/camera.md §6)");
  keys.number("roi.target.log_sigma", FOGRADAR_KEY_FIELD(roi.target.log_sigma), closed(0.0, 3.0),
              "standard deviation of ln ρ; assumption (EVT: dark body, lighter parts)");
  keys.number("roi.background.median_reflectance",
              FOGRADAR_KEY_FIELD(roi.background.median_reflectance), closed(1e-4, 1.5),
              "assumption (a light hall); Fig. 8 shows dark and bright background");
  keys.number("roi.background.log_sigma", FOGRADAR_KEY_FIELD(roi.background.log_sigma),
              closed(0.0, 3.0), "assumption");
  return keys;
}

void CameraParams::validate() const { camera_keys().check(*this); }

}  // namespace fogradar::camera
