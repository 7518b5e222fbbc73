// Parameters of the camera (scenario section [camera]): band, exposure, sensor pipeline, region of
// interest and metrics. Defaults are the paper scenario's; every key, its unit, range and source is
// listed in docs/camera.md ("Scenario keys").
#pragma once

#include <cstddef>
#include <string_view>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/keys.hpp"

namespace fogradar::camera {

// Spectral weighting of the pixels (docs/camera.md §2): the CIE photopic luminous efficiency
// V(lambda) (one grey channel), three colour channels R, G, B (the sRGB primaries' colour matching
// functions, negative lobes clipped) converted to grey with the luma weights, or one wavelength.
enum class Band { photopic, rgb, monochromatic };
// How the exposure is set: fixed (exposure.ambient_level), or per step so that the noise-free ROI
// mean grey equals exposure.auto_target_grey.
enum class ExposureMode { fixed, automatic };
// The sensor's transfer (encoding) curve: IEC 61966-2-1 sRGB, or a pure power law v^(1/gamma).
enum class TransferCurve { srgb, gamma };

inline constexpr auto band_names = enum_names<Band>(
    {{Band::photopic, "photopic"}, {Band::rgb, "rgb"}, {Band::monochromatic, "monochromatic"}});
inline constexpr auto exposure_mode_names =
    enum_names<ExposureMode>({{ExposureMode::fixed, "fixed"}, {ExposureMode::automatic, "auto"}});
inline constexpr auto transfer_curve_names =
    enum_names<TransferCurve>({{TransferCurve::srgb, "srgb"}, {TransferCurve::gamma, "gamma"}});
constexpr std::string_view to_string(Band band) noexcept { return band_names.name(band); }
constexpr std::string_view to_string(ExposureMode mode) noexcept {
  return exposure_mode_names.name(mode);
}
constexpr std::string_view to_string(TransferCurve curve) noexcept {
  return transfer_curve_names.name(curve);
}

struct ExposureParams {
  ExposureMode mode = ExposureMode::fixed;  // TOML "fixed" | "auto"
  // Linear sensor signal (fraction of full scale, before clipping) of a surface whose radiance is
  // the hall's ambient radiance L_a (a white Lambertian surface in the uniform diffuse hall light):
  // the product of ambient radiance and exposure gain, the only combination grey values depend on.
  // Calibrated on the study's 0- and 2-layer means (docs/camera.md §6).
  double ambient_level = 0.05508;
  double auto_target_grey = 46.0;  // automatic mode: ROI mean grey held at every step
};

struct NoiseParams {
  bool enabled = true;
  double full_well_electrons = 10000.0;  // electrons at full scale: shot noise sqrt(N_e)
  double read_noise_electrons = 5.0;     // rms, Gaussian, per pixel and channel
};

// The clear-weather appearance of one region (target or background): reflectance factors
// rho = L0 / L_a, lognormal over the ROI's cells.
struct RegionParams {
  double median_reflectance = 0.1;
  double log_sigma = 0.5;  // standard deviation of ln rho
};

// The region of interest: width x height pixels in square cells of cell_px pixels, each cell one
// reflectance (the cell grid carries the edges). The target (EVT) is the central rectangle of
// cells holding target_fraction of the cells; the background surrounds it.
struct RoiParams {
  std::size_t width_px = 160;
  std::size_t height_px = 120;
  std::size_t cell_px = 8;
  double target_fraction = 0.6;
  RegionParams target{.median_reflectance = 0.2923, .log_sigma = 0.6};
  RegionParams background{.median_reflectance = 0.8, .log_sigma = 0.6};
};

struct CameraParams {
  Band band = Band::photopic;
  double wavelength_nm = 550.0;  // band = monochromatic only
  // Spacing of the wavelengths at which Mie gives beta(lambda) and omega(lambda) (from 400 to 720
  // nm, where V(lambda) holds 99.99 % of its integral), interpolated piecewise quadratically onto
  // the CIE table's 5 nm nodes (held constant outside): beta(lambda) of fog is smooth;
  // docs/camera.md §2 gives the error and when to refine (monodisperse fogs ripple).
  double mie_step_nm = 160.0;
  ExposureParams exposure;
  TransferCurve transfer = TransferCurve::srgb;
  double gamma = 2.2;  // transfer = gamma only
  NoiseParams noise;
  RoiParams roi;
  std::size_t frames_per_step = 10;
  // Weber contrast threshold of an edge and of the target (CIE 5 %, paper eq. 9).
  double contrast_threshold = 0.05;
  bool write_roi_images = false;  // keep the first frame of each step (camera_roi_<step>.pgm)
  // Water film on the lens window (the study's water-covered sensor): the scene's radiance, target
  // and airlight alike, crosses it once (propagation::window_film_transmittance per wavelength).
  double window_water_film_m = 0.0;

  // Throws InvalidParameter naming "camera.<key>" (nested keys dotted, e.g.
  // "camera.roi.target.log_sigma") with the value and the allowed range (camera_keys).
  void validate() const;
};

// The keys of [camera] and its sub-tables, each with its unit, range and source.
KeyTable<CameraParams> camera_keys();

}  // namespace fogradar::camera
