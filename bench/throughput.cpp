// Throughput of a radar workload (the bench scenario by default) against its FFT floor
// (docs/architecture.md, Contracts), all measured in one process, interleaved, so the ratios
// compare like with like on the same (possibly shared) machine.
//
// end to end: experiment::run_experiment (the code path of `fogradar run`: scenario check,
//   chamber, per frame scene paths, synthesis with noise and window, range and Doppler FFTs, CFAR,
//   grouping, peak interpolation, RCS) followed by experiment::summarize. Writing the result files
//   is NOT included.
// whole process (with --fogradar PATH): `PATH run --scenario FILE --out DIR --threads N` as a
//   child process: start-up, the run and the result files, all included. Its radar_samples.csv must
//   equal the in-process run's, bit for bit, or throughput stops: both time one computation.
// FFT floor: the fastest range + Doppler transform of the frame that FFTW does on this machine in
//   complex double at the same thread count, over the layouts below, with FFTW_MEASURE plans made
//   before any timing (docs/performance.md). Candidates, all in one FFTW planner (wisdom shared
//   within this process):
//     MEASURE rows + columns     range FFT of every chirp, Doppler FFT down the columns (one
//                                strided batch), both FFTW_MEASURE;
//     MEASURE rows + blocks      the same range plan, Doppler by radar::ColumnBlockFft with
//                                FFTW_MEASURE (columns gathered in L1-sized blocks);
//     MEASURE chirps + blocks    the range FFT by a one-chirp out-of-place FFTW_MEASURE plan
//                                from a copy of each chirp into its row, the same blocks;
//     MEASURE 2-D in place       fftw_plan_dft_2d, in place;
//     MEASURE 2-D out of place   fftw_plan_dft_2d from one buffer into another.
//   The floor at a thread count is the smallest median of these, and each repeat's ratio uses the
//   smallest candidate of that repeat.
// References, not floor candidates: the old floor (FFTW_ESTIMATE rows + one strided column batch,
//   what the chain did before ColumnBlockFft), the chain's plans before the shipped wisdom
//   (ESTIMATE rows in place + ESTIMATE column blocks) and the chain's plans now (the one-chirp
//   range plan and the column blocks, both FftPlanner::shipped_wisdom; the range plan from a copy
//   of each chirp back into its row, as RangeDopplerProcessor::transform_windowed). The chain
//   itself runs the range FFT chirp by chirp inside the noise pass (the same plan's bits), which
//   only end to end times.
// noise alone: the thermal-noise stage, which no FFT bounds: ComplexNormalGenerator over every
//   sample of the same number of frames, into a buffer per thread.
//
// Multi-threaded transforms: the frames are split into equal contiguous shares, each thread
// transforms its own buffer, the plans are shared (new-array execute). Every measurement runs at 1
// thread and at all hardware threads, repeated --repeats times, interleaved (all of them at 1
// thread, then all at all threads, then again), and medians with their ranges are reported. The
// transforms are timed per frame over up to --transform-seconds of frames (all frames of the
// scenario when they fit), so slow reference layouts do not dominate the run. Run (Release build):
//   ./build/release/bench/throughput [--scenario FILE] [--repeats N] [--measurements N]
//                                    [--fogradar PATH] [--transform-seconds S]
// bench/throughput_sizes.sh runs it for the three frame sizes of docs/performance.md.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "fogradar/core/complex_normal_generator.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/radar/fft.hpp"
#include "fogradar/radar/outputs.hpp"
#include "fogradar/radar/sensor.hpp"
#include "throughput_transforms.hpp"

#ifndef FOGRADAR_SOURCE_DIR
#error "FOGRADAR_SOURCE_DIR must be defined (bench/CMakeLists.txt)"
#endif

