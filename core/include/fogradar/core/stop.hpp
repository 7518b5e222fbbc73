// A stop asked for by another thread (experiment::RunOptions::stop, set on SIGINT or SIGTERM), seen
// inside long work: one item of a sensor can take minutes (a lidar scan of 36001 beams x 667129
// samples, a radar frame of 65536 x 4096 cells), so the work looks between its parts (beams, FFT
// column blocks, objects) and a stop is honoured within a part instead of an item. Looking draws
// nothing and changes nothing: a run that is not stopped is bit-identical either way.
#pragma once

#include <atomic>
#include <exception>

namespace fogradar {

// Thrown from inside work whose StopToken says stop; its partial result is dropped.
class Stopped : public std::exception {
 public:
  const char* what() const noexcept override { return "stopped"; }
};

class StopToken {
 public:
  StopToken() = default;  // never stops
  explicit StopToken(const std::atomic<bool>* flag) : flag_(flag) {}
  bool requested() const { return flag_ != nullptr && flag_->load(std::memory_order_relaxed); }
  // Throws Stopped when a stop was asked for.
  void check() const {
    if (requested()) throw Stopped();
  }

 private:
  const std::atomic<bool>* flag_ = nullptr;
};

}  // namespace fogradar
