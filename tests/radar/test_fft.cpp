// FftPlan tests. Reference: a naive O(n^2) DFT in long double (exact twiddles from the reduced
// index j k mod n), and the DFT identities (Parseval, inverse, linearity of batching).
// Tolerances: 1e-12 relative (max error / max magnitude), tighter than the 1e-9 the radar chain
// needs; FFTW's measured error is ~1e-16 relative times log2 n.
#include <fftw3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/radar/fft.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;

constexpr double kRelTol = 1e-12;

const char* direction_name(FftDirection direction) {
  return direction == FftDirection::forward ? "forward" : "inverse";
}

// Records and checks max |FFT - DFT| / max |DFT| <= kRelTol against the long-double DFT.
void validate_against_dft(const std::string& id, const std::string& conditions, double error) {
  fogradar::testing::validate({.id = id,
                               .group = "radar: signal processing",
                               .quantity = "max |FFT - DFT| / max |DFT|",
                               .unit = "1",
                               .conditions = conditions,
                               .reference = kRelTol,
                               .source = "direct O(n^2) DFT in long double (this test)",
                               .value = error,
                               .tolerance = 0.0,
                               .kind = Tolerance::at_most});
}

ComplexVector random_signal(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  ComplexVector x(n);
  for (auto& value : x) value = {normal(rng), normal(rng)};
  return x;
}

// X[k] = sum_j x[j] exp(-+2 pi i j k / n) in long double.
std::vector<std::complex<long double>> naive_dft(const ComplexVector& x, FftDirection direction) {
  const std::size_t n = x.size();
  const long double sign = direction == FftDirection::forward ? -1.0L : 1.0L;
  const long double two_pi = 2.0L * std::numbers::pi_v<long double>;
  std::vector<std::complex<long double>> twiddle(n);  // exp(-+2 pi i m / n), m = j k mod n
  for (std::size_t m = 0; m < n; ++m) {
    const long double angle =
        sign * two_pi * static_cast<long double>(m) / static_cast<long double>(n);
    twiddle[m] = {std::cos(angle), std::sin(angle)};
  }
  std::vector<std::complex<long double>> result(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::complex<long double> sum = 0.0L;
    for (std::size_t j = 0; j < n; ++j) {
      sum += std::complex<long double>(x[j].real(), x[j].imag()) * twiddle[(j * k) % n];
    }
    result[k] = sum;
  }
  return result;
}

// max |a - b| / max |b|
template <class A, class B>
double relative_error(const A& a, const B& b, std::size_t count) {
  long double max_error = 0.0L;
  long double max_magnitude = 0.0L;
  for (std::size_t i = 0; i < count; ++i) {
    const std::complex<long double> ai(a[i].real(), a[i].imag());
    const std::complex<long double> bi(b[i].real(), b[i].imag());
    max_error = std::max(max_error, std::abs(ai - bi));
    max_magnitude = std::max(max_magnitude, std::abs(bi));
  }
  return static_cast<double>(max_error / max_magnitude);
}

// Column c of a row-major rows x columns matrix.
ComplexVector column_of(const ComplexVector& matrix, std::size_t rows, std::size_t columns,
                        std::size_t c) {
  ComplexVector column(rows);
  for (std::size_t r = 0; r < rows; ++r) column[r] = matrix[r * columns + c];
  return column;
}

// --- Against the naive DFT --------------------------------------------------------------------

class FftSize : public ::testing::TestWithParam<std::size_t> {};

// Forward and inverse transforms against the long-double DFT for powers of 2, composite and
// prime sizes (FFTW uses different algorithms for each). Tolerance kRelTol.
TEST_P(FftSize, MatchesNaiveDft) {
  const std::size_t n = GetParam();
  const ComplexVector x = random_signal(n, n);
  for (const FftDirection direction : {FftDirection::forward, FftDirection::inverse}) {
    const FftPlan plan(n, direction);
    ComplexVector y(n);
    plan.execute(x, y);
    const double error = relative_error(y, naive_dft(x, direction), n);
    validate_against_dft(
        "radar.fft.naive_dft." + std::string(direction_name(direction)) + ".n" + std::to_string(n),
        std::string(direction_name(direction)) + ", n = " + std::to_string(n), error);
    if (direction == FftDirection::forward && (n == 1000 || n == 1009 || n == 1024)) {
      std::printf("[ measured ] n=%zu forward FFT relative error vs long-double DFT %.2e\n", n,
                  error);
    }
  }
}

