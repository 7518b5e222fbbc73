// The run-time estimate (experiment/run_time.hpp, each sensor's item_time and setup_time): how it
// scales with an item's size and count, how threads share it, that set-up is counted once per
// process and per sensor made, and the refusal over a limit naming the key that dominates; and a
// stop honoured inside one long item (a lidar scan, a radar frame).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

#include "fogradar/camera/spectral.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/experiment/run_time.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/sensor.hpp"
#include "sensors.hpp"

namespace fogradar::experiment {
namespace {

Scenario lidar_only() {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"lidar"};
  return s;
}

// The scan: 36001 beams x 667129 samples, about 33 s on the project's 2-core VM.
Scenario huge_scan() {
  Scenario s = lidar_only();
  s.experiment.max_active_layers = 0;
  lidar::LidarParams& p = lidar_of(s);
  p.scans_per_step = 1;
  p.field_of_view_deg = 360.0;
  p.angular_step_deg = 0.01;
  p.max_range_m = 1000.0;
  p.sample_interval_ns = 0.01;
  return s;
}

double item_seconds(const Scenario& s) {
  return estimate_run_time(s, 1).sensors.front().time.item_seconds;
}

TEST(RunTimeEstimate, ALidarScanScalesWithItsBeamsAndTheRunWithItsScans) {
  Scenario s = lidar_only();
  const double one = item_seconds(s);
  const std::size_t beams = lidar_of(s).beam_count();
  lidar_of(s).field_of_view_deg *= 2.0;  // 90 -> 180 degrees: 361 -> 721 beams
  const double wider = item_seconds(s);
  EXPECT_NEAR(wider / one,
              static_cast<double>(lidar_of(s).beam_count()) / static_cast<double>(beams), 1e-12);
  const double run = estimate_run_time(s, 1).cpu_seconds();
  lidar_of(s).scans_per_step *= 2;
  EXPECT_DOUBLE_EQ(estimate_run_time(s, 1).cpu_seconds(), 2.0 * run);
  EXPECT_EQ(estimate_run_time(s, 1).sensors.front().items, 5u * lidar_of(s).scans_per_step);
}

TEST(RunTimeEstimate, ARadarFrameAndACameraFrameScaleWithTheirCells) {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"radar"};
  // Fog clutter tones cost per sample of one chirp, not per cell: left out here, priced below.
  const double foggy = item_seconds(s);
  s.fog.density = propagation::LiquidWaterContent{0.0};
  const double frame = item_seconds(s);
  // One tone per scatterer in every range bin of the active layers.
  EXPECT_GT(foggy, frame);
  s.fog = paper_scenario().fog;
  radar_of(s).clutter_scatterers_per_bin *= 2;
  EXPECT_NEAR(item_seconds(s) - frame, 2.0 * (foggy - frame), 1e-9 * foggy);
  s.fog.density = propagation::LiquidWaterContent{0.0};
  radar_of(s).radar.chirps_per_frame *= 2;
  // Twice the cells, each cell's transforms one log2 step longer (16 / 15), and each object's peak
  // search over twice the map.
  EXPECT_GE(item_seconds(s), 2.0 * frame);
  EXPECT_LT(item_seconds(s), 2.0 * 16.0 / 15.0 * frame);
  s.experiment.sensors = {"camera"};
  const double image = item_seconds(s);
  camera_of(s).roi.width_px *= 2;
  EXPECT_DOUBLE_EQ(item_seconds(s), 2.0 * image);
}

