#include "fogradar/experiment/memory.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <thread>

#include "fogradar/core/error.hpp"

namespace fogradar::experiment {
namespace {

double mib(std::size_t bytes) {
  return static_cast<double>(bytes) / static_cast<double>(std::size_t{1} << 20);
}

}  // namespace

std::size_t MemoryEstimate::total_bytes() const {
  std::size_t total = process_bytes;
  for (const Part& part : sensors) total += part.memory.bytes;
  return total;
}

unsigned worker_threads(unsigned requested, std::size_t items) {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::min<std::size_t>(requested == 0 ? hardware : requested, items));
}

MemoryEstimate estimate_peak_memory(const Scenario& scenario, unsigned requested_threads) {
  const sensor::Context context = scenario.context();
  // One pool takes every sensor's items (runner.cpp): the thread count follows from all of them.
  std::size_t items = 0;
  std::vector<std::shared_ptr<const sensor::ConfiguredSensor>> configured;
  for (const std::string& name : scenario.experiment.sensors) {
    configured.push_back(scenario.configure(name));
    items += context.steps * configured.back()->items_per_step();
  }
  MemoryEstimate e;
  e.threads = worker_threads(requested_threads, items);
  for (std::size_t i = 0; i < configured.size(); ++i) {
    e.sensors.push_back({scenario.experiment.sensors[i], configured[i]->memory(e.threads)});
  }
  return e;
}

std::size_t default_memory_limit_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_bytes = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_bytes <= 0) return SIZE_MAX;  // unknown: no default limit
  return static_cast<std::size_t>(pages) / 2 * static_cast<std::size_t>(page_bytes);
}

void require_memory_within(const Scenario& scenario, unsigned requested_threads,
                           std::size_t limit_bytes) {
  const MemoryEstimate estimate = estimate_peak_memory(scenario, requested_threads);
  if (estimate.total_bytes() <= limit_bytes) return;
  std::ostringstream out;
  out.precision(6);
  out << "the run needs an estimated " << mib(estimate.total_bytes()) << " MiB with --threads "
      << requested_threads << " (" << estimate.threads << " workers), more than the limit of "
      << mib(limit_bytes) << " MiB (--memory-limit-mib; default half the physical memory): ";
  std::string field = "--threads";
  std::size_t largest = 0;
  for (const MemoryEstimate::Part& part : estimate.sensors) {
    out << part.sensor << ' ' << mib(part.memory.bytes) << " MiB (" << part.memory.detail << "), ";
    if (part.memory.bytes > largest) {
      field = part.memory.key;
      largest = part.memory.bytes;
    }
  }
  out << mib(estimate.process_bytes) << " MiB for the process itself; reduce these";
  throw InvalidParameter(field, out.str());
}

}  // namespace fogradar::experiment