// Parseval: sum |x|^2 = sum |X|^2 / n, within 1e-12 relative.
TEST_P(FftSize, Parseval) {
  const std::size_t n = GetParam();
  const ComplexVector x = random_signal(n, n + 1);
  ComplexVector y(n);
  FftPlan(n, FftDirection::forward).execute(x, y);
  long double energy_time = 0.0L;
  long double energy_freq = 0.0L;
  for (std::size_t i = 0; i < n; ++i) {
    energy_time += std::norm(std::complex<long double>(x[i].real(), x[i].imag()));
    energy_freq += std::norm(std::complex<long double>(y[i].real(), y[i].imag()));
  }
  const double ratio = static_cast<double>(energy_freq / static_cast<long double>(n) / energy_time);
  fogradar::testing::validate({.id = "radar.fft.parseval.n" + std::to_string(n),
                               .group = "radar: signal processing",
                               .quantity = "sum |X|^2 / (n sum |x|^2)",
                               .unit = "1",
                               .conditions = "forward, n = " + std::to_string(n),
                               .reference = 1.0,
                               .source = "Parseval's theorem of the DFT",
                               .value = ratio,
                               .tolerance = 1e-12,
                               .kind = Tolerance::relative});
}

// inverse(forward(x)) = n x (FFTW's unnormalised inverse), within kRelTol of n max|x|; the
// input of an out-of-place plan is preserved; in-place plans give the same result.
TEST_P(FftSize, ForwardThenInverseReturnsScaledInput) {
  const std::size_t n = GetParam();
  const ComplexVector x = random_signal(n, n + 2);
  const ComplexVector x_copy = x;
  ComplexVector spectrum(n);
  ComplexVector back(n);
  FftPlan(n, FftDirection::forward).execute(x, spectrum);
  EXPECT_EQ(x, x_copy);  // FFTW_PRESERVE_INPUT
  FftPlan(n, FftDirection::inverse).execute(spectrum, back);
  ComplexVector scaled(n);
  for (std::size_t i = 0; i < n; ++i) scaled[i] = static_cast<double>(n) * x[i];
  fogradar::testing::validate({.id = "radar.fft.inverse_of_forward.n" + std::to_string(n),
                               .group = "radar: signal processing",
                               .quantity = "max |inverse(forward(x)) - n x| / max |n x|",
                               .unit = "1",
                               .conditions = "out of place, n = " + std::to_string(n),
                               .reference = kRelTol,
                               .source = "DFT inversion identity: unnormalised inverse gives n x",
                               .value = relative_error(back, scaled, n),
                               .tolerance = 0.0,
                               .kind = Tolerance::at_most});

  ComplexVector in_place = x;
  FftPlan(n, FftDirection::forward, {.placement = FftPlacement::in_place}).execute(in_place);
  EXPECT_LE(relative_error(in_place, spectrum, n), kRelTol) << "n=" << n;
}

INSTANTIATE_TEST_SUITE_P(Sizes, FftSize,
                         ::testing::Values(1, 2, 3, 5, 7, 8, 12, 60, 64, 97, 100, 243, 512, 1000,
                                           1009, 1024));

// --- Batched layouts --------------------------------------------------------------------------

