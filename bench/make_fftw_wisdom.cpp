// Writes the FFTW wisdom that fogradar ships (data/fftw_wisdom.txt, FftPlanner::shipped_wisdom):
// FFTW_MEASURE plans of the radar chain's two transform problems, for every power-of-two size the
// radar parameters allow, made with the same classes, flags and alignment the chain uses, so that
// each wisdom entry is the one the chain's FFTW_ESTIMATE request looks up:
//   range:   one chirp of n = 16 ... 65536 samples, out of place (RangeDopplerProcessor's range
//            plan; the batch is that plan looped over the chirps);
//   Doppler: the column block of ColumnBlockFft for rows = 1 ... 16384 chirps, in place, block
//            width ColumnBlockFft::default_block_columns(rows).
// FFTW_MEASURE times candidate plans, so the output differs from run to run and machine to machine;
// it is made once, committed and reviewed like source (docs/performance.md, "FFTW wisdom"). Run
// on an idle machine (Release build):
//   ./build/release/bench/make_fftw_wisdom > data/fftw_wisdom.txt
#include <fftw3.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "fogradar/radar/fft.hpp"

int main() {
  namespace radar = fogradar::radar;
  try {
    fftw_forget_wisdom();
    for (std::size_t n = 16; n <= (std::size_t{1} << 16); n *= 2) {
      const radar::FftPlan range(n, radar::FftDirection::forward,
                                 {.planner = radar::FftPlanner::measure,
                                  .alignment = radar::FftAlignment::aligned,
                                  .placement = radar::FftPlacement::out_of_place});
      std::fprintf(stderr, "range n = %zu planned\n", n);
    }
    for (std::size_t rows = 1; rows <= (std::size_t{1} << 14); rows *= 2) {
      const std::size_t block = radar::ColumnBlockFft::default_block_columns(rows);
      const radar::ColumnBlockFft doppler(rows, block, radar::FftDirection::forward,
                                          radar::FftPlanner::measure);
      std::fprintf(stderr, "Doppler rows = %zu, block = %zu planned\n", rows, block);
    }
    char* wisdom = fftw_export_wisdom_to_string();
    if (wisdom == nullptr) return 1;
    std::fputs(wisdom, stdout);
    std::free(wisdom);  // allocated by FFTW with malloc
    return std::fflush(stdout) == 0 ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "make_fftw_wisdom: %s\n", error.what());
    return 1;
  }
}
