// What writing a result set, a raw-data file and a sweep's directory have in common: writing a file
// whole or not at all and the lock one run holds on the path it writes (public: sweep/ uses them),
// and, for this module's writers alone, closing descriptors and syncing.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace fogradar::experiment {

// Writes `content` into `path` whole or not at all: into a temporary file beside it, fsynced, then
// renamed over it, the directory fsynced. False (errno set, nothing left behind) when a step fails.
bool write_file_atomically(const std::filesystem::path& path, std::string_view content);

// An exclusive flock on `.NAME.lock` beside `path` (NAME its file name), held for the object's
// life; the lock file is unlinked before it is let go. Throws InvalidParameter naming `option` with
// `given` as typed when another fogradar run holds it ("a <what> no other fogradar run is writing
// to") or it cannot be made.
class PathLock {
 public:
  PathLock(const std::filesystem::path& path, std::string_view option, const std::string& given,
           std::string_view what);
  ~PathLock();
  PathLock(const PathLock&) = delete;
  PathLock& operator=(const PathLock&) = delete;

 private:
  std::filesystem::path lock_path_;
  int fd_ = -1;
};

namespace detail {

// Closes a file descriptor when it goes out of scope.
struct Descriptor {
  int fd;
  explicit Descriptor(int descriptor) : fd(descriptor) {}
  ~Descriptor();
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
};

std::string errno_text();

// fsync of a directory or a file by its path; false when it cannot be opened or synced.
bool sync_path(const std::filesystem::path& path, bool directory);

}  // namespace detail
}  // namespace fogradar::experiment
