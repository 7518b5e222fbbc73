// Per-beam cost of the lidar (docs/lidar.md, Speed): one scan of the paper scenario's lidar
// (LidarParams defaults, 361 beams over 90 deg) through 0, 1 and 4 active layers, in beams per
// second; one paper radar frame (RadarChain::measure, all four layers on, the EVT with floor
// multipath: chain_bench's BM_Measure) for the ratio; and the paper scenario's lidar part, 5 steps
// x 40 scans, at one thread; and the lidar's floor (docs/performance.md): the receiver noise every
// waveform sample of a scan needs, drawn as the scan draws it (one ComplexNormalGenerator call of
// ceil(samples / 2) complex values per beam into a reused buffer), and nothing else. Run
// interleaved so the ratio is stable on a loaded machine:
//   ./build/release/bench/lidar_bench --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <algorithm>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "fogradar/core/complex_normal_generator.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/scene.hpp"
#include "run_times.hpp"

namespace {

using namespace fogradar;

const propagation::SegelsteinTable& table() {
  static const propagation::SegelsteinTable instance;
  return instance;
}

const lidar::Lidar& paper_lidar() {
  static const lidar::Lidar instance(lidar::LidarParams{}, propagation::ChamberSpec{}, table());
  return instance;
}

void BM_LidarScan(benchmark::State& state) {
  const lidar::Lidar& sensor = paper_lidar();
  const auto layers = static_cast<std::size_t>(state.range(0));
  const auto active = propagation::first_layers_active(layers, 4);
  const lidar::FogFluctuationSeries fog = sensor.fog_fluctuation(RandomStream(1, 2, 3));
  std::uint64_t i = 0;
  for (auto _ : state) {
    RandomStream stream = sensor_stream(1, lidar::stream_key, layers, i);
    benchmark::DoNotOptimize(sensor.measure(active, fog.scan(i % 40), stream));
    ++i;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sensor.beam_count()));
  state.SetLabel("items = beams");
}

void BM_LidarNoiseFloor(benchmark::State& state) {
  const lidar::Lidar& sensor = paper_lidar();
  std::vector<std::complex<double>> noise((sensor.samples_per_beam() + 1) / 2);
  std::uint64_t i = 0;
  for (auto _ : state) {
    RandomStream stream = sensor_stream(1, lidar::stream_key, 0, i++);
    ComplexNormalGenerator generator(stream);
    for (std::size_t beam = 0; beam < sensor.beam_count(); ++beam) {
      std::fill(noise.begin(), noise.end(), std::complex<double>{});
      generator.add(noise, 1.0);
      benchmark::DoNotOptimize(noise.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sensor.beam_count()));
  state.SetLabel("items = beams");
}

void BM_RadarFrame(benchmark::State& state) {
  static const radar::RadarChain chain{radar::RadarParams{}};
  static const propagation::Chamber chamber(propagation::ChamberSpec{},
                                            chain.params().centre_frequency_hz, table());
  radar::Scene scene = radar::evt_rear_scene();
  scene.surfaces = {radar::coefficient_floor(-0.7)};
  const auto active = propagation::first_layers_active(4, 4);
  radar::MeasurementWorkspace workspace = chain.make_workspace();
  radar::Measurement m;
  std::uint64_t i = 0;
  for (auto _ : state) {
    RandomStream rng(6, i++);
    chain.measure(scene, chamber, active, rng, workspace, m);
  }
}

// The paper scenario's lidar part as experiment/ runs it, at one thread.
void BM_PaperLidarPart(benchmark::State& state) {
  const lidar::Lidar& sensor = paper_lidar();
  for (auto _ : state) {
    for (std::size_t step = 0; step <= 4; ++step) {
      const auto active = propagation::first_layers_active(step, 4);
      const lidar::FogFluctuationSeries fog = sensor.fog_fluctuation(
          sensor_stream(1, lidar::stream_key, step, sensor.fog_series_index()));
      for (std::size_t s = 0; s < 40; ++s) {
        RandomStream stream = sensor_stream(1, lidar::stream_key, step, s);
        benchmark::DoNotOptimize(sensor.measure(active, fog.scan(s), stream));
      }
    }
  }
  state.SetItemsProcessed(state.iterations() * 200 *
                          static_cast<std::int64_t>(sensor.beam_count()));
}

BENCHMARK(BM_LidarScan)->Arg(0)->Arg(1)->Arg(4)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LidarNoiseFloor)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RadarFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PaperLidarPart)->Unit(benchmark::kMillisecond);

// Console output plus, at the end, the ratios the issue asks for, from CPU time (stable on a shared
// machine; the median when --benchmark_repetitions > 1): each scan in radar frames, and the paper
// lidar part against the paper radar part (measurements_per_step x 5 steps = 1000 frames).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    times_.add(runs);
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    const std::map<std::string, double> seconds = times_.seconds();
    const auto frame = seconds.find("BM_RadarFrame");
    if (frame == seconds.end()) return;
    const double frame_s = frame->second;
    std::printf("\nCPU time as a ratio to one paper radar frame (%.1f us):\n", frame_s * 1e6);
    for (const auto& [key, time_s] : seconds) {
      std::printf("  %-22s %12.1f us  %8.2f frames\n", key.c_str(), time_s * 1e6, time_s / frame_s);
    }
    const auto floor = seconds.find("BM_LidarNoiseFloor");
    if (floor != seconds.end()) {
      std::printf("\nCPU time as a ratio to the lidar's floor (the scan's noise, %.1f us):\n",
                  floor->second * 1e6);
      for (const auto& [key, time_s] : seconds) {
        if (key.starts_with("BM_LidarScan"))
          std::printf("  %-22s %8.2f x the floor\n", key.c_str(), time_s / floor->second);
      }
    }
    const auto part = seconds.find("BM_PaperLidarPart");
    if (part != seconds.end()) {
      std::printf("paper lidar part / paper radar part (1000 frames): %.2f\n",
                  part->second / (1000.0 * frame_s));
    }
  }

 private:
  fogradar::bench::RunTimes times_{fogradar::bench::RunTimes::Clock::cpu};
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
