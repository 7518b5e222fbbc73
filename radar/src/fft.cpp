#include "fogradar/radar/fft.hpp"

#include <fftw3.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <functional>
#include <mutex>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "fogradar/core/error.hpp"

namespace fogradar::radar {
namespace detail {
// Text of data/fftw_wisdom.txt, embedded at build time by cmake/EmbedText.cmake.
std::string_view fftw_wisdom_text();
}  // namespace detail

namespace {

// FFTW's planner (fftw_plan_*) and fftw_destroy_plan mutate global planner state (wisdom,
// codelet tables) and are not thread-safe; only the execute functions are (FFTW 3.3 manual
// §5.4 "Thread safety"). Every plan creation and destruction in the process goes through this
// one mutex. A function-local static (rather than a namespace-scope one) is constructed on first
// use, so it is valid even for plans created during static initialisation of other objects.
std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

int to_fftw_int(std::string_view field, std::size_t value) {
  if (value == 0 || value > static_cast<std::size_t>(INT_MAX)) {
    throw_invalid(field, static_cast<double>(value), "in [1, 2147483647]");
  }
  return static_cast<int>(value);
}

fftw_complex* as_fftw(std::complex<double>* pointer) {
  // std::complex<double> and fftw_complex (double[2]) are layout-compatible (FFTW manual §4.1.1).
  return reinterpret_cast<fftw_complex*>(pointer);
}

fftw_complex* as_fftw_mutable(const std::complex<double>* pointer) {
  // FFTW's execute signature is not const-correct; out-of-place plans are made with
  // FFTW_PRESERVE_INPUT, so the input is never written.
  return reinterpret_cast<fftw_complex*>(const_cast<std::complex<double>*>(pointer));
}

bool aligned_for(const FftOptions& options, const void* pointer) {
  return options.alignment == FftAlignment::unaligned || fft_is_aligned(pointer);
}

// For its lifetime the planner holds the shipped wisdom alone; the process's wisdom is exported
// on entry and restored on exit (forget, then import: FFTW 3.3 manual §4.7). FFTW hashes its
// solver set for every export and import (about 0.15 ms each here), so the export is one pass
// through fftw_export_wisdom rather than fftw_export_wisdom_to_string's two. The caller holds
// planner_mutex().
class ShippedWisdomOnly {
 public:
  ShippedWisdomOnly() {
    struct Export {
      std::string text;
      bool out_of_memory = false;
    } exported;
    // No exception may cross FFTW's C frames.
    fftw_export_wisdom(
        [](char c, void* data) {
          auto& to = *static_cast<Export*>(data);
          try {
            if (!to.out_of_memory) to.text.push_back(c);
          } catch (const std::bad_alloc&) {
            to.out_of_memory = true;
          }
        },
        &exported);
    if (exported.out_of_memory) throw std::bad_alloc();
    process_wisdom_ = std::move(exported.text);
    fftw_forget_wisdom();
    // Refused only by an FFTW with another solver set; its plans are then estimate's.
    fftw_import_wisdom_from_string(fft_shipped_wisdom().data());
  }
  ~ShippedWisdomOnly() {
    fftw_forget_wisdom();
    fftw_import_wisdom_from_string(process_wisdom_.c_str());
  }
  ShippedWisdomOnly(const ShippedWisdomOnly&) = delete;
  ShippedWisdomOnly& operator=(const ShippedWisdomOnly&) = delete;

