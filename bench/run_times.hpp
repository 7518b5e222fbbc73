// What a Google Benchmark run reported, per benchmark: the median of its repetitions when it ran
// repeated (--benchmark_repetitions), else the mean of its runs. Shared by the ratio reporters of
// chain_bench and lidar_bench, which print each benchmark's time over a reference benchmark's.
#pragma once

#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

namespace fogradar::bench {

class RunTimes {
 public:
  enum class Clock { real, cpu };
  explicit RunTimes(Clock clock) : clock_(clock) {}

  // Keys are "function_name" or "function_name/args".
  void add(const std::vector<benchmark::BenchmarkReporter::Run>& runs) {
    for (const benchmark::BenchmarkReporter::Run& run : runs) {
      if (run.error_occurred) continue;
      const std::string& args = run.run_name.args;
      Entry& entry = entries_[run.run_name.function_name + (args.empty() ? "" : "/" + args)];
      const double seconds =
          (clock_ == Clock::real ? run.GetAdjustedRealTime() : run.GetAdjustedCPUTime()) *
          unit_seconds(run.time_unit);
      if (run.run_type == benchmark::BenchmarkReporter::Run::RT_Aggregate) {
        if (run.aggregate_name == "median") entry.median_s = seconds;
      } else {
        entry.sum_s += seconds;
        entry.count += 1;
      }
    }
  }

  // Seconds per iteration of each benchmark, by key.
  std::map<std::string, double> seconds() const {
    std::map<std::string, double> out;
    for (const auto& [key, entry] : entries_)
      out[key] = entry.median_s >= 0.0 ? entry.median_s : entry.sum_s / entry.count;
    return out;
  }

 private:
  struct Entry {
    double median_s = -1.0;
    double sum_s = 0.0;
    int count = 0;
  };
  static double unit_seconds(benchmark::TimeUnit unit) {
    return unit == benchmark::kNanosecond    ? 1e-9
           : unit == benchmark::kMicrosecond ? 1e-6
           : unit == benchmark::kMillisecond ? 1e-3
                                             : 1.0;
  }
  Clock clock_;
  std::map<std::string, Entry> entries_;
};

}  // namespace fogradar::bench
