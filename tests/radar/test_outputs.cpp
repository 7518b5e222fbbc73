// The radar's result files: every number in radar_samples.csv and radar_summary.csv reads back to
// exactly the double the run computed, and radar_summary.csv carries every per-step field of
// radar_summary.json with the same values.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/radar/outputs.hpp"
#include "fogradar/radar/sensor.hpp"
#include "radar_sensor.hpp"

namespace fogradar::experiment {
namespace {

using radar::MeasurementRecord;
using radar::StepResult;

// A small run with everything the files can hold: target detections and misses of a weak target
// (-55 dBsm, about 10 dB SNR), noise false alarms and gate associations (P_fa = 1e-2), fog
// detections (a dense 0.5 mm fog), intervals unbounded for want of detections.
Scenario mixed_scenario() {
  Scenario s = paper_scenario();
  s.experiment.sensors = {"radar"};  // the radar's subject; test_multisensor.cpp runs all
  radar_of(s).radar.chirps_per_frame = 16;
  radar_of(s).radar.cfar.false_alarm_probability = 1e-2;
  s.params<fogradar::radar::SensorParams>("radar").measurements_per_step = 8;
  radar_of(s).target.rcs_dbsm = -55.0;
  s.fog.density = propagation::LiquidWaterContent{100.0};
  s.fog.droplets = propagation::Monodisperse{0.5e-3};
  return s;
}

// Fields between separators; a trailing separator ends an empty last field.
std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

// Lines of a file that ends with a newline.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines = split(text, '\n');
  EXPECT_TRUE(!lines.empty() && lines.back().empty());
  lines.pop_back();
  return lines;
}

// The double a field reads back to with std::from_chars (the library's own writer uses to_chars);
// "" is NaN (a value that does not exist).
double parse(const std::string& field) {
  if (field.empty()) return std::nan("");
  double value = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  EXPECT_EQ(error, std::errc()) << field;
  EXPECT_EQ(end, field.data() + field.size()) << field;
  return value;
}

// Same double (NaN equal to NaN); JSON null stands for NaN or an infinite bound.
void expect_same(double csv, const nlohmann::json& json, const std::string& what) {
  if (json.is_null()) {
    EXPECT_TRUE(std::isnan(csv) || std::isinf(csv)) << what << ": " << csv;
  } else {
    EXPECT_EQ(csv, json.get<double>()) << what;
  }
}

class Outputs : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    summary_ = new ExperimentSummary(summarize(run_experiment(mixed_scenario())));
  }
  static void TearDownTestSuite() { delete summary_; }
  static const std::vector<StepResult>& steps() { return radar_report(*summary_).steps(); }
  static const radar::RadarSummary& radar_summary() { return radar_report(*summary_).summary(); }
  static ExperimentSummary* summary_;
};
ExperimentSummary* Outputs::summary_ = nullptr;

TEST_F(Outputs, TheRunHoldsEveryKindOfRecord) {
  std::size_t detected = 0, false_associations = 0, fog = 0, false_alarms = 0, missed = 0;
  for (const StepResult& step : steps()) {
    for (const MeasurementRecord& r : step.records) {
      detected += r.detected ? 1 : 0;
      false_associations += r.associated && !r.detected ? 1 : 0;
      missed += r.associated ? 0 : 1;
      fog += r.fog_detections;
      false_alarms += r.false_alarms;
    }
  }
  EXPECT_GT(detected, 0u);
  EXPECT_GT(false_associations, 0u);
  EXPECT_GT(fog, 0u);
  EXPECT_GT(false_alarms, 0u);
  EXPECT_GT(missed, 0u);
  std::printf(
      "[ measured ] %zu target detections, %zu false associations, %zu without association, "
      "%zu fog detections, %zu false alarms\n",
      detected, false_associations, missed, fog, false_alarms);
}

// radar_samples.csv: one row per measurement; range, RCS, SNR and velocity of the associated
// detection read back to exactly the record's doubles, the origin is the associated detection's,
// counts are exact.
TEST_F(Outputs, SamplesCsvNumbersReadBackExactly) {
  const std::vector<std::string> lines = lines_of(radar::samples_csv(steps()));
  ASSERT_EQ(lines.front(),
            "active_layers,item,detected,range_m,rcs_dbsm,snr_db,origin,fog_detections,"
            "false_alarms,velocity_m_per_s");
  std::size_t row = 1;
  for (const StepResult& step : steps()) {
    for (std::size_t i = 0; i < step.records.size(); ++i, ++row) {
      const MeasurementRecord& r = step.records[i];
      ASSERT_LT(row, lines.size());
      const std::vector<std::string> f = split(lines[row], ',');
      ASSERT_EQ(f.size(), 10u) << lines[row];
      EXPECT_EQ(f[0], std::to_string(step.active_layers));
      EXPECT_EQ(f[1], std::to_string(i));
      EXPECT_EQ(f[2], r.detected ? "1" : "0");
      if (r.associated) {
        EXPECT_EQ(parse(f[3]), r.range_m) << lines[row];
        EXPECT_EQ(parse(f[4]), r.rcs_dbsm) << lines[row];
        EXPECT_EQ(parse(f[5]), r.snr_db) << lines[row];
        EXPECT_EQ(f[6], radar::to_string(r.associated_origin));
        EXPECT_EQ(parse(f[9]), r.velocity_m_per_s) << lines[row];
      } else {
        EXPECT_EQ(f[3] + f[4] + f[5] + f[6] + f[9], "") << lines[row];
      }
      EXPECT_EQ(f[7], std::to_string(r.fog_detections));
      EXPECT_EQ(f[8], std::to_string(r.false_alarms));
    }
  }
  EXPECT_EQ(row, lines.size());
}