namespace {

using namespace fogradar;
using bench::Clock;
using bench::make_buffers;
using bench::rescale_exponent_for;
using bench::seconds_since;
using bench::ThreadBuffers;
using bench::time_transform;
using bench::Transforms;
using bench::Variant;

struct Options {
  std::string scenario_path = std::string(FOGRADAR_SOURCE_DIR) + "/examples/bench.toml";
  int repeats = 5;
  long measurements = -1;          // < 0: the scenario's measurements_per_step
  std::string fogradar_path;       // empty: no whole-process timing
  double transform_seconds = 1.0;  // time budget per transform measurement
};

[[noreturn]] void usage(const char* message) {
  std::fprintf(
      stderr,
      "throughput: %s\n"
      "usage: throughput [--scenario FILE] [--repeats N (>= 1, default 5)] "
      "[--measurements N (measurements per step, >= 1)] [--fogradar PATH (time `PATH run` as a "
      "process too)] [--transform-seconds S (> 0, default 1)]\n",
      message);
  std::exit(2);
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") usage("times a radar workload against its FFT floor");
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
      if (*end != '\0' || n < 1 || n > 1000000)
        usage("--measurements must be an integer in [1, 1000000]");
      o.measurements = n;
    } else if (arg == "--fogradar") {
      o.fogradar_path = value;
    } else if (arg == "--transform-seconds") {
      const double t = std::strtod(value.c_str(), &end);
      if (*end != '\0' || !(t > 0.0 && t <= 600.0))
        usage("--transform-seconds must be in (0, 600]");
      o.transform_seconds = t;
    } else {
      usage(("unknown option " + arg).c_str());
    }
  }
  if (!o.fogradar_path.empty() && o.measurements > 0) {
    usage("--fogradar runs the scenario file as it is: leave out --measurements");
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

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// "median (min-max)" of per-frame milliseconds.
std::string summary_ms(const std::vector<double>& seconds_per_frame) {
  const auto [low, high] = std::minmax_element(seconds_per_frame.begin(), seconds_per_frame.end());
  char text[96];
  std::snprintf(text, sizeof text, "%7.3f ms (%.3f-%.3f)", 1e3 * median(seconds_per_frame),
                1e3 * *low, 1e3 * *high);
  return text;
}

std::string summary_ratio(const std::vector<double>& ratios) {
  const auto [low, high] = std::minmax_element(ratios.begin(), ratios.end());
  char text[64];
  std::snprintf(text, sizeof text, "%5.2f x (%.2f-%.2f)", median(ratios), *low, *high);
  return text;
}

// --- End to end -------------------------------------------------------------------------------

struct EndToEnd {
  double seconds = 0.0;
  double summarize_seconds = 0.0;
  std::size_t detections = 0;  // printed, so nothing can be optimised away
  std::string samples_csv;     // the run's radar_samples.csv, formed after the timing
};

EndToEnd time_end_to_end(const experiment::Scenario& scenario, unsigned threads) {
  const Clock::time_point start = Clock::now();
  const experiment::ExperimentResult result =
      experiment::run_experiment(scenario, {.threads = threads, .progress = {}});
  const Clock::time_point summary_start = Clock::now();
  const experiment::ExperimentSummary summary = experiment::summarize(result);
  EndToEnd e;
  e.seconds = seconds_since(start);
  e.summarize_seconds = seconds_since(summary_start);
  const auto& radar_report = summary.of<radar::RadarReport>("radar");
  for (const radar::StepSummary& step : radar_report.summary().steps)
    e.detections += step.detections;
  e.samples_csv = radar::samples_csv(radar_report.steps());
  return e;
}

// The in-process run must be the computation `fogradar run` does: its radar_samples.csv (every
// measurement's RCS, SNR and detections, to the last bit) equal to the child's.
void require_same_samples(const std::filesystem::path& out_dir, const std::string& in_process) {
  std::ifstream file(out_dir / "radar_samples.csv", std::ios::binary);
  const std::string written{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (written != in_process) {
    std::fprintf(
        stderr,
        "throughput: the in-process run's radar_samples.csv differs from %s/radar_samples.csv: the "
        "two timings are not of the same computation\n",
        out_dir.c_str());
    std::exit(1);
  }
}

// `fogradar run` as a child process writing its files into `out_dir` (replaced each time).
double time_process(const Options& options, const std::filesystem::path& out_dir,
                    unsigned threads) {
  std::filesystem::remove_all(out_dir);
  const std::string command = "'" + options.fogradar_path + "' run --scenario '" +
                              options.scenario_path + "' --out '" + out_dir.string() +
                              "' --threads " + std::to_string(threads) + " > /dev/null 2>&1";
  const Clock::time_point start = Clock::now();
  const int status = std::system(command.c_str());
  const double seconds = seconds_since(start);
  if (status != 0) {
    std::fprintf(stderr, "throughput: `%s` failed (status %d)\n", command.c_str(), status);
    std::exit(1);
  }
  return seconds;
}

// --- Thermal noise alone ----------------------------------------------------------------------

// The stage the FFT floor does not bound: per frame, a ComplexNormalGenerator from a fresh stream
// adds CN(0, 1) samples to the whole frame (what synthesize_frame draws per frame), nothing else.
// Frames split into shares as for the transforms; each thread adds into its own buffer (the values
// grow only as the square root of the frame count).
double time_noise(std::vector<radar::ComplexVector>& buffers, std::size_t frames,
                  unsigned threads) {
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

// --- Run --------------------------------------------------------------------------------------

struct Series {
  std::vector<double> e2e, process, noise,
      floor;  // seconds per frame; floor: best candidate per repeat
};

int run(const Options& options) {
  experiment::Scenario scenario = experiment::load_scenario_file(options.scenario_path);
  if (options.measurements > 0)
    scenario.params<fogradar::radar::SensorParams>("radar").measurements_per_step =
        static_cast<std::size_t>(options.measurements);
  scenario.validate();
  const std::size_t steps = scenario.steps();
  const std::size_t frames =
      steps * scenario.params<fogradar::radar::SensorParams>("radar").measurements_per_step;
  const radar::RadarParams& radar_params = scenario.params<radar::SensorParams>("radar").radar;
  const std::size_t rows = radar_params.chirps_per_frame, columns = radar_params.samples_per_chirp;
  const unsigned all = std::max(1u, std::thread::hardware_concurrency());
  const auto frames_d = static_cast<double>(frames);

  std::printf("fogradar throughput: workload vs FFT floor (docs/performance.md)\n");
  std::printf("  scenario      %s\n", options.scenario_path.c_str());
  std::printf(
      "  frame         %zu chirps x %zu samples (complex double), %zu frames = %zu steps x %zu "
      "measurements\n",
      rows, columns, frames, steps,
      scenario.params<fogradar::radar::SensorParams>("radar").measurements_per_step);
  std::printf("  CPU           %s; %u hardware threads\n", cpu_model().c_str(), all);
  std::printf("  load average  %s (at start)\n", load_average().c_str());
  std::printf("  repeats       %d, interleaved; medians (min-max) reported\n", options.repeats);
  std::printf("  end to end    run_experiment + summarize, result files not written\n");
  if (!options.fogradar_path.empty())
    std::printf("  whole process %s run (files written)\n", options.fogradar_path.c_str());
  std::printf(
      "  FFT floor     fastest FFTW_MEASURE range + Doppler transform (candidates below)\n");
  std::printf("  noise alone   ComplexNormalGenerator over every frame's samples\n");
  std::fflush(stdout);

  const Clock::time_point planning = Clock::now();
  Transforms transforms(rows, columns, rescale_exponent_for(rows, columns));
  // The MEASURE wisdom made here does not reach the in-process end to end: the chain plans with
  // the shipped wisdom alone (FftPlanner::shipped_wisdom sets the process's wisdom aside while it
  // plans), as `fogradar run` does in a fresh process; require_same_samples checks it.
  std::printf(
      "  planning      %.2f s (FFTW_MEASURE, before any timing); Doppler blocks of %zu columns\n\n",
      seconds_since(planning), transforms.measure_blocks.block_columns());
  std::vector<ThreadBuffers> buffers;
  for (unsigned t = 0; t < all; ++t) buffers.push_back(make_buffers(rows * columns, 100 + t));
  std::vector<radar::ComplexVector> noise_buffers(all, radar::ComplexVector(rows * columns));
  // Calibration (also the warm-up): frames per timing within --transform-seconds, at least 16.
  for (Variant& v : transforms.variants) {
    const std::size_t probe = std::min<std::size_t>(frames, 8);
    const double per_frame = std::min(time_transform(transforms, v, buffers, probe, 1),
                                      time_transform(transforms, v, buffers, probe, 1));
    const auto fit = static_cast<std::size_t>(options.transform_seconds / per_frame);
    v.frames = std::min(frames, std::max<std::size_t>(16, fit));
  }

  const unsigned thread_counts[] = {1u, all};
  const std::size_t slots = all > 1 ? 2 : 1;
  Series series[2];
  std::size_t detections = 0;
  double summarize_s = 0.0;
  const std::filesystem::path out_dir = std::filesystem::temp_directory_path() /
                                        ("fogradar-throughput-" + std::to_string(::getpid()));
  for (int r = 0; r < options.repeats; ++r) {
    for (std::size_t slot = 0; slot < slots; ++slot) {
      const unsigned threads = thread_counts[slot];
      Series& s = series[slot];
      const EndToEnd e = time_end_to_end(scenario, threads);
      s.e2e.push_back(e.seconds / frames_d);
      detections = e.detections;
      summarize_s = std::max(summarize_s, e.summarize_seconds);
      if (!options.fogradar_path.empty()) {
        s.process.push_back(time_process(options, out_dir, threads) / frames_d);
        require_same_samples(out_dir, e.samples_csv);
      }
      double best = 0.0;
      for (Variant& v : transforms.variants) {
        const double t = time_transform(transforms, v, buffers, v.frames, threads);
        v.seconds_per_frame[slot].push_back(t);
        if (v.floor_candidate && (best == 0.0 || t < best)) best = t;
      }
      s.floor.push_back(best);
      s.noise.push_back(time_noise(noise_buffers, frames, threads) / frames_d);
      char process_text[64] = "";
      if (!s.process.empty()) {
        std::snprintf(process_text, sizeof process_text, ", whole process %.3f ms/frame",
                      1e3 * s.process.back());
      }
      std::printf(
          "  repeat %d, %u thread%s: end to end %.3f ms/frame, floor %.3f ms/frame (%.2f x)%s, "
          "load %s\n",
          r + 1, threads, threads == 1 ? "" : "s", 1e3 * s.e2e.back(), 1e3 * best,
          s.e2e.back() / best, process_text, load_average().c_str());
      std::fflush(stdout);
    }
  }
  std::filesystem::remove_all(out_dir);

  double floor_med[2] = {0, 0};
  for (std::size_t slot = 0; slot < slots; ++slot) {
    const unsigned threads = thread_counts[slot];
    const Series& s = series[slot];
    std::string floor_name;
    for (const Variant& v : transforms.variants) {
      const double m = median(v.seconds_per_frame[slot]);
      if (v.floor_candidate && (floor_med[slot] == 0.0 || m < floor_med[slot])) {
        floor_med[slot] = m;
        floor_name = v.name;
      }
    }
    std::printf(
        "\n  %u thread%s, per frame: median (min-max) over %d repeats; x = median / the floor's "
        "median\n",
        threads, threads == 1 ? "" : "s", options.repeats);
    for (const Variant& v : transforms.variants) {
      std::printf("    %-38s %s %6.2f x   (%zu frames per timing)%s\n", v.name.c_str(),
                  summary_ms(v.seconds_per_frame[slot]).c_str(),
                  median(v.seconds_per_frame[slot]) / floor_med[slot], v.frames,
                  v.name == floor_name ? "  <- floor" : "");
    }
    std::printf("    %-38s %s %6.2f x\n", "noise alone", summary_ms(s.noise).c_str(),
                median(s.noise) / floor_med[slot]);
    std::printf("    %-38s %s %6.2f x\n", "end to end (in process)", summary_ms(s.e2e).c_str(),
                median(s.e2e) / floor_med[slot]);
    std::vector<double> paired;
    for (std::size_t r = 0; r < s.e2e.size(); ++r) paired.push_back(s.e2e[r] / s.floor[r]);
    std::printf("    end to end / floor per repeat (best candidate of the repeat): %s\n",
                summary_ratio(paired).c_str());
    std::printf("    end to end without the noise: %.2f x the floor\n",
                (median(s.e2e) - median(s.noise)) / floor_med[slot]);
    if (!s.process.empty()) {
      std::vector<double> process_ratio;
      for (std::size_t r = 0; r < s.e2e.size(); ++r)
        process_ratio.push_back(s.process[r] / s.e2e[r]);
      std::printf("    %-38s %s %6.2f x; / end to end in process, per repeat: %s\n",
                  "whole process (fogradar run)", summary_ms(s.process).c_str(),
                  median(s.process) / floor_med[slot], summary_ratio(process_ratio).c_str());
    }
  }
  if (slots == 2) {
    std::vector<double> speedup;
    for (std::size_t r = 0; r < series[0].e2e.size(); ++r)
      speedup.push_back(series[0].e2e[r] / series[1].e2e[r]);
    std::printf("\n  speed-up 1 -> %u threads: end to end %.2f x (per repeat %s), floor %.2f x\n",
                all, median(series[0].e2e) / median(series[1].e2e), summary_ratio(speedup).c_str(),
                floor_med[0] / floor_med[1]);
  }
  std::printf(
      "  summarize (statistics) took at most %.1f ms of a run; target detections %zu of %zu\n",
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
