// FFTW behind one RAII class: complex double 1-D transforms, single or
// batched, planned once and executed concurrently by any number of threads on caller buffers.
//
// fftw3.h is deliberately not included here: FFTW is linked PRIVATE to fogradar::radar and the
// API uses std::complex<double>, which FFTW documents as layout-compatible with fftw_complex
// (FFTW 3.3 manual, "Complex numbers").
#pragma once

#include <complex>
#include <cstddef>
#include <limits>
#include <new>
#include <span>
#include <string_view>
#include <vector>

#include "fogradar/core/stop.hpp"

struct fftw_plan_s;  // FFTW's opaque plan type (fftw_plan is fftw_plan_s*).

namespace fogradar::radar {

// --- Aligned memory ---------------------------------------------------------------------------

// fftw_malloc / fftw_free: memory aligned for FFTW's SIMD codelets. Throws std::bad_alloc.
void* fft_aligned_allocate(std::size_t bytes);
void fft_aligned_free(void* pointer) noexcept;

// True when `pointer` has the alignment FFTW's SIMD plans assume (fftw_alignment_of == 0), i.e.
// the alignment of memory from fft_aligned_allocate.
bool fft_is_aligned(const void* pointer) noexcept;

// Standard allocator on fftw_malloc, so std::vector storage can be handed to an aligned FftPlan.
template <class T>
struct FftAllocator {
  using value_type = T;
  FftAllocator() noexcept = default;
  template <class U>
  FftAllocator(const FftAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor)
  T* allocate(std::size_t count) {
    if (count > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_alloc();
    return static_cast<T*>(fft_aligned_allocate(count * sizeof(T)));
  }
  void deallocate(T* pointer, std::size_t /*count*/) noexcept { fft_aligned_free(pointer); }
  template <class U>
  bool operator==(const FftAllocator<U>&) const noexcept {
    return true;
  }
};

// Vector whose data() is FFTW-aligned: the buffer type for frames and FFT work arrays.
template <class T>
using AlignedVector = std::vector<T, FftAllocator<T>>;
using ComplexVector = AlignedVector<std::complex<double>>;

// --- Plans ------------------------------------------------------------------------------------

// Sign of the exponent: forward X[k] = sum_j x[j] exp(-2 pi i j k / n); inverse uses +i and is
// unnormalised (inverse(forward(x)) = n x), as in FFTW.
enum class FftDirection { forward, inverse };

// FFTW planner effort. `estimate` (FFTW_ESTIMATE) plans in microseconds from heuristics and
// always picks the same algorithm, so results are bit-reproducible between runs; `measure`
// (FFTW_MEASURE) times candidate algorithms (seconds for large sizes) and may pick a different
// algorithm in another run, which can change results in the last bits. Use estimate for
// simulation runs that promise byte-identical output, measure for throughput benchmarks.
// FFTW keeps one planner per process, and an estimate request takes a measured plan of the same
// problem or sub-problem from it (wisdom; FFTW 3.3 manual §4.3.2): after measure plans of the
// chain's transforms (or imported wisdom), estimate plans are other algorithms with other bits
// until fftw_forget_wisdom().
// `shipped_wisdom` is FFTW_ESTIMATE given fft_shipped_wisdom() and no other wisdom: FFTW_MEASURE
// plans of the radar chain's problems, made once and versioned with the source
// (data/fftw_wisdom.txt, bench/make_fftw_wisdom.cpp). While the plan is made the process's
// wisdom is set aside (exported, forgotten, re-imported after), so the plan, and its bits, are
// the same in every process on a machine whatever else the process planned or imported. Where the
// shipped wisdom does not apply (a problem it lacks, another FFTW build, a CPU without the
// codelets it names) FFTW plans that problem as estimate does, again the same in every process.
// The radar chain plans with it; `fogradar run` never measures.
enum class FftPlanner { estimate, measure, shipped_wisdom };

// The shipped wisdom (data/fftw_wisdom.txt, compiled in), in FFTW's wisdom format.
std::string_view fft_shipped_wisdom();

// Which buffers a plan accepts at execute time.
//   aligned:   buffers must satisfy fft_is_aligned (AlignedVector, fft_aligned_allocate); FFTW
//              may use its aligned SIMD codelets. Passing an unaligned buffer is a programmer
//              error caught by FOGRADAR_CHECK (InternalError), never silent misbehaviour.
//   unaligned: FFTW_UNALIGNED: any buffer aligned for std::complex<double>; may be slower.
enum class FftAlignment { aligned, unaligned };

// Whether the plan transforms in place (execute(data)) or out of place (execute(in, out)); FFTW
// requires the new-array execute to match the placement the plan was made for.
enum class FftPlacement { out_of_place, in_place };

// `howmany` transforms of length n over one buffer (fftw_plan_many_dft with rank 1): element j
// of transform b lives at buffer[b * distance + j * stride]. distance = 0 means n (packed
// rows). The same layout is used for input and output.
struct FftLayout {
  std::size_t n = 1;
  std::size_t howmany = 1;
  std::size_t stride = 1;
  std::size_t distance = 0;
};

struct FftOptions {
  FftPlanner planner = FftPlanner::estimate;
  FftAlignment alignment = FftAlignment::aligned;
  FftPlacement placement = FftPlacement::out_of_place;
};

// Owner of one FFTW plan. Non-copyable, movable; destroying it calls fftw_destroy_plan.
//
// Thread safety: construction and destruction take one process-wide mutex, because FFTW's
// planner and fftw_destroy_plan are not thread-safe (FFTW 3.3 manual, "Thread safety").
// execute() is const and uses fftw_execute_dft on the caller's buffers (the "new-array execute"
// interface, documented thread-safe), so one plan can be shared by many threads at once as long
// as each thread passes its own buffers.
class FftPlan {
 public:
  // One transform of length n (n >= 1).
  FftPlan(std::size_t n, FftDirection direction, FftOptions options = {});
  // Batched transforms; throws InvalidParameter naming "fft.n", "fft.howmany", "fft.stride" or
  // "fft.distance" for zero or too-large (> INT_MAX for FFTW) values.
  FftPlan(const FftLayout& layout, FftDirection direction, FftOptions options = {});