// radar_detections.csv: every detection of every measurement. Per frame its fog- and noise-origin
// rows count what radar_samples.csv's fog_detections and false_alarms say; its in-gate rows are
// those within the association gate (0.5 m) of the chamber's 10 m target range; the one marked
// associated is radar_samples.csv's detection, the strongest in the gate (received power).
TEST_F(Outputs, DetectionsCsvHoldsEveryDetectionOfEveryFrame) {
  const std::vector<std::string> lines = lines_of(radar::detections_csv(steps()));
  ASSERT_EQ(lines.front(),
            "active_layers,item,range_m,velocity_m_per_s,power_dbm,snr_db,rcs_dbsm,origin,in_gate,"
            "associated,layer");
  struct Frame {
    std::size_t fog = 0, noise = 0, associated = 0;
    double strongest_in_gate_dbm = -1e300;
    std::vector<std::string> associated_row;
  };
  std::map<std::pair<std::size_t, std::size_t>, Frame> frames;
  for (std::size_t row = 1; row < lines.size(); ++row) {
    const std::vector<std::string> f = split(lines[row], ',');
    ASSERT_EQ(f.size(), 11u) << lines[row];
    EXPECT_EQ(f[10] == "-1", f[7] != "fog") << lines[row];
    Frame& frame = frames[{std::stoul(f[0]), std::stoul(f[1])}];
    frame.fog += f[7] == "fog" ? 1 : 0;
    frame.noise += f[7] == "noise" ? 1 : 0;
    EXPECT_EQ(f[8] == "1", std::abs(parse(f[2]) - 10.0) <= 0.5) << lines[row];
    if (f[8] == "1")
      frame.strongest_in_gate_dbm = std::max(frame.strongest_in_gate_dbm, parse(f[4]));
    if (f[9] == "1") {
      ++frame.associated;
      frame.associated_row = f;
    }
  }
  std::size_t checked = 0;
  for (const StepResult& step : steps()) {
    for (std::size_t i = 0; i < step.records.size(); ++i) {
      const MeasurementRecord& r = step.records[i];
      const Frame& frame = frames[{step.active_layers, i}];
      EXPECT_EQ(frame.fog, r.fog_detections);
      EXPECT_EQ(frame.noise, r.false_alarms);
      ASSERT_EQ(frame.associated, r.associated ? 1u : 0u);
      if (!r.associated) continue;
      EXPECT_EQ(parse(frame.associated_row[2]), r.range_m);
      EXPECT_EQ(parse(frame.associated_row[6]), r.rcs_dbsm);
      EXPECT_EQ(frame.associated_row[7], radar::to_string(r.associated_origin));
      EXPECT_EQ(parse(frame.associated_row[4]), frame.strongest_in_gate_dbm);
      ++checked;
    }
  }
  EXPECT_GT(checked, 0u);
}

// radar_summary.csv against radar_summary.json, step by step: the same fields (the JSON interval
// median_shift_ci95_db = [low, high] is the CSV's median_shift_ci95_low_db and _high_db, the JSON
// outlier array the CSV's ';'-list) with the same doubles, and no CSV column without a JSON field.
TEST_F(Outputs, SummaryCsvHasEveryPerStepFieldOfSummaryJson) {
  const nlohmann::json json = radar::summary_json(radar_summary());
  const std::vector<std::string> lines = lines_of(radar::step_table(radar_summary()).csv());
  const std::vector<std::string> header = split(lines.front(), ',');
  const nlohmann::json& steps = json.at("steps");
  ASSERT_EQ(lines.size(), steps.size() + 1);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const std::vector<std::string> fields = split(lines[k + 1], ',');
    ASSERT_EQ(fields.size(), header.size()) << lines[k + 1];
    std::map<std::string, std::string> csv;
    for (std::size_t c = 0; c < header.size(); ++c) csv[header[c]] = fields[c];
    std::size_t matched = 0;
    for (const auto& [key, value] : steps[k].items()) {
      if (key == "outliers") {
        const std::vector<std::string> listed =
            csv.at(key).empty() ? std::vector<std::string>{} : split(csv.at(key), ';');
        ASSERT_EQ(listed.size(), value.size()) << k;
        for (std::size_t i = 0; i < listed.size(); ++i)
          EXPECT_EQ(parse(listed[i]), value[i].get<double>());
        ++matched;
      } else if (value.is_array()) {
        ASSERT_EQ(value.size(), 2u) << key;
        const std::string stem = key.substr(0, key.size() - 3);  // without "_db"
        ASSERT_TRUE(csv.contains(stem + "_low_db") && csv.contains(stem + "_high_db")) << key;
        expect_same(parse(csv.at(stem + "_low_db")), value[0], key + " low");
        expect_same(parse(csv.at(stem + "_high_db")), value[1], key + " high");
        matched += 2;
      } else {
        ASSERT_TRUE(csv.contains(key)) << "radar_summary.csv lacks " << key;
        expect_same(parse(csv.at(key)), value, key);
        ++matched;
      }
    }
    EXPECT_EQ(matched, header.size()) << "radar_summary.csv has columns radar_summary.json lacks";
  }
}

}  // namespace
}  // namespace fogradar::experiment
