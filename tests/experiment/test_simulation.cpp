// A scenario's sensors made once (experiment::Simulation): runs repeat bit for bit, and an item
// measured alone (ItemRun) is the run's item, with its raw data kept in memory (RawCapture).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/capture.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/radar/sensor.hpp"
#include "sensors.hpp"

namespace fogradar::experiment {
namespace {

Scenario small_scenario() {
  Scenario s = paper_scenario();
  radar_of(s).radar.chirps_per_frame = 16;
  s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 6;
  lidar_of(s).scans_per_step = 3;
  camera_of(s).frames_per_step = 2;
  return s;
}

std::size_t kind_index(const ItemRun& run, std::string_view name) {
  const std::vector<sensor::RawKind>& kinds = run.raw_kinds();
  const auto it = std::find_if(kinds.begin(), kinds.end(),
                               [name](const sensor::RawKind& k) { return k.name == name; });
  EXPECT_NE(it, kinds.end()) << name;
  return static_cast<std::size_t>(it - kinds.begin());
}

TEST(Simulation, RunsRepeatBitForBit) {
  const Simulation simulation(small_scenario());
  const ExperimentResult first = simulation.run({.threads = 2, .progress = {}});
  const ExperimentResult second = simulation.run({.threads = 1, .progress = {}});
  const auto first_report = radar_run(first), second_report = radar_run(second);
  const std::vector<radar::StepResult>& a = first_report->steps();
  const std::vector<radar::StepResult>& b = second_report->steps();
  ASSERT_EQ(a.size(), 5u);
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t i = 0; i < a[k].records.size(); ++i) {
      EXPECT_EQ(a[k].records[i].rcs_dbsm, b[k].records[i].rcs_dbsm);
      EXPECT_EQ(a[k].records[i].detections.size(), b[k].records[i].detections.size());
    }
  }
  // The two runs' records are their own: the sensor is shared, the storage is not.
  EXPECT_NE(&a, &b);
  EXPECT_EQ(&first_report->chain(), &second_report->chain());
}

TEST(Simulation, AnItemAloneIsTheRunsItemWithItsRawData) {
  const Simulation simulation(small_scenario());
  const ExperimentResult result = simulation.run();
  const auto report = radar_run(result);
  const std::vector<radar::StepResult>& steps = report->steps();
  ItemRun items(simulation, "radar");
  EXPECT_EQ(items.steps(), 5u);
  EXPECT_EQ(items.items_per_step(), 6u);
  const std::size_t detections = kind_index(items, "detections");
  for (const auto& [step, index] :
       {std::pair{4ul, 5ul}, std::pair{0ul, 0ul}, std::pair{2ul, 3ul}}) {
    RawCapture capture(items.raw_kinds(), {detections});
    items.measure(step, index, &capture);
    const radar::MeasurementRecord& record = steps[step].records[index];
    const RawCapture::Kept& kept = capture.kept().front();
    ASSERT_EQ(kept.rows, record.detections.size());
    for (std::size_t r = 0; r < kept.rows; ++r) {
      const radar::DetectionRecord& d = record.detections[r];
      EXPECT_EQ(kept.columns[0].numbers[r], d.range_m);                 // range_m
      EXPECT_EQ(kept.columns[4].numbers[r], d.rcs_dbsm);                // rcs_dbsm
      EXPECT_EQ(kept.columns[5].codes[r], static_cast<int>(d.origin));  // origin, an enumeration
      EXPECT_EQ(kept.columns[7].integers[r], d.associated ? 1 : 0);     // associated, an integer
    }
  }
}

TEST(Simulation, KeepsTheBeatsPartsApartWithoutChangingIt) {
  const Simulation simulation(small_scenario());
  ItemRun items(simulation, "radar");
  const std::size_t beat = kind_index(items, "beat"), signal = kind_index(items, "signal"),
                    noise = kind_index(items, "noise");
  RawCapture alone(items.raw_kinds(), {beat});
  items.measure(3, 2, &alone);
  RawCapture parts(items.raw_kinds(), {beat, signal, noise});
  items.measure(3, 2, &parts);
  const std::vector<std::complex<double>>& b = parts.kept()[0].complex128;
  EXPECT_EQ(b, alone.kept()[0].complex128);
  for (std::size_t n = 0; n < b.size(); ++n) {
    ASSERT_EQ(parts.kept()[1].complex128[n] + parts.kept()[2].complex128[n], b[n]) << n;
  }
}

TEST(Simulation, RefusesItemsAndSensorsOutsideTheScenario) {
  Scenario s = small_scenario();
  s.experiment.sensors = {"lidar"};
  const Simulation simulation(s);
  ItemRun lidar(simulation, "lidar");
  const auto field_of = [&](std::size_t step, std::size_t index) {
    try {
      lidar.measure(step, index, nullptr);
    } catch (const InvalidParameter& e) {
      return e.field();
    }
    return std::string("none");
  };
  EXPECT_EQ(field_of(5, 0), "step");
  EXPECT_EQ(field_of(0, 3), "index");
  EXPECT_EQ(field_of(4, 2), "none");
  try {
    ItemRun radar(simulation, "radar");
    FAIL() << "radar does not run";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "sensor");
    EXPECT_NE(std::string(e.what()).find("experiment.sensors: lidar"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace fogradar::experiment
