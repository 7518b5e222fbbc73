// The radar's raw data kinds (docs/data-out.md): each kind's shape, axes, columns and attributes.
#include <cmath>
#include <cstddef>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/radar/sensor.hpp"
#include "fogradar/radar/window.hpp"

namespace fogradar::radar {

std::vector<sensor::RawKind> radar_raw_kinds(const SensorParams& params) {
  const RadarParams& p = params.radar;
  const RadarDerived d = derive(p);
  const std::size_t chirps = p.chirps_per_frame, samples = p.samples_per_chirp;
  sensor::RawAxis chirp_time{"chirp_time_s", "s", {}}, sample_time{"sample_time_s", "s", {}},
      velocity{"velocity_m_per_s", "m/s", {}}, range{"range_m", "m", {}};
  for (std::size_t c = 0; c < chirps; ++c) {
    chirp_time.values.push_back(static_cast<double>(c) * p.chirp_interval_s);
    // Row c of the map is Doppler bin c, or c - N_c from N_c/2 on (processing.hpp).
    const double bin =
        static_cast<double>(c) - (2 * c >= chirps ? static_cast<double>(chirps) : 0.0);
    velocity.values.push_back(d.sweep_sign * bin * d.velocity_resolution_m_per_s);
  }
  for (std::size_t n = 0; n < samples; ++n) {
    sample_time.values.push_back(static_cast<double>(n) / p.sample_rate_hz);
    range.values.push_back(static_cast<double>(n) * d.range_bin_m);
  }
  const std::size_t detections =
      4 + static_cast<std::size_t>(std::ceil(2.0 * p.cfar.false_alarm_probability *
                                             static_cast<double>(chirps * samples)));
  // The map's scale (processing.hpp): thermal noise of k T0 F fs per sample reaches each cell as
  // that times sum(w_r^2) sum(w_d^2); a tone of amplitude a on a bin centre peaks at
  // |X| = a N CG_r N_c CG_d.
  const std::vector<double> range_window = make_window(p.window, samples);
  const std::vector<double> doppler_window = make_window(p.window, chirps);
  const double noise_level = d.noise_power_w * noise_power_gain(range_window, doppler_window);
  const double gain = coherent_amplitude_gain(range_window, doppler_window);
  std::vector<sensor::RawKind> kinds(7);
  kinds[raw_beat] = {
      .name = "beat",
      .description =
          "the beat signal as synthesised, complex baseband I/Q at the receiver input "
          "before the window: chirps x samples",
      .units = "sqrt(W)",
      .element = sensor::RawElement::complex128,
      .dimensions = {"chirp", "sample"},
      .shape = {chirps, samples},
      .axes = {chirp_time, sample_time},
      .columns = {},
      .rows_per_item = 0,
      .attributes = {}};
  kinds[raw_range_doppler] = {
      .name = "range_doppler",
      .description =
          "|X|^2 of the windowed 2-D DFT of the beat, as the CFAR sees it: Doppler rows "
          "in FFT order (bin d >= N_c/2 is d - N_c) x range columns; range_m is the "
          "range of a static echo in each column, velocity_m_per_s each row's",
      .units = "W (beat units squared, with the window's and the DFT's gains)",
      .element = sensor::RawElement::float64,
      .dimensions = {"doppler", "range"},
      .shape = {chirps, samples},
      .axes = {velocity, range},
      .columns = {},
      .rows_per_item = 0,
      .attributes = {{"thermal_noise_level", noise_level}, {"coherent_amplitude_gain", gain}}};
  kinds[raw_detections] = {
      .name = "detections",
      .description =
          "every detection of the frame with its origin (radar_detections.csv): range "
          "corrected for the range-Doppler coupling, received power at the receiver "
          "input; in_gate: within the association gate; associated: the gate's "
          "strongest, radar_samples.csv's; range_cell, doppler_cell: the peak cell the "
          "attribution looked at (column and row of range_doppler and origins); layer: for "
          "a fog origin, the chamber layer (chamber.layers[layer]) that dominates the fog "
          "there, else -1",
      .units = "",
      .element = sensor::RawElement::table,
      .dimensions = {},
      .shape = {},
      .axes = {},
      .columns = {{"range_m", "m", false, {}},
                  {"velocity_m_per_s", "m/s", false, {}},
                  {"power_dbm", "dBm", false, {}},
                  {"snr_db", "dB", false, {}},
                  {"rcs_dbsm", "dBsm", false, {}},
                  {"origin", "", false, sensor::origin_labels()},
                  {"in_gate", "", true, {}},
                  {"associated", "", true, {}},
                  {"range_cell", "", true, {}},
                  {"doppler_cell", "", true, {}},
                  {"layer", "", true, {}}},
      .rows_per_item = detections,
      .attributes = {}};
  // The beat's parts (synthesis.hpp, FrameParts), on request: beat = signal + noise exactly for
  // static paths, to rounding with moving ones, both before the ADC.
  kinds[raw_signal] = kinds[raw_beat];
  kinds[raw_signal].name = "signal";
  kinds[raw_signal].description =
      "the beat signal without its thermal noise: the paths, the fog clutter and the phase noise "
      "(before the ADC); beat = signal + noise";
  kinds[raw_signal].by_default = false;
  kinds[raw_noise] = kinds[raw_beat];
  kinds[raw_noise].name = "noise";
  kinds[raw_noise].description =
      "the receiver's thermal noise of the beat signal as drawn, CN(0, k T0 F fs) per sample "
      "(before the ADC)";
  kinds[raw_noise].by_default = false;
  // Where a detection of the frame would come from, per cell: what the chain's attribution gives a
  // detection peaking there. A detection names its peak cell (range_cell, doppler_cell); from its
  // range_m and velocity_m_per_s alone the column is near range bin (range_m + range_coupling_s
  // velocity_m_per_s) / range_bin_m (the coupling the estimate removed) and the row near Doppler
  // bin velocity_m_per_s / velocity_bin_m_per_s, within the interpolation's offset from the peak.
  kinds[raw_origins] = kinds[raw_range_doppler];
  kinds[raw_origins].name = "origins";
  kinds[raw_origins].description =
      "the frame's ground truth per cell: the origin the chain's attribution gives a detection "
      "peaking there (target, fog, sidelobe, noise, or clipping in a frame whose ADC clipped), "
      "Doppler rows in FFT order x range columns as range_doppler";
  kinds[raw_origins].units = "";
  kinds[raw_origins].element = sensor::RawElement::uint8;
  kinds[raw_origins].labels = sensor::origin_labels();
  kinds[raw_origins].by_default = false;
  kinds[raw_origins].attributes = {
      {"range_bin_m", d.range_bin_m},
      {"velocity_bin_m_per_s", d.sweep_sign * d.velocity_resolution_m_per_s},
      {"range_coupling_s",
       doppler_shift_hz(1.0, d) * speed_of_light_m_per_s / (2.0 * d.chirp_slope_hz_per_s)}};
  kinds[raw_origin_layers] = kinds[raw_origins];
  kinds[raw_origin_layers].name = "origin_layers";
  kinds[raw_origin_layers].description =
      "the frame's fog layer per cell, beside origins: where the origin is fog, the chamber layer "
      "(the index in chamber.layers, 0-based from the sensor) whose echoes dominate the fog "
      "there; -1 elsewhere";
  kinds[raw_origin_layers].element = sensor::RawElement::int16;
  kinds[raw_origin_layers].labels = {};
  return kinds;
}

}  // namespace fogradar::radar