  // `rows` transforms of length `columns` over a row-major rows x columns matrix: e.g. the
  // range FFT of every chirp of a frame stored chirp-major.
  static FftPlan along_rows(std::size_t rows, std::size_t columns, FftDirection direction,
                            FftOptions options = {});
  // `columns` transforms of length `rows` down the columns of a row-major rows x columns
  // matrix (stride = columns, distance = 1): e.g. the Doppler FFT across chirps.
  static FftPlan along_columns(std::size_t rows, std::size_t columns, FftDirection direction,
                               FftOptions options = {});

  FftPlan(const FftPlan&) = delete;
  FftPlan& operator=(const FftPlan&) = delete;
  FftPlan(FftPlan&& other) noexcept;
  FftPlan& operator=(FftPlan&& other) noexcept;
  ~FftPlan();

  // Out-of-place plan: transforms `in` into `out`. Both must hold at least buffer_size()
  // elements, must not overlap, and (aligned plans) satisfy fft_is_aligned. `in` is preserved.
  void execute(std::span<const std::complex<double>> in, std::span<std::complex<double>> out) const;
  // In-place plan: transforms `data` (at least buffer_size() elements) in place.
  void execute(std::span<std::complex<double>> data) const;

  const FftLayout& layout() const noexcept { return layout_; }
  FftDirection direction() const noexcept { return direction_; }
  const FftOptions& options() const noexcept { return options_; }
  // Smallest buffer the layout addresses: (howmany-1)*distance + (n-1)*stride + 1.
  std::size_t buffer_size() const noexcept { return buffer_size_; }
  // A shipped_wisdom plan that FFTW made from the shipped wisdom; false where that wisdom did not
  // apply (the plan is then estimate's) and for the other planners.
  bool from_shipped_wisdom() const noexcept { return from_shipped_wisdom_; }