TEST(RunTimeEstimate, ThreadsShareTheItemsButNotOneItem) {
  const Scenario paper = paper_scenario();
  const TimeEstimate one = estimate_run_time(paper, 1), two = estimate_run_time(paper, 2);
  EXPECT_EQ(one.threads, 1u);
  EXPECT_EQ(two.threads, 2u);
  EXPECT_DOUBLE_EQ(one.items_wall_seconds(), one.cpu_seconds());
  EXPECT_DOUBLE_EQ(two.items_wall_seconds(), one.cpu_seconds() / 2.0);
  // Set-up runs on one thread however many there are.
  EXPECT_DOUBLE_EQ(two.setup_seconds(), one.setup_seconds());
  EXPECT_DOUBLE_EQ(two.wall_seconds(), one.setup_seconds() + one.cpu_seconds() / 2.0);
  // One scan runs on one thread, however many there are.
  const TimeEstimate huge = estimate_run_time(huge_scan(), 8);
  EXPECT_EQ(huge.threads, 1u);  // one item: one worker
  EXPECT_DOUBLE_EQ(huge.items_wall_seconds(), huge.sensors.front().time.item_seconds);
  EXPECT_GT(huge.wall_seconds(), 10.0);
  EXPECT_NE(huge.text().find("lidar 1 x "), std::string::npos) << huge.text();
}

// The items grow linearly with their count; what is made once does not grow with it.
TEST(RunTimeEstimate, ItemsGrowLinearlyInMeasurementsAndTheSensorIsMadeOnce) {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"radar"};
  std::vector<TimeEstimate> e;
  for (const std::size_t m : {100u, 200u, 300u}) {
    s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = m;
    e.push_back(estimate_run_time(s, 1));
  }
  EXPECT_NEAR(e[2].cpu_seconds() - e[1].cpu_seconds(), e[1].cpu_seconds() - e[0].cpu_seconds(),
              1e-12 * e[2].cpu_seconds());
  EXPECT_NEAR(e[2].cpu_seconds(), 3.0 * e[0].cpu_seconds(), 1e-12 * e[2].cpu_seconds());
  EXPECT_GT(e[0].sensors.front().setup.make_seconds, 0.0);
  EXPECT_EQ(e[2].sensors.front().setup.make_seconds, e[0].sensors.front().setup.make_seconds);
  EXPECT_GT(e[0].process_seconds, 0.0);
  EXPECT_EQ(e[2].process_seconds, e[0].process_seconds);
  // The set-up is part of the wall time: a run of one measurement per step is not free.
  s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 1;
  const TimeEstimate one = estimate_run_time(s, 1);
  EXPECT_GT(one.wall_seconds(), one.process_seconds + one.sensors.front().setup.make_seconds);
  EXPECT_GT(one.setup_seconds(), 10.0 * one.cpu_seconds());
}

// A camera makes its fog optics at every Mie wavelength of its band for every distinct fog: four
// distinct layers cost four times one, a layer repeated nothing more, and a finer Mie grid more.
TEST(RunTimeEstimate, FogOpticsAreCountedPerDistinctFogAndWavelength) {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"camera"};
  const auto make = [](const Scenario& scenario) {
    return estimate_run_time(scenario, 1).sensors.front().setup.make_seconds;
  };
  // One fog's Mie sums: resolved at 550 nm, then at each Mie wavelength of the band.
  const camera::CameraParams& p = camera_of(s);
  double per_fog = propagation::fog_resolution_seconds(s.fog);
  for (const double wavelength_m :
       camera::mie_wavelengths_m(p.band, p.wavelength_nm, p.mie_step_nm))
    per_fog += propagation::bulk_optics_seconds(s.fog.droplets, wavelength_m);
  const double one_fog = make(s);  // the study's four layers of one fog
  ASSERT_EQ(s.chamber.layers_in_use(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    propagation::FogLayerSpec layer{.length_m = 1.0, .fog = s.fog};
    if (i > 0) layer.fog.density = propagation::OpticalExtinction{100.0 * static_cast<double>(i)};
    s.chamber.layers.push_back(layer);
  }
  EXPECT_NEAR(make(s), one_fog + 3.0 * per_fog, 1e-12 * one_fog);
  const double grid = make(s);
  camera_of(s).mie_step_nm /= 4.0;  // 160 -> 40 nm: 3 -> 9 wavelengths
  EXPECT_GT(make(s), 2.0 * grid);
}

