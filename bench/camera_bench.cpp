// The camera's part of the paper scenario: its cost, and the study's Fig. 7 means under both of the
// study's fog readings (docs/camera.md §6-§7). Run by hand (Release build), not a test:
//
//   camera_bench [--frames N] [--repeats R] [--sensitivity] [--out DIR]
//
// --out writes each reading's camera_histograms.svg/.csv and camera_summary.csv/.json into
// DIR/beta900/ and DIR/v574/ (the directories must exist).
//
// --sensitivity also recalibrates under other values of every key the two means do not pin down
// (one at a time) and prints the 4-layer prediction each gives.
//
// For each fog reading (beta = 900 /km at 550 nm; V = 5.74 m) it calibrates the two keys the 0- and
// 2-layer means pin down (calibrate_to_means), then runs the 5 steps with noise (seed 1) and prints
// the per-step table, the noise-free means and the 4-layer prediction. Timing: Camera construction
// (Mie over the band, once per fog) and the 5 steps x frames at one thread, median of R repeats,
// each repeat followed by the camera's floor (docs/performance.md): the standard normals the same
// frames need (pixels x channels, drawn as Camera::frame draws them, one ComplexNormalGenerator
// call per frame) and nothing else; the ratio is taken repeat by repeat.
#include <algorithm>
#include <chrono>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "fogradar/camera/calibration.hpp"
#include "fogradar/camera/camera.hpp"
#include "fogradar/camera/spectral.hpp"
#include "fogradar/core/complex_normal_generator.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/propagation/visibility.hpp"

