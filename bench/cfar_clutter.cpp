// Each CFAR shape (range, range_doppler) and kind in zero-Doppler clutter beside a slow target
// (docs/radar.md §7.1). Run by hand (Release build), not a test:
//
//   cfar_clutter [--frames F]
//
// The room's own clutter beside a slow target is scripts/cfar-room.sh's table (the room's back wall
// and barrels through the whole chain). This synthetic frame holds what the room does not make, and
// what the chain does not write: static clutter spread over 60 range cells (the room's back wall
// returns as one specular point; the floor's and side walls' own returns are left out,
// docs/radar.md §3.3) and each detector's margin at the target's cell. The frame is the default
// radar's (512 samples x 64 chirps, Hann in both dimensions, white noise of unit variance per
// sample): a "wall", static scatterers of random phase in every range cell 200-259 at +25 dB per
// cell, and four "barrels", static points at cells 140, 150, 300 and 310 at +40 dB, all at zero
// Doppler (static: exactly Doppler bin 0). A target of +20 dB per cell sits on a range cell (230:
// inside the wall's extent; 305: between two barrels) and a Doppler bin 0-5 (one bin: 0.59 m/s at
// 77 GHz). Every tone is centred on its cells. For each case, F frames (default 40) of independent
// noise: the share in which the target's cell is detected, and the median margin 10 log10(|Y|^2 /
// threshold) there. Then the cells detected in the clutter's rows (Doppler -1, 0, 1) within the
// wall's and barrels' ranges +-3 cells, per frame, and the detections elsewhere (false alarms,
// design P_fa 1e-6). Then each detector's CPU time per map.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <string>
#include <vector>

#include "fogradar/core/random.hpp"
#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/cfar_design.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/processing.hpp"

using namespace fogradar;
using namespace fogradar::radar;

namespace {

struct Tone {
  double range_cell, doppler_bin, snr_db;
  double phase = 0.0;
};

// x_c[n] = sum a e^{i (2 pi (k n / N + d c / N_c) + phase)} + CN(0, 1), a from the SNR per cell:
// a^2 (gain_amplitude)^2 / gain_noise = 10^(snr/10).
void make_frame(const std::vector<Tone>& tones, const RangeDopplerProcessor& processor,
                RandomStream& rng, std::vector<std::complex<double>>& frame) {
  const std::size_t rows = processor.chirps(), columns = processor.samples();
  for (auto& x : frame) x = rng.complex_normal(1.0);
  for (const Tone& t : tones) {
    const double a = std::sqrt(std::pow(10.0, t.snr_db / 10.0) * processor.noise_power_gain()) /
                     processor.coherent_amplitude_gain();
    for (std::size_t c = 0; c < rows; ++c) {
      for (std::size_t n = 0; n < columns; ++n) {
        const double phase =
            2.0 * std::numbers::pi *
                (t.range_cell * static_cast<double>(n) / static_cast<double>(columns) +
                 t.doppler_bin * static_cast<double>(c) / static_cast<double>(rows)) +
            t.phase;
        frame[c * columns + n] += std::polar(a, phase);
      }
    }
  }
}

struct Detector {
  std::string name;
  CfarDetector cfar;
};

}  // namespace

