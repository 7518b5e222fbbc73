// The camera's sensor pipeline, metrics, determinism, result files and bad input. References:
// IEC 61966-2-1 sRGB values computed by hand from the standard's formula; ITU-R BT.601 weights;
// the pipeline's own public pure functions as the second method for the frame's look-up-table
// quantisation; the study's direction (Fig. 7: mean up, tonal range down with layers).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "fogradar/camera/calibration.hpp"
#include "fogradar/camera/camera.hpp"
#include "fogradar/camera/pipeline.hpp"
#include "fogradar/core/error.hpp"
#include "rejected_field.hpp"
#include "svg_check.hpp"
#include "validation.hpp"

namespace fogradar::camera {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

using test_support::rejected_field;

const propagation::SegelsteinTable& table() {
  static const propagation::SegelsteinTable instance;
  return instance;
}

propagation::ChamberSpec paper_chamber() {
  propagation::ChamberSpec spec;
  for (auto& layer : spec.layers) layer.fog.density = propagation::OpticalExtinction{900.0};
  return spec;
}

const Camera& default_camera() {
  static const Camera camera(CameraParams{}, paper_chamber(), table());
  return camera;
}

TEST(Pipeline, SrgbKnownValuesAndRoundTrip) {
  // IEC 61966-2-1: 1.055 v^(1/2.4) - 0.055; 0.5 -> 0.735356983, 0.18 -> 0.461356129 (evaluated by
  // hand to 9 digits), the linear segment 12.92 v below 0.0031308.
  const auto check = [](const std::string& id, const std::string& linear, double reference,
                        double value, double tolerance, const std::string& source) {
    validate({.id = "camera.srgb.encode." + id,
              .group = "camera",
              .quantity = "sRGB encoded value",
              .unit = "1",
              .conditions = "linear value " + linear,
              .reference = reference,
              .source = source,
              .value = value,
              .tolerance = tolerance,
              .kind = Tolerance::absolute});
  };
  const std::string iec = "IEC 61966-2-1: 1.055 v^(1/2.4) - 0.055, evaluated by hand to 9 digits";
  check("0.5", "0.5", 0.735356983, srgb_encode(0.5), 1e-9, iec);
  check("0.18", "0.18", 0.461356129, srgb_encode(0.18), 1e-9, iec);
  EXPECT_DOUBLE_EQ(srgb_encode(0.001), 0.01292);
  check("0", "0", 0.0, srgb_encode(0.0), 0.0, "IEC 61966-2-1: linear segment 12.92 v at v = 0");
  check("1", "1", 1.0, srgb_encode(1.0), 1e-15, "IEC 61966-2-1: 1.055 - 0.055 = 1 at v = 1");
  // The two segments meet (continuity at the break to 1e-4, the standard's rounded constants).
  check("break", "0.0031308 (1 + 1e-12)", 12.92 * 0.0031308, srgb_encode(0.0031308 * (1 + 1e-12)),
        1e-4, "IEC 61966-2-1: the linear segment 12.92 v at the break 0.0031308");
  for (double v = 0.0; v <= 1.0; v += 1.0 / 1024.0) {
    EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-12);
    EXPECT_NEAR(gamma_decode(gamma_encode(v, 2.2), 2.2), v, 1e-12);
  }
  EXPECT_DOUBLE_EQ(gamma_encode(0.25, 2.0), 0.5);
}