namespace {

using namespace fogradar;
using Clock = std::chrono::steady_clock;

propagation::ChamberSpec paper_chamber(propagation::FogDensity density) {
  propagation::ChamberSpec chamber;
  for (auto& layer : chamber.layers) layer.fog.density = density;
  return chamber;
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The 4-layer noise-free mean after recalibrating on (46, 64) with one unpinned key changed.
void print_sensitivity(const camera::CameraParams& base, const propagation::ChamberSpec& chamber,
                       const propagation::SegelsteinTable& table) {
  struct Variant {
    std::string name;
    camera::CameraParams params;
  };
  std::vector<Variant> variants;
  const auto add = [&](const std::string& name, auto change) {
    camera::CameraParams p = base;
    change(p);
    variants.push_back({name, p});
  };
  add("defaults", [](camera::CameraParams&) {});
  for (double v : {0.05, 0.1, 0.5, 1.0}) {
    add("roi.background.median_reflectance = " + std::to_string(v),
        [v](camera::CameraParams& p) { p.roi.background.median_reflectance = v; });
  }
  for (double v : {0.0, 0.4, 1.2}) {
    add("roi.background.log_sigma = " + std::to_string(v),
        [v](camera::CameraParams& p) { p.roi.background.log_sigma = v; });
  }
  for (double v : {0.0, 0.3, 1.0, 1.5}) {
    add("roi.target.log_sigma = " + std::to_string(v),
        [v](camera::CameraParams& p) { p.roi.target.log_sigma = v; });
  }
  for (double v : {0.3, 0.9}) {
    add("roi.target_fraction = " + std::to_string(v),
        [v](camera::CameraParams& p) { p.roi.target_fraction = v; });
  }
  add("transfer = gamma 2.2",
      [](camera::CameraParams& p) { p.transfer = camera::TransferCurve::gamma; });
  add("band = rgb", [](camera::CameraParams& p) { p.band = camera::Band::rgb; });
  add("band = monochromatic 550 nm",
      [](camera::CameraParams& p) { p.band = camera::Band::monochromatic; });
  for (const Variant& variant : variants) {
    const camera::Camera camera(variant.params, chamber, table);
    try {
      const auto calibration = camera::calibrate_to_means(camera, 46.0, 2, 64.0);
      const camera::Camera calibrated = camera.with_scene(calibration.params);
      const auto optics = calibrated.step_optics(propagation::first_layers_active(4, 4));
      std::printf("  %-45s ambient_level %.4f target median %.4f -> 4 layers %.2f\n",
                  variant.name.c_str(), calibration.params.exposure.ambient_level,
                  calibration.params.roi.target.median_reflectance,
                  calibrated.expected_mean_grey(optics));
    } catch (const InvalidParameter& error) {
      std::printf("  %-45s no calibration: %s\n", variant.name.c_str(), error.what());
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t frames = camera::CameraParams{}.frames_per_step;
  int repeats = 5;
  bool sensitivity = false;
  std::string out_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--sensitivity") sensitivity = true;
    if (i + 1 >= argc) continue;
    if (flag == "--frames") frames = std::strtoul(argv[i + 1], nullptr, 10);
    if (flag == "--repeats") repeats = std::atoi(argv[i + 1]);
    if (flag == "--out") out_dir = argv[i + 1];
  }
  const propagation::SegelsteinTable table;

  struct Reading {
    const char* name;
    const char* folder;
    propagation::FogDensity density;
  };
  const std::vector<Reading> readings{
      {"beta = 900 /km at 550 nm", "beta900", propagation::OpticalExtinction{900.0}},
      {"V = 5.74 m (beta = 681.5 /km)", "v574", propagation::Visibility{5.74}},
  };
  for (const Reading& reading : readings) {
    const propagation::ChamberSpec chamber = paper_chamber(reading.density);
    camera::CameraParams params;
    params.frames_per_step = frames;

    std::vector<double> build_times;
    for (int r = 0; r < repeats; ++r) {
      const auto build_start = Clock::now();
      const camera::Camera timed(params, chamber, table);
      build_times.push_back(seconds_since(build_start));
    }
    const double build_s = median(build_times);
    const camera::Camera uncalibrated(params, chamber, table);

    const auto calibration_start = Clock::now();
    const camera::CalibrationResult calibration =
        camera::calibrate_to_means(uncalibrated, 46.0, 2, 64.0);
    const double calibration_s = seconds_since(calibration_start);
    const camera::Camera camera = uncalibrated.with_scene(calibration.params);

    std::printf("== %s\n", reading.name);
    std::printf(
        "calibrated: exposure.ambient_level = %.6g, roi.target.median_reflectance = %.6g "
        "(noise-free means %.3f, %.3f)\n",
        calibration.params.exposure.ambient_level, calibration.params.roi.target.median_reflectance,
        calibration.clear_mean_grey, calibration.fog_mean_grey);
    std::printf(
        "beta of one layer at the 550 nm band node (interpolated from the Mie wavelengths): %.1f "
        "/km\n",
        1e3 * camera.layer_extinction_per_m(0)[38]);
    std::printf("noise-free mean grey per active layers:");
    for (std::size_t n = 0; n <= camera.layer_count(); ++n) {
      const auto optics =
          camera.step_optics(propagation::first_layers_active(n, camera.layer_count()));
      std::printf("  %zu: %.2f (t = %.4f)", n, camera.expected_mean_grey(optics),
                  optics.transmittance[0]);
    }
    std::printf("\n");

    std::vector<double> run_s, floor_s, ratios;
    std::vector<camera::CameraStepResult> steps;
    const std::size_t normals = params.roi.width_px * params.roi.height_px * camera.channel_count();
    std::vector<std::complex<double>> noise((normals + 1) / 2);
    for (int r = 0; r < repeats; ++r) {
      steps.clear();
      const auto start = Clock::now();
      for (std::size_t n = 0; n <= camera.layer_count(); ++n) {
        steps.push_back(
            camera.measure_step(n, propagation::first_layers_active(n, camera.layer_count()), 1));
      }
      run_s.push_back(seconds_since(start));
      const auto floor_start = Clock::now();
      for (std::size_t f = 0; f < (camera.layer_count() + 1) * frames; ++f) {
        RandomStream stream(1, f);
        ComplexNormalGenerator generator(stream);
        std::fill(noise.begin(), noise.end(), std::complex<double>{});
        generator.add(noise, 2.0);
        if (noise[0].real() == 12345.0) std::printf(" ");  // keeps the draws
      }
      floor_s.push_back(seconds_since(floor_start));
      ratios.push_back(run_s.back() / floor_s.back());
    }
    // The whole camera part as `fogradar run` would do it (construction, 5 steps, summary), in CPU
    // time of this process: comparable with the radar run's user time on a loaded machine.
    std::vector<double> cpu_s;
    for (int r = 0; r < repeats; ++r) {
      const std::clock_t start = std::clock();
      const camera::Camera part(camera.params(), chamber, table);
      std::vector<camera::CameraStepResult> part_steps;
      for (std::size_t n = 0; n <= part.layer_count(); ++n) {
        part_steps.push_back(
            part.measure_step(n, propagation::first_layers_active(n, part.layer_count()), 1));
      }
      (void)camera::summarize(part.params(), part_steps);
      cpu_s.push_back(static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC);
    }
    const camera::CameraSummary summary = camera::summarize(camera.params(), steps);
    std::printf("%s", camera::summary_table(summary).c_str());
    std::printf("camera part (construction + %zu steps + summary), CPU time: median %.4f s\n",
                steps.size(), median(cpu_s));
    std::printf(
        "timing (1 thread): construction (Mie at %zu wavelengths, interpolated onto %zu band "
        "nodes) median %.4f s, calibration %.3f s, %zu steps x %zu frames of %zux%zu px: median "
        "%.4f s "
        "over %d repeats\n\n",
        camera::mie_wavelengths_m(params.band, params.wavelength_nm, params.mie_step_nm).size(),
        camera.band_wavelengths_m().size(), build_s, calibration_s, steps.size(), frames,
        params.roi.width_px, params.roi.height_px, median(run_s), repeats);
    std::printf(
        "floor (the same frames' %zu standard normals each): median %.4f s; the steps "
        "over the floor, repeat by repeat: median %.2f [%.2f, %.2f]\n\n",
        normals, median(floor_s), median(ratios), *std::min_element(ratios.begin(), ratios.end()),
        *std::max_element(ratios.begin(), ratios.end()));
    if (sensitivity) print_sensitivity(params, chamber, table);
    if (!out_dir.empty()) {
      const std::string folder = out_dir + "/" + reading.folder + "/";
      write_file(folder + "camera_histograms.svg", camera::histograms_svg(summary));
      write_file(folder + "camera_histograms.csv", camera::histograms_csv(summary));
      write_file(folder + "camera_summary.csv", camera::step_table(summary).csv());
      write_file(folder + "camera_summary.json", camera::summary_json(summary).dump(2) + "\n");
    }
  }
  return 0;
}