 private:
  std::string process_wisdom_;
};

}  // namespace

std::string_view fft_shipped_wisdom() { return detail::fftw_wisdom_text(); }

void* fft_aligned_allocate(std::size_t bytes) {
  void* pointer = fftw_malloc(bytes == 0 ? 1 : bytes);
  if (pointer == nullptr) throw std::bad_alloc();
  return pointer;
}

void fft_aligned_free(void* pointer) noexcept { fftw_free(pointer); }

bool fft_is_aligned(const void* pointer) noexcept {
  // fftw_alignment_of only inspects the address; the cast does not access memory.
  return fftw_alignment_of(static_cast<double*>(const_cast<void*>(pointer))) == 0;
}

FftPlan::FftPlan(std::size_t n, FftDirection direction, FftOptions options)
    : FftPlan(FftLayout{n, 1, 1, 0}, direction, options) {}

FftPlan::FftPlan(const FftLayout& layout, FftDirection direction, FftOptions options)
    : layout_(layout), direction_(direction), options_(options) {
  // Validate the layout (FFTW takes int sizes).
  const int n = to_fftw_int("fft.n", layout.n);
  const int howmany = to_fftw_int("fft.howmany", layout.howmany);
  const int stride = to_fftw_int("fft.stride", layout.stride);
  if (layout_.distance == 0) layout_.distance = layout_.n;
  const int distance = to_fftw_int("fft.distance", layout_.distance);
  buffer_size_ = (layout_.howmany - 1) * layout_.distance + (layout_.n - 1) * layout_.stride + 1;

  unsigned flags = options.planner == FftPlanner::measure ? FFTW_MEASURE : FFTW_ESTIMATE;
  if (options.alignment == FftAlignment::unaligned) flags |= FFTW_UNALIGNED;
  if (options.placement == FftPlacement::out_of_place) flags |= FFTW_PRESERVE_INPUT;
  const int sign = direction == FftDirection::forward ? FFTW_FORWARD : FFTW_BACKWARD;

  // Plan on private, fftw_malloc-aligned scratch arrays (FFTW_MEASURE overwrites them). The plan
  // is only ever run through fftw_execute_dft with caller arrays, so the scratch is freed after
  // planning.
  struct Scratch {
    fftw_complex* data = nullptr;
    explicit Scratch(std::size_t count)
        : data(static_cast<fftw_complex*>(fft_aligned_allocate(count * sizeof(fftw_complex)))) {}
    ~Scratch() { fftw_free(data); }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
  };
  Scratch in(buffer_size_);
  std::optional<Scratch> out;
  fftw_complex* out_data = in.data;
  if (options.placement == FftPlacement::out_of_place) {
    out.emplace(buffer_size_);
    out_data = out->data;
  }

  {
    const std::lock_guard<std::mutex> lock(planner_mutex());
    const auto plan_with = [&](unsigned with_flags) {
      return fftw_plan_many_dft(1, &n, howmany, in.data, nullptr, stride, distance, out_data,
                                nullptr, stride, distance, sign, with_flags);
    };
    if (options.planner == FftPlanner::shipped_wisdom) {
      const ShippedWisdomOnly shipped;
      // FFTW_WISDOM_ONLY plans only from wisdom (FFTW 3.3 manual §4.3.2), which tells whether the
      // shipped wisdom made the plan; the same wisdom entries that a plain estimate request uses.
      plan_ = plan_with(flags | FFTW_WISDOM_ONLY);
      from_shipped_wisdom_ = plan_ != nullptr;
      if (plan_ == nullptr) plan_ = plan_with(flags);
    } else {
      plan_ = plan_with(flags);
    }
  }
  if (plan_ == nullptr) throw InternalError("FFTW could not create a plan for the given layout");
}

FftPlan FftPlan::along_rows(std::size_t rows, std::size_t columns, FftDirection direction,
                            FftOptions options) {
  return FftPlan(FftLayout{columns, rows, 1, columns}, direction, options);
}

FftPlan FftPlan::along_columns(std::size_t rows, std::size_t columns, FftDirection direction,
                               FftOptions options) {
  return FftPlan(FftLayout{rows, columns, columns, 1}, direction, options);
}

FftPlan::FftPlan(FftPlan&& other) noexcept
    : plan_(std::exchange(other.plan_, nullptr)),
      from_shipped_wisdom_(other.from_shipped_wisdom_),
      layout_(other.layout_),
      direction_(other.direction_),
      options_(other.options_),
      buffer_size_(other.buffer_size_) {}

FftPlan& FftPlan::operator=(FftPlan&& other) noexcept {
  if (this != &other) {
    reset();
    plan_ = std::exchange(other.plan_, nullptr);
    from_shipped_wisdom_ = other.from_shipped_wisdom_;
    layout_ = other.layout_;
    direction_ = other.direction_;
    options_ = other.options_;
    buffer_size_ = other.buffer_size_;
  }
  return *this;
}

FftPlan::~FftPlan() { reset(); }

void FftPlan::reset() noexcept {
  if (plan_ != nullptr) {
    const std::lock_guard<std::mutex> lock(planner_mutex());
    fftw_destroy_plan(plan_);
    plan_ = nullptr;
  }
}

void FftPlan::execute(std::span<const std::complex<double>> in,
                      std::span<std::complex<double>> out) const {
  FOGRADAR_CHECK(plan_ != nullptr);  // not moved-from
  FOGRADAR_CHECK(options_.placement == FftPlacement::out_of_place);
  FOGRADAR_CHECK(in.size() >= buffer_size_ && out.size() >= buffer_size_);
  const std::less<const std::complex<double>*> before;
  FOGRADAR_CHECK(!before(out.data(), in.data() + in.size()) ||
                 !before(in.data(), out.data() + out.size()));  // no overlap
  FOGRADAR_CHECK(aligned_for(options_, in.data()) && aligned_for(options_, out.data()));
  fftw_execute_dft(plan_, as_fftw_mutable(in.data()), as_fftw(out.data()));
}

void FftPlan::execute(std::span<std::complex<double>> data) const {
  FOGRADAR_CHECK(plan_ != nullptr);
  FOGRADAR_CHECK(options_.placement == FftPlacement::in_place);
  FOGRADAR_CHECK(data.size() >= buffer_size_);
  FOGRADAR_CHECK(aligned_for(options_, data.data()));
  fftw_execute_dft(plan_, as_fftw(data.data()), as_fftw(data.data()));
}

namespace {

std::size_t block_or_default(std::size_t block, std::size_t rows) {
  if (block == 0) return ColumnBlockFft::default_block_columns(rows);
  return block;
}

}  // namespace

ColumnBlockFft::ColumnBlockFft(std::size_t rows, std::size_t columns, FftDirection direction,
                               FftPlanner planner, std::size_t block)
    : rows_(rows),
      columns_(columns),
      block_(block_or_default(block, rows)),
      plan_(FftLayout{rows, block_, block_, 1}, direction,
            {.planner = planner,
             .alignment = FftAlignment::aligned,
             .placement = FftPlacement::in_place}) {
  to_fftw_int("fft.columns", columns);
}

std::size_t ColumnBlockFft::default_block_columns(std::size_t rows) noexcept {
  constexpr std::size_t value_bytes = sizeof(std::complex<double>);
  if (rows * 32 * value_bytes <= 32 * 1024) return 32;
  std::size_t block = 16;
  while (block > 2 && rows * block * value_bytes > 128 * 1024) block /= 2;
  return block;
}

void ColumnBlockFft::execute(std::span<std::complex<double>> data, const StopToken& stop) const {
  FOGRADAR_CHECK(data.size() >= rows_ * columns_);
  ComplexVector buffer(rows_ * block_);
  for (std::size_t first = 0; first < columns_; first += block_) {
    stop.check();
    const std::size_t width = std::min(block_, columns_ - first);
    const std::size_t bytes = width * sizeof(std::complex<double>);
    for (std::size_t r = 0; r < rows_; ++r)
      std::memcpy(&buffer[r * block_], &data[r * columns_ + first], bytes);
    plan_.execute(buffer);
    for (std::size_t r = 0; r < rows_; ++r)
      std::memcpy(&data[r * columns_ + first], &buffer[r * block_], bytes);
  }
}

}  // namespace fogradar::radar