// In one process (a sweep), the process is counted once and a sensor made again only when it
// differs from every recent one: N runs of one scenario cost the process and one making plus N
// runs; N runs of N fogs make every sensor N times.
TEST(RunTimeEstimate, ASweepCountsTheProcessOnceAndEachSensorWhereItIsMade) {
  const Scenario paper = paper_scenario();
  const auto runs = [](const std::vector<Scenario>& scenarios) {
    std::vector<const Scenario*> order;
    for (const Scenario& s : scenarios) order.push_back(&s);
    return estimate_runs(order, 1).wall_seconds;
  };
  const double one = runs({paper}), two = runs({paper, paper}), three = runs({paper, paper, paper});
  const TimeEstimate e = estimate_run_time(paper, 1);
  double make = 0.0;
  for (const TimeEstimate::Part& part : e.sensors) make += part.setup.make_seconds;
  const double per_run = two - one;
  EXPECT_NEAR(three - two, per_run, 1e-12 * three);
  EXPECT_NEAR(one - per_run, process_seconds() + make, 1e-12 * three);
  // A run alone writes a result set (fog reports, files, the chamber), which a sweep's runs do not.
  EXPECT_GT(e.wall_seconds(), one);
  std::vector<Scenario> fogs(3, paper);
  for (std::size_t i = 0; i < fogs.size(); ++i)
    fogs[i].fog.density = propagation::OpticalExtinction{300.0 * (1.0 + static_cast<double>(i))};
  EXPECT_NEAR(runs(fogs) - three, 2.0 * make, 1e-9 * three);
}

// The refusal names the key of the item's size when one item alone exceeds the limit, else the key
// of the item count.
TEST(RunTimeEstimate, RefusesOverTheLimitNamingTheKeyThatDominates) {
  EXPECT_NO_THROW(require_time_within(paper_scenario(), 0, 600.0));
  try {
    require_time_within(huge_scan(), 0, 1.0);
    FAIL() << "the huge scan was not refused";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "lidar.sample_interval_ns");
    const std::string message = e.what();
    EXPECT_NE(message.find("--time-limit"), std::string::npos) << message;
    EXPECT_NE(message.find("36001 beams"), std::string::npos) << message;
  }
  Scenario many = lidar_only();
  lidar_of(many).scans_per_step = 100000;
  const double limit = 0.5 * estimate_run_time(many, 1).wall_seconds();
  try {
    require_time_within(many, 1, limit);
    FAIL() << "500000 scans were not refused";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "lidar.scans_per_step") << e.what();
  }
}

// A set-up that outweighs the items is refused naming its key: here the radar's correlated CFAR
// design of a wide GO window against one measurement per step.
TEST(RunTimeEstimate, RefusesASetUpOverTheLimitNamingItsKey) {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"radar"};
  s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 1;
  radar_of(s).radar.cfar.kind = radar::CfarKind::go;
  radar_of(s).radar.cfar.training_cells = 32;
  const TimeEstimate design = estimate_run_time(s, 1);
  ASSERT_GT(design.sensors.front().setup.make_seconds, 10.0 * design.cpu_seconds());
  try {
    require_time_within(s, 1, 0.5 * design.wall_seconds());
    FAIL() << "the design was not refused";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "radar.processing.cfar.threshold_design") << e.what();
    EXPECT_NE(std::string(e.what()).find("CFAR design"), std::string::npos) << e.what();
  }
  radar_of(s).radar.cfar.threshold_design = radar::CfarThresholdDesign::independent;
  EXPECT_LT(estimate_run_time(s, 1).wall_seconds(), design.wall_seconds());
}

