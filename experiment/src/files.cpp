#include "fogradar/experiment/files.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "fogradar/core/error.hpp"

namespace fogradar::experiment {
namespace detail {

Descriptor::~Descriptor() {
  if (fd >= 0) ::close(fd);
}

std::string errno_text() { return std::strerror(errno); }

bool sync_path(const std::filesystem::path& path, bool directory) {
  const Descriptor file(
      ::open(path.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDWR) | O_CLOEXEC));
  return file.fd >= 0 && ::fsync(file.fd) == 0;
}

}  // namespace detail

using detail::Descriptor;
using detail::errno_text;
using detail::sync_path;

bool write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  std::string temporary = path.parent_path() / ".";
  temporary += path.filename().string();
  temporary += ".tmp-XXXXXX";
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) return false;
  bool ok = ::fchmod(fd, 0644) == 0;
  for (std::size_t written = 0; ok && written < content.size();) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) written += static_cast<std::size_t>(n);
  }
  ok = ok && ::fsync(fd) == 0;
  ok = ::close(fd) == 0 && ok;
  ok = ok && ::rename(temporary.c_str(), path.c_str()) == 0;
  if (!ok) {
    const int error = errno;
    ::unlink(temporary.c_str());
    errno = error;
    return false;
  }
  return sync_path(path.parent_path(), true);
}

namespace {

// ".NAME.lock" beside `path`, appended piece by piece (GCC 12 warns -Wrestrict, wrongly, on
// "." + name + ".lock").
std::filesystem::path lock_path_of(const std::filesystem::path& path) {
  std::string name = ".";
  name += path.filename().string();
  name += ".lock";
  return path.parent_path() / name;
}

}  // namespace

PathLock::PathLock(const std::filesystem::path& path, std::string_view option,
                   const std::string& given, std::string_view what)
    : lock_path_(lock_path_of(path)) {
  const std::string a(what);
  // The lock file is unlinked by its holder before it lets go, so a run that locked a file someone
  // has since unlinked holds nothing: it checks that the name still leads to its file, else
  // retries.
  for (;;) {
    fd_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw_invalid(option, given, a + " whose parent is writable (" + errno_text() + ")");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const bool busy = errno == EWOULDBLOCK;
      const std::string why = errno_text();
      ::close(fd_);
      if (busy) {
        throw_invalid(
            option, given,
            a + " no other fogradar run is writing to (" + lock_path_.string() + " is locked)");
      }
      throw_invalid(option, given, a + " that can be locked (" + why + ")");
    }
    struct stat held {
    }, named{};
    if (::fstat(fd_, &held) == 0 && ::stat(lock_path_.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino) {
      return;
    }
    ::close(fd_);
  }
}

PathLock::~PathLock() {
  ::unlink(lock_path_.c_str());
  ::close(fd_);
}

}  // namespace fogradar::experiment
