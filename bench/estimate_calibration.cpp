// The per-unit constants of the run-time estimate's cost models (docs/scenario.md, "Time limit"),
// measured on this machine: each is the least-squares fit of measured CPU seconds against the
// model's count of that unit over a few workloads that vary it, and the program prints the fit, the
// constant the code holds and each workload's measured / modelled ratio with the code's constants.
// Run by hand on an idle machine, Release build:
//   nice build/release/bench/estimate_calibration [build/release/cli/fogradar]
// The last part runs the executable on a one-item scenario and a one-point sweep to measure what a
// process costs beyond the modelled work (its start, the scenario's reading, writing its files).
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fogradar/camera/sensor.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/run_time.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/lidar/sensor.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/radar/cfar_design.hpp"
#include "fogradar/radar/costs.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/noise_correlation.hpp"
#include "fogradar/radar/sensor.hpp"
#include "fogradar/radar/window.hpp"

namespace {

using namespace fogradar;

// CPU seconds of this process (every thread): the models estimate CPU time, which a machine shared
// with other work stretches into longer wall times but does not change.
double seconds_now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The median of `repeats` values of f.
double median_of(const std::function<double()>& f, int repeats = 7) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) t.push_back(f());
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// CPU seconds of the finished child processes, user and system.
double children_seconds() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// The median of `repeats` timings of f.
double median_seconds(const std::function<void()>& f, int repeats = 7) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const double start = seconds_now();
    f();
    t.push_back(seconds_now() - start);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// Least squares of the relative error of y = a x1 + b x2 (b = 0 when every x2 is 0): the estimate
// is judged by its ratio to the measurement, over workloads that differ by decades.
std::pair<double, double> fit(const std::vector<double>& x1, const std::vector<double>& x2,
                              const std::vector<double>& y) {
  double s11 = 0, s12 = 0, s22 = 0, s1y = 0, s2y = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double w = 1.0 / (y[i] * y[i]);
    s11 += w * x1[i] * x1[i];
    s12 += w * x1[i] * x2[i];
    s22 += w * x2[i] * x2[i];
    s1y += w * x1[i] * y[i];
    s2y += w * x2[i] * y[i];
  }
  if (s22 == 0.0) return {s1y / s11, 0.0};
  const double det = s11 * s22 - s12 * s12;
  return {(s1y * s22 - s2y * s12) / det, (s2y * s11 - s1y * s12) / det};
}

struct Case {
  std::string name;
  double x1 = 0.0, x2 = 0.0;  // the model's counts
  double measured = 0.0;      // seconds
  double modelled = 0.0;      // with the code's constants
};

void report(const char* what, const char* unit1, const char* unit2,
            const std::vector<Case>& cases) {
  std::vector<double> x1, x2, y;
  for (const Case& c : cases) {
    x1.push_back(c.x1);
    x2.push_back(c.x2);
    y.push_back(c.measured);
  }
  const auto [a, b] = fit(x1, x2, y);
  std::printf("%s: fit %.3g s per %s", what, a, unit1);
  if (unit2 != nullptr) std::printf(", %.3g s per %s", b, unit2);
  std::printf("\n");
  for (const Case& c : cases) {
    std::printf("  %-44s measured %9.3g s  modelled %9.3g s  ratio %.2f\n", c.name.c_str(),
                c.measured, c.modelled, c.measured / c.modelled);
  }
}

radar::SensorParams& radar_of(experiment::Scenario& s) {
  return s.params<radar::SensorParams>("radar");
}
lidar::LidarParams& lidar_of(experiment::Scenario& s) {
  return s.params<lidar::LidarParams>("lidar");
}
camera::CameraParams& camera_of(experiment::Scenario& s) {
  return s.params<camera::CameraParams>("camera");
}

experiment::Scenario only(const std::string& sensor) {
  experiment::Scenario s = experiment::paper_scenario();
  s.experiment.sensors = {sensor};
  return s;
}

