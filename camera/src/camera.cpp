#include "fogradar/camera/camera.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <complex>
#include <numeric>

#include "fogradar/camera/pipeline.hpp"
#include "fogradar/camera/spectral.hpp"
#include "fogradar/core/complex_normal_generator.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/propagation/water_film.hpp"

namespace fogradar::camera {
namespace {

// Exposure search range of the automatic mode: linear signal of L_a from 1e-6 to 1e3 of full scale.
constexpr double auto_exposure_min = 1e-6;
constexpr double auto_exposure_max = 1e3;
constexpr int bisection_steps = 80;

// Weber contrast of the darker of two radiances against the brighter (CIE 5 % threshold applies):
// |L1 - L2| / max(L1, L2), symmetric and in [0, 1] (docs/camera.md §5).
double edge_contrast(double a, double b) {
  const double high = std::max(a, b);
  return high > 0.0 ? std::abs(a - b) / high : 0.0;
}

// Adjacent cell pairs (right and lower neighbours) of a cells_x-wide grid whose edge contrast is at
// least `threshold`.
std::size_t count_edges(const std::vector<double>& value, std::size_t cells_x, double threshold) {
  std::size_t edges = 0;
  for (std::size_t c = 0; c < value.size(); ++c) {
    if ((c + 1) % cells_x != 0 && edge_contrast(value[c], value[c + 1]) >= threshold) ++edges;
    if (c + cells_x < value.size() && edge_contrast(value[c], value[c + cells_x]) >= threshold)
      ++edges;
  }
  return edges;
}

// Grey level of a linear signal: g with thresholds[g - 1] <= linear < thresholds[g], walking from
// `start`.
inline std::size_t walk_level(const std::array<double, grey_levels - 1>& thresholds, double linear,
                              std::size_t start) {
  std::size_t g = start;
  while (g + 1 < grey_levels && linear >= thresholds[g]) ++g;
  while (g > 0 && linear < thresholds[g - 1]) --g;
  return g;
}

// Lognormal reflectance at probability q: median exp(sigma Phi^-1(q)).
double lognormal_quantile(const RegionParams& region, double q) {
  const boost::math::normal standard;
  return region.median_reflectance *
         std::exp(region.log_sigma * boost::math::quantile(standard, q));
}

// A stride coprime to n near n / golden ratio: index i -> (i stride) mod n scatters the quantiles
// over the cells without a random stream (the scene is the same in every frame and every run).
std::size_t scatter_stride(std::size_t n) {
  std::size_t stride =
      std::max<std::size_t>(1, static_cast<std::size_t>(0.6180339887 * static_cast<double>(n)));
  while (std::gcd(stride, n) != 1) ++stride;
  return stride;
}

}  // namespace

Camera::Camera(const CameraParams& params, const propagation::ChamberSpec& chamber,
               const propagation::SegelsteinTable& table)
    : params_(params) {
  params_.validate();
  chamber.validate();
  layer_count_ = chamber.layers.size();

  const BandQuadrature quadrature =
      band_quadrature(params_.band, params_.wavelength_nm, cie1931_table());
  wavelengths_m_ = quadrature.wavelength_m;
  weights_ = quadrature.weight;
  channel_count_ = weights_.size();
  // Optical wavelengths take the Segelstein table at its 25 C, as the fog's optics do.
  for (const double wavelength_m : wavelengths_m_) {
    window_transmittance_.push_back(propagation::window_film_transmittance(
        params_.window_water_film_m, table.refractive_index(wavelength_m), wavelength_m));
  }

  // Mie over the band once per distinct fog, never per step, frame or pixel.
  const std::vector<double> mie_wavelengths =
      mie_wavelengths_m(params_.band, params_.wavelength_nm, params_.mie_step_nm);
  std::vector<propagation::FogSpec> distinct;
  for (const propagation::FogLayerSpec& layer : chamber.layers) {
    layer_lengths_m_.push_back(layer.length_m);
    const auto found = std::find(distinct.begin(), distinct.end(), layer.fog);
    layer_fog_.push_back(static_cast<std::size_t>(found - distinct.begin()));
    if (found != distinct.end()) continue;
    distinct.push_back(layer.fog);
    const propagation::Fog fog(layer.fog, table);
    std::vector<double> extinction;
    std::vector<double> albedo;
    for (double wavelength : mie_wavelengths) {
      const propagation::FogOptics optics = fog.at_optical_wavelength(wavelength);
      extinction.push_back(optics.extinction_per_m);
      albedo.push_back(
          optics.extinction_per_m > 0.0 ? optics.scattering_per_m / optics.extinction_per_m : 1.0);
    }
    extinction_.push_back(interpolate_quadratic(mie_wavelengths, extinction, wavelengths_m_));
    albedo_.push_back(interpolate_quadratic(mie_wavelengths, albedo, wavelengths_m_));
  }

  build_scene();
}

void Camera::build_scene() {
  cells_.clear();
  // The pipeline's look-up tables: grey level g holds linear values in [thresholds_[g - 1],
  // thresholds_[g]) (round(255 encode(v)) = g), and decodes to grey_linear_[g].
  for (std::size_t g = 0; g < grey_levels; ++g) {
    grey_linear_[g] = decode(params_.transfer, params_.gamma, static_cast<double>(g) / 255.0);
    if (g + 1 < grey_levels) {
      thresholds_[g] =
          decode(params_.transfer, params_.gamma, (static_cast<double>(g) + 0.5) / 255.0);
    }
  }
  for (std::size_t b = 0; b < bucket_levels_.size(); ++b) {
    const double start = static_cast<double>(b) / static_cast<double>(bucket_levels_.size());
    bucket_levels_[b] = static_cast<std::uint8_t>(
        walk_level(thresholds_, start, b == 0 ? 0 : bucket_levels_[b - 1]));
  }
  // The ROI's cell grid; the target is the central rectangle holding target_fraction of the cells.
  const RoiParams& roi = params_.roi;
  cells_x_ = (roi.width_px + roi.cell_px - 1) / roi.cell_px;
  cells_y_ = (roi.height_px + roi.cell_px - 1) / roi.cell_px;
  const double side = std::sqrt(roi.target_fraction);
  const auto target_cells = [side](std::size_t n) {
    return std::clamp<std::size_t>(
        static_cast<std::size_t>(std::lround(side * static_cast<double>(n))), 1, n - 1);
  };
  const std::size_t tx = target_cells(cells_x_);
  const std::size_t ty = target_cells(cells_y_);
  const std::size_t x0 = (cells_x_ - tx) / 2;
  const std::size_t y0 = (cells_y_ - ty) / 2;
  std::vector<bool> is_target(cells_x_ * cells_y_);
  for (std::size_t cy = 0; cy < cells_y_; ++cy) {
    for (std::size_t cx = 0; cx < cells_x_; ++cx) {
      is_target[cy * cells_x_ + cx] = cx >= x0 && cx < x0 + tx && cy >= y0 && cy < y0 + ty;
    }
  }
  // Each region's cells take the quantiles (j + 1/2) / n of its lognormal, scattered by a stride.
  const std::size_t n_target = tx * ty;
  const std::size_t n_background = cells_x_ * cells_y_ - n_target;
  const std::size_t stride_target = scatter_stride(n_target);
  const std::size_t stride_background = scatter_stride(n_background);
  std::size_t i_target = 0;
  std::size_t i_background = 0;
  for (std::size_t c = 0; c < is_target.size(); ++c) {
    const bool target = is_target[c];
    const std::size_t n = target ? n_target : n_background;
    std::size_t& i = target ? i_target : i_background;
    const std::size_t j = (i++ * (target ? stride_target : stride_background)) % n;
    const double q = (static_cast<double>(j) + 0.5) / static_cast<double>(n);
    cells_.push_back({.x0 = (c % cells_x_) * roi.cell_px,
                      .y0 = (c / cells_x_) * roi.cell_px,
                      .reflectance = lognormal_quantile(target ? roi.target : roi.background, q),
                      .target = target});
  }
}

Camera Camera::with_scene(const CameraParams& params) const {
  params.validate();
  if (params.band != params_.band || params.wavelength_nm != params_.wavelength_nm ||
      params.mie_step_nm != params_.mie_step_nm ||
      params.window_water_film_m != params_.window_water_film_m) {
    throw InvalidParameter("camera.band",
                           "with_scene keeps the fog optics: camera.band, camera.wavelength_nm, "
                           "camera.mie_step_nm and camera.window_water_film_m must equal the built "
                           "camera's");
  }
  Camera copy = *this;
  copy.params_ = params;
  copy.build_scene();
  return copy;
}

const std::vector<double>& Camera::layer_extinction_per_m(std::size_t layer) const {
  return extinction_.at(layer_fog_.at(layer));
}

StepOptics Camera::step_optics(const propagation::ActiveLayers& active) const {
  if (active.size() != layer_count_) {
    throw_invalid("active_layers", static_cast<double>(active.size()),
                  "equal to the chamber's layer count");
  }
  StepOptics optics;
  optics.active_layer_count =
      static_cast<std::size_t>(std::count(active.begin(), active.end(), true));
  optics.transmittance.assign(channel_count_, 0.0);
  optics.airlight_factor.assign(channel_count_, 0.0);
  for (std::size_t k = 0; k < wavelengths_m_.size(); ++k) {
    // From the camera's window outwards: each active layer emits omega_i (1 - t_i) L_a (uniform
    // diffuse field, single scattering), attenuated by the layers in front of it; air gaps are
    // clear.
    double transmittance = window_transmittance_[k];
    double airlight = 0.0;
    for (std::size_t i = 0; i < layer_count_; ++i) {
      if (!active[i]) continue;
      const std::size_t fog = layer_fog_[i];
      const double layer_t = std::exp(-extinction_[fog][k] * layer_lengths_m_[i]);
      airlight += path_radiance_factor(albedo_[fog][k]) * (1.0 - layer_t) * transmittance;
      transmittance *= layer_t;
    }
    for (std::size_t c = 0; c < channel_count_; ++c) {
      optics.transmittance[c] += weights_[c][k] * transmittance;
      optics.airlight_factor[c] += weights_[c][k] * airlight;
    }
  }
  optics.clear_contrast = clear_contrast();
  optics.clear_edges = clear_edge_count();
  optics.exposure_level = params_.exposure.ambient_level;
  if (params_.exposure.mode == ExposureMode::automatic) {
    // The mean grey rises monotonically with the exposure: bisection in log exposure.
    double low = std::log(auto_exposure_min);
    double high = std::log(auto_exposure_max);
    for (int step = 0; step < bisection_steps; ++step) {
      const double mid = 0.5 * (low + high);
      optics.exposure_level = std::exp(mid);
      (expected_mean_grey(optics) < params_.exposure.auto_target_grey ? low : high) = mid;
    }
    optics.exposure_level = std::exp(0.5 * (low + high));
  }
  return optics;
}

double Camera::expected_mean_grey(const StepOptics& optics) const {
  const RoiParams& roi = params_.roi;
  double sum = 0.0;
  std::size_t pixels = 0;
  for (const Cell& cell : cells_) {
    const std::size_t w = std::min(roi.cell_px, roi.width_px - cell.x0);
    const std::size_t h = std::min(roi.cell_px, roi.height_px - cell.y0);
    std::array<double, 3> encoded{};
    for (std::size_t c = 0; c < channel_count_; ++c) {
      // Eq. 8 in units of L_a: rho t_c + a_c, times the exposure.
      const double radiance = optics.exposure_level * (cell.reflectance * optics.transmittance[c] +
                                                       optics.airlight_factor[c]);
      encoded[c] = encode(params_.transfer, params_.gamma, radiance);
    }
    const double grey =
        channel_count_ == 3 ? luma_bt601(encoded[0], encoded[1], encoded[2]) : encoded[0];
    sum += 255.0 * grey * static_cast<double>(w * h);
    pixels += w * h;
  }
  return sum / static_cast<double>(pixels);
}

double Camera::clear_contrast() const {
  double target = 0.0;
  double background = 0.0;
  std::size_t n_target = 0;
  for (const Cell& cell : cells_) {
    const std::size_t w = std::min(params_.roi.cell_px, params_.roi.width_px - cell.x0);
    const std::size_t h = std::min(params_.roi.cell_px, params_.roi.height_px - cell.y0);
    (cell.target ? target : background) += cell.reflectance * static_cast<double>(w * h);
    if (cell.target) n_target += w * h;
  }
  const std::size_t n_background = params_.roi.width_px * params_.roi.height_px - n_target;
  return weber_contrast(target / static_cast<double>(n_target),
                        background / static_cast<double>(n_background));
}

std::size_t Camera::clear_edge_count() const {
  std::vector<double> reflectance;
  for (const Cell& cell : cells_) reflectance.push_back(cell.reflectance);
  return count_edges(reflectance, cells_x_, params_.contrast_threshold);
}

std::uint8_t Camera::quantise(double linear) const {
  if (!(linear > 0.0)) return 0;
  if (linear >= 1.0) return grey_levels - 1;
  const auto bucket = static_cast<std::size_t>(linear * static_cast<double>(bucket_levels_.size()));
  const std::uint8_t low = bucket_levels_[bucket];
  // Most buckets lie inside one grey level; a bucket with a threshold in it takes one compare.
  if (low == grey_levels - 1 || linear < thresholds_[low]) return low;
  return static_cast<std::uint8_t>(walk_level(thresholds_, linear, low + 1u));
}

CameraFrame Camera::frame(const StepOptics& optics, RandomStream& stream, bool keep_pixels) const {
  FOGRADAR_CHECK(optics.transmittance.size() == channel_count_);
  const RoiParams& roi = params_.roi;
  const NoiseParams& noise = params_.noise;
  const std::size_t pixels = roi.width_px * roi.height_px;

  // Standard normals for every pixel and channel, two per complex sample of CN(0, 2).
  std::vector<std::complex<double>> normals;
  if (noise.enabled) {
    normals.assign((pixels * channel_count_ + 1) / 2, {0.0, 0.0});
    ComplexNormalGenerator generator(stream);
    generator.add(normals, 2.0);
  }
  // A complex<double> array is an array of its real and imaginary parts ([complex.numbers]).
  const double* normal = reinterpret_cast<const double*>(normals.data());

  CameraFrame result;
  if (keep_pixels) result.pixels.assign(pixels, 0);
  std::vector<double> cell_linear(cells_.size(), 0.0);
  double target_sum = 0.0;
  double background_sum = 0.0;
  std::size_t target_pixels = 0;
  std::size_t draw = 0;

  for (std::size_t ci = 0; ci < cells_.size(); ++ci) {
    const Cell& cell = cells_[ci];
    std::array<double, 3> signal{};
    std::array<double, 3> sigma{};
    for (std::size_t c = 0; c < channel_count_; ++c) {
      // Eq. 8 in units of L_a, rho t_c + a_c, times the exposure: the linear signal (full scale 1).
      signal[c] = optics.exposure_level *
                  (cell.reflectance * optics.transmittance[c] + optics.airlight_factor[c]);
      // Shot noise (Poisson in electrons, Gaussian approximation, variance N_e) and read noise.
      const double electrons = signal[c] * noise.full_well_electrons;
      sigma[c] = std::sqrt(electrons + noise.read_noise_electrons * noise.read_noise_electrons) /
                 noise.full_well_electrons;
    }
    const std::size_t x_end = std::min(cell.x0 + roi.cell_px, roi.width_px);
    const std::size_t y_end = std::min(cell.y0 + roi.cell_px, roi.height_px);
    double linear_sum = 0.0;
    for (std::size_t y = cell.y0; y < y_end; ++y) {
      for (std::size_t x = cell.x0; x < x_end; ++x) {
        std::array<std::uint8_t, 3> q{};
        for (std::size_t c = 0; c < channel_count_; ++c) {
          const double v = noise.enabled ? signal[c] + sigma[c] * normal[draw++] : signal[c];
          q[c] = quantise(v);
        }
        // Rgb: each channel quantised to 8 bits, then the luma rounded, as cvtColor on an 8-bit
        // image.
        const std::uint8_t grey =
            channel_count_ == 3 ? quantise_8bit(luma_bt601(q[0], q[1], q[2]) / 255.0) : q[0];
        ++result.histogram[grey];
        linear_sum += grey_linear_[grey];
        if (!result.pixels.empty()) result.pixels[y * roi.width_px + x] = grey;
      }
    }
    cell_linear[ci] = linear_sum;
    const std::size_t count = (x_end - cell.x0) * (y_end - cell.y0);
    (cell.target ? target_sum : background_sum) += cell_linear[ci];
    if (cell.target) target_pixels += count;
    cell_linear[ci] /= static_cast<double>(count);
  }

  double grey_sum = 0.0;
  for (std::size_t g = 0; g < grey_levels; ++g) {
    grey_sum += static_cast<double>(g) * static_cast<double>(result.histogram[g]);
  }
  result.mean_grey = grey_sum / static_cast<double>(pixels);
  const double target_mean = target_sum / static_cast<double>(target_pixels);
  const double background_mean = background_sum / static_cast<double>(pixels - target_pixels);
  result.target_contrast =
      background_mean > 0.0 ? weber_contrast(target_mean, background_mean) : 0.0;
  result.edges_above_threshold = count_edges(cell_linear, cells_x_, params_.contrast_threshold);
  return result;
}

CameraStepResult Camera::measure_step(std::size_t step, const propagation::ActiveLayers& active,
                                      std::uint64_t seed) const {
  CameraStepResult result;
  result.optics = step_optics(active);
  result.active_layers = result.optics.active_layer_count;
  result.frames.reserve(params_.frames_per_step);
  for (std::size_t index = 0; index < params_.frames_per_step; ++index) {
    RandomStream stream = sensor_stream(seed, stream_key, step, index);
    result.frames.push_back(frame(result.optics, stream));
  }
  return result;
}

}  // namespace fogradar::camera
