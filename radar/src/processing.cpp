#include "fogradar/radar/processing.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <numeric>
#include <optional>

#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::radar {
namespace {

double sum_of_squares(std::span<const double> w) {
  return std::inner_product(w.begin(), w.end(), w.begin(), 0.0);
}

// Each value twice, to scale interleaved (re, im) pairs.
std::vector<double> doubled(std::span<const double> w) {
  std::vector<double> pairs(2 * w.size());
  for (std::size_t n = 0; n < w.size(); ++n) pairs[2 * n] = pairs[2 * n + 1] = w[n];
  return pairs;
}

// The out-of-place range FFT of one chirp if it reproduces the in-place batch `batch` bit for bit
// on a frame of pseudo-random values (xorshift64*, any fixed sequence does): FFTW's codelets are
// fixed sequences of operations, so equal results on such values mean the same operations. The
// batch applies one plan to every chirp in turn, so its first two and its last chirp are compared
// (faulting in the frame's fresh pages is most of the cost, so no second frame is made). Null if
// not equal, or if a chirp of an aligned frame is not aligned.
std::optional<FftPlan> chirp_plan_with_batch_bits(const FftPlan& batch, std::size_t chirps,
                                                  std::size_t samples, FftPlanner planner) {
  ComplexVector frame(chirps * samples);
  if (chirps > 1 && !fft_is_aligned(frame.data() + samples)) return std::nullopt;
  FftPlan chirp(samples, FftDirection::forward,
                {.planner = planner,
                 .alignment = FftAlignment::aligned,
                 .placement = FftPlacement::out_of_place});
  std::uint64_t state = 0x9E3779B97F4A7C15ULL;
  const auto next = [&state] {
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return static_cast<double>((state * 0x2545F4914F6CDD1DULL) >> 11) * 0x1p-53 - 0.5;
  };
  for (std::complex<double>& value : frame) value = {next(), next()};
  const std::size_t compared[] = {0, std::min<std::size_t>(1, chirps - 1), chirps - 1};
  ComplexVector by_chirp(std::size(compared) * samples);
  const std::span<const std::complex<double>> input(frame);
  for (std::size_t j = 0; j < std::size(compared); ++j) {
    chirp.execute(input.subspan(compared[j] * samples, samples),
                  std::span(by_chirp).subspan(j * samples, samples));
  }
  batch.execute(frame);
  for (std::size_t j = 0; j < std::size(compared); ++j) {
    if (std::memcmp(&frame[compared[j] * samples], &by_chirp[j * samples],
                    samples * sizeof(frame[0])) != 0) {
      return std::nullopt;
    }
  }
  return chirp;
}

}  // namespace

RangeDopplerProcessor::RangeDopplerProcessor(const RadarParams& params, FftPlanner planner)
    : chirps_(params.chirps_per_frame),
      samples_(params.samples_per_chirp),
      range_window_(make_window(params.window, samples_)),
      doppler_window_(make_window(params.window, chirps_)),
      range_window_pairs_(doubled(range_window_)),
      range_fft_(FftPlan::along_rows(chirps_, samples_, FftDirection::forward,
                                     {.planner = planner, .placement = FftPlacement::in_place})),
      doppler_fft_(chirps_, samples_, FftDirection::forward, planner),
      coherent_amplitude_gain_(static_cast<double>(samples_) * coherent_gain(range_window_) *
                               static_cast<double>(chirps_) * coherent_gain(doppler_window_)),
      noise_power_gain_(sum_of_squares(range_window_) * sum_of_squares(doppler_window_)) {
  range_chirp_fft_ = chirp_plan_with_batch_bits(range_fft_, chirps_, samples_, planner);
}

// Cloned so that AVX2 squares and adds four values per instruction (element-wise: the same bits in
// every clone); the baseline's two-lane SSE2 loop took 1.25-1.39 x as long over a bench map.
FOGRADAR_SIMD_CLONES
void squared_magnitudes(std::span<const std::complex<double>> values, std::span<double> power) {
  FOGRADAR_CHECK(power.size() == values.size());
  for (std::size_t i = 0; i < values.size(); ++i) power[i] = std::norm(values[i]);
}

void RangeDopplerProcessor::process(std::span<std::complex<double>> frame,
                                    std::span<double> power) const {
  FOGRADAR_CHECK(power.size() == frame.size());
  transform(frame);
  squared_magnitudes(frame, power);
}

void RangeDopplerProcessor::transform(std::span<std::complex<double>> frame) const {
  FOGRADAR_CHECK(frame.size() == chirps_ * samples_);
  // Both windows at once: the 2-D window is separable and the transforms are linear.
  apply_frame_window(window(), frame);
  transform_windowed(frame);
}

void RangeDopplerProcessor::transform_windowed(std::span<std::complex<double>> frame) const {
  FOGRADAR_CHECK(frame.size() == chirps_ * samples_);
  range_fft_.execute(frame);
  doppler_fft_.execute(frame);
}

void RangeDopplerProcessor::doppler_transform(std::span<std::complex<double>> frame) const {
  FOGRADAR_CHECK(frame.size() == chirps_ * samples_);
  doppler_fft_.execute(frame);
}

}  // namespace fogradar::radar
