// The throughput benchmark's FFT floor: the candidate layouts and references, timed per frame.
#include "throughput_transforms.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <thread>

#include "fogradar/core/random.hpp"

namespace fogradar::bench {
namespace {

fftw_complex* as_fftw(Complex* p) { return reinterpret_cast<fftw_complex*>(p); }

// Frames between the rescalings of a thread's buffers (ThreadBuffers).
constexpr std::size_t rescale_period_frames = 16;

void transform_frames(const Transforms& t, const Variant& variant, ThreadBuffers& buffers,
                      std::size_t count) {
  for (std::size_t f = 0; f < count; ++f) {
    variant.transform(buffers);
    if (++buffers.transformed % rescale_period_frames == 0) {
      Complex* frame = buffers.current();
      for (std::size_t i = 0; i < t.rows * t.columns; ++i) {
        frame[i] = {std::ldexp(frame[i].real(), t.rescale_exponent),
                    std::ldexp(frame[i].imag(), t.rescale_exponent)};
      }
    }
  }
}

}  // namespace

ThreadBuffers make_buffers(std::size_t size, std::uint64_t seed) {
  ThreadBuffers buffers{radar::ComplexVector(size), radar::ComplexVector(size)};
  RandomStream rng(seed);
  for (auto& v : buffers.a) v = rng.complex_normal(1.0);
  return buffers;
}

Transforms::Transforms(std::size_t r, std::size_t c, int rescale)
    : rows(r),
      columns(c),
      rescale_exponent(rescale),
      estimate_rows(radar::FftPlan::along_rows(r, c, radar::FftDirection::forward,
                                               {.placement = radar::FftPlacement::in_place})),
      estimate_columns(radar::FftPlan::along_columns(r, c, radar::FftDirection::forward,
                                                     {.placement = radar::FftPlacement::in_place})),
      estimate_blocks(r, c, radar::FftDirection::forward),
      shipped_chirp(c, radar::FftDirection::forward,
                    {.planner = radar::FftPlanner::shipped_wisdom,
                     .alignment = radar::FftAlignment::aligned,
                     .placement = radar::FftPlacement::out_of_place}),
      shipped_blocks(r, c, radar::FftDirection::forward, radar::FftPlanner::shipped_wisdom),
      measure_rows(radar::FftPlan::along_rows(
          r, c, radar::FftDirection::forward,
          {.planner = radar::FftPlanner::measure, .placement = radar::FftPlacement::in_place})),
      measure_columns(radar::FftPlan::along_columns(
          r, c, radar::FftDirection::forward,
          {.planner = radar::FftPlanner::measure, .placement = radar::FftPlacement::in_place})),
      measure_chirp(c, radar::FftDirection::forward,
                    {.planner = radar::FftPlanner::measure,
                     .alignment = radar::FftAlignment::aligned,
                     .placement = radar::FftPlacement::out_of_place}),
      measure_blocks(r, c, radar::FftDirection::forward, radar::FftPlanner::measure) {
  // FFTW_MEASURE overwrites the arrays it plans on: plan on scratch, execute on the threads'
  // buffers.
  radar::ComplexVector in(r * c), out(r * c);
  const int n0 = static_cast<int>(r), n1 = static_cast<int>(c);
  measure_2d_in_place = std::make_unique<RawPlan>(
      fftw_plan_dft_2d(n0, n1, as_fftw(in.data()), as_fftw(in.data()), FFTW_FORWARD, FFTW_MEASURE));
  measure_2d_out_of_place = std::make_unique<RawPlan>(fftw_plan_dft_2d(
      n0, n1, as_fftw(in.data()), as_fftw(out.data()), FFTW_FORWARD, FFTW_MEASURE));

  const std::size_t size = r * c;
  const auto span = [size](Complex* p) { return std::span<Complex>(p, size); };
  add_variant("ESTIMATE rows + columns (old floor)", false, [this, span](ThreadBuffers& b) {
    estimate_rows.execute(span(b.current()));
    estimate_columns.execute(span(b.current()));
  });
  add_variant("ESTIMATE rows + blocks (chain before)", false, [this, span](ThreadBuffers& b) {
    estimate_rows.execute(span(b.current()));
    estimate_blocks.execute(span(b.current()));
  });
  // The range FFT by a one-chirp out-of-place plan, from a copy of each chirp into its row.
  const auto by_chirp = [this, span](const radar::FftPlan& chirp_plan,
                                     const radar::ColumnBlockFft& blocks, ThreadBuffers& b) {
    const std::span<Complex> frame = span(b.current());
    radar::ComplexVector chirp(columns);
    for (std::size_t row = 0; row < rows; ++row) {
      const std::span<Complex> chirp_row = frame.subspan(row * columns, columns);
      std::copy(chirp_row.begin(), chirp_row.end(), chirp.begin());
      chirp_plan.execute(chirp, chirp_row);
    }
    blocks.execute(frame);
  };
  add_variant("shipped chirps + blocks (chain's plans)", false,
              [this, by_chirp](ThreadBuffers& b) { by_chirp(shipped_chirp, shipped_blocks, b); });
  add_variant("MEASURE rows + columns", true, [this, span](ThreadBuffers& b) {
    measure_rows.execute(span(b.current()));
    measure_columns.execute(span(b.current()));
  });
  add_variant("MEASURE rows + blocks", true, [this, span](ThreadBuffers& b) {
    measure_rows.execute(span(b.current()));
    measure_blocks.execute(span(b.current()));
  });
  add_variant("MEASURE chirps + blocks", true,
              [this, by_chirp](ThreadBuffers& b) { by_chirp(measure_chirp, measure_blocks, b); });
  add_variant("MEASURE 2-D in place", true, [this](ThreadBuffers& b) {
    fftw_execute_dft(measure_2d_in_place->plan, as_fftw(b.current()), as_fftw(b.current()));
  });
  add_variant("MEASURE 2-D out of place", true, [this](ThreadBuffers& b) {
    fftw_execute_dft(measure_2d_out_of_place->plan, as_fftw(b.current()), as_fftw(b.other()));
    b.in_b = !b.in_b;
  });
}

double time_transform(const Transforms& t, const Variant& variant,
                      std::vector<ThreadBuffers>& buffers, std::size_t frames, unsigned threads) {
  const Clock::time_point start = Clock::now();
  std::vector<std::thread> pool;
  const auto share = [&](unsigned i) { return frames * (i + 1) / threads - frames * i / threads; };
  for (unsigned i = 1; i < threads; ++i) {
    pool.emplace_back([&, i] { transform_frames(t, variant, buffers[i], share(i)); });
  }
  transform_frames(t, variant, buffers[0], share(0));
  for (std::thread& thread : pool) thread.join();
  return seconds_since(start) / static_cast<double>(frames);
}

int rescale_exponent_for(std::size_t rows, std::size_t columns) {
  const std::size_t n = rows * columns;
  if ((n & (n - 1)) != 0) {
    std::fprintf(stderr,
                 "throughput: chirps x samples = %zu is not a power of two; the FFT floor's "
                 "rescaling assumes one\n",
                 n);
    std::exit(2);
  }
  int log2n = 0;
  while ((std::size_t{1} << log2n) < n) ++log2n;
  // 16 frames = 4 periods of F^4: growth (n^2)^4 = 2^(8 log2 n).
  return -8 * log2n;
}

}  // namespace fogradar::bench
