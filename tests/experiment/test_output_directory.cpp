// OutputDirectory (docs/scenario.md, Results): the result set is replaced whole or not at all, a
// directory holding anything but result files is refused, one run at a time holds a directory, and
// nothing but the result directory is left beside it. The files are plain strings: the rendering is
// test_outputs.cpp's subject.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/outputs.hpp"

namespace fogradar::experiment {
namespace {

namespace fs = std::filesystem;
using Files = std::vector<sensor::ResultFile>;

Files result_set(const std::string& tag) {
  return {{"radar_samples.csv", "samples " + tag},
          {"radar_summary.csv", "summary " + tag},
          {"summary.json", "{\"" + tag + "\": 1}"},
          {"radar_rcs_boxplot.svg", "<svg>" + tag + "</svg>"},
          {"scenario.toml", "# " + tag}};
}

// The result set of the paper scenario's sensors.
OutputDirectory output_directory(const fs::path& dir) { return OutputDirectory(dir); }

// Every entry of `dir` with its content ("<dir>" for a directory).
std::map<std::string, std::string> listing(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    std::ifstream file(entry.path(), std::ios::binary);
    out[entry.path().filename().string()] =
        entry.is_directory() ? "<dir>" : std::string(std::istreambuf_iterator<char>(file), {});
  }
  return out;
}

// A set's listing: its files and its record of their names, sorted.
std::map<std::string, std::string> as_listing(const Files& files) {
  std::map<std::string, std::string> out;
  for (const sensor::ResultFile& file : files) out[file.name] = file.content;
  std::string record;
  for (const auto& [name, content] : out) record += name + '\n';
  out[std::string(record_file_name)] = record;
  return out;
}

// The refusal of `dir` as an output directory names --out and, as the reason, `file`.
void expect_refused_for(const fs::path& dir, const std::string& file) {
  try {
    OutputDirectory refused(dir);
    ADD_FAILURE() << "accepted a directory holding the user's " << file;
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "--out") << file;
    EXPECT_NE(std::string(e.what()).find("'" + file + "' is not one"), std::string::npos)
        << e.what();
  }
}

class OutputDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // The process id keeps two builds' test runs on one machine apart.
    parent_ = fs::temp_directory_path() /
              ("fogradar-output-directory-" + std::to_string(::getpid()) + "-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(parent_);
    fs::create_directories(parent_);
  }
  void TearDown() override { fs::remove_all(parent_); }
  // Only the result directory stands in the parent: no staging directory, no lock file.
  void expect_only_result_directory() const {
    const std::map<std::string, std::string> entries = listing(parent_);
    EXPECT_EQ(entries.size(), 1u);
    EXPECT_TRUE(entries.contains("out"));
  }
  fs::path parent_;
};

TEST_F(OutputDirectoryTest, CreatesThenReplacesTheWholeSet) {
  const fs::path dir = parent_ / "out";
  EXPECT_TRUE(output_directory(dir).replace(result_set("first")));
  EXPECT_EQ(listing(dir), as_listing(result_set("first")));
  // A second set with one file fewer: the replacement leaves no file of the first behind.
  Files second = result_set("second");
  second.pop_back();
  EXPECT_TRUE(output_directory(dir).replace(second));
  EXPECT_EQ(listing(dir), as_listing(second));
  expect_only_result_directory();
}

TEST_F(OutputDirectoryTest, AnAbandonedReplacementLeavesThePreviousSet) {
  const fs::path dir = parent_ / "out";
  output_directory(dir).replace(result_set("first"));
  EXPECT_FALSE(output_directory(dir).replace(result_set("second"), [] { return true; }));
  EXPECT_EQ(listing(dir), as_listing(result_set("first")));
  expect_only_result_directory();
}

