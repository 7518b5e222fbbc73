#include "fogradar/experiment/outputs.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <string_view>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/files.hpp"
#include "fogradar/propagation/fog.hpp"

namespace fogradar::experiment {
namespace {

namespace fs = std::filesystem;
using detail::Descriptor;
using detail::errno_text;
using detail::sync_path;

// The files of a result set that belong to no one sensor.
constexpr std::string_view common_file_names[] = {"summary.json", "scenario.toml", "benchmark.svg"};

// The files fogradar wrote before result sets recorded theirs: then every sensor ran under its
// kind's name, and the radar's files of fogradar 0.1 had no prefix. These names never change.
constexpr std::string_view pre_record_file_names[] = {
    "radar_samples.csv",   "radar_detections.csv",  "radar_summary.csv",
    "radar_summary.json",  "radar_rcs_boxplot.svg", "samples.csv",
    "summary.csv",         "rcs_boxplot.svg",       "lidar_echoes.csv",
    "lidar_summary.csv",   "lidar_summary.json",    "lidar_intensity_boxplot.svg",
    "lidar_scans.svg",     "camera_histograms.csv", "camera_summary.csv",
    "camera_summary.json", "camera_histograms.svg"};

bool is_listed(std::span<const std::string_view> names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// camera_roi_<step>.pgm, the step as the camera writes it (no leading zero, so that a
// camera_roi_01.pgm is never taken for a set's file).
bool is_pre_record_roi_file_name(std::string_view name) {
  const std::string_view prefix = "camera_roi_", suffix = ".pgm";
  if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) ||
      !name.ends_with(suffix)) {
    return false;
  }
  const std::string_view digits =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  return digits.size() <= 7 && (digits.size() == 1 || digits.front() != '0') &&
         std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

bool is_pre_record_file_name(std::string_view name) {
  return is_listed(common_file_names, name) || is_listed(pre_record_file_names, name) ||
         is_pre_record_roi_file_name(name);
}

[[noreturn]] void refuse(const fs::path& path, const std::string& constraint) {
  throw_invalid("--out", path.string(), constraint);
}

// Writes `content` to a new file and fsyncs it, so the data is on disk before the rename that
// publishes it (a crash after the rename must not expose an empty file).
void write_file(const fs::path& path, const std::string& content) {
  const Descriptor file(::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
  if (file.fd < 0) refuse(path, "a writable location (" + errno_text() + ")");
  for (std::size_t written = 0; written < content.size();) {
    const ssize_t n = ::write(file.fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) refuse(path, "a writable location (" + errno_text() + ")");
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(file.fd) != 0) refuse(path, "a writable location (" + errno_text() + ")");
}

bool is_regular(const fs::directory_entry& entry) {
  return entry.symlink_status().type() == fs::file_type::regular;
}

// The names a set's record lists, one a line; refuses a record that is not a regular file or
// cannot be read (it is then the user's, or the set's files cannot be told from the user's).
std::set<std::string> recorded_names(const fs::directory_entry& record, const fs::path& given) {
  const std::string allowed = "a directory whose record of its result files ('" +
                              std::string(record_file_name) + "') is a readable file";
  if (!is_regular(record)) refuse(given, allowed);
  std::ifstream in(record.path(), std::ios::binary);
  std::set<std::string> names;
  for (std::string line; std::getline(in, line);) names.insert(line);
  if (in.bad() || !in.eof()) refuse(given, allowed);
  return names;
}

// The entries of an existing `dir` that are its result set's: those the set's record lists (result
// file names, regular files), and the record. A set written before sets were recorded is known by
// its summary.json, which every run writes: its files are those of the names fogradar wrote then.
// Any other entry is the user's: the directory is replaced whole, and no file of the user's may go
// with it, so it is refused, naming the file.
std::vector<fs::path> previous_set(const fs::path& dir, const fs::path& given) {
  std::error_code error;
  std::vector<fs::path> set;
  if (!fs::is_directory(fs::symlink_status(dir, error))) return set;
  const fs::directory_entry record(dir / record_file_name, error);
  std::optional<std::set<std::string>> recorded;
  if (fs::exists(record.symlink_status(error))) recorded = recorded_names(record, given);
  const fs::directory_entry summary(dir / "summary.json", error);
  const bool earlier_set = recorded || is_regular(summary);
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const bool ours =
        recorded ? (name == record_file_name ||
                    (recorded->contains(name) && is_result_file_name(name) && is_regular(entry)))
                 : earlier_set && is_pre_record_file_name(name) && is_regular(entry);
    if (!ours) {
      refuse(given,
             "a directory holding only the result files of an earlier run, as it is "
             "replaced whole ('" +
                 name + "' is not one)");
    }
    set.push_back(entry.path());
  }
  return set;
}

}  // namespace

bool is_result_file_name(std::string_view name) {
  if (is_listed(common_file_names, name)) return true;
  // The instance's name up to its first '_' is enough: the rest of the name may hold '_' too.
  const std::size_t split = name.find('_');
  if (split == 0 || split == std::string_view::npos || split + 1 == name.size()) return false;
  const std::string_view first = name.substr(0, split);
  return first.front() >= 'a' && first.front() <= 'z' &&
         std::all_of(first.begin(), first.end(),
                     [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); });
}

