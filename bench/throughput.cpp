// Throughput of the bench workload against its FFT floor (DESIGN §5), both measured in one process
// and one run, so the ratio compares like with like on the same (possibly shared) machine.
//
//   end to end  experiment::run_experiment (the code path of `fogradar run`: scenario check, chamber,
//               per frame scene paths, synthesis with noise, window, range and Doppler FFTs, power,
//               CFAR, grouping, peak interpolation, RCS) followed by experiment::summarize (box plots,
//               tests, sensor limit). Writing the result files is NOT included.
//   FFT floor   the same number of frames (one per measurement) and the same transforms: an in-place
//               range FFT of every chirp and an in-place Doppler FFT of every range bin, with
//               radar::FftPlan (FFTW, complex double, FFTW_ESTIMATE as the chain plans them) on a
//               preplanned aligned frame buffer, nothing else. Multi-threaded: the frames are split
//               into equal contiguous shares, each thread transforms its own buffer, the two plans
//               are shared (new-array execute).
//   noise alone the thermal-noise stage, which the floor does not bound: ComplexNormalGenerator over
//               every sample of the same number of frames, into a buffer per thread.
//
// Both are timed at 1 thread and at all hardware threads; each of the four measurements is repeated
// --repeats times, interleaved (e2e/1, floor/1, e2e/all, floor/all, then again), and the median is
// reported, with the median of each repeat's own ratio and the ratio of the fastest runs. Run (Release build):
//   ./build/perf/bench/throughput [--scenario FILE] [--repeats N] [--measurements N]
// Default scenario: examples/bench.toml of the source tree (128 chirps x 1024 samples, 5 x 200
// frames).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "fogradar/core/complex_normal_generator.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/radar/fft.hpp"

#ifndef FOGRADAR_SOURCE_DIR
#error "FOGRADAR_SOURCE_DIR must be defined (bench/CMakeLists.txt)"
#endif

namespace {

using namespace fogradar;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string scenario_path = std::string(FOGRADAR_SOURCE_DIR) + "/examples/bench.toml";
  int repeats = 5;
  long measurements = -1;  // < 0: the scenario's measurements_per_step
};

[[noreturn]] void usage(const char* message) {
  std::fprintf(stderr,
               "throughput: %s\n"
               "usage: throughput [--scenario FILE] [--repeats N (>= 1, default 5)] "
               "[--measurements N (measurements per step, >= 1)]\n",
               message);
  std::exit(2);
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") usage("times the bench workload against its FFT floor");
    if (i + 1 >= argc) usage(("missing value after " + arg).c_str());
    const std::string value = argv[++i];
    char* end = nullptr;
    if (arg == "--scenario") {
      o.scenario_path = value;
    } else if (arg == "--repeats") {
      const long n = std::strtol(value.c_str(), &end, 10);
      if (*end != '\0' || n < 1 || n > 1000) usage("--repeats must be an integer in [1, 1000]");
      o.repeats = static_cast<int>(n);
    } else if (arg == "--measurements") {
      const long n = std::strtol(value.c_str(), &end, 10);
      if (*end != '\0' || n < 1 || n > 1000000) usage("--measurements must be an integer in [1, 1000000]");
      o.measurements = n;
    } else {
      usage(("unknown option " + arg).c_str());
    }
  }
  return o;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  }
  return "unknown";
}

unsigned cpuinfo_processors() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  unsigned count = 0;
  while (std::getline(in, line)) count += line.rfind("processor", 0) == 0 ? 1 : 0;
  return count;
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// --- End to end -------------------------------------------------------------------------------

struct EndToEnd {
  double seconds = 0.0;
  double summarize_seconds = 0.0;
  std::size_t detections = 0;  // printed, so nothing can be optimised away
};