TEST_F(OutputDirectoryTest, AFailedWriteLeavesThePreviousSet) {
  const fs::path dir = parent_ / "out";
  output_directory(dir).replace(result_set("first"));
  Files bad = result_set("second");
  bad.emplace_back("missing/sub.csv",
                   "x");  // a name in a directory that does not exist: open fails
  EXPECT_THROW(output_directory(dir).replace(bad), InvalidParameter);
  EXPECT_EQ(listing(dir), as_listing(result_set("first")));
  expect_only_result_directory();
}

TEST_F(OutputDirectoryTest, RefusesADirectoryHoldingOtherFiles) {
  const fs::path dir = parent_ / "out";
  fs::create_directories(dir / "samples.csv");  // a result file's name, but a directory
  std::ofstream(dir / "notes.txt") << "mine";
  try {
    OutputDirectory refused(dir);
    FAIL() << "a directory with a user's files was accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.field(), "--out");
  }
  EXPECT_EQ(listing(dir),
            (std::map<std::string, std::string>{{"notes.txt", "mine"}, {"samples.csv", "<dir>"}}));
  expect_only_result_directory();
}

// A file the user puts into the directory while the run measures is not replaced away with the
// previous set: the replacement is refused and both stay.
TEST_F(OutputDirectoryTest, AFileAddedDuringTheRunKeepsThePreviousSet) {
  const fs::path dir = parent_ / "out";
  output_directory(dir).replace(result_set("first"));
  OutputDirectory second(dir);
  std::ofstream(dir / "notes.txt") << "mine";
  EXPECT_THROW(second.replace(result_set("second")), InvalidParameter);
  std::map<std::string, std::string> expected = as_listing(result_set("first"));
  expected["notes.txt"] = "mine";
  EXPECT_EQ(listing(dir), expected);
}

TEST_F(OutputDirectoryTest, OneHolderAtATime) {
  const fs::path dir = parent_ / "out";
  {
    OutputDirectory first(dir);
    try {
      OutputDirectory second(dir);
      FAIL() << "two holders of one directory";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.field(), "--out");
    }
    EXPECT_TRUE(first.replace(result_set("first")));
  }
  // Released: the next one takes it.
  EXPECT_TRUE(output_directory(dir).replace(result_set("second")));
  EXPECT_EQ(listing(dir), as_listing(result_set("second")));
  expect_only_result_directory();
}

// A set written by a run of other sensors (every sensor's file names as docs/scenario.md lists
// them) is an earlier result set: a radar-only run replaces it whole, leaving none of its files; a
// file its record does not list is still refused.
TEST_F(OutputDirectoryTest, ReplacesAnEarlierSetOfAnySensors) {
  const fs::path dir = parent_ / "out";
  Files every = {{"camera_roi_0.pgm", "P5"},
                 {"camera_roi_12.pgm", "P5"}};  // camera.write_roi_images
  for (const char* name :
       {"radar_samples.csv", "radar_summary.csv", "radar_summary.json", "radar_rcs_boxplot.svg",
        "radar_origins.svg", "lidar_echoes.csv", "lidar_summary.csv", "lidar_summary.json",
        "lidar_intensity_boxplot.svg", "lidar_scans.svg", "camera_histograms.csv",
        "camera_summary.csv", "camera_summary.json", "camera_histograms.svg", "summary.json",
        "scenario.toml", "benchmark.svg"}) {
    every.push_back({name, "earlier " + std::string(name)});
  }
  ASSERT_TRUE(output_directory(dir).replace(every));
  EXPECT_TRUE(output_directory(dir).replace(result_set("radar only")));
  EXPECT_EQ(listing(dir), as_listing(result_set("radar only")));
  for (const char* foreign : {"lidar_notes.csv", "camera_roi_x.pgm", "camera_roi_.pgm"}) {
    std::ofstream(dir / foreign) << "mine";
    EXPECT_THROW(OutputDirectory refused(dir), InvalidParameter) << foreign;
    fs::remove(dir / foreign);
  }
  expect_only_result_directory();
}

