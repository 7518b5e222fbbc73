// The throughput benchmark's FFT floor (throughput.cpp): its candidate transforms and references.
#pragma once

#include <fftw3.h>

#include <chrono>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/radar/fft.hpp"

namespace fogradar::bench {

using Clock = std::chrono::steady_clock;
using Complex = std::complex<double>;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One FFTW plan made directly (the 2-D candidates, which radar::FftPlan does not offer).
struct RawPlan {
  fftw_plan plan = nullptr;
  explicit RawPlan(fftw_plan p) : plan(p) {
    if (plan == nullptr) throw InternalError("FFTW could not create a plan");
  }
  RawPlan(const RawPlan&) = delete;
  RawPlan& operator=(const RawPlan&) = delete;
  ~RawPlan() { fftw_destroy_plan(plan); }
};

// A thread's frame buffers: the frame is in `a` or, after an out-of-place transform, in `b`. The
// unnormalised 2-D forward DFT F of an n = rows x columns frame satisfies F^4 = n^2 I, so the frame
// grows by exactly n^8 every 16 frames; with n a power of two, scaling it back by that power of two
// (std::ldexp, exact) every 16 frames returns the original noise frame up to rounding. It costs one
// pass every 16 frames and keeps the data finite noise-like values: no inf, NaN or denormals that
// could make FFTW run at another speed than on real frames. Every variant computes the same F.
struct ThreadBuffers {
  radar::ComplexVector a, b;
  bool in_b = false;
  std::size_t transformed = 0;
  Complex* current() { return in_b ? b.data() : a.data(); }
  Complex* other() { return in_b ? a.data() : b.data(); }
};

ThreadBuffers make_buffers(std::size_t size, std::uint64_t seed);

struct Variant {
  std::string name;
  bool floor_candidate = false;
  std::function<void(ThreadBuffers&)> transform;  // one frame, in place or a -> b
  std::size_t frames = 0;                         // frames per timing (set by calibration)
  std::vector<double> seconds_per_frame[2];       // per repeat, per thread-count slot
};

struct Transforms {
  std::size_t rows, columns;
  int rescale_exponent;
  radar::FftPlan estimate_rows, estimate_columns;
  radar::ColumnBlockFft estimate_blocks;
  radar::FftPlan shipped_chirp;
  radar::ColumnBlockFft shipped_blocks;
  radar::FftPlan measure_rows, measure_columns, measure_chirp;
  radar::ColumnBlockFft measure_blocks;
  std::unique_ptr<RawPlan> measure_2d_in_place, measure_2d_out_of_place;
  std::vector<Variant> variants;

  void add_variant(std::string name, bool floor_candidate,
                   std::function<void(ThreadBuffers&)> transform) {
    Variant v;
    v.name = std::move(name);
    v.floor_candidate = floor_candidate;
    v.transform = std::move(transform);
    variants.push_back(std::move(v));
  }

  Transforms(std::size_t r, std::size_t c, int rescale);
};

// Seconds per frame of `frames` frames split into `threads` contiguous shares; thread i owns
// buffers[i].
double time_transform(const Transforms& t, const Variant& variant,
                      std::vector<ThreadBuffers>& buffers, std::size_t frames, unsigned threads);

// The power of two that scales a frame back every 16 frames (ThreadBuffers); rows x columns must
// be a power of two, else throughput exits with status 2.
int rescale_exponent_for(std::size_t rows, std::size_t columns);

}  // namespace fogradar::bench
