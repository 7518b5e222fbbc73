// Shared helpers for the radar-chain tests (test_chain.cpp, test_scene.cpp, test_params.cpp):
// chambers, radars and small reference computations written out independently of the library.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstddef>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "fogradar/propagation/chamber.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/radar/estimation.hpp"
#include "fogradar/radar/params.hpp"
#include "fogradar/radar/window.hpp"

namespace fogradar::radar::test {

inline constexpr WindowType kAllWindows[] = {WindowType::rectangular, WindowType::hann,
                                             WindowType::hamming, WindowType::blackman_harris,
                                             WindowType::chebyshev};

inline std::string window_name(const ::testing::TestParamInfo<WindowType>& info) {
  return std::string(to_string(info.param));
}

inline const propagation::SegelsteinTable& segelstein_table() {
  static const propagation::SegelsteinTable instance;
  return instance;
}

// The study's chamber (paper Fig. 1): l_s = 2 m, four 1 m layers, l_t = 4 m (target at 10 m),
// every layer with the given fog.
inline propagation::ChamberSpec paper_chamber_spec(
    const propagation::FogSpec& fog = propagation::FogSpec{}) {
  propagation::ChamberSpec spec;
  for (propagation::FogLayerSpec& layer : spec.layers) layer.fog = fog;
  return spec;
}

inline propagation::Chamber make_chamber(const propagation::ChamberSpec& spec,
                                         double frequency_hz) {
  return propagation::Chamber(spec, frequency_hz, segelstein_table());
}

// The strongest detection of a list, or nullptr.
inline const Detection* strongest(const std::vector<Detection>& detections) {
  const Detection* best = nullptr;
  for (const Detection& d : detections) {
    if (best == nullptr || d.received_power_w > best->received_power_w) best = &d;
  }
  return best;
}

// Radar equation written out here (Skolnik, Introduction to Radar Systems, eq. 2.1; paper eq. 7
// solved for P_r): P_r = P_t G_t G_r lambda^2 sigma / ((4 pi)^3 R^4), inputs in dB / dBm.
inline double reference_received_power_w(const RadarParams& p, double rcs_m2, double range_m) {
  const double pt_w = 1e-3 * std::pow(10.0, p.tx_power_dbm / 10.0);
  const double gt = std::pow(10.0, p.tx_gain_dbi / 10.0);
  const double gr = std::pow(10.0, p.rx_gain_dbi / 10.0);
  const double lambda_m = 299'792'458.0 / p.centre_frequency_hz;
  const double four_pi = 4.0 * std::numbers::pi;
  return pt_w * gt * gr * lambda_m * lambda_m * rcs_m2 /
         (four_pi * four_pi * four_pi * std::pow(range_m, 4));
}

// k T0 F fs for the radar (W), written out here.
inline double reference_noise_power_w(const RadarParams& p) {
  return 1.380649e-23 * p.reference_temperature_k * std::pow(10.0, p.noise_figure_db / 10.0) *
         p.sample_rate_hz;
}

// One range-FFT bin in metres: c / (2 S T_s N) with T_s = 1/fs, i.e. c fs / (2 S N).
inline double reference_range_bin_m(const RadarParams& p) {
  const double slope = p.sweep_bandwidth_hz / p.chirp_duration_s;
  return 299'792'458.0 * p.sample_rate_hz /
         (2.0 * slope * static_cast<double>(p.samples_per_chirp));
}

inline double sum_of(std::span<const double> w) {
  double s = 0.0;
  for (double v : w) s += v;
  return s;
}

inline double sum_of_squares(std::span<const double> w) {
  double s = 0.0;
  for (double v : w) s += v * v;
  return s;
}

}  // namespace fogradar::radar::test
