// Performance contract (docs/architecture.md, Contracts): no per-sample (indeed no per-frame) heap
// allocation once a workspace has served one frame. This file replaces the global operator
// new/delete of the test program with counting versions (malloc/free underneath); only the
// counts taken inside the test below are examined.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "chain_test_support.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/radar/measurement.hpp"

namespace {
std::atomic<long> g_allocations{0};

void* counted_allocate(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) { return counted_allocate(size); }
void* operator new[](std::size_t size) { return counted_allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace fogradar::radar {
namespace {

// After one warm-up measurement, 5 more measurements of the EVT (floor on) behind all four
// layers of the default fog, with thermal noise, phase noise and an ADC, allocate nothing.
TEST(Allocation, SteadyStateMeasurementDoesNotAllocate) {
  RadarParams p;
  p.phase_noise_rms_rad = 0.01;
  p.adc_bits = 14;
  const RadarChain chain(p);
  const propagation::Chamber chamber =
      test::make_chamber(test::paper_chamber_spec(), p.centre_frequency_hz);
  const auto all_on =
      propagation::first_layers_active(chamber.layer_count(), chamber.layer_count());
  Scene scene = evt_rear_scene();
  scene.surfaces = {coefficient_floor(-0.7)};
  MeasurementWorkspace ws = chain.make_workspace();
  Measurement m;
  RandomStream warm_up(1);
  chain.measure(scene, chamber, all_on, warm_up, ws, m);
  ASSERT_TRUE(m.target.has_value());
  // Give the detection lists room for more objects and detected cells than the warm-up had (a
  // measurement with more detections than any before it may grow a list once; that is amortised,
  // not per frame).
  m.detections.reserve(64);
  ws.estimation.detected_cells.reserve(4096);

  const long before = g_allocations.load();
  for (std::uint64_t i = 0; i < 5; ++i) {
    RandomStream rng(2, i);
    chain.measure(scene, chamber, all_on, rng, ws, m);
  }
  const long allocations = g_allocations.load() - before;
  std::printf("[ measured ] heap allocations in 5 steady-state measurements: %ld\n", allocations);
  EXPECT_EQ(allocations, 0);
}

}  // namespace
}  // namespace fogradar::radar
