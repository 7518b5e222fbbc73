// Per-frame cost of the radar DSP building blocks (docs/performance.md): window + range FFT +
// Doppler FFT on a chirps x samples complex frame, the FFT work alone (the performance floor), and
// CFAR along range in every Doppler bin. Frames: 64 x 512 (paper scenario) and 128 x 1024
// (bench workload). Run: ./build/release/bench/dsp_bench
#include <benchmark/benchmark.h>

#include <complex>
#include <cstddef>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/fft.hpp"
#include "fogradar/radar/window.hpp"

namespace {

using fogradar::radar::CfarConfig;
using fogradar::radar::CfarDetector;
using fogradar::radar::CfarKind;
using fogradar::radar::CfarWorkspace;
using fogradar::radar::ComplexVector;
using fogradar::radar::FftDirection;
using fogradar::radar::FftOptions;
using fogradar::radar::FftPlacement;
using fogradar::radar::FftPlan;
using fogradar::radar::FftPlanner;
using fogradar::radar::make_window;
using fogradar::radar::WindowType;

ComplexVector random_frame(std::size_t chirps, std::size_t samples) {
  std::mt19937_64 rng(1);
  std::normal_distribution<double> normal;
  ComplexVector frame(chirps * samples);
  for (auto& value : frame) value = {normal(rng), normal(rng)};
  return frame;
}

FftPlanner planner_from(const benchmark::State& state) {
  return state.range(2) != 0 ? FftPlanner::measure : FftPlanner::estimate;
}

// The FFT floor: batched range FFTs (rows, raw frame -> work buffer) then batched Doppler FFTs
// (columns, in place in the work buffer).
void BM_FrameFftOnly(benchmark::State& state) {
  const auto chirps = static_cast<std::size_t>(state.range(0));
  const auto samples = static_cast<std::size_t>(state.range(1));
  const FftPlanner planner = planner_from(state);
  const FftPlan range_fft =
      FftPlan::along_rows(chirps, samples, FftDirection::forward, {.planner = planner});
  const FftPlan doppler_fft =
      FftPlan::along_columns(chirps, samples, FftDirection::forward,
                             {.planner = planner, .placement = FftPlacement::in_place});
  const ComplexVector input = random_frame(chirps, samples);
  ComplexVector frame(input.size());
  for (auto _ : state) {
    range_fft.execute(input, frame);
    doppler_fft.execute(frame);
    benchmark::DoNotOptimize(frame.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Window (range window on every chirp, Doppler window across chirps) + both FFTs, out of place
// from the raw frame, as the processing chain does.
void BM_FrameWindowFft(benchmark::State& state) {
  const auto chirps = static_cast<std::size_t>(state.range(0));
  const auto samples = static_cast<std::size_t>(state.range(1));
  const FftOptions options{.planner = planner_from(state), .placement = FftPlacement::in_place};
  const FftPlan range_fft = FftPlan::along_rows(chirps, samples, FftDirection::forward, options);
  const FftPlan doppler_fft =
      FftPlan::along_columns(chirps, samples, FftDirection::forward, options);
  const std::vector<double> range_window = make_window(WindowType::hann, samples);
  const std::vector<double> doppler_window = make_window(WindowType::hann, chirps);
  const ComplexVector input = random_frame(chirps, samples);
  ComplexVector frame(input.size());
  for (auto _ : state) {
    for (std::size_t c = 0; c < chirps; ++c) {
      const double wd = doppler_window[c];
      const std::complex<double>* in_row = input.data() + c * samples;
      std::complex<double>* out_row = frame.data() + c * samples;
      for (std::size_t s = 0; s < samples; ++s) out_row[s] = in_row[s] * (wd * range_window[s]);
    }
    range_fft.execute(frame);
    doppler_fft.execute(frame);
    benchmark::DoNotOptimize(frame.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// CFAR along range in every Doppler bin of one frame (power = |X|^2 of exponential noise).
void BM_FrameCfar(benchmark::State& state) {
  const auto chirps = static_cast<std::size_t>(state.range(0));
  const auto samples = static_cast<std::size_t>(state.range(1));
  const auto kind = static_cast<CfarKind>(state.range(2));
  const CfarDetector detector(CfarConfig{
      .kind = kind, .guard_cells = 2, .training_cells = 16, .false_alarm_probability = 1e-6});
  std::mt19937_64 rng(2);
  std::exponential_distribution<double> exponential(1.0);
  std::vector<double> power(chirps * samples);
  for (double& value : power) value = exponential(rng);
  CfarWorkspace workspace;
  std::size_t detections = 0;
  for (auto _ : state) {
    for (std::size_t c = 0; c < chirps; ++c) {
      detector.detect(std::span<const double>(power).subspan(c * samples, samples), workspace);
      detections += workspace.detections.size();
    }
    benchmark::DoNotOptimize(detections);
  }
  state.SetLabel(std::string(fogradar::radar::to_string(kind)));
  state.counters["cells/s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * chirps * samples), benchmark::Counter::kIsRate);
}

// Args: chirps, samples, planner (0 estimate, 1 measure).
BENCHMARK(BM_FrameFftOnly)
    ->Args({64, 512, 0})
    ->Args({64, 512, 1})
    ->Args({128, 1024, 0})
    ->Args({128, 1024, 1})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FrameWindowFft)
    ->Args({64, 512, 0})
    ->Args({128, 1024, 0})
    ->Args({128, 1024, 1})
    ->Unit(benchmark::kMicrosecond);
// Args: chirps, samples, CfarKind (0 ca, 1 go, 2 so, 3 os).
BENCHMARK(BM_FrameCfar)
    ->ArgsProduct({{64}, {512}, {0, 1, 2, 3}})
    ->ArgsProduct({{128}, {1024}, {0, 1, 2, 3}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