// Rows of a row-major matrix (range FFTs of every chirp) in one batched call equal one plan per
// row; columns (Doppler FFTs, stride = columns) equal per-column transforms of the extracted
// column. Tolerance kRelTol per vector (FFTW may choose different codelets when batched).
TEST(FftBatch, RowsAndColumnsEqualPerVectorTransforms) {
  for (const auto& [rows, columns] :
       {std::pair<std::size_t, std::size_t>{7, 60}, {64, 512}, {5, 97}, {16, 1}}) {
    const ComplexVector matrix = random_signal(rows * columns, rows * 1000 + columns);

    ComplexVector by_rows(matrix.size());
    FftPlan::along_rows(rows, columns, FftDirection::forward).execute(matrix, by_rows);
    const FftPlan row_plan(columns, FftDirection::forward);
    for (std::size_t r = 0; r < rows; ++r) {
      const ComplexVector row(matrix.begin() + static_cast<long>(r * columns),
                              matrix.begin() + static_cast<long>((r + 1) * columns));
      ComplexVector expected(columns);
      row_plan.execute(row, expected);
      EXPECT_LE(relative_error(by_rows.data() + r * columns, expected, columns), kRelTol)
          << rows << "x" << columns << " row " << r;
    }

    ComplexVector by_columns(matrix.size());
    FftPlan::along_columns(rows, columns, FftDirection::forward).execute(matrix, by_columns);
    const FftPlan column_plan(rows, FftDirection::forward);
    for (std::size_t c = 0; c < columns; ++c) {
      ComplexVector expected(rows);
      column_plan.execute(column_of(matrix, rows, columns, c), expected);
      EXPECT_LE(relative_error(column_of(by_columns, rows, columns, c), expected, rows), kRelTol)
          << rows << "x" << columns << " column " << c;
    }
  }
}

// A general layout (stride 2, distance 3n: interleaved vectors with gaps) transforms exactly the
// addressed elements and leaves the others untouched; buffer_size() is the addressed extent.
TEST(FftBatch, GeneralLayoutTouchesOnlyAddressedElements) {
  const FftLayout layout{.n = 12, .howmany = 3, .stride = 2, .distance = 36};
  const FftPlan plan(layout, FftDirection::forward);
  EXPECT_EQ(plan.buffer_size(), 2 * 36 + 11 * 2 + 1);
  const ComplexVector input = random_signal(plan.buffer_size(), 5);
  const std::complex<double> sentinel(-7.0, 3.0);
  ComplexVector output(plan.buffer_size(), sentinel);
  plan.execute(input, output);
  std::vector<bool> addressed(plan.buffer_size(), false);
  const FftPlan single(12, FftDirection::forward);
  for (std::size_t b = 0; b < 3; ++b) {
    ComplexVector vector(12);
    ComplexVector got(12);
    for (std::size_t j = 0; j < 12; ++j) {
      addressed[b * 36 + j * 2] = true;
      vector[j] = input[b * 36 + j * 2];
      got[j] = output[b * 36 + j * 2];
    }
    ComplexVector expected(12);
    single.execute(vector, expected);
    EXPECT_LE(relative_error(got, expected, 12), kRelTol) << "transform " << b;
  }
  for (std::size_t i = 0; i < output.size(); ++i) {
    if (!addressed[i]) {
      EXPECT_EQ(output[i], sentinel) << i;
    }
  }
}

// --- Column transforms in blocks -------------------------------------------------------------

// ColumnBlockFft against the long-double DFT of every column, for block widths that divide the
// column count and ones that leave a narrower last block, forward and inverse.
// Tolerance kRelTol per column (FFTW's error is ~1e-16 log2 n relative; header comment).
TEST(FftColumnBlocks, MatchesNaiveDftOfEveryColumn) {
  struct Case {
    std::size_t rows, columns, block;
  };
  for (const Case& c :
       {Case{12, 37, 8}, Case{64, 20, 0}, Case{5, 16, 4}, Case{1, 3, 2}, Case{30, 7, 16}}) {
    for (const FftDirection direction : {FftDirection::forward, FftDirection::inverse}) {
      const ComplexVector input = random_signal(c.rows * c.columns, c.rows * 100 + c.columns);
      ComplexVector data = input;
      ColumnBlockFft(c.rows, c.columns, direction, FftPlanner::estimate, c.block).execute(data);
      for (std::size_t col = 0; col < c.columns; ++col) {
        const ComplexVector column = column_of(input, c.rows, c.columns, col);
        const ComplexVector got = column_of(data, c.rows, c.columns, col);
        validate_against_dft("radar.fft.column_blocks." + std::to_string(c.rows) + "x" +
                                 std::to_string(c.columns) + ".block" + std::to_string(c.block) +
                                 "." + direction_name(direction) + ".column" + std::to_string(col),
                             "ColumnBlockFft " + std::string(direction_name(direction)) + ", " +
                                 std::to_string(c.rows) + " x " + std::to_string(c.columns) +
                                 ", block " + std::to_string(c.block) + ", column " +
                                 std::to_string(col),
                             relative_error(got, naive_dft(column, direction), c.rows));
      }
    }
  }
}