TEST(Pipeline, QuantisationAndLuma) {
  EXPECT_EQ(quantise_8bit(0.0), 0);
  EXPECT_EQ(quantise_8bit(0.5 / 255.0 - 1e-9), 0);
  EXPECT_EQ(quantise_8bit(0.5 / 255.0 + 1e-9), 1);
  EXPECT_EQ(quantise_8bit(46.0 / 255.0), 46);
  EXPECT_EQ(quantise_8bit(1.2), 255);  // clipped
  EXPECT_EQ(quantise_8bit(-0.3), 0);
  // BT.601 weights sum to 1: a grey pixel keeps its value.
  validate({.id = "camera.luma.bt601.grey0.4",
            .group = "camera",
            .quantity = "BT.601 luma",
            .unit = "1",
            .conditions = "R = G = B = 0.4",
            .reference = 0.4,
            .source = "ITU-R BT.601: weights 0.299, 0.587, 0.114 sum to 1",
            .value = luma_bt601(0.4, 0.4, 0.4),
            .tolerance = 1e-15,
            .kind = Tolerance::absolute});
  validate({.id = "camera.luma.bt601.red",
            .group = "camera",
            .quantity = "BT.601 luma",
            .unit = "1",
            .conditions = "R = 1, G = B = 0",
            .reference = 0.299,
            .source = "ITU-R BT.601: red weight 0.299",
            .value = luma_bt601(1.0, 0.0, 0.0),
            .tolerance = 1e-15,
            .kind = Tolerance::absolute});
}

TEST(Pipeline, FrameQuantisationEqualsThePureFunctions) {
  // Uniform target and background (log_sigma 0), no noise: every pixel of a region has the grey
  // round(255 srgb(k (rho t + a))) computed here from the step's optics with the public functions.
  CameraParams params;
  params.noise.enabled = false;
  params.roi.target.log_sigma = 0.0;
  params.roi.background.log_sigma = 0.0;
  const Camera camera = default_camera().with_scene(params);
  for (std::size_t n = 0; n <= 4; ++n) {
    const StepOptics optics = camera.step_optics(propagation::first_layers_active(n, 4));
    RandomStream stream(1);
    const CameraFrame frame = camera.frame(optics, stream);
    std::size_t expected_levels = 0;
    for (const double rho :
         {params.roi.target.median_reflectance, params.roi.background.median_reflectance}) {
      const double linear =
          optics.exposure_level * (rho * optics.transmittance[0] + optics.airlight_factor[0]);
      EXPECT_GT(frame.histogram[quantise_8bit(srgb_encode(linear))], 0u) << n;
      ++expected_levels;
    }
    std::size_t levels = 0;
    for (const auto count : frame.histogram) levels += count > 0 ? 1 : 0;
    EXPECT_LE(levels, expected_levels);
  }
}

TEST(Pipeline, AutoExposureHoldsItsTarget) {
  // Noise-free mean held to 1e-6 grey by the bisection; a noisy, quantised frame within 1 level.
  CameraParams params;
  params.exposure.mode = ExposureMode::automatic;
  params.exposure.auto_target_grey = 100.0;
  const Camera camera = default_camera().with_scene(params);
  for (std::size_t n = 0; n <= 4; ++n) {
    const StepOptics optics = camera.step_optics(propagation::first_layers_active(n, 4));
    EXPECT_NEAR(camera.expected_mean_grey(optics), 100.0, 1e-6) << n;
    RandomStream stream(sensor_stream(5, stream_key, n, 0));
    EXPECT_NEAR(camera.frame(optics, stream).mean_grey, 100.0, 1.0) << n;
  }
}

std::vector<CameraStepResult> run_steps(const Camera& camera, std::uint64_t seed) {
  std::vector<CameraStepResult> steps;
  for (std::size_t n = 0; n <= camera.layer_count(); ++n) {
    steps.push_back(
        camera.measure_step(n, propagation::first_layers_active(n, camera.layer_count()), seed));
  }
  return steps;
}

