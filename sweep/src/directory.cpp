// The sweep's directory: what it may hold, its lock, its committed pieces filed by the hash of
// their point's definition, and its kept result sets.
#include <sys/stat.h>

#include <charconv>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "engine.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/experiment/files.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/sweep/sweep.hpp"

namespace fogradar::sweep::detail {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::set<std::string, std::less<>> table_names = {
    "sweep.toml", "points.csv",   "results.csv",         "limits.csv",  "comparison.svg",
    "limits.svg", "envelope.csv", "envelope_limits.csv", "envelope.svg"};
constexpr std::string_view state_dir = ".sweep";
constexpr std::string_view points_dir = "points";
constexpr std::string_view origin_file = "origin";  // in .sweep/: the sweep file's directory

std::string fnv_hex(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(hash));
  return out;
}

}  // namespace

SweepDirectory::SweepDirectory(const fs::path& dir, Mode mode,
                               const std::vector<std::string>& definitions, std::size_t shard) {
  const std::string given = dir.string();
  const std::string option = mode == Mode::merge ? "--merge" : "--out";
  std::error_code error;
  dir_ = fs::absolute(dir, error).lexically_normal();
  if (!dir_.has_filename()) dir_ = dir_.parent_path();
  if (error || given.empty() || dir_.filename() == "." || dir_.filename() == "..") {
    throw_invalid(option, given, "a directory name");
  }
  if (fs::is_symlink(fs::symlink_status(dir_, error))) {
    throw_invalid(option, given, "a directory, not a symbolic link");
  }
  if (fs::exists(dir_, error) && !fs::is_directory(dir_, error)) {
    throw_invalid(option, given, "a directory");
  }
  if (mode == Mode::merge && !fs::is_directory(dir_ / state_dir)) {
    throw_invalid(option, given, "a sweep's directory (it has no " + std::string(state_dir) + "/)");
  }
  fs::create_directories(dir_, error);
  if (error) {
    throw_invalid(option, given, "a directory that can be created (" + error.message() + ")");
  }
  if (mode != Mode::shard) {
    lock_ = std::make_unique<experiment::PathLock>(dir_, option, given, "a sweep directory");
  }
  const auto refuse = [&](const fs::path& path) {
    throw_invalid(option, given,
                  "a new directory or one holding only a sweep's files (it holds " +
                      fs::relative(path, dir_).string() +
                      ", which fogradar would not replace; fogradar never deletes a file of "
                      "yours)");
  };
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    if (table_names.contains(name) && entry.is_regular_file()) continue;
    if (name.starts_with(".") && name.find(".tmp-") != std::string::npos) continue;  // a crash's
    if ((name == state_dir || name == points_dir) && entry.is_directory()) continue;
    refuse(entry.path());
  }
  for (const std::string_view sub : {state_dir, points_dir}) {
    if (!fs::is_directory(dir_ / sub)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_ / sub)) {
      const std::string name = entry.path().filename().string();
      // points/<index>/, and .sweep/<definition>.json (an earlier version's .sweep/<index>.json).
      const std::string stem = name.substr(0, name.find('.'));
      const bool hex = sub == state_dir;
      const bool ours = !stem.empty() && std::all_of(stem.begin(), stem.end(), [hex](char c) {
        return (c >= '0' && c <= '9') || (hex && c >= 'a' && c <= 'f');
      });
      if (ours || name.starts_with(".") || name == origin_file) continue;
      refuse(entry.path());
    }
  }
  fs::create_directories(dir_ / state_dir, error);
  if (error) {
    throw_invalid(option, given, "a directory that can be written (" + error.message() + ")");
  }
  // Shards of one sweep run side by side: each holds its own lock, the others' points stay.
  if (mode == Mode::shard) {
    lock_ = std::make_unique<experiment::PathLock>(
        dir_ / state_dir / ("shard-" + std::to_string(shard)), option, given, "a sweep directory");
  }
  // A crash's temporary files go; without --resume an earlier sweep's files, with it the pieces of
  // points this sweep does not have. A shard removes nothing (the others write beside it), nor
  // does a merge.
  if (mode == Mode::shard || mode == Mode::merge) return;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    if ((name.starts_with(".") && name.find(".tmp-") != std::string::npos) ||
        (mode == Mode::fresh && table_names.contains(name))) {
      fs::remove_all(entry.path(), error);
    }
  }
  if (mode == Mode::fresh) fs::remove_all(dir_ / points_dir, error);
  const std::set<std::string, std::less<>> own(definitions.begin(), definitions.end());
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_ / state_dir)) {
    const std::string name = entry.path().filename().string();
    const bool piece = name.ends_with(".json") && !name.starts_with(".");
    const bool stale =
        name.starts_with(".") || (piece && !own.contains(name.substr(0, name.size() - 5)));
    if (mode == Mode::fresh || stale) fs::remove(entry.path(), error);
  }
}