 private:
  void reset() noexcept;

  fftw_plan_s* plan_ = nullptr;
  bool from_shipped_wisdom_ = false;
  FftLayout layout_{};
  FftDirection direction_ = FftDirection::forward;
  FftOptions options_{};
  std::size_t buffer_size_ = 0;
};

// The `columns` transforms of length `rows` down the columns of a row-major rows x columns matrix
// (what FftPlan::along_columns does), in place, done block by block: `block` adjacent columns are
// gathered into a contiguous rows x block buffer, transformed there by one batched FFTW plan
// (howmany = block, stride = block, distance = 1) and written back.
//
// Why: FFTW_ESTIMATE plans the whole strided batch as one codelet (or one Cooley-Tukey plan)
// looped over all columns, reading `rows` elements `columns` * 16 bytes apart; at 1024 columns
// every element of a column falls into the same L1 set, and range + Doppler took 2.0-2.2 x (64 x
// 512, 128 x 1024) to 14-21 x (256 x 2048) the time of FFTW_MEASURE's best (docs/performance.md).
// The block fits in L1 or L2; with `estimate` the plan applied to each column is the one ESTIMATE
// chose for the whole batch (the same codelets, looped over `block` columns instead of all), so
// the results are the same bits as along_columns' (pinned by tests/radar/test_fft.cpp for the
// frame sizes the project uses). The radar chain plans the block with `shipped_wisdom`, whose
// wisdom holds FFTW_MEASURE's plan of this block problem. A last block narrower than `block` uses
// the same plan; the buffer's other columns still hold the previous block's (finite) results, or
// zeros, and FFTW transforms each column independently, so they do not change the gathered
// columns' results.
//
// Thread safety as FftPlan: execute() is const and may run on many threads at once; each call
// uses its own block buffer (one FFTW-aligned allocation of rows * block values per call).
class ColumnBlockFft {
 public:
  // block: columns per block; 0 (the default) takes default_block_columns(rows). Throws
  // InvalidParameter naming "fft.n" (rows), "fft.columns" or "fft.howmany" (block) for sizes FFTW
  // cannot take, as FftPlan does.
  ColumnBlockFft(std::size_t rows, std::size_t columns, FftDirection direction,
                 FftPlanner planner = FftPlanner::estimate, std::size_t block = 0);

  // The block width used when none is given: 32 columns while that block (rows x 32 complex
  // doubles) stays within 32 KiB (up to 64 rows), else 16 (256 bytes of each row) halved while the
  // block exceeds 128 KiB, at least 2. Measured on the project's machine (docs/performance.md):
  // 32 was the fastest of 4-64 at 32 and 64 rows (0.75-0.8 of 16's time), 16 at 128-512 rows, and
  // 32 and more were 2-4 x slower from 256 rows on.
  static std::size_t default_block_columns(std::size_t rows) noexcept;

  // Transforms the columns of `data` (rows * columns values, row-major; any alignment, since only
  // the block buffer is handed to FFTW) in place. Throws Stopped, `data` part transformed, before a
  // block when `stop` says stop (a 65536 x 4096 frame's blocks take seconds in all).
  void execute(std::span<std::complex<double>> data, const StopToken& stop = {}) const;

  std::size_t rows() const noexcept { return rows_; }
  std::size_t columns() const noexcept { return columns_; }
  std::size_t block_columns() const noexcept { return block_; }
  // The plan applied to each block (rows transforms of `block` columns, in place).
  const FftPlan& block_plan() const noexcept { return plan_; }

 private:
  std::size_t rows_;
  std::size_t columns_;
  std::size_t block_;
  FftPlan plan_;  // `block` transforms of length `rows` over a packed rows x block buffer
};

}  // namespace fogradar::radar