namespace {

// A file of instance `outcome` under its own name: the kind names its files for its own instance
// ("radar_summary.csv"), another instance's take its name ("radar_24_summary.csv").
std::string instance_file_name(const SensorOutcome& outcome, const std::string& file) {
  const std::string prefix = std::string(outcome.kind->name()) + '_';
  if (!file.starts_with(prefix) || file.size() == prefix.size()) {
    throw InternalError("sensor kind '" + std::string(outcome.kind->name()) + "' wrote '" + file +
                        "': a sensor's file names begin with its kind's name and '_'");
  }
  return outcome.name + file.substr(prefix.size() - 1);
}

}  // namespace

std::string sensor_tables(const ExperimentSummary& summary) {
  std::string out;
  for (const SensorOutcome& sensor : summary.sensors) {
    out += sensor.name + '\n' + sensor.summary->table() + '\n';
  }
  return out;
}

std::string benchmark_table(const ExperimentSummary& summary) {
  std::string out = "benchmark (the study's criterion: active fog layers until the sensor fails)\n";
  for (const SensorOutcome& sensor : summary.sensors) {
    const sensor::Verdict v = sensor.summary->verdict();
    std::string name = sensor.name;
    name.resize(std::max<std::size_t>(name.size() + 1, 7), ' ');
    out += name + "layers to failure: " +
           (v.layers_to_failure ? std::to_string(*v.layers_to_failure)
                                : "not reached (" + v.margin + ")") +
           "\n       criterion: " + v.criterion + "\n";
  }
  return out;
}

namespace {

nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// The chamber as the run resolved it: each layer's place and fog, and the fog as each running
// sensor sees it at its own band (ConfiguredSensor::fog_report, the numbers the run uses).
nlohmann::json chamber_json(const Scenario& scenario) {
  const sensor::Context context = scenario.context();
  const propagation::SegelsteinTable table;
  std::vector<std::pair<std::string, std::shared_ptr<const sensor::ConfiguredSensor>>> running;
  for (const SensorSetting& setting : scenario.sensors) {
    if (scenario.runs(setting.name)) {
      running.emplace_back(setting.name, scenario.configure(setting.name));
    }
  }
  nlohmann::json layers = nlohmann::json::array();
  double start_m = context.chamber.sensor_gap_m;
  for (std::size_t i = 0; i < context.chamber.layers.size(); ++i) {
    const propagation::FogLayerSpec& layer = context.chamber.layers[i];
    // A layer like an earlier one (the study's four) reports what that one did.
    std::size_t same = 0;
    while (same < i && context.chamber.layers[same] != layer) ++same;
    nlohmann::json entry;
    if (same < i) {
      entry = layers[same];
    } else {
      const propagation::Fog fog(layer.fog, table);
      entry = {{"length_m", layer.length_m},
               {"droplets", propagation::distribution_name(layer.fog.droplets)},
               {"lwc_g_per_m3", fog.lwc_g_per_m3()},
               {"optical_extinction_per_km", fog.optical_extinction_per_km()},
               {"visibility_m", finite_or_null(fog.visibility_m())},
               {"sensors", nlohmann::json::object()}};
      for (const auto& [name, configured] : running) {
        entry["sensors"][name] = configured->fog_report(layer.fog, layer.length_m, table).json;
      }
    }
    entry["index"] = i;
    entry["start_m"] = start_m;
    entry["end_m"] = start_m + layer.length_m;
    start_m += layer.length_m;
    layers.push_back(std::move(entry));
  }
  return {{"target_range_m", context.chamber.target_range_m()},
          {"switching_order", context.switching_order},
          {"layers", std::move(layers)}};
}

}  // namespace

std::string summary_json(const Scenario& scenario, const ExperimentSummary& summary) {
  std::ostringstream scenario_json;
  scenario_json << toml::json_formatter{toml::parse(to_toml(scenario))};
  nlohmann::json sensors = nlohmann::json::object();
  for (const SensorOutcome& sensor : summary.sensors) {
    const sensor::Verdict v = sensor.summary->verdict();
    sensors[sensor.name] = {
        {"sensor_limit_layers",
         v.layers_to_failure ? nlohmann::json(*v.layers_to_failure) : nlohmann::json(nullptr)},
        {"criterion", v.criterion},
        {"margin", v.margin},
        {"summary", sensor.summary->json()}};
  }
  const nlohmann::json out = {{"scenario", nlohmann::json::parse(scenario_json.str())},
                              {"chamber", chamber_json(scenario)},
                              {"sensors", std::move(sensors)}};
  return out.dump(2) + '\n';
}