SweepDirectory::~SweepDirectory() = default;

std::optional<json> SweepDirectory::committed(const std::string& definition) const {
  std::ifstream in(dir_ / state_dir / (definition + ".json"));
  if (!in) return std::nullopt;
  try {
    json piece = json::parse(in);
    if (piece.value("definition", std::string()) == definition) return piece;
  } catch (const json::exception&) {
  }
  return std::nullopt;
}

void SweepDirectory::commit(const json& piece) const {
  write_table(std::string(state_dir) + "/" + piece.at("definition").get<std::string>() + ".json",
              piece.dump() + "\n");
}

void SweepDirectory::write_table(std::string_view name, std::string_view content) const {
  const fs::path path = dir_ / name;
  if (!experiment::write_file_atomically(path, content)) {
    throw_invalid("--out", dir_.string(),
                  "a directory that can be written (" + path.filename().string() + ": " +
                      experiment::detail::errno_text() + ")");
  }
}

void SweepDirectory::keep(std::size_t index, const std::vector<sensor::ResultFile>& files) const {
  std::error_code error;
  fs::create_directories(dir_ / points_dir, error);
  experiment::OutputDirectory out(dir_ / points_dir / std::to_string(index));
  out.replace(files);
}

bool SweepDirectory::holds_kept(const Point& point) const {
  std::ifstream in(dir_ / points_dir / std::to_string(point.index) / "scenario.toml",
                   std::ios::binary);
  if (!in) return false;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str() == experiment::to_toml(with_seed(point.scenario, point.seed));
}

std::string definition_of(const Point& point, std::size_t replications) {
  std::string text =
      experiment::to_toml(point.scenario) + "\nreplications " + std::to_string(replications);
  for (const experiment::Scenario& setup : point.setups) {
    text += "\nsetup\n" + experiment::to_toml(setup);
  }
  return fnv_hex(text);
}

void SweepDirectory::remove_stale_kept(const std::vector<Point>& points,
                                       const std::vector<std::size_t>& indices, bool all) const {
  std::error_code error;
  if (!fs::is_directory(dir_ / points_dir, error)) return;
  for (const std::size_t index : indices) {
    const fs::path kept = dir_ / points_dir / std::to_string(index);
    if (fs::exists(kept, error) && !holds_kept(points[index])) fs::remove_all(kept, error);
  }
  if (!all) return;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_ / points_dir, error)) {
    const std::string name = entry.path().filename().string();
    std::size_t index = 0;
    const auto [end, parsed] = std::from_chars(name.data(), name.data() + name.size(), index);
    if (parsed == std::errc() && end == name.data() + name.size() && index >= points.size())
      fs::remove_all(entry.path(), error);
  }
}

std::vector<std::string> definitions_of(const std::vector<Point>& points,
                                        std::size_t replications) {
  std::vector<std::string> definitions;
  for (const Point& point : points) definitions.push_back(definition_of(point, replications));
  return definitions;
}

void write_origin(const SweepDirectory& out, const fs::path& sweep_directory) {
  std::error_code error;
  const fs::path absolute = fs::absolute(sweep_directory, error).lexically_normal();
  out.write_table(std::string(state_dir) + "/" + std::string(origin_file),
                  absolute.string() + "\n");
}

SweepSpec read_spec(const fs::path& dir) {
  std::ifstream text_in(dir / "sweep.toml"), origin_in(dir / state_dir / origin_file);
  if (!text_in || !origin_in) {
    throw_invalid("--merge", dir.string(),
                  "a sweep's directory (sweep.toml and " + std::string(state_dir) + "/" +
                      std::string(origin_file) + " written by its shards)");
  }
  std::ostringstream text;
  text << text_in.rdbuf();
  std::string origin;
  std::getline(origin_in, origin);
  return parse_sweep(text.str(), (dir / "sweep.toml").string(), origin);
}

}  // namespace fogradar::sweep::detail