void mie(const propagation::SegelsteinTable& water) {
  std::vector<Case> cases;
  const auto add = [&](const std::string& name, propagation::DropSizeDistribution droplets,
                       double wavelength_m, bool radio) {
    propagation::FogSpec spec;
    spec.density = propagation::LiquidWaterContent{0.1};
    spec.droplets = droplets;
    const propagation::Fog fog(spec, water);
    Case c{.name = name};
    c.measured = median_seconds([&] {
      if (radio) {
        (void)fog.at_frequency(299792458.0 / wavelength_m);
      } else {
        (void)fog.at_optical_wavelength(wavelength_m);
      }
    });
    const propagation::MieCost node{.seconds_per_node = 1.0, .seconds_per_step = 0.0};
    const propagation::MieCost step{.seconds_per_node = 0.0, .seconds_per_step = 1.0};
    c.x1 = propagation::bulk_optics_seconds(droplets, wavelength_m, node);
    c.x2 = propagation::bulk_optics_seconds(droplets, wavelength_m, step);
    c.modelled = propagation::bulk_optics_seconds(droplets, wavelength_m);
    cases.push_back(c);
  };
  const propagation::DropSizeDistribution paper = propagation::default_fog_droplets();
  propagation::Lognormal large{.median_diameter_m = 4e-6, .geometric_std = 1.5};
  propagation::Lognormal wide{.median_diameter_m = 1e-6, .geometric_std = 2.0};
  add("lognormal 1 um, 77 GHz", paper, 299792458.0 / 77e9, true);
  add("lognormal 1 um, 550 nm", paper, 550e-9, false);
  add("lognormal 1 um, 905 nm", paper, 905e-9, false);
  add("lognormal 4 um, 550 nm", large, 550e-9, false);
  add("lognormal 1 um sigma 2, 400 nm", wide, 400e-9, false);
  report("Mie sums (propagation::mie_cost)", "node", "recurrence step", cases);
}

// A radar chain's making besides its fog: plans, windows, noise correlation, CFAR design.
void radar_chain() {
  std::vector<Case> cases;
  for (const auto& [samples, chirps] : {std::pair{512u, 64u}, std::pair{1024u, 128u},
                                        std::pair{2048u, 256u}, std::pair{4096u, 512u}}) {
    experiment::Scenario s = only("radar");
    radar::RadarParams& p = radar_of(s).radar;
    p.samples_per_chirp = samples;
    p.chirps_per_frame = chirps;
    p.sample_rate_hz = samples / p.chirp_duration_s;
    p.cfar.threshold_design = radar::CfarThresholdDesign::independent;
    Case c{.name = std::to_string(samples) + " x " + std::to_string(chirps) + ", iid CFAR"};
    c.measured = median_seconds([&] { const radar::RadarChain chain(p); });
    c.x1 = 1.0;
    c.x2 = static_cast<double>(samples) * chirps;
    c.modelled = radar::setup_cost(radar_of(s), s.context()).chain_seconds;
    cases.push_back(c);
  }
  report("radar chain (radar sensor_costs.cpp chain_seconds)", "chain", "cell", cases);
  // The design's own cost model (cfar_design.hpp, cfar_design_seconds) as the one count: a fitted
  // scale near 1 says its constants still hold on this machine, for guard_cells 0 and 2, solved at
  // n (4-16 training cells) and at an anchor (64 and 128).
  for (const auto kind : {radar::CfarKind::ca, radar::CfarKind::go}) {
    std::vector<Case> design;
    for (const unsigned guard : {0u, 2u}) {
      for (const unsigned training : {4u, 8u, 16u, 64u, 128u}) {
        experiment::Scenario s = only("radar");
        radar::RadarParams& p = radar_of(s).radar;
        p.cfar.kind = kind;
        p.cfar.guard_cells = guard;
        p.cfar.training_cells = training;
        Case c{.name = std::string(radar::to_string(kind)) + ", " + std::to_string(guard) +
                       " guard, " + std::to_string(training) + " training cells, correlated"};
        const double with = median_seconds([&] { const radar::RadarChain chain(p); }, 3);
        p.cfar.threshold_design = radar::CfarThresholdDesign::independent;
        const double without = median_seconds([&] { const radar::RadarChain chain(p); }, 3);
        p.cfar.threshold_design = radar::CfarThresholdDesign::correlated;
        c.measured = with - without;
        c.modelled = radar::cfar_design_seconds(
            p.cfar,
            radar::window_noise_correlation(radar::make_window(p.window, p.samples_per_chirp),
                                            radar::cfar_correlation_lags(p.cfar)));
        c.x1 = c.modelled;
        design.push_back(c);
      }
    }
    report(kind == radar::CfarKind::ca ? "CFAR design, CA (cfar_design.cpp)"
                                       : "CFAR design, GO (cfar_design.cpp)",
           "modelled second", nullptr, design);
  }
}

// Items: each sensor alone, items measured one at a time on this thread.
double item_seconds(const experiment::Scenario& s, std::size_t items) {
  const experiment::Simulation simulation(s);
  experiment::ItemRun run(simulation, s.experiment.sensors.front());
  run.measure(0, 0, nullptr);  // prepares the step, makes the workspace
  return median_seconds(
             [&] {
               for (std::size_t i = 1; i <= items; ++i)
                 run.measure(0, i % run.items_per_step(), nullptr);
             },
             3) /
         static_cast<double>(items);
}

