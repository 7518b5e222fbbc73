// Per-frame cost of every stage of the radar chain (docs/performance.md), for the paper radar (64
// chirps x 512 samples at 10 MS/s) and the bench workload (128 chirps x 1024 samples; the sample
// rate is raised to 20 MS/s so the 1024 samples fit the 51.2 us chirp, as in
// examples/long_chamber.toml). Scene: the paper chamber (propagation::ChamberSpec defaults, all
// four layers on, default fog of 900/km optical extinction) and the EVT rear (evt_rear_scene, floor
// multipath on), thermal noise on. Stages as RadarChain::measure runs them: scene_tones,
// synthesize_frame given the processor's window (with noise, the window is applied in the noise
// pass; without, after the tones), the range and Doppler FFTs
// (RangeDopplerProcessor::transform_windowed), estimate_detections (|.|^2 and CFAR row by row,
// grouping, interpolation, RCS), the full RadarChain::measure, and the floor: the range and Doppler
// FFTs alone with FFTW_MEASURE plans (range FFT of every chirp, Doppler FFT in column blocks: the
// candidate bench/throughput most often finds fastest; throughput takes the fastest of four
// layouts, docs/performance.md). Arg 0: 0 = paper frame, 1 = bench frame. Run:
//   ./build/chain-rel/bench/chain_bench --benchmark_repetitions=9
//       --benchmark_enable_random_interleaving=true --benchmark_min_time=0.2
// The last lines print each stage as a ratio to the FFT-only floor measured in the same run
// (docs/radar.md §9); interleaving keeps the ratios stable on a loaded machine.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fogradar/core/random.hpp"
#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/radar/measurement.hpp"
#include "run_times.hpp"

