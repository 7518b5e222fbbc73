// The SIGINT and SIGTERM watch of the long-running commands (run, sweep).
#pragma once

#include <poll.h>
#include <pthread.h>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdint>
#include <string>
#include <thread>

#include "commands.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::cli {

// SIGINT and SIGTERM are blocked in every thread (the workers inherit the mask) and taken by a
// thread of its own through a signalfd, so no code runs in a signal handler. The first one is
// recorded; the workers stop at their next measurement and the result set is not replaced. The
// thread also polls an eventfd the destructor writes, so the run ends as soon as its work does
// (a timed wait would add up to its period to every run).
class SignalWatch {
 public:
  SignalWatch() {
    ::sigemptyset(&signals_);
    ::sigaddset(&signals_, SIGINT);
    ::sigaddset(&signals_, SIGTERM);
    ::pthread_sigmask(SIG_BLOCK, &signals_, nullptr);
    signal_fd_ = ::signalfd(-1, &signals_, SFD_CLOEXEC);
    finished_fd_ = ::eventfd(0, EFD_CLOEXEC);
    if (signal_fd_ < 0 || finished_fd_ < 0) {
      close_fds();
      throw InternalError("cannot watch SIGINT and SIGTERM: signalfd or eventfd failed");
    }
    thread_ = std::thread([this] { watch(); });
  }
  // The signals stay blocked: one arriving from here on stays pending, unseen, until the exit.
  ~SignalWatch() {
    const std::uint64_t one = 1;
    // eventfd's counter cannot overflow from one write, so the write succeeds.
    [[maybe_unused]] const ssize_t written = ::write(finished_fd_, &one, sizeof one);
    thread_.join();
    close_fds();
  }
  SignalWatch(const SignalWatch&) = delete;
  SignalWatch& operator=(const SignalWatch&) = delete;

  const std::atomic<bool>& stop() const { return stop_; }

  // Interrupted("interrupted by SIGINT: " + what), with the signal's number.
  [[noreturn]] void throw_interrupted(const std::string& what) const {
    const int signal_number = signal_.load();
    throw Interrupted(signal_number, std::string("interrupted by ") +
                                         (signal_number == SIGINT ? "SIGINT" : "SIGTERM") + ": " +
                                         what);
  }

 private:
  void watch() {
    pollfd fds[2] = {{.fd = signal_fd_, .events = POLLIN, .revents = 0},
                     {.fd = finished_fd_, .events = POLLIN, .revents = 0}};
    for (;;) {
      if (::poll(fds, 2, -1) < 0) continue;  // EINTR: nothing to do but wait again
      if (fds[1].revents != 0 || (fds[0].revents & (POLLERR | POLLNVAL)) != 0) return;
      signalfd_siginfo info{};
      if ((fds[0].revents & POLLIN) != 0 &&
          ::read(signal_fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
        signal_ = static_cast<int>(info.ssi_signo);
        stop_ = true;
        return;
      }
    }
  }

  void close_fds() {
    if (signal_fd_ >= 0) ::close(signal_fd_);
    if (finished_fd_ >= 0) ::close(finished_fd_);
  }

  sigset_t signals_{};
  int signal_fd_ = -1, finished_fd_ = -1;
  std::atomic<bool> stop_{false};
  std::atomic<int> signal_{0};
  std::thread thread_;
};

}  // namespace fogradar::cli
