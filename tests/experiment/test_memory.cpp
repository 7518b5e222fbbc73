// The peak-memory estimate (experiment/src/memory.cpp) against a byte count done by hand from the
// buffer sizes the chain keeps, and the refusal message naming the keys.
#include <gtest/gtest.h>

#include <complex>
#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/radar/costs.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/radar/sensor.hpp"
#include "sensors.hpp"

namespace fogradar::experiment {
namespace {

Scenario small_frame() {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"radar"};  // the radar's subject; test_multisensor.cpp runs all
  radar_of(s).radar.samples_per_chirp = 64;
  radar_of(s).radar.chirps_per_frame = 16;
  radar_of(s).clutter_scatterers_per_bin = 4;
  s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 3;
  s.experiment.max_active_layers = 4;  // 5 steps: 15 measurements
  return s;
}

// Hand count for S = 64 samples, C = 16 chirps, 4 scatterers per bin; premises: 16-byte complex,
// 8-byte double, 40-byte Tone (double, complex, double, 1-byte origin padded to 8).
TEST(MemoryEstimate, MatchesAHandCountForASmallFrame) {
  static_assert(sizeof(std::complex<double>) == 16 && sizeof(double) == 8);
  ASSERT_EQ(sizeof(radar::Tone), 40u);
  const Scenario s = small_frame();
  const radar::MemoryEstimate e = radar::memory_estimate(radar_of(s), 15);
  // frame 64*16*16 = 16384, mask 1024, chirp 64*16 = 1024; CFAR one row 6*64*8 = 3072, four rows
  // 4*5*64*8 = 10240 and their one-row workspace 3072; kernels 2*4*2*64*8 = 8192, Doppler columns
  // 4*16*16 = 1024, peak search 4*64*8 = 2048, tables 8*80*8 = 5120; Doppler block 32*16*16 = 8192;
  // tones 2*40*(4*64 + 5*41 + 64 + 1) = 42080 (clutter, the EVT's paths in a room of five planes,
  // the objects and the back wall). Sum 101472.
  EXPECT_EQ(e.per_thread_bytes, 101472u);
  // windows (3*64 + 16)*8 = 1664; spectra 16*82*16 = 20992; plans 2*80*16 = 2560.
  EXPECT_EQ(e.shared_bytes, 1664u + 20992u + 2560u);
  // Records: per measurement the record and a 128-byte CSV row, and 4 + ceil(2 x 1e-6 x 1024) = 5
  // detections of their own size and a CSV row each.
  const std::size_t record_bytes =
      sizeof(radar::MeasurementRecord) + 128 + 5 * (sizeof(radar::DetectionRecord) + 128);
  EXPECT_EQ(e.records_bytes, 15 * record_bytes);
  // The run's estimate: two workers' frames, the shared part, the records and the process (16 MiB).
  const MemoryEstimate run = estimate_peak_memory(s, 2);
  EXPECT_EQ(run.threads, 2u);
  ASSERT_EQ(run.sensors.size(), 1u);
  EXPECT_EQ(run.total_bytes(),
            2 * 101472u + 1664u + 20992u + 2560u + 16777216u + 15 * record_bytes);
}

TEST(MemoryEstimate, UsesTheThreadsTheRunStarts) {
  EXPECT_EQ(estimate_peak_memory(small_frame(), 100).threads, 15u);  // one per measurement at most
  EXPECT_EQ(worker_threads(100, 15), 15u);
  EXPECT_EQ(worker_threads(3, 15), 3u);
  EXPECT_GE(worker_threads(0, 15), 1u);
}

TEST(MemoryEstimate, TheFrameDominatesALargeRun) {
  Scenario s = small_frame();
  radar_of(s).radar.sample_rate_hz = 1.28e9;  // 65536 samples fill the paper's 51.2 us chirp
  radar_of(s).radar.samples_per_chirp = 65536;
  radar_of(s).radar.chirps_per_frame = 16384;
  const MemoryEstimate e = estimate_peak_memory(s, 1);
  const double frame_bytes = 65536.0 * 16384.0 * 17.0;  // complex frame plus 1-byte mask per cell
  EXPECT_GT(static_cast<double>(e.total_bytes()), frame_bytes);
  EXPECT_LT(static_cast<double>(e.total_bytes()), 1.01 * frame_bytes);
}

TEST(MemoryEstimate, RefusalNamesTheKeysAndTheLimit) {
  const Scenario s = small_frame();
  EXPECT_NO_THROW(require_memory_within(s, 2, estimate_peak_memory(s, 2).total_bytes()));
  try {
    require_memory_within(s, 2, estimate_peak_memory(s, 2).total_bytes() - 1);
    FAIL() << "no refusal one byte below the estimate";
  } catch (const InvalidParameter& e) {
    const std::string message = e.what();
    for (const char* key :
         {"radar.samples_per_chirp = 64", "radar.chirps_per_frame = 16",
          "radar.measurements_per_step = 3", "--threads 2", "--memory-limit-mib"}) {
      EXPECT_NE(message.find(key), std::string::npos) << key << " missing from: " << message;
    }
  }
}

// The lidar's and the camera's parts are their modules' own estimates, counted once each, and their
// items count for the threads; a refusal driven by the lidar names its keys and is filed under it.
TEST(MemoryEstimate, AddsTheLidarAndTheCamera) {
  Scenario s = small_frame();
  s.experiment.sensors = {"radar", "lidar", "camera"};
  const MemoryEstimate all = estimate_peak_memory(s, 100);
  const std::size_t items = 5 * (3 + lidar_of(s).scans_per_step + camera_of(s).frames_per_step);
  EXPECT_EQ(all.threads, worker_threads(100, items));
  const radar::MemoryEstimate radar_part = radar::memory_estimate(radar_of(s), 15);
  ASSERT_EQ(all.sensors.size(), 3u);
  EXPECT_EQ(all.sensors[0].memory.bytes, all.threads * radar_part.per_thread_bytes +
                                             radar_part.shared_bytes + radar_part.records_bytes);
  EXPECT_EQ(all.sensors[1].memory.bytes, lidar::lidar_memory_bytes(lidar_of(s), 5, all.threads));
  EXPECT_EQ(all.sensors[2].memory.bytes, camera::memory_bytes(camera_of(s), 5));
  EXPECT_EQ(all.total_bytes(), all.sensors[0].memory.bytes + all.sensors[1].memory.bytes +
                                   all.sensors[2].memory.bytes + process_baseline_bytes);
  lidar_of(s).scans_per_step = 100000;
  try {
    require_memory_within(s, 1, estimate_peak_memory(s, 1).total_bytes() - 1);
    FAIL() << "no refusal one byte below the estimate";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "lidar.scans_per_step") << e.what();
    const std::string message = e.what();
    for (const char* key : {"lidar.scans_per_step = 100000", "lidar.field_of_view_deg",
                            "camera.frames_per_step", "radar.samples_per_chirp = 64"}) {
      EXPECT_NE(message.find(key), std::string::npos) << key << " missing from: " << message;
    }
  }
}

TEST(MemoryEstimate, DefaultLimitIsHalfThePhysicalMemory) {
  const std::size_t limit = default_memory_limit_bytes();
  EXPECT_GT(limit, std::size_t{64} << 20);  // any machine that builds fogradar has 128 MiB
}

}  // namespace
}  // namespace fogradar::experiment