namespace {

using namespace fogradar;
using namespace fogradar::radar;

radar::RadarParams params_for(std::int64_t size) {
  RadarParams p;  // the paper scenario's radar (examples/paper.toml)
  if (size == 1) {
    p.chirps_per_frame = 128;
    p.samples_per_chirp = 1024;
    p.sample_rate_hz = 20e6;
  }
  return p;
}

// Everything made once per size: chain, chamber, scene, and one measurement's tones and map.
struct Setup {
  explicit Setup(std::int64_t size)
      : chain(params_for(size)),
        chamber(propagation::ChamberSpec{}, chain.params().centre_frequency_hz, table()),
        active(propagation::first_layers_active(chamber.layer_count(), chamber.layer_count())),
        scene(make_scene()),
        workspace(chain.make_workspace()) {
    chain.check_compatible(scene, chamber);
    RandomStream rng(1);
    chain.synthesize_and_process(scene, chamber, active, rng, workspace);
  }
  static const propagation::SegelsteinTable& table() {
    static const propagation::SegelsteinTable instance;
    return instance;
  }
  static Scene make_scene() {
    Scene s = evt_rear_scene();
    s.surfaces = {coefficient_floor(-0.7)};
    return s;
  }
  RadarChain chain;
  propagation::Chamber chamber;
  propagation::ActiveLayers active;
  Scene scene;
  MeasurementWorkspace workspace;  // holds the processed map of one measurement
};

Setup& setup(std::int64_t size) {
  static std::unique_ptr<Setup> setups[2];
  if (!setups[size]) setups[size] = std::make_unique<Setup>(size);
  return *setups[size];
}

void label(benchmark::State& state, const Setup& s) {
  state.counters["chirps"] = static_cast<double>(s.chain.params().chirps_per_frame);
  state.counters["samples"] = static_cast<double>(s.chain.params().samples_per_chirp);
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The floor: range FFT of every chirp (out of place from the raw frame, so every iteration starts
// from the same data) and the Doppler FFT of every range bin (in place, column blocks), both
// FFTW_MEASURE, planned before timing.
void BM_FftOnly(benchmark::State& state) {
  Setup& s = setup(state.range(0));
  const std::size_t rows = s.chain.params().chirps_per_frame,
                    cols = s.chain.params().samples_per_chirp;
  const FftPlan range_fft =
      FftPlan::along_rows(rows, cols, FftDirection::forward, {.planner = FftPlanner::measure});
  const ColumnBlockFft doppler_fft(rows, cols, FftDirection::forward, FftPlanner::measure);
  ComplexVector input(rows * cols), frame(rows * cols);
  RandomStream rng(2);
  for (auto& v : input) v = rng.complex_normal(1.0);
  for (auto _ : state) {
    range_fft.execute(input, frame);
    doppler_fft.execute(frame);
    benchmark::DoNotOptimize(frame.data());
  }
  label(state, s);
}

void BM_SceneTones(benchmark::State& state) {
  Setup& s = setup(state.range(0));
  std::vector<Tone> tones;
  std::uint64_t i = 0;
  for (auto _ : state) {
    RandomStream rng(3, i++);
    scene_tones(s.scene, s.chamber, s.active, s.chain.params(), s.chain.derived(), rng, tones);
    benchmark::DoNotOptimize(tones.data());
  }
  state.counters["tones"] = static_cast<double>(tones.size());
  label(state, s);
}

// Synthesis given the processor's window, as RadarChain::measure runs it. Arg 1: thermal noise on
// (1) or off (0, to attribute the cost: tones and window vs noise generation).
void BM_Synthesize(benchmark::State& state) {
  Setup& s = setup(state.range(0));
  RadarParams params = s.chain.params();
  params.thermal_noise = state.range(1) != 0;
  std::vector<Tone> tones;
  RandomStream tone_rng(3);
  scene_tones(s.scene, s.chamber, s.active, params, s.chain.derived(), tone_rng, tones);
  const FrameWindow window = s.chain.processor().window();
  ComplexVector frame(s.workspace.frame.size());
  std::uint64_t i = 0;
  for (auto _ : state) {
    RandomStream rng(4, i++);
    benchmark::DoNotOptimize(
        synthesize_frame(tones, params, s.chain.derived(), rng, frame, &window));
    benchmark::DoNotOptimize(frame.data());
  }
  state.counters["noise"] = static_cast<double>(state.range(1));
  label(state, s);
}

// The range and Doppler FFTs of a windowed frame, as RadarChain::measure runs them. They work in
// place, so each iteration first restores the synthesised frame (copy excluded from the timing).
void BM_Processing(benchmark::State& state) {
  Setup& s = setup(state.range(0));
  std::vector<Tone> tones;
  RandomStream rng(5);
  scene_tones(s.scene, s.chamber, s.active, s.chain.params(), s.chain.derived(), rng, tones);
  const FrameWindow window = s.chain.processor().window();
  ComplexVector raw(s.workspace.frame.size()), frame(raw.size());
  synthesize_frame(tones, s.chain.params(), s.chain.derived(), rng, raw, &window);
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(raw.begin(), raw.end(), frame.begin());
    state.ResumeTiming();
    s.chain.processor().transform_windowed(frame);
    benchmark::DoNotOptimize(frame.data());
  }
  label(state, s);
}

// CFAR in every Doppler bin, grouping, peak interpolation and RCS of one processed map.
void BM_Estimation(benchmark::State& state) {
  Setup& s = setup(state.range(0));
  EstimationWorkspace ws;
  std::vector<Detection> detections;
  for (auto _ : state) {
    estimate_detections(s.workspace.frame, s.chain.processor(), s.chain.cfar(), s.chain.params(),
                        s.chain.derived(), ws, detections);
    benchmark::DoNotOptimize(detections.data());
  }
  state.counters["detections"] = static_cast<double>(detections.size());
  label(state, s);
}

void BM_Measure(benchmark::State& state) {
  Setup& s = setup(state.range(0));
  MeasurementWorkspace ws = s.chain.make_workspace();
  Measurement m;
  std::uint64_t i = 0, detected = 0;
  for (auto _ : state) {
    RandomStream rng(6, i++);
    s.chain.measure(s.scene, s.chamber, s.active, rng, ws, m);
    detected += m.target ? 1 : 0;
  }
  state.counters["target_detected"] = static_cast<double>(detected) / static_cast<double>(i);
  label(state, s);
}

BENCHMARK(BM_FftOnly)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SceneTones)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Synthesize)->ArgsProduct({{0, 1}, {1, 0}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Processing)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Estimation)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Measure)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// Console output plus, at the end, every stage's real time per frame as a ratio to the FFT-only
// floor of the same size measured in the same run (the median when --benchmark_repetitions > 1).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    times_.add(runs);
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    const std::map<std::string, double> seconds = times_.seconds();
    // Keys are "name/size/...": the first argument is the frame size.
    const auto first_argument = [](const std::string& key) {
      const std::size_t begin = key.find('/');
      if (begin == std::string::npos) return std::string();
      return key.substr(begin + 1, key.find('/', begin + 1) - begin - 1);
    };
    std::printf("\nReal time per frame as a ratio to the FFT-only floor of the same run:\n");
    for (const std::string size : {"0", "1"}) {
      const auto floor = seconds.find("BM_FftOnly/" + size);
      if (floor == seconds.end()) continue;
      const double floor_us = floor->second * 1e6;
      std::printf("  %s frame: FFT-only %.1f us\n",
                  size == "0" ? "paper 64 x 512" : "bench 128 x 1024", floor_us);
      for (const auto& [key, time_s] : seconds) {
        if (first_argument(key) != size) continue;
        std::printf("    %-22s %10.1f us  %6.2f x\n", key.c_str(), time_s * 1e6,
                    time_s * 1e6 / floor_us);
      }
    }
  }

 private:
  fogradar::bench::RunTimes times_{fogradar::bench::RunTimes::Clock::real};
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