EndToEnd time_end_to_end(const experiment::Scenario& scenario, unsigned threads) {
  const Clock::time_point start = Clock::now();
  const experiment::ExperimentResult result = experiment::run_experiment(scenario, {.threads = threads, .progress = {}});
  const Clock::time_point summary_start = Clock::now();
  const experiment::ExperimentSummary summary = experiment::summarize(result);
  EndToEnd e;
  e.seconds = seconds_since(start);
  e.summarize_seconds = seconds_since(summary_start);
  for (const experiment::StepSummary& step : summary.steps) e.detections += step.detections;
  return e;
}

// --- FFT floor --------------------------------------------------------------------------------

// The transforms of one frame, planned once like RangeDopplerProcessor plans them.
struct FloorPlans {
  FloorPlans(std::size_t chirps, std::size_t samples)
      : rows(chirps),
        columns(samples),
        range(radar::FftPlan::along_rows(chirps, samples, radar::FftDirection::forward,
                                         {.planner = radar::FftPlanner::estimate,
                                          .placement = radar::FftPlacement::in_place})),
        doppler(radar::FftPlan::along_columns(chirps, samples, radar::FftDirection::forward,
                                              {.planner = radar::FftPlanner::estimate,
                                               .placement = radar::FftPlacement::in_place})) {}
  std::size_t rows, columns;
  radar::FftPlan range;
  radar::FftPlan doppler;
};

// One thread's frame buffer, transformed in place frame after frame. The unnormalised 2-D forward
// DFT F of an n = rows x columns frame satisfies F^4 = n^2 I, so the buffer grows by exactly n^8 every
// 16 frames; with n a power of two, scaling it back by that power of two (std::ldexp, exact) every 16
// frames returns the original noise frame up to rounding. It costs one pass over the buffer every 16
// frames (about 0.2 % of the transform work) and keeps the data finite noise-like values: no inf,
// NaN or denormals that could make FFTW run at another speed than on real frames.
constexpr std::size_t rescale_period_frames = 16;

struct FloorBuffer {
  radar::ComplexVector frame;
  std::size_t transformed = 0;  // frames so far, over all calls
};

FloorBuffer make_floor_buffer(const FloorPlans& plans, std::uint64_t seed) {
  FloorBuffer buffer{radar::ComplexVector(plans.rows * plans.columns), 0};
  RandomStream rng(seed);
  for (auto& v : buffer.frame) v = rng.complex_normal(1.0);
  return buffer;
}

void transform_frames(const FloorPlans& plans, FloorBuffer& buffer, std::size_t count, int rescale_exponent) {
  for (std::size_t f = 0; f < count; ++f) {
    plans.range.execute(buffer.frame);
    plans.doppler.execute(buffer.frame);
    if (++buffer.transformed % rescale_period_frames == 0) {
      for (auto& v : buffer.frame) {
        v = {std::ldexp(v.real(), rescale_exponent), std::ldexp(v.imag(), rescale_exponent)};
      }
    }
  }
}

// Frames split into `threads` contiguous shares; each thread owns buffers[t].
double time_fft_floor(const FloorPlans& plans, std::vector<FloorBuffer>& buffers, std::size_t frames,
                      unsigned threads, int rescale_exponent) {
  const Clock::time_point start = Clock::now();
  std::vector<std::thread> pool;
  const auto share = [&](unsigned t) { return frames * (t + 1) / threads - frames * t / threads; };
  for (unsigned t = 1; t < threads; ++t) {
    pool.emplace_back([&, t] { transform_frames(plans, buffers[t], share(t), rescale_exponent); });
  }
  transform_frames(plans, buffers[0], share(0), rescale_exponent);
  for (std::thread& thread : pool) thread.join();
  return seconds_since(start);
}

int rescale_exponent_for(const FloorPlans& plans) {
  const std::size_t n = plans.rows * plans.columns;
  if ((n & (n - 1)) != 0) {
    std::fprintf(stderr, "throughput: chirps x samples = %zu is not a power of two; the FFT floor's "
                         "rescaling assumes one\n", n);
    std::exit(2);
  }
  int log2n = 0;
  while ((std::size_t{1} << log2n) < n) ++log2n;
  // 16 frames = 4 periods of F^4: growth (n^2)^4 = 2^(8 log2 n).
  return -8 * log2n;
}