TEST(Sensor, DirectionOfTheStudysFigure7) {
  // Mean grey rises, std and the 5-95 % tonal range narrow, the target's contrast falls, strictly
  // with every active layer (the study: 46, 64, 68 and a narrowing histogram).
  const CameraSummary summary =
      summarize(default_camera().params(), run_steps(default_camera(), 1));
  ASSERT_EQ(summary.steps.size(), 5u);
  for (std::size_t i = 1; i < summary.steps.size(); ++i) {
    const CameraStepSummary& a = summary.steps[i - 1];
    const CameraStepSummary& b = summary.steps[i];
    EXPECT_GT(b.mean_grey, a.mean_grey) << i;
    EXPECT_LT(b.std_grey, a.std_grey) << i;
    EXPECT_LE(b.tonal_range, a.tonal_range) << i;
    EXPECT_LT(std::abs(b.target_contrast), std::abs(a.target_contrast)) << i;
    EXPECT_LE(b.edges_above_threshold, a.edges_above_threshold) << i;
  }
  EXPECT_LT(summary.steps.back().tonal_range, summary.steps.front().tonal_range);
  // clear weather, quantisation only
  validate({.id = "camera.sensor.relative_contrast.0layers",
            .group = "camera",
            .quantity = "target contrast relative to clear weather",
            .unit = "1",
            .conditions = "default camera, paper fog, 0 active layers",
            .reference = 1.0,
            .source = "limiting case: clear weather, contrast unchanged but for quantisation",
            .value = summary.steps[0].relative_contrast,
            .tolerance = 0.02,
            .kind = Tolerance::absolute});
}

TEST(Sensor, DefaultsReproduceTheCalibrationMeans) {
  // The defaults are the calibrated keys (docs/camera.md §6), rounded to 4 digits: noise-free means
  // 46 and 64 to 0.05 grey; calibrating again from them returns them to 0.1 %.
  const Camera& camera = default_camera();
  for (const auto& [layers, grey] : {std::pair<std::size_t, double>{0, 46.0}, {2, 64.0}}) {
    validate({.id = "camera.paper.mean_grey." + std::to_string(layers) + "layers",
              .group = "paper comparison",
              .quantity = "noise-free mean grey value",
              .unit = "grey level",
              .conditions = "default (calibrated) camera, paper fog, " + std::to_string(layers) +
                            " active layers",
              .reference = grey,
              .source = "the study's Fig. 7: mean grey values 46 (clear) and 64 (2 layers)",
              .value = camera.expected_mean_grey(
                  camera.step_optics(propagation::first_layers_active(layers, 4))),
              .tolerance = 0.05,
              .kind = Tolerance::absolute,
              .plot = "paper_comparison",
              .x = static_cast<double>(layers),
              .x_label = "active fog layers"});
  }
  const CalibrationResult calibration = calibrate_to_means(camera, 46.0, 2, 64.0);
  EXPECT_NEAR(calibration.params.exposure.ambient_level / camera.params().exposure.ambient_level,
              1.0, 1e-3);
  EXPECT_NEAR(calibration.params.roi.target.median_reflectance /
                  camera.params().roi.target.median_reflectance,
              1.0, 1e-3);
}

TEST(Sensor, DeterministicAndIndependentOfFrameOrder) {
  // Same seed: identical steps; a frame measured alone from its own stream equals the same frame
  // inside measure_step (what any thread count does); another seed differs.
  const Camera& camera = default_camera();
  const auto a = run_steps(camera, 42);
  const auto b = run_steps(camera, 42);
  const auto c = run_steps(camera, 43);
  for (std::size_t s = 0; s < a.size(); ++s) {
    for (std::size_t f = 0; f < a[s].frames.size(); ++f) {
      EXPECT_EQ(a[s].frames[f].histogram, b[s].frames[f].histogram);
    }
  }
  EXPECT_NE(a[2].frames[0].histogram, c[2].frames[0].histogram);
  RandomStream stream = sensor_stream(42, stream_key, 3, 7);
  const CameraFrame alone =
      camera.frame(camera.step_optics(propagation::first_layers_active(3, 4)), stream);
  EXPECT_EQ(alone.histogram, a[3].frames[7].histogram);
}