// A file the user puts beside a set under a name a sensor could have written (the camera's ROI
// images, camera_roi_<step>.pgm, in a set written with camera.write_roi_images off, or in forms the
// camera never writes) is not the set's: its record does not list it. The directory is refused
// naming the file, before the run and again before the swap, and the file stays.
TEST_F(OutputDirectoryTest, AUsersFileUnderAResultNameIsNeverDeleted) {
  const fs::path dir = parent_ / "out";
  ASSERT_TRUE(output_directory(dir).replace(result_set("first")));
  for (const std::string mine : {"camera_roi_1.pgm", "camera_roi_01.pgm", "camera_roi_999.pgm"}) {
    std::ofstream(dir / mine) << "mine";
    expect_refused_for(dir, mine);
    // Put in while the run measured: the swap is refused.
    fs::remove(dir / mine);
    OutputDirectory second(dir);
    std::ofstream(dir / mine) << "mine";
    EXPECT_THROW(second.replace(result_set("second")), InvalidParameter) << mine;
    std::map<std::string, std::string> expected = as_listing(result_set("first"));
    expected[mine] = "mine";
    EXPECT_EQ(listing(dir), expected) << mine;
    fs::remove(dir / mine);
  }
  // A record that is not a file of the set's is the user's.
  fs::remove(dir / record_file_name);
  fs::create_directory(dir / record_file_name);
  EXPECT_THROW(output_directory(dir), InvalidParameter);
  EXPECT_TRUE(fs::is_directory(dir / record_file_name));
}

// The ROI images a previous run wrote are its set's, and go with it: replaced by the next run's,
// or by none.
TEST_F(OutputDirectoryTest, APreviousRunsRoiImagesAreReplaced) {
  const fs::path dir = parent_ / "out";
  Files with_images = result_set("first");
  with_images.push_back({"camera_roi_0.pgm", "P5 first 0"});
  with_images.push_back({"camera_roi_12.pgm", "P5 first 12"});
  ASSERT_TRUE(output_directory(dir).replace(with_images));
  Files other_images = result_set("second");
  other_images.push_back({"camera_roi_1.pgm", "P5 second 1"});
  EXPECT_TRUE(output_directory(dir).replace(other_images));
  EXPECT_EQ(listing(dir), as_listing(other_images));
  EXPECT_TRUE(output_directory(dir).replace(result_set("third")));
  EXPECT_EQ(listing(dir), as_listing(result_set("third")));
  expect_only_result_directory();
}

// A set written before sets were recorded (no record, but the summary.json every run writes) is
// known by the names fogradar wrote then: replaced whole. A ROI image's name the camera never
// writes is still the user's, and so is a file under a sensor's prefix that no sensor wrote then
// (sensor instances came after the record), and any file in a directory without a summary.json.
TEST_F(OutputDirectoryTest, ASetWrittenBeforeTheRecordIsKnownByItsNames) {
  const fs::path dir = parent_ / "out";
  fs::create_directories(dir);
  for (const char* name :
       {"summary.json", "samples.csv", "radar_summary.csv", "camera_roi_3.pgm"}) {
    std::ofstream(dir / name) << "earlier";
  }
  for (const char* mine : {"camera_roi_01.pgm", "radar_notes.txt", "radar_24_summary.csv"}) {
    std::ofstream(dir / mine) << "mine";
    expect_refused_for(dir, mine);
    fs::remove(dir / mine);
  }
  EXPECT_TRUE(output_directory(dir).replace(result_set("new")));
  EXPECT_EQ(listing(dir), as_listing(result_set("new")));

  const fs::path bare = parent_ / "bare";
  fs::create_directories(bare);
  std::ofstream(bare / "camera_roi_1.pgm") << "mine";
  expect_refused_for(bare, "camera_roi_1.pgm");
  EXPECT_EQ(listing(bare), (std::map<std::string, std::string>{{"camera_roi_1.pgm", "mine"}}));
}