void items() {
  std::vector<Case> radar_cases;
  for (const auto& [samples, chirps, pfa] :
       {std::tuple{512u, 64u, 1e-6}, std::tuple{2048u, 256u, 1e-6}, std::tuple{512u, 64u, 1e-3},
        std::tuple{1024u, 128u, 1e-4}, std::tuple{8192u, 256u, 1e-4}}) {
    experiment::Scenario s = only("radar");
    radar::RadarParams& p = radar_of(s).radar;
    p.samples_per_chirp = samples;
    p.chirps_per_frame = chirps;
    p.sample_rate_hz = samples / p.chirp_duration_s;
    p.cfar.false_alarm_probability = pfa;
    const double cells = static_cast<double>(samples) * chirps;
    Case c{.name = std::to_string(samples) + " x " + std::to_string(chirps) + ", P_fa " +
                   std::to_string(pfa)};
    c.measured = item_seconds(s, cells > 1e6 ? 2 : cells > 1e5 ? 20 : 100);
    c.x1 = cells * std::log2(cells);
    c.x2 = cells * (3.0 + pfa * cells);
    c.modelled = experiment::estimate_run_time(s, 1).sensors.front().time.item_seconds;
    radar_cases.push_back(c);
  }
  report("radar frame", "cell x log2(cells)", "cell and object", radar_cases);
  // Fog clutter: the long chamber's 40 layers of fog against the same chamber clear.
  std::vector<Case> tone_cases;
  for (const double lwc : {0.0, 1.0}) {
    experiment::Scenario s = only("radar");
    s.chamber.layer_count = 40;
    s.chamber.target_gap_m = 2.0;
    s.experiment.max_active_layers = 40;
    s.fog.density = propagation::LiquidWaterContent{lwc};
    radar::RadarParams& p = radar_of(s).radar;
    p.samples_per_chirp = 1024;
    p.sample_rate_hz = 20e6;
    const experiment::Simulation simulation(s);
    experiment::ItemRun run(simulation, "radar");
    run.measure(40, 0, nullptr);
    Case c{.name = lwc > 0.0 ? "40 active layers of fog, 1024 samples" : "the same, clear"};
    c.measured = median_seconds(
                     [&] {
                       for (std::size_t i = 1; i <= 20; ++i) run.measure(40, i, nullptr);
                     },
                     3) /
                 20.0;
    const experiment::TimeEstimate e = experiment::estimate_run_time(s, 1);
    // The last step's tones, twice the mean over steps 0..40 (every layer is wet).
    c.modelled = e.sensors.front().time.item_seconds;
    tone_cases.push_back(c);
  }
  std::printf(
      "fog clutter tones (radar sensor_type.cpp frame_seconds_per_tone_sample): the last step's"
      " frame %.3g s more than clear, %.3g s per tone and sample\n",
      tone_cases[1].measured - tone_cases[0].measured,
      (tone_cases[1].measured - tone_cases[0].measured) / (40.0 * 7.0 * 4.0 * 1024.0));
  std::vector<Case> lidar_cases;
  for (const auto& [fov, range] :
       {std::pair{90.0, 30.0}, std::pair{90.0, 120.0}, std::pair{360.0, 30.0}}) {
    experiment::Scenario s = only("lidar");
    lidar::LidarParams& p = lidar_of(s);
    p.field_of_view_deg = fov;
    p.max_range_m = range;
    Case c{.name = std::to_string(p.beam_count()) + " beams x " +
                   std::to_string(p.samples_per_beam()) + " samples"};
    c.measured = item_seconds(s, 10);
    c.x1 = static_cast<double>(p.beam_count() * p.samples_per_beam());
    c.x2 = static_cast<double>(p.beam_count());
    c.modelled = experiment::estimate_run_time(s, 1).sensors.front().time.item_seconds;
    lidar_cases.push_back(c);
  }
  report("lidar scan", "sample", "beam", lidar_cases);
  std::vector<Case> camera_cases;
  for (const std::size_t scale : {1u, 4u}) {
    experiment::Scenario s = only("camera");
    camera::CameraParams& p = camera_of(s);
    p.roi.width_px *= scale;
    p.roi.height_px *= scale;
    Case c{.name =
               std::to_string(p.roi.width_px) + " x " + std::to_string(p.roi.height_px) + " px"};
    c.measured = item_seconds(s, 20);
    c.x1 = static_cast<double>(p.roi.width_px * p.roi.height_px);
    c.modelled = experiment::estimate_run_time(s, 1).sensors.front().time.item_seconds;
    camera_cases.push_back(c);
  }
  report("camera frame", "pixel", nullptr, camera_cases);
}