TEST(Summary, SensorLimitIsTheFirstStepBelowTheThreshold) {
  CameraParams params;
  std::vector<CameraStepResult> steps;
  for (const double contrast : {-0.6, -0.2, -0.06, -0.049, -0.01}) {
    CameraStepResult step;
    step.active_layers = steps.size();
    step.optics.clear_contrast = -0.6;
    CameraFrame frame;
    frame.histogram[40] = 10;
    frame.target_contrast = contrast;
    step.frames = {frame};
    steps.push_back(step);
  }
  const CameraSummary summary = summarize(params, steps);
  ASSERT_TRUE(summary.sensor_limit_layers.has_value());
  EXPECT_EQ(*summary.sensor_limit_layers, 3u);
  EXPECT_NEAR(summary.steps[1].relative_contrast, 1.0 / 3.0, 1e-15);
  steps.pop_back();
  steps.pop_back();
  EXPECT_FALSE(summarize(params, steps).sensor_limit_layers.has_value());
}

TEST(Summary, ResultFiles) {
  CameraParams params = default_camera().params();
  params.write_roi_images = true;
  params.frames_per_step = 2;
  const Camera camera = default_camera().with_scene(params);
  const auto steps = run_steps(camera, 9);
  const CameraSummary summary = summarize(params, steps);

  const std::string histograms = histograms_csv(summary);
  EXPECT_EQ(std::count(histograms.begin(), histograms.end(), '\n'), 1 + 5 * 256);
  EXPECT_TRUE(histograms.starts_with("active_layers,grey_level,count\n0,0,"));
  const std::string csv = step_table(summary).csv();
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 6);
  const nlohmann::json json = summary_json(summary);
  EXPECT_EQ(json["steps"].size(), 5u);
  EXPECT_TRUE(json.contains("sensor_limit_layers"));
  const std::string svg = histograms_svg(summary);
  EXPECT_EQ(test_support::xml_error(svg), "");
  EXPECT_NE(svg.find("mean 46."), std::string::npos);
  const std::string pgm = roi_pgm(params, steps[0].frames[0]);
  EXPECT_TRUE(pgm.starts_with("P5\n160 120\n255\n"));
  EXPECT_EQ(pgm.size(), std::string("P5\n160 120\n255\n").size() + 160 * 120);
  EXPECT_NE(summary_table(summary).find("camera limit"), std::string::npos);
  EXPECT_GT(memory_bytes(params, 5), 5u * 2u * 160u * 120u);
  EXPECT_EQ(rejected_field([&] { roi_pgm(default_camera().params(), CameraFrame{}); }),
            "camera.write_roi_images");
}

