// A scenario file read from disk: a regular file of at most 1 MiB, refused unread otherwise.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/files.hpp"
#include "fogradar/experiment/scenario.hpp"

namespace fogradar::experiment {

Scenario load_scenario_file(const std::string& path, const SensorRegistry& registry) {
  const std::string wanted = "a readable regular TOML file of at most " +
                             std::to_string(max_scenario_file_bytes) + " bytes (1 MiB)";
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it unread.
  const detail::Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  const int fd = file.fd;
  if (fd < 0) throw_invalid("--scenario", path, wanted + " (" + std::strerror(errno) + ")");
  struct stat info {};
  if (::fstat(fd, &info) != 0)
    throw_invalid("--scenario", path, wanted + " (" + std::strerror(errno) + ")");
  if (!S_ISREG(info.st_mode)) {
    const char* kind = S_ISDIR(info.st_mode)    ? "a directory"
                       : S_ISFIFO(info.st_mode) ? "a FIFO"
                       : S_ISCHR(info.st_mode)  ? "a character device"
                       : S_ISBLK(info.st_mode)  ? "a block device"
                       : S_ISSOCK(info.st_mode) ? "a socket"
                                                : "not a regular file";
    throw_invalid("--scenario", path, wanted + "; it is " + kind);
  }
  if (static_cast<std::uintmax_t>(info.st_size) > max_scenario_file_bytes) {
    throw_invalid("--scenario", path,
                  wanted + "; it holds " + std::to_string(info.st_size) + " bytes");
  }
  std::string text(static_cast<std::size_t>(info.st_size), '\0');
  std::size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw_invalid("--scenario", path, wanted + " (" + std::strerror(errno) + ")");
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  text.resize(got);
  return parse_scenario(text, path, registry);
}

}  // namespace fogradar::experiment