// Each sensor's set-up as a whole (its Mie sums with the constants above), its run's part and its
// result set's part, at two item counts.
void sensor_parts(const propagation::SegelsteinTable& water) {
  for (const char* name : {"radar", "lidar", "camera"}) {
    std::vector<Case> make, per_run, per_report;
    for (const std::size_t scale : {1u, 4u}) {
      experiment::Scenario s = only(name);
      s.params<fogradar::radar::SensorParams>("radar").measurements_per_step *= scale;
      lidar_of(s).scans_per_step *= scale;
      camera_of(s).frames_per_step *= scale;
      const sensor::Context context = s.context();
      const std::shared_ptr<const sensor::ConfiguredSensor> configured = s.configure(name);
      const double items = static_cast<double>(context.steps * configured->items_per_step());
      const sensor::SetupTime model = configured->cost().setup;
      make.push_back(
          {.name = std::string(name) + " make",
           .x1 = 1.0,
           .x2 = 0.0,
           .measured = median_seconds([&] { (void)configured->make(water, StopToken()); }, 5),
           .modelled = model.make_seconds});
      const experiment::Simulation simulation(s);
      const experiment::ExperimentResult result =
          simulation.run({.threads = 1, .progress = {}, .stop = nullptr, .raw = nullptr});
      per_run.push_back(
          {.name = std::string(name) + " summarize, " +
                   std::to_string(static_cast<std::size_t>(items)) + " items",
           .x1 = items,
           .x2 = 0.0,
           .measured = median_seconds([&] { (void)experiment::summarize(result); }, 3),
           .modelled = model.run_seconds});
      const experiment::ExperimentSummary summary = experiment::summarize(result);
      per_report.push_back({.name = std::string(name) + " fog report and files, " +
                                    std::to_string(static_cast<std::size_t>(items)) + " items",
                            .x1 = items,
                            .x2 = 0.0,
                            .measured = median_seconds(
                                [&] {
                                  (void)configured->fog_report(context.chamber.layers[0].fog,
                                                               context.chamber.layers[0].length_m,
                                                               water);
                                  (void)summary.sensors.front().summary->files();
                                },
                                3),
                            .modelled = model.report_seconds});
    }
    report((std::string(name) + " make (Mie model above + its own)").c_str(), "make", nullptr,
           make);
    report((std::string(name) + " run (summary)").c_str(), "item", nullptr, per_run);
    report((std::string(name) + " result set (fog report, files)").c_str(), "item", nullptr,
           per_report);
  }
}

// What a process costs beyond the modelled parts: the executable on a one-item-per-sensor run and
// on a one-point sweep of it.
void process(const std::string& fogradar) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "fogradar-calibration";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "tiny.toml") << "[radar]\nmeasurements_per_step = 1\n[lidar]\n"
                                      "scans_per_step = 1\n[camera]\nframes_per_step = 1\n";
  std::ofstream(dir / "tiny_sweep.toml") << "[sweep]\nbase = \"tiny.toml\"\n[[axis]]\n"
                                            "key = \"radar.tx_power_dbm\"\nvalues = [10.0]\n";
  const std::string run = fogradar + " run --threads 1 --scenario " + (dir / "tiny.toml").string() +
                          " --out " + (dir / "out").string() + " >/dev/null";
  const std::string sweep = fogradar + " sweep --threads 1 --sweep " +
                            (dir / "tiny_sweep.toml").string() + " --out " +
                            (dir / "sweep").string() + " >/dev/null";
  std::string tiny_text;
  {
    std::ifstream in(dir / "tiny.toml");
    tiny_text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const experiment::Scenario tiny = experiment::parse_scenario(tiny_text, "tiny.toml");
  const experiment::TimeEstimate e = experiment::estimate_run_time(tiny, 1);
  const auto child_seconds = [](const std::string& command) {
    return median_of([&] {
      const double before = children_seconds();
      if (std::system(command.c_str()) != 0) std::exit(1);
      return children_seconds() - before;
    });
  };
  const double run_wall = child_seconds(run);
  const double sweep_wall = child_seconds("rm -rf " + (dir / "sweep").string() + " && " + sweep);
  const double modelled_work = e.wall_seconds() - e.process_seconds;
  const std::vector<const experiment::Scenario*> runs{&tiny};
  std::printf(
      "process (experiment run_time.cpp process_seconds): `run` of 1 item per sensor %.3g s"
      " CPU, %.3g s of it modelled work: %.3g s per process (the code holds %.3g s)\n",
      run_wall, modelled_work, run_wall - modelled_work, e.process_seconds);
  std::printf("  one-point `sweep` of it %.3g s CPU (its estimate %.3g s)\n", sweep_wall,
              experiment::estimate_runs(runs, 1).wall_seconds);
  std::filesystem::remove_all(dir);
}

}  // namespace

int main(int argc, char** argv) {
  const propagation::SegelsteinTable water;
  mie(water);
  radar_chain();
  items();
  sensor_parts(water);
  if (argc > 1) process(argv[1]);
  return 0;
}