std::vector<sensor::ResultFile> result_files(const Scenario& scenario,
                                             const ExperimentSummary& summary) {
  std::vector<sensor::ResultFile> files;
  for (const SensorOutcome& sensor : summary.sensors) {
    for (sensor::ResultFile& file : sensor.summary->files()) {
      file.name = instance_file_name(sensor, file.name);
      files.push_back(std::move(file));
    }
  }
  files.push_back({"summary.json", summary_json(scenario, summary)});
  files.push_back({"scenario.toml", to_toml(scenario)});
  files.push_back({"benchmark.svg", benchmark_svg(scenario, summary)});
  return files;
}

OutputDirectory::OutputDirectory(fs::path dir) {
  const fs::path given = dir;
  std::error_code error;
  dir_ = fs::absolute(dir, error).lexically_normal();
  if (!dir_.has_filename()) dir_ = dir_.parent_path();  // "out/" names "out"
  const std::string name = dir_.filename().string();
  if (error || given.empty() || name.empty() || name == "." || name == "..") {
    refuse(given, "a directory name");
  }
  // Swapping the working directory away would leave this process and its shell in a deleted one.
  if (dir_ == fs::current_path(error).lexically_normal()) {
    refuse(given, "a directory other than the current one (it is replaced whole)");
  }
  parent_ = dir_.parent_path();
  const fs::file_status status = fs::symlink_status(dir_, error);
  if (fs::is_symlink(status))
    refuse(given, "a directory, not a symbolic link (it is replaced whole)");
  if (fs::exists(status) && !fs::is_directory(status)) refuse(given, "a directory");
  // The lock and the staging directory need the parent; what of it this run creates goes again
  // unless a set is put in place, so a failed run leaves no directory it made.
  for (fs::path missing = parent_;
       fs::symlink_status(missing, error).type() == fs::file_type::not_found &&
       missing != missing.parent_path();
       missing = missing.parent_path()) {
    created_.push_back(missing);
  }
  try {
    fs::create_directories(parent_, error);
    if (error) refuse(given, "a directory that can be created (" + error.message() + ")");

    lock_ = std::make_unique<PathLock>(dir_, "--out", given.string(), "a directory");
    previous_set(dir_, given);
    std::string staging =
        (parent_ / ("." + name + ".tmp-" + std::to_string(::getpid()) + "-XXXXXX")).string();
    if (::mkdtemp(staging.data()) == nullptr) {
      refuse(given, "a directory whose parent is writable (" + errno_text() + ")");
    }
    staging_ = staging;
  } catch (...) {
    release();
    throw;
  }
}

OutputDirectory::~OutputDirectory() { release(); }

void OutputDirectory::release() noexcept {
  std::error_code ignored;
  if (!staging_.empty()) fs::remove_all(staging_, ignored);
  staging_.clear();
  lock_.reset();  // its file stands in the parent
  // Deepest first; one that is no longer empty (another run's, or the user's by now) stays.
  for (const fs::path& created : created_) fs::remove(created, ignored);
  created_.clear();
}

bool OutputDirectory::replace(const std::vector<sensor::ResultFile>& files,
                              const std::function<bool()>& abandon) {
  std::vector<std::string> names;
  for (const sensor::ResultFile& file : files) {
    write_file(staging_ / file.name, file.content);
    names.push_back(file.name);
  }
  // Sorted, so that a set's bytes depend only on its files.
  std::sort(names.begin(), names.end());
  std::string record;
  for (const std::string& name : names) record += name + '\n';
  write_file(staging_ / record_file_name, record);
  if (!sync_path(staging_, true))
    refuse(staging_, "a directory that can be synced (" + errno_text() + ")");
  if (abandon && abandon()) return false;
  std::vector<fs::path> previous;
  if (fs::exists(fs::symlink_status(dir_))) {
    // Checked again: a file put into `dir` while the run measured must not go with the old set.
    previous = previous_set(dir_, dir_);
    // Readers see the old set or the new one, never a mixture and never no directory at all.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, dir_.c_str(), RENAME_EXCHANGE) != 0) {
      refuse(dir_, "a directory that can be replaced (renameat2: " + errno_text() + ")");
    }
  } else if (::rename(staging_.c_str(), dir_.c_str()) != 0) {
    refuse(dir_, "a directory that can be created (" + errno_text() + ")");
  } else {
    staging_.clear();
  }
  created_.clear();
  // The set is in place; a failed sync of the rename is the kernel's to retry, not the run's
  // failure.
  sync_path(parent_, true);
  // The previous set, now under the staging name: the files found to be its before the swap,
  // then the directory if that left it empty (only a file put into `dir` in the instant of the
  // swap would keep it).
  if (!staging_.empty()) {
    std::error_code ignored;
    for (const fs::path& file : previous) fs::remove(staging_ / file.filename(), ignored);
    fs::remove(staging_, ignored);
  }
  staging_.clear();
  return true;
}

}  // namespace fogradar::experiment