int main(int argc, char** argv) {
  std::size_t frames = 40;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--frames") frames = std::strtoul(argv[i + 1], nullptr, 10);
  }
  RadarParams p;  // 512 x 64, Hann, CFAR g = 2, n = 8, P_fa 1e-6
  const RangeDopplerProcessor processor(p);
  const std::size_t rows = p.chirps_per_frame, columns = p.samples_per_chirp;
  std::vector<Detector> detectors;
  for (const CfarShape shape : {CfarShape::range, CfarShape::range_doppler}) {
    for (const CfarKind kind : {CfarKind::ca, CfarKind::go, CfarKind::so, CfarKind::os}) {
      CfarConfig c = p.cfar;  // ring: g_d = 1, n_d = 2 (the defaults), N = 132
      c.kind = kind;
      c.shape = shape;
      const NoiseCorrelation range_noise =
          window_noise_correlation(processor.range_window(), cfar_correlation_lags(c));
      const NoiseCorrelation doppler_noise =
          window_noise_correlation(processor.doppler_window(), cfar_doppler_correlation_lags(c));
      detectors.push_back({std::string(to_string(shape)) + " " + std::string(to_string(kind)),
                           CfarDetector(c, range_noise, doppler_noise)});
    }
  }
  RandomStream phases(7);
  std::vector<Tone> clutter;
  for (int k = 200; k < 260; ++k)
    clutter.push_back(
        {static_cast<double>(k), 0.0, 25.0, 2.0 * std::numbers::pi * phases.uniform()});
  for (const int k : {140, 150, 300, 310}) clutter.push_back({static_cast<double>(k), 0.0, 40.0});
  const auto in_clutter = [](std::size_t d, std::size_t k, std::size_t rows_) {
    const bool clutter_row = d == 0 || d == 1 || d == rows_ - 1;
    const bool clutter_range =
        (k >= 197 && k <= 262) || (k >= 137 && k <= 153) || (k >= 297 && k <= 313);
    return clutter_row && clutter_range;
  };

  std::vector<std::complex<double>> frame(rows * columns);
  std::vector<double> power(rows * columns);
  CfarWorkspace ws;
  CfarMapWorkspace map_ws;
  std::vector<double> seconds(detectors.size(), 0.0);
  std::vector<double> clutter_cells(detectors.size(), 0.0), false_alarms(detectors.size(), 0.0);
  double maps = 0.0;
  std::printf("| target (range cell, Doppler bin) |");
  for (const Detector& d : detectors) std::printf(" %s |", d.name.c_str());
  std::printf("\n|---|");
  for (std::size_t i = 0; i < detectors.size(); ++i) std::printf("---|");
  std::printf("\n");
  std::uint64_t stream = 0;
  for (const double target_cell : {230.0, 305.0}) {
    for (const double target_bin : {0.0, 1.0, 2.0, 3.0, 5.0}) {
      std::vector<double> kept(detectors.size(), 0.0);
      std::vector<std::vector<double>> margins(detectors.size());
      std::vector<Tone> tones = clutter;
      tones.push_back({target_cell, target_bin, 20.0});
      const std::size_t target =
          static_cast<std::size_t>(target_bin) * columns + static_cast<std::size_t>(target_cell);
      for (std::size_t f = 0; f < frames; ++f) {
        RandomStream rng(2026, ++stream);
        make_frame(tones, processor, rng, frame);
        processor.process(frame, power);
        maps += 1.0;
        for (std::size_t i = 0; i < detectors.size(); ++i) {
          const CfarDetector& cfar = detectors[i].cfar;
          std::vector<double> threshold(rows * columns);
          std::vector<std::size_t> detected;
          const std::clock_t start = std::clock();
          if (cfar.config().shape == CfarShape::range) {
            for (std::size_t d = 0; d < rows; ++d) {
              cfar.detect(std::span<const double>(power).subspan(d * columns, columns), ws);
              std::copy(ws.threshold.begin(), ws.threshold.end(),
                        threshold.begin() + static_cast<std::ptrdiff_t>(d * columns));
              for (const std::size_t k : ws.detections) detected.push_back(d * columns + k);
            }
          } else {
            cfar.detect_map(power, rows, map_ws);
            threshold = map_ws.threshold;
            detected = map_ws.detections;
          }
          seconds[i] += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
          kept[i] += power[target] > threshold[target] ? 1.0 : 0.0;
          margins[i].push_back(10.0 * std::log10(power[target] / threshold[target]));
          for (const std::size_t cell : detected) {
            const std::size_t d = cell / columns, k = cell % columns;
            if (in_clutter(d, k, rows)) {
              clutter_cells[i] += 1.0;
            } else if (std::abs(static_cast<double>(k) - target_cell) > 3.0 ||
                       std::abs(static_cast<double>(d) - target_bin) > 1.0) {
              false_alarms[i] += 1.0;
            }
          }
        }
      }
      std::printf("| %.0f, %.0f |", target_cell, target_bin);
      for (std::size_t i = 0; i < detectors.size(); ++i) {
        std::vector<double>& m = margins[i];
        std::nth_element(m.begin(), m.begin() + static_cast<std::ptrdiff_t>(m.size() / 2), m.end());
        std::printf(" %.0f %% (%+.1f dB) |", 100.0 * kept[i] / static_cast<double>(frames),
                    m[m.size() / 2]);
      }
      std::printf("\n");
    }
  }
  std::printf("| clutter cells detected per map |");
  for (std::size_t i = 0; i < detectors.size(); ++i)
    std::printf(" %.1f |", clutter_cells[i] / maps);
  std::printf("\n| other detections per map |");
  for (std::size_t i = 0; i < detectors.size(); ++i) std::printf(" %.2f |", false_alarms[i] / maps);
  std::printf("\n| CPU ms per map of 512 x 64 |");
  for (std::size_t i = 0; i < detectors.size(); ++i)
    std::printf(" %.2f |", 1e3 * seconds[i] / maps);
  std::printf("\n");
  return 0;
}