// The blocked Doppler transform gives the same bits as the one strided FFTW_ESTIMATE plan over all
// columns (FftPlan::along_columns) that the chain used before it, for the frame sizes of the
// project's scenarios (paper 64 x 512, bench 128 x 1024, long frames 256 x 2048) and column
// counts the default block (32 or 16) does not divide (a narrower last block): the plan ESTIMATE
// applies to each column is the same, only the loop over columns is split. Exact equality.
TEST(FftColumnBlocks, SameBitsAsOneStridedEstimatePlan) {
  for (const auto& [rows, columns] : {std::pair<std::size_t, std::size_t>{64, 512},
                                      {128, 1024},
                                      {256, 2048},
                                      {128, 1000},
                                      {96, 300},
                                      {64, 200},
                                      {32, 256}}) {
    const ComplexVector input = random_signal(rows * columns, rows + columns);
    ComplexVector strided = input;
    FftPlan::along_columns(rows, columns, FftDirection::forward,
                           {.placement = FftPlacement::in_place})
        .execute(strided);
    ComplexVector blocked = input;
    const ColumnBlockFft blocks(rows, columns, FftDirection::forward);
    blocks.execute(blocked);
    EXPECT_TRUE(blocked == strided)
        << rows << "x" << columns << " block " << blocks.block_columns();
  }
}

TEST(FftColumnBlocks, DefaultBlockFollowsTheBufferSize) {
  EXPECT_EQ(ColumnBlockFft::default_block_columns(64), 32u);    // 32 columns: 32 KiB
  EXPECT_EQ(ColumnBlockFft::default_block_columns(65), 16u);    // 32 would exceed 32 KiB
  EXPECT_EQ(ColumnBlockFft::default_block_columns(512), 16u);   // 128 KiB
  EXPECT_EQ(ColumnBlockFft::default_block_columns(1024), 8u);   // 128 KiB
  EXPECT_EQ(ColumnBlockFft::default_block_columns(16384), 2u);  // the minimum, 512 KiB
  EXPECT_EQ(ColumnBlockFft(128, 1024, FftDirection::forward).block_columns(), 16u);
}