// --- Thermal noise alone ----------------------------------------------------------------------

// The stage the FFT floor does not bound: per frame, a ComplexNormalGenerator from a fresh stream
// adds CN(0, 1) samples to the whole frame (what synthesize_frame draws per frame), nothing else.
// Frames split into shares as for the floor; each thread adds into its own buffer (the values
// grow only as the square root of the frame count).
double time_noise(std::vector<radar::ComplexVector>& buffers, std::size_t frames, unsigned threads) {
  const Clock::time_point start = Clock::now();
  const auto work = [&](unsigned t) {
    const std::size_t first = frames * t / threads, last = frames * (t + 1) / threads;
    for (std::size_t f = first; f < last; ++f) {
      RandomStream rng(7, f);
      ComplexNormalGenerator(rng).add(buffers[t], 1.0);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& thread : pool) thread.join();
  return seconds_since(start);
}

// --- Report -----------------------------------------------------------------------------------

struct Series {
  std::vector<double> e2e, floor, noise;
};

void print_row(const char* label, double e2e_s, double floor_s, std::size_t frames) {
  std::printf("  %-16s %10.3f s %8.1f frames/s   %10.3f s %8.1f frames/s   %7.2f x\n", label, e2e_s,
              static_cast<double>(frames) / e2e_s, floor_s, static_cast<double>(frames) / floor_s,
              e2e_s / floor_s);
}

int run(const Options& options) {
  experiment::Scenario scenario = experiment::load_scenario_file(options.scenario_path);
  if (options.measurements > 0) scenario.experiment.measurements_per_step = static_cast<std::size_t>(options.measurements);
  scenario.validate();
  const std::size_t steps = scenario.experiment.max_active_layers + 1;
  const std::size_t frames = steps * scenario.experiment.measurements_per_step;
  const std::size_t rows = scenario.radar.chirps_per_frame, columns = scenario.radar.samples_per_chirp;
  const unsigned all = std::max(1u, std::thread::hardware_concurrency());

  std::printf("fogradar throughput: bench workload vs FFT floor (DESIGN §5)\n");
  std::printf("  scenario      %s\n", options.scenario_path.c_str());
  std::printf("  frame         %zu chirps x %zu samples (complex double), %zu frames = %zu steps x %zu "
              "measurements\n", rows, columns, frames, steps, scenario.experiment.measurements_per_step);
  std::printf("  CPU           %s; %u hardware threads (std::thread), %u processors in /proc/cpuinfo\n",
              cpu_model().c_str(), all, cpuinfo_processors());
  std::printf("  load average  %s (at start)\n", load_average().c_str());
  std::printf("  repeats       %d, interleaved; medians reported\n", options.repeats);
  std::printf("  end to end    run_experiment + summarize, result files not written\n");
  std::printf("  FFT floor     in-place range + Doppler FFT per frame, FftPlan FFTW_ESTIMATE, same "
              "frame count\n");
  std::printf("  noise alone   ComplexNormalGenerator over every frame's samples, same frame count\n\n");
  std::fflush(stdout);

  const FloorPlans plans(rows, columns);
  const int rescale = rescale_exponent_for(plans);
  std::vector<FloorBuffer> buffers;
  for (unsigned t = 0; t < all; ++t) buffers.push_back(make_floor_buffer(plans, 100 + t));
  time_fft_floor(plans, buffers, std::min<std::size_t>(frames, 2 * all), all, rescale);  // warm-up
  std::vector<radar::ComplexVector> noise_buffers(all, radar::ComplexVector(rows * columns));

  const unsigned thread_counts[] = {1u, all};
  const std::size_t variants = all > 1 ? 2 : 1;
  Series series[2];
  std::size_t detections = 0;
  double summarize_s = 0.0;
  for (int r = 0; r < options.repeats; ++r) {
    for (std::size_t v = 0; v < variants; ++v) {
      const EndToEnd e = time_end_to_end(scenario, thread_counts[v]);
      series[v].e2e.push_back(e.seconds);
      detections = e.detections;
      summarize_s = std::max(summarize_s, e.summarize_seconds);
      series[v].floor.push_back(time_fft_floor(plans, buffers, frames, thread_counts[v], rescale));
      series[v].noise.push_back(time_noise(noise_buffers, frames, thread_counts[v]));
      std::printf("  repeat %d, %u thread%s: end to end %.3f s, FFT floor %.3f s, noise alone %.3f s\n", r + 1,
                  thread_counts[v], thread_counts[v] == 1 ? "" : "s", series[v].e2e.back(), series[v].floor.back(),
                  series[v].noise.back());
      std::fflush(stdout);
    }
  }

  std::printf("\n  %-16s %-32s %-32s %s\n", "medians", "end to end", "FFT floor", "ratio");
  double e2e_med[2] = {0, 0}, floor_med[2] = {0, 0};
  for (std::size_t v = 0; v < variants; ++v) {
    e2e_med[v] = median(series[v].e2e);
    floor_med[v] = median(series[v].floor);
    const std::string label = std::to_string(thread_counts[v]) + (thread_counts[v] == 1 ? " thread" : " threads");
    print_row(label.c_str(), e2e_med[v], floor_med[v], frames);
  }
  // The machine's speed drifts between repeats (other tenants): the ratio of each repeat's end to end
  // and its floor, timed seconds apart, and the ratio of the fastest of each, both vary less than
  // the ratio of medians taken at different moments.
  for (std::size_t v = 0; v < variants; ++v) {
    std::vector<double> paired;
    for (std::size_t r = 0; r < series[v].e2e.size(); ++r) paired.push_back(series[v].e2e[r] / series[v].floor[r]);
    const auto [low, high] = std::minmax_element(paired.begin(), paired.end());
    std::printf("  %u thread%s: ratio per repeat median %.2f x (%.2f-%.2f), fastest end to end / fastest floor %.2f x\n",
                thread_counts[v], thread_counts[v] == 1 ? "" : "s", median(paired), *low, *high,
                *std::min_element(series[v].e2e.begin(), series[v].e2e.end()) /
                    *std::min_element(series[v].floor.begin(), series[v].floor.end()));
  }
  std::printf("\n  per frame at 1 thread: end to end %.3f ms, FFT floor %.3f ms\n", 1e3 * e2e_med[0] / static_cast<double>(frames),
              1e3 * floor_med[0] / static_cast<double>(frames));
  for (std::size_t v = 0; v < variants; ++v) {
    const double noise_med = median(series[v].noise);
    std::printf("  %u thread%s: noise alone %.3f s = %.2f x the FFT floor (%.2f ns per complex sample per thread); "
                "end to end without it %.2f x the floor\n",
                thread_counts[v], thread_counts[v] == 1 ? "" : "s", noise_med, noise_med / floor_med[v],
                1e9 * noise_med * thread_counts[v] / static_cast<double>(frames * rows * columns),
                (e2e_med[v] - noise_med) / floor_med[v]);
  }
  if (variants == 2) {
    std::printf("  speed-up 1 -> %u threads: end to end %.2f x, FFT floor %.2f x\n", all, e2e_med[0] / e2e_med[1],
                floor_med[0] / floor_med[1]);
  }
  std::printf("  summarize (statistics) took at most %.1f ms of a run; target detections %zu of %zu\n",
              1e3 * summarize_s, detections, frames);
  std::printf("  load average  %s (at end)\n", load_average().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse_options(argc, argv));
  } catch (const InvalidParameter& e) {
    std::fprintf(stderr, "throughput: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "throughput: internal error: %s\n", e.what());
    return 1;
  }
}