// Missing parents of the directory are created for the run (the lock and the staging directory
// stand in the parent) and removed again unless a set is put in place: an abandoned run, a failed
// write, a run that never replaces leave no directory of theirs; an existing parent stays.
TEST_F(OutputDirectoryTest, MissingParentsStayOnlyWithASet) {
  const fs::path dir = parent_ / "new" / "deeper" / "out";
  { OutputDirectory unused = output_directory(dir); }
  EXPECT_FALSE(fs::exists(parent_ / "new"));
  EXPECT_FALSE(output_directory(dir).replace(result_set("first"), [] { return true; }));
  EXPECT_FALSE(fs::exists(parent_ / "new"));
  Files bad = result_set("first");
  bad.emplace_back("missing/sub.csv", "x");
  EXPECT_THROW(output_directory(dir).replace(bad), InvalidParameter);
  EXPECT_FALSE(fs::exists(parent_ / "new"));
  // The parent existed before: only what the run created goes.
  fs::create_directories(parent_ / "new");
  EXPECT_THROW(output_directory(dir).replace(bad), InvalidParameter);
  EXPECT_EQ(listing(parent_ / "new"), (std::map<std::string, std::string>{}));
  fs::remove(parent_ / "new");

  EXPECT_TRUE(output_directory(dir).replace(result_set("first")));
  EXPECT_EQ(listing(dir), as_listing(result_set("first")));
  EXPECT_EQ(listing(dir.parent_path()), (std::map<std::string, std::string>{{"out", "<dir>"}}));
}

// A result file's name is the run's own or an instance's: its name (lower-case letters and digits
// up to the first '_', as instance_name_rule allows) as its prefix, then something.
TEST(ResultFileNames, AreTheRunsOwnOrCarryAnInstancesNameAsTheirPrefix) {
  for (const char* name : {"summary.json", "scenario.toml", "benchmark.svg", "radar_summary.csv",
                           "radar_24_summary.csv", "lidar_1550_scans.svg", "camera_roi_3.pgm",
                           "rangefinder_shots.csv", "x_y"}) {
    EXPECT_TRUE(is_result_file_name(name)) << name;
  }
  for (const char* name :
       {"notes.txt", "summary.csv", "Radar_summary.csv", "1radar_summary.csv", "_summary.csv",
        "radar_", "radar-24_summary.csv", "radar.summary.csv", "", ".fogradar-files"}) {
    EXPECT_FALSE(is_result_file_name(name)) << name;
  }
}

// A set its record lists is replaced whole whatever instances wrote it: no scenario's list of
// sensors or file names decides, the record and the names' form do. A file the record does not
// list is the user's even under an instance's prefix, and a record cannot make a file of another
// form the set's.
TEST_F(OutputDirectoryTest, ASetOfOtherInstancesIsReplacedByItsRecord) {
  const fs::path dir = parent_ / "out";
  const Files instances = {{"radar_24_summary.csv", "24"},
                           {"lidar_1550_echoes.csv", "1550"},
                           {"rangefinder_shots.csv", "shots"},
                           {"summary.json", "{}"}};
  ASSERT_TRUE(output_directory(dir).replace(instances));
  std::ofstream(dir / "radar_24_notes.txt") << "mine";
  expect_refused_for(dir, "radar_24_notes.txt");
  fs::remove(dir / "radar_24_notes.txt");
  EXPECT_TRUE(output_directory(dir).replace(result_set("radar only")));
  EXPECT_EQ(listing(dir), as_listing(result_set("radar only")));

  std::ofstream(dir / "notes.txt") << "mine";
  std::ofstream(dir / record_file_name, std::ios::app) << "notes.txt\n";
  expect_refused_for(dir, "notes.txt");
  EXPECT_EQ(listing(dir).at("notes.txt"), "mine");
}

TEST_F(OutputDirectoryTest, RefusesAFile) {
  std::ofstream(parent_ / "out") << "a file";
  EXPECT_THROW(output_directory(parent_ / "out"), InvalidParameter);
  expect_only_result_directory();
}

}  // namespace
}  // namespace fogradar::experiment