TEST(Params, EveryInvalidKeyIsRefusedByName) {
  const auto rejected = [](auto change) {
    CameraParams params;
    change(params);
    return rejected_field([&] { params.validate(); });
  };
  EXPECT_EQ(rejected([](CameraParams&) {}), "accepted");
  // A key is checked where it takes effect (a wavelength with the monochromatic band, ...).
  EXPECT_EQ(rejected([](CameraParams& p) {
              p.band = Band::monochromatic;
              p.wavelength_nm = 200.0;
            }),
            "camera.wavelength_nm");
  EXPECT_EQ(rejected([](CameraParams& p) { p.mie_step_nm = 2.0; }), "camera.mie_step_nm");
  EXPECT_EQ(rejected([](CameraParams& p) { p.exposure.ambient_level = 0.0; }),
            "camera.exposure.ambient_level");
  EXPECT_EQ(rejected([](CameraParams& p) { p.exposure.ambient_level = std::nan(""); }),
            "camera.exposure.ambient_level");
  EXPECT_EQ(rejected([](CameraParams& p) {
              p.exposure.mode = ExposureMode::automatic;
              p.exposure.auto_target_grey = 255.0;
            }),
            "camera.exposure.auto_target_grey");
  EXPECT_EQ(rejected([](CameraParams& p) {
              p.transfer = TransferCurve::gamma;
              p.gamma = 0.5;
            }),
            "camera.gamma");
  for (const double bad : {-1e-4, 0.5e-6, 0.011, std::nan("")}) {
    EXPECT_EQ(rejected([&](CameraParams& p) { p.window_water_film_m = bad; }),
              "camera.window_water_film_m")
        << bad;
  }
  EXPECT_EQ(rejected([](CameraParams& p) { p.noise.full_well_electrons = 10.0; }),
            "camera.noise.full_well_electrons");
  EXPECT_EQ(rejected([](CameraParams& p) { p.noise.read_noise_electrons = -1.0; }),
            "camera.noise.read_noise_electrons");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.width_px = 4; }), "camera.roi.width_px");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.height_px = 5000; }), "camera.roi.height_px");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.cell_px = 1; }), "camera.roi.cell_px");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.cell_px = 70; }), "camera.roi.cell_px");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.target_fraction = 1.0; }),
            "camera.roi.target_fraction");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.target.median_reflectance = 0.0; }),
            "camera.roi.target.median_reflectance");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.target.log_sigma = -0.1; }),
            "camera.roi.target.log_sigma");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.background.median_reflectance = 2.0; }),
            "camera.roi.background.median_reflectance");
  EXPECT_EQ(rejected([](CameraParams& p) { p.roi.background.log_sigma = 4.0; }),
            "camera.roi.background.log_sigma");
  EXPECT_EQ(rejected([](CameraParams& p) { p.frames_per_step = 0; }), "camera.frames_per_step");
  EXPECT_EQ(rejected([](CameraParams& p) { p.contrast_threshold = 0.0; }),
            "camera.contrast_threshold");
  EXPECT_EQ(rejected_field([] { band_names.parse("infrared", "camera.band"); }), "camera.band");
  EXPECT_EQ(rejected_field([] { exposure_mode_names.parse("manual", "camera.exposure.mode"); }),
            "camera.exposure.mode");
  EXPECT_EQ(rejected_field([] { transfer_curve_names.parse("log", "camera.transfer"); }),
            "camera.transfer");
  EXPECT_EQ(exposure_mode_names.parse("auto", "camera.exposure.mode"), ExposureMode::automatic);
  EXPECT_EQ(to_string(Band::rgb), "rgb");
  // The sensor refuses bad params and a wrong active-layer list at construction / per step.
  CameraParams bad;
  bad.transfer = TransferCurve::gamma;
  bad.gamma = 9.0;
  EXPECT_EQ(rejected_field([&] { Camera(bad, paper_chamber(), table()); }), "camera.gamma");
  EXPECT_EQ(rejected_field([] { default_camera().step_optics({true}); }), "active_layers");
}

TEST(Sensor, RgbBandRunsAndAgreesWithPhotopicForAGreyScene) {
  // A spectrally flat scene: the rgb channels' transmittances differ by the fog's weak wavelength
  // dependence only, so the luma mean stays within 1 grey level of the photopic mean.
  CameraParams params;
  params.band = Band::rgb;
  params.frames_per_step = 2;
  const Camera rgb(params, paper_chamber(), table());
  ASSERT_EQ(rgb.channel_count(), 3u);
  const auto active = propagation::first_layers_active(2, 4);
  EXPECT_NEAR(rgb.expected_mean_grey(rgb.step_optics(active)),
              default_camera().expected_mean_grey(default_camera().step_optics(active)), 1.0);
  const CameraStepResult step = rgb.measure_step(2, active, 1);
  validate({.id = "camera.paper.mean_grey.rgb.2layers",
            .group = "paper comparison",
            .quantity = "mean grey value, rgb band (luma)",
            .unit = "grey level",
            .conditions = "rgb band, paper fog, 2 active layers, 2 frames",
            .reference = 64.0,
            .source = "the study's Fig. 7: mean grey value 64 at 2 layers",
            .value = summarize(params, {step}).steps[0].mean_grey,
            .tolerance = 1.5,
            .kind = Tolerance::absolute,
            .plot = "paper_comparison",
            .x = 2.0,
            .x_label = "active fog layers"});
}

}  // namespace
}  // namespace fogradar::camera