// One ColumnBlockFft shared by threads, each with its own frame: the same bits as one thread
// (each call has its own block buffer).
TEST(FftColumnBlocks, SharedByThreadsGivesIdenticalResults) {
  constexpr std::size_t kRows = 32;
  constexpr std::size_t kColumns = 200;
  const ColumnBlockFft blocks(kRows, kColumns, FftDirection::forward);
  const ComplexVector input = random_signal(kRows * kColumns, 17);
  ComplexVector reference = input;
  blocks.execute(reference);
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < mismatches.size(); ++t) {
    threads.emplace_back([&, t] {
      for (int repeat = 0; repeat < 10; ++repeat) {
        ComplexVector data = input;
        blocks.execute(data);
        if (data != reference) ++mismatches[t];
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (std::size_t t = 0; t < mismatches.size(); ++t) EXPECT_EQ(mismatches[t], 0) << t;
}

TEST(FftColumnBlocks, RejectsInvalidSizes) {
  const auto field = [](std::size_t rows, std::size_t columns) {
    return test_support::rejected_field(
        [&] { const ColumnBlockFft blocks(rows, columns, FftDirection::forward); });
  };
  EXPECT_EQ(field(0, 8), "fft.n");
  EXPECT_EQ(field(8, 0), "fft.columns");
  EXPECT_EQ(field(8, 8), "accepted");
}

// --- Sharing and ownership --------------------------------------------------------------------

// One plan shared by several std::threads (each with its own buffers) gives results
// bit-identical to a single-threaded run; meanwhile other threads create and destroy plans
// (the planner mutex). Exact equality: same plan, same alignment, same codelets.
TEST(FftThreads, SharedPlanGivesIdenticalResults) {
  constexpr std::size_t kRows = 32;
  constexpr std::size_t kColumns = 256;
  constexpr int kThreads = 4;
  constexpr int kRepeats = 20;
  const FftPlan plan = FftPlan::along_rows(kRows, kColumns, FftDirection::forward);
  const ComplexVector input = random_signal(kRows * kColumns, 99);
  ComplexVector reference(input.size());
  plan.execute(input, reference);

  std::vector<int> mismatches(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      ComplexVector output(input.size());
      for (int repeat = 0; repeat < kRepeats; ++repeat) {
        plan.execute(input, output);
        if (output != reference) ++mismatches[static_cast<std::size_t>(t)];
        // Concurrent planning and destruction elsewhere in the process.
        const FftPlan scratch(static_cast<std::size_t>(64 + t + repeat), FftDirection::inverse);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(mismatches[static_cast<std::size_t>(t)], 0) << t;
}

// Moving transfers ownership (the moved-to plan works, the moved-from one is inert and safe to
// destroy); FftPlan is not copyable.
TEST(FftPlanOwnership, MoveTransfersThePlan) {
  static_assert(!std::is_copy_constructible_v<FftPlan>);
  static_assert(!std::is_copy_assignable_v<FftPlan>);
  static_assert(std::is_nothrow_move_constructible_v<FftPlan>);
  const ComplexVector x = random_signal(16, 1);
  ComplexVector expected(16);
  FftPlan(16, FftDirection::forward).execute(x, expected);

  FftPlan original(16, FftDirection::forward);
  FftPlan moved(std::move(original));
  ComplexVector y(16);
  moved.execute(x, y);
  EXPECT_EQ(y, expected);
  EXPECT_THROW(original.execute(x, y), InternalError);  // NOLINT(bugprone-use-after-move)

  FftPlan assigned(8, FftDirection::inverse);
  assigned = std::move(moved);
  assigned.execute(x, y);
  EXPECT_EQ(y, expected);
  EXPECT_EQ(assigned.layout().n, 16u);
}

// --- Alignment and misuse ---------------------------------------------------------------------

TEST(FftAlignment, AlignedVectorIsAligned) {
  for (const std::size_t n : {1u, 3u, 17u, 1024u}) {
    const ComplexVector v(n);
    EXPECT_TRUE(fft_is_aligned(v.data())) << n;
  }
}

// An aligned plan rejects a misaligned buffer (programmer error -> InternalError); an
// FftAlignment::unaligned plan accepts it and is correct (kRelTol vs the naive DFT).
TEST(FftAlignment, UnalignedBuffersNeedAnUnalignedPlan) {
  constexpr std::size_t n = 60;
  // Complex values placed 8 bytes past an aligned address: valid for std::complex<double>
  // (alignment 8) but not for FFTW's SIMD alignment.
  AlignedVector<std::byte> raw_in((n + 1) * sizeof(std::complex<double>));
  AlignedVector<std::byte> raw_out((n + 1) * sizeof(std::complex<double>));
  auto* in = reinterpret_cast<std::complex<double>*>(raw_in.data() + sizeof(double));
  auto* out = reinterpret_cast<std::complex<double>*>(raw_out.data() + sizeof(double));
  const ComplexVector x = random_signal(n, 3);
  std::uninitialized_copy(x.begin(), x.end(), in);
  std::uninitialized_fill_n(out, n, std::complex<double>());
  ASSERT_FALSE(fft_is_aligned(in));

  const FftPlan aligned(n, FftDirection::forward);
  EXPECT_THROW(aligned.execute(std::span<const std::complex<double>>(in, n),
                               std::span<std::complex<double>>(out, n)),
               InternalError);

  const FftPlan unaligned(n, FftDirection::forward, {.alignment = FftAlignment::unaligned});
  unaligned.execute(std::span<const std::complex<double>>(in, n),
                    std::span<std::complex<double>>(out, n));
  validate_against_dft("radar.fft.unaligned_plan.n60",
                       "forward, n = 60, buffers 8 bytes past SIMD alignment",
                       relative_error(out, naive_dft(x, FftDirection::forward), n));
}

TEST(FftPlanMisuse, WrongPlacementOrShortBufferIsAnInternalError) {
  ComplexVector a(32);
  ComplexVector b(32);
  ComplexVector short_buffer(31);
  const FftPlan out_of_place(32, FftDirection::forward);
  const FftPlan in_place(32, FftDirection::forward, {.placement = FftPlacement::in_place});
  EXPECT_THROW(out_of_place.execute(a), InternalError);
  EXPECT_THROW(in_place.execute(a, b), InternalError);
  EXPECT_THROW(out_of_place.execute(short_buffer, b), InternalError);
  EXPECT_THROW(out_of_place.execute(a, a), InternalError);  // overlapping
  EXPECT_THROW(in_place.execute(short_buffer), InternalError);
}

// Invalid layouts are bad input naming the field.
TEST(FftPlanConfig, RejectsInvalidLayout) {
  const auto expect_field = [](const FftLayout& layout, const std::string& field) {
    EXPECT_EQ(
        test_support::rejected_field([&] { const FftPlan plan(layout, FftDirection::forward); }),
        field);
  };
  expect_field({.n = 0}, "fft.n");
  expect_field({.n = 8, .howmany = 0}, "fft.howmany");
  expect_field({.n = 8, .howmany = 2, .stride = 0}, "fft.stride");
  expect_field({.n = std::size_t{1} << 40}, "fft.n");
}

// FFTW_MEASURE plans compute the same transform (kRelTol vs the estimate plan).
TEST(FftPlanner, MeasureMatchesEstimate) {
  const ComplexVector x = random_signal(256, 4);
  ComplexVector estimate(256);
  ComplexVector measure(256);
  FftPlan(256, FftDirection::forward).execute(x, estimate);
  FftPlan(256, FftDirection::forward, {.planner = FftPlanner::measure}).execute(x, measure);
  EXPECT_LE(relative_error(measure, estimate, 256), kRelTol);
}

// --- The shipped wisdom (FftPlanner::shipped_wisdom) ------------------------------------------

FftOptions shipped_one_chirp() {
  return {.planner = FftPlanner::shipped_wisdom,
          .alignment = FftAlignment::aligned,
          .placement = FftPlacement::out_of_place};
}

// The chain's plans at every power-of-two size the radar parameters allow (radar.samples_per_chirp
// 16 ... 65536, radar.chirps_per_frame 1 ... 16384) come from the shipped wisdom: the one-chirp
// range plan, and the Doppler column block at its default width, as RangeDopplerProcessor makes
// them. A failure means FFTW ignored data/fftw_wisdom.txt (an FFTW with another solver set than
// Debian 12's 3.3.10, or a CPU without the AVX codelets it names) and the chain planned as
// estimate, or that bench/make_fftw_wisdom and the chain plan different problems.
TEST(FftShippedWisdom, MakesEveryChainPlanOfAPowerOfTwoSize) {
  for (std::size_t n = 16; n <= (std::size_t{1} << 16); n *= 2) {
    EXPECT_TRUE(FftPlan(n, FftDirection::forward, shipped_one_chirp()).from_shipped_wisdom())
        << "range, n = " << n;
  }
  for (std::size_t rows = 1; rows <= (std::size_t{1} << 14); rows *= 2) {
    const ColumnBlockFft doppler(rows, 512, FftDirection::forward, FftPlanner::shipped_wisdom);
    EXPECT_TRUE(doppler.block_plan().from_shipped_wisdom()) << "Doppler, rows = " << rows;
  }
  // Not for problems the wisdom lacks: the plan is then estimate's.
  EXPECT_FALSE(FftPlan(1000, FftDirection::forward, shipped_one_chirp()).from_shipped_wisdom());
  EXPECT_FALSE(FftPlan(512, FftDirection::inverse, shipped_one_chirp()).from_shipped_wisdom());
  EXPECT_FALSE(FftPlan(512, FftDirection::forward).from_shipped_wisdom());
}

// Plans from the shipped wisdom compute the DFT: the range plan against the long-double DFT up to
// 4096 points and, where that O(n^2) reference is too slow, against the estimate plan (itself
// checked against the DFT above); the Doppler blocks against the DFT of every column, 1 ... 1024
// rows of 20 columns (one block narrower than the default width, or full blocks and a narrower
// last one). Tolerance kRelTol.
TEST(FftShippedWisdom, PlansComputeTheDft) {
  for (std::size_t n = 16; n <= (std::size_t{1} << 16); n *= 2) {
    const ComplexVector x = random_signal(n, n + 7);
    ComplexVector shipped(n);
    FftPlan(n, FftDirection::forward, shipped_one_chirp()).execute(x, shipped);
    if (n <= 4096) {
      validate_against_dft("radar.fft.shipped_wisdom.range.n" + std::to_string(n),
                           "shipped-wisdom range plan, forward, n = " + std::to_string(n),
                           relative_error(shipped, naive_dft(x, FftDirection::forward), n));
    } else {
      ComplexVector estimate(n);
      FftPlan(n, FftDirection::forward).execute(x, estimate);
      EXPECT_LE(relative_error(shipped, estimate, n), kRelTol) << "n = " << n;
    }
  }
  constexpr std::size_t columns = 20;
  for (std::size_t rows = 1; rows <= 1024; rows *= 2) {
    const ComplexVector input = random_signal(rows * columns, rows + 11);
    ComplexVector data = input;
    ColumnBlockFft(rows, columns, FftDirection::forward, FftPlanner::shipped_wisdom).execute(data);
    for (std::size_t col = 0; col < columns; ++col) {
      const ComplexVector column = column_of(input, rows, columns, col);
      const ComplexVector got = column_of(data, rows, columns, col);
      validate_against_dft("radar.fft.shipped_wisdom.doppler.rows" + std::to_string(rows) +
                               ".column" + std::to_string(col),
                           "shipped-wisdom Doppler blocks, forward, " + std::to_string(rows) +
                               " x 20, column " + std::to_string(col),
                           relative_error(got, naive_dft(column, FftDirection::forward), rows));
    }
  }
}

// FFTW's wisdom as a set of lines: one entry per line, in the order of FFTW's hash table, which
// an import does not keep.
std::vector<std::string> exported_wisdom() {
  char* text = fftw_export_wisdom_to_string();
  std::vector<std::string> lines;
  std::istringstream stream(text != nullptr ? text : "");
  std::free(text);  // allocated by FFTW with malloc
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  std::sort(lines.begin(), lines.end());
  return lines;
}

// The process's own wisdom neither reaches a shipped_wisdom plan nor is changed by one. FFTW gives
// an estimate request the plan of any wisdom it holds for the problem (manual §4.3.2), so after
// FFTW_MEASURE plans of the chain's problems a plain estimate plan may be another algorithm; a
// shipped plan made then must give the bits of one made before them, and the wisdom FFTW exports
// must be the same before and after the shipped plan is made (the measured entries kept).
TEST(FftShippedWisdom, IsIsolatedFromTheProcessWisdom) {
  constexpr std::size_t rows = 64;
  constexpr std::size_t samples = 512;
  const ComplexVector chirp = random_signal(samples, 3);
  const ComplexVector frame = random_signal(rows * samples, 4);
  const auto shipped_bits = [&] {
    ComplexVector range(samples);
    FftPlan(samples, FftDirection::forward, shipped_one_chirp()).execute(chirp, range);
    ComplexVector doppler = frame;
    ColumnBlockFft(rows, samples, FftDirection::forward, FftPlanner::shipped_wisdom)
        .execute(doppler);
    range.insert(range.end(), doppler.begin(), doppler.end());
    return range;
  };
  const ComplexVector before = shipped_bits();

  const FftPlan measured_range(samples, FftDirection::forward,
                               {.planner = FftPlanner::measure,
                                .alignment = FftAlignment::aligned,
                                .placement = FftPlacement::out_of_place});
  const ColumnBlockFft measured_doppler(rows, samples, FftDirection::forward, FftPlanner::measure);
  const std::vector<std::string> process_wisdom = exported_wisdom();
  ASSERT_GT(process_wisdom.size(), 2U);  // the header, measured entries, the closing parenthesis

  const ComplexVector after = shipped_bits();
  EXPECT_EQ(std::memcmp(before.data(), after.data(), before.size() * sizeof before[0]), 0);
  EXPECT_EQ(exported_wisdom(), process_wisdom);
}

}  // namespace
}  // namespace fogradar::radar