// A stop set while the scan runs ends the run within a few beams: well before the scan's 33 s
// (the sanitizer build's beams are ~10 x slower, still a fraction of a second each).
TEST(StopInsideAnItem, ALongLidarScanStopsWithinASecond) {
  const Simulation simulation(huge_scan());
  std::atomic<bool> stop{false};
  std::atomic<long long> stopped_at_ns{0};
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    stopped_at_ns = std::chrono::steady_clock::now().time_since_epoch().count();
    stop = true;
  });
  EXPECT_THROW(simulation.run({.threads = 1, .progress = {}, .stop = &stop, .raw = nullptr}),
               Interrupted);
  const long long ended_ns = std::chrono::steady_clock::now().time_since_epoch().count();
  stopper.join();
  EXPECT_LT(static_cast<double>(ended_ns - stopped_at_ns.load()) * 1e-9, 5.0);
}

// A stop reaches the radar's CFAR design while the sensor is made: the StopToken of the run is
// handed to the sensor, and the design looks at it before every sample it draws (a stop already set
// ends it at its first; tests/radar/test_cfar_correlated.cpp) and is itself bounded (~0.2 s of CPU
// for every window, cfar_design.hpp). GO with no guard cells and 32 training cells, the longest
// kind of design: with the stop already set the Simulation ends as a run does, with Interrupted,
// and run_experiment stops before the design, as it stops before the first item.
TEST(StopWhileMade, TheRadarsCfarDesignSeesTheStop) {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"radar"};
  radar_of(s).radar.cfar.kind = radar::CfarKind::go;
  radar_of(s).radar.cfar.guard_cells = 0;
  radar_of(s).radar.cfar.training_cells = 32;
  const propagation::SegelsteinTable water;
  std::atomic<bool> stop{true};
  EXPECT_THROW(Simulation(s, water, nullptr, &stop), Interrupted);
  EXPECT_THROW(run_experiment(s, {.threads = 1, .progress = {}, .stop = &stop, .raw = nullptr}),
               Interrupted);
  SensorCache cache;
  EXPECT_THROW(Simulation(s, water, &cache, &stop), Interrupted);
}

// A radar frame looks before it starts and while its workspace is zeroed: a stop already set throws
// Stopped, nothing measured; and a frame whose stop never comes is the frame measured without one.
TEST(StopInsideAnItem, ARadarFrameSeesTheStop) {
  Scenario s = paper_scenario();
  radar_of(s).radar.chirps_per_frame = 16;
  const Simulation simulation(s);
  const SensorRunEntry entry = simulation.begin_run("radar");
  const std::shared_ptr<const sensor::SensorSummary> summary = entry.run->summarize();
  const radar::RadarReport& sensor = dynamic_cast<const radar::RadarReport&>(*summary);
  radar::MeasurementWorkspace ws = sensor.chain().make_workspace();
  radar::Measurement with_token, without;
  std::atomic<bool> stop{true};
  EXPECT_THROW((void)sensor.chain().make_workspace(StopToken(&stop)), Stopped);
  RandomStream first(7);
  EXPECT_THROW(sensor.chain().measure(sensor.scene(), sensor.chamber(), s.context().active(4),
                                      first, ws, with_token, radar::FrameTaps{}, StopToken(&stop)),
               Stopped);
  stop = false;
  RandomStream a(7), b(7);
  sensor.chain().measure(sensor.scene(), sensor.chamber(), s.context().active(4), a, ws, with_token,
                         radar::FrameTaps{}, StopToken(&stop));
  sensor.chain().measure(sensor.scene(), sensor.chamber(), s.context().active(4), b, ws, without);
  ASSERT_EQ(with_token.detections.size(), without.detections.size());
  for (std::size_t d = 0; d < without.detections.size(); ++d) {
    EXPECT_EQ(with_token.detections[d].range_m, without.detections[d].range_m);
    EXPECT_EQ(with_token.detections[d].received_power_w, without.detections[d].received_power_w);
  }
}

}  // namespace
}  // namespace fogradar::experiment
