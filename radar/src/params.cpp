#include "fogradar/radar/params.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::radar {
namespace {

constexpr double degree_rad = pi / 180.0;

}  // namespace

KeyTable<RadarParams> radar_param_keys() {
  KeyTable<RadarParams> keys;
  // Its value was the start of a down-chirp, which a reader of "carrier" could not know.
  keys.retired("radar.carrier_frequency_hz",
               "give the sweep centre as radar.centre_frequency_hz and the direction as "
               "radar.sweep_direction = \"up\" | \"down\" (the old 77e9 meant a 77 -> 76 GHz "
               "down-chirp: centre_frequency_hz = 76.5e9, sweep_direction = \"down\")");
  // 1-300 GHz: the radar bands the water models cover (Liebe ends at 1 THz).
  keys.number(
      "radar.centre_frequency_hz", FOGRADAR_KEY_FIELD(centre_frequency_hz), closed(1e9, 300e9),
      "f_c, the centre of the sweep: λ = c/f_c in eq. 7 and the Doppler scale, the phase of "
      "echoes sharing a range cell, and the frequency the chamber's fog is resolved at; "
      "the water models cover it");
  keys.choice("radar.sweep_direction", FOGRADAR_KEY_FIELD(sweep_direction), sweep_direction_names,
              "up: f_c − B/2 → f_c + B/2 (most automotive front ends); down: the reverse "
              "(docs/radar.md §3.2)");
  // B <= f_c / 2 keeps the whole sweep above 3 f_c / 4.
  keys.number("radar.sweep_bandwidth_hz", FOGRADAR_KEY_FIELD(sweep_bandwidth_hz),
              "[1e6, centre_frequency_hz/2]", nullptr, "B; range resolution c/(2B)")
      .within([](const RadarParams& p) {
        const double half = 0.5 * p.centre_frequency_hz;
        return CrossBound{.range = closed(1e6, half),
                          .low_text = "1e6",
                          .high_text = "radar.centre_frequency_hz / 2 = " + message_number(half),
                          .note = ""};
      });
  keys.number("radar.chirp_duration_s", FOGRADAR_KEY_FIELD(chirp_duration_s), closed(1e-7, 1e-2),
              "T_c; slope S = B/T_c");
  keys.number("radar.chirp_interval_s", FOGRADAR_KEY_FIELD(chirp_interval_s),
              "[chirp_duration_s, 1]", nullptr, "chirp start to chirp start (Doppler sampling)")
      .within([](const RadarParams& p) {
        return CrossBound{
            .range = closed(p.chirp_duration_s, 1.0),
            .low_text = "radar.chirp_duration_s = " + message_number(p.chirp_duration_s),
            .high_text = "1",
            .note = ""};
      });
  keys.integer("radar.samples_per_chirp", FOGRADAR_KEY_FIELD(samples_per_chirp), 16, 1 << 16,
               "complex I/Q samples per chirp")
      .within([](const RadarParams& p) {
        // The samples must fit inside the chirp: N / fs <= T_c.
        const double fitting = p.chirp_duration_s * p.sample_rate_hz;
        const double most = std::min(65536.0, std::floor(fitting * (1.0 + 1e-12)));
        return CrossBound{.range = closed(16.0, most),
                          .low_text = "16",
                          .high_text = message_number(most),
                          .integer = true,
                          .note =
                              ": the samples fit in the chirp, radar.chirp_duration_s x "
                              "radar.sample_rate_hz = " +
                              message_number(fitting)};
      })
      .documented_as("integer [16, 65536], ≤ chirp_duration_s · sample_rate_hz");
  keys.number("radar.sample_rate_hz", FOGRADAR_KEY_FIELD(sample_rate_hz), closed(1e5, 1e10),
              "complex sampling; unambiguous range c·fs/(2S)");
  keys.integer("radar.chirps_per_frame", FOGRADAR_KEY_FIELD(chirps_per_frame), 1, 1 << 14,
               "chirps per measurement");
  keys.number("radar.tx_power_dbm", FOGRADAR_KEY_FIELD(tx_power_dbm), closed(-30.0, 50.0), "P_t");
  keys.number("radar.tx_gain_dbi", FOGRADAR_KEY_FIELD(tx_gain_dbi), closed(0.0, 60.0),
              "boresight transmit antenna gain");
  keys.number("radar.rx_gain_dbi", FOGRADAR_KEY_FIELD(rx_gain_dbi), closed(0.0, 60.0),
              "boresight receive antenna gain");
  keys.number("radar.azimuth_beamwidth_deg", FOGRADAR_KEY_FIELD(azimuth_beamwidth_deg),
              closed(0.1, 180.0), "one-way 3 dB azimuth beamwidth (Gaussian beam)");
  keys.number("radar.elevation_beamwidth_deg", FOGRADAR_KEY_FIELD(elevation_beamwidth_deg),
              closed(0.1, 180.0), "one-way 3 dB elevation beamwidth (Gaussian beam)");
  keys.choice("radar.polarisation", FOGRADAR_KEY_FIELD(polarisation), polarisation_names,
              "linear polarisation of both antennas; picks each room reflection's Fresnel "
              "coefficient (an assumption: the study names none)");
  keys.number("radar.noise_figure_db", FOGRADAR_KEY_FIELD(noise_figure_db), closed(0.0, 40.0),
              "F; noise power k·T0·F·fs");
  keys.number("radar.reference_temperature_k", FOGRADAR_KEY_FIELD(reference_temperature_k),
              closed(1.0, 1000.0), "T0");
  keys.integer("radar.adc_bits", FOGRADAR_KEY_FIELD(adc_bits), 0, 24,
               "0: ideal ADC; else mid-rise quantiser per I/Q rail");
  keys.number("radar.adc_full_scale_dbm", FOGRADAR_KEY_FIELD(adc_full_scale_dbm),
              closed(-100.0, 30.0), "power of a full-scale complex tone")
      .when([](const RadarParams& p) { return p.adc_bits > 0; },
            "with radar.adc_bits > 0 (0: an ideal ADC, which neither quantises nor clips)");
  keys.number("radar.phase_noise_rms_rad", FOGRADAR_KEY_FIELD(phase_noise_rms_rad), closed(0.0, pi),
              "white phase noise per sample")
      .documented_as("[0, π]");
  // A radome of no thickness is no layer: its material would change nothing.
  const auto has_radome = [](const RadarParams& p) { return p.radome.thickness_m > 0.0; };
  const std::string radome_text =
      "with radar.radome.thickness_m > 0 (0: no radome, whose material changes nothing)";
  keys.number("radar.radome.thickness_m", FOGRADAR_KEY_FIELD(radome.thickness_m), closed(0.0, 0.05),
              "flat radome in front of the antenna; 0: none");
  keys.number("radar.radome.relative_permittivity",
              FOGRADAR_KEY_FIELD(radome.relative_permittivity), closed(1.0, 100.0),
              "ε_r′ of the radome (default 2.9: of the order of polycarbonate at W band)")
      .when(has_radome, radome_text);
  keys.number("radar.radome.loss_tangent", FOGRADAR_KEY_FIELD(radome.loss_tangent),
              closed(0.0, 1.0), "tan δ = ε_r″/ε_r′ of the radome (default 0.01)")
      .when(has_radome, radome_text);
  keys.number("radar.radome.water_film_m", FOGRADAR_KEY_FIELD(radome.water_film_m),
              closed(0.0, 0.01),
              "water film on the radome's outer face (the study's water-covered sensor), with the "
              "water model and temperature of the first layer's fog; also without a radome");
  keys.choice("radar.processing.window", FOGRADAR_KEY_FIELD(window), window_type_names,
              "range and Doppler window");
  keys.number("radar.processing.association_gate_m", FOGRADAR_KEY_FIELD(association_gate_m),
              closed(0.0, 1e3),
              "the tracked target is the strongest detection within this of the chamber's target "
              "range");
  keys.include(cfar_keys("radar.processing.cfar."), FOGRADAR_KEY_FIELD(cfar));
  // The CFAR slides along range, one Doppler bin at a time: its window must fit in a range profile.
  // The range-Doppler ring spans its columns in every row it reaches: fewer than all of them (a
  // tapered window's zero end sample makes the noise of all N cells linearly dependent).
  const auto ring = [](const RadarParams& p) { return p.cfar.shape == CfarShape::range_doppler; };
  const auto columns = [ring](const RadarParams& p) {
    return ring(p) ? p.samples_per_chirp - 1 : p.samples_per_chirp;
  };
  const auto profile = [ring](const RadarParams& p) {
    return "a profile of radar.samples_per_chirp = " + std::to_string(p.samples_per_chirp) +
           " cells" +
           (ring(p) ? " less one for radar.processing.cfar.shape = \"range_doppler\"" : "");
  };
  Key<RadarParams>& guard = keys.at("radar.processing.cfar.guard_cells");
  guard
      .within([profile, columns](const RadarParams& p) {
        return p.cfar.guard_bound(columns(p), "radar.processing.cfar.", profile(p));
      })
      .documented_as(guard.allowed +
                     ", with 2·(guard + training) + 1 ≤ samples_per_chirp (− 1 for the ring)");
  Key<RadarParams>& training = keys.at("radar.processing.cfar.training_cells");
  training
      .within([profile, columns](const RadarParams& p) {
        return p.cfar.training_bound(columns(p), "radar.processing.cfar.", profile(p));
      })
      .documented_as(training.allowed +
                     ", with 2·(guard + training) + 1 ≤ samples_per_chirp (− 1 for the ring)");
  // The ring's Doppler rows are distinct around the circular Doppler axis of chirps_per_frame rows.
  const auto map = [](const RadarParams& p) {
    return "a map of radar.chirps_per_frame = " + std::to_string(p.chirps_per_frame) + " rows";
  };
  Key<RadarParams>& doppler_guard = keys.at("radar.processing.cfar.doppler_guard_cells");
  doppler_guard
      .within([map](const RadarParams& p) {
        return p.cfar.doppler_guard_bound(p.chirps_per_frame, "radar.processing.cfar.", map(p));
      })
      .documented_as(doppler_guard.allowed +
                     ", with 2·(doppler guard + doppler training) + 1 ≤ chirps_per_frame − 1");
  Key<RadarParams>& doppler_training = keys.at("radar.processing.cfar.doppler_training_cells");
  doppler_training
      .within([map](const RadarParams& p) {
        return p.cfar.doppler_training_bound(p.chirps_per_frame, "radar.processing.cfar.", map(p));
      })
      .documented_as(doppler_training.allowed +
                     ", with 2·(doppler guard + doppler training) + 1 ≤ chirps_per_frame − 1");
  return keys;
}

void RadarParams::validate() const { radar_param_keys().check(*this); }

RadarDerived derive(const RadarParams& p) {
  p.validate();
  RadarDerived d{};
  d.wavelength_m = wavelength_from_frequency_m(p.centre_frequency_hz);
  d.sweep_sign = p.sweep_direction == SweepDirection::up ? 1.0 : -1.0;
  d.start_frequency_hz = p.centre_frequency_hz - 0.5 * d.sweep_sign * p.sweep_bandwidth_hz;
  d.chirp_slope_hz_per_s = p.sweep_bandwidth_hz / p.chirp_duration_s;
  d.range_resolution_m = speed_of_light_m_per_s / (2.0 * p.sweep_bandwidth_hz);
  d.max_range_m = speed_of_light_m_per_s * p.sample_rate_hz / (2.0 * d.chirp_slope_hz_per_s);
  d.range_bin_m = d.max_range_m / static_cast<double>(p.samples_per_chirp);
  d.velocity_resolution_m_per_s =
      d.wavelength_m / (2.0 * static_cast<double>(p.chirps_per_frame) * p.chirp_interval_s);
  d.max_unambiguous_velocity_m_per_s = d.wavelength_m / (4.0 * p.chirp_interval_s);
  // Thermal noise k T0 F B with B = fs for complex sampling (noise figure definition, IEEE Std
  // 100).
  d.noise_power_w = boltzmann_j_per_k * p.reference_temperature_k *
                    db_to_power_ratio(p.noise_figure_db) * p.sample_rate_hz;
  d.tx_power_w = dbm_to_watt(p.tx_power_dbm);
  d.tx_gain = db_to_power_ratio(p.tx_gain_dbi);
  d.rx_gain = db_to_power_ratio(p.rx_gain_dbi);
  d.beam_solid_angle_sr = two_way_beam_solid_angle_sr(p.azimuth_beamwidth_deg * degree_rad,
                                                      p.elevation_beamwidth_deg * degree_rad);
  return d;
}

double beat_frequency_hz(double path_length_m, double chirp_slope_hz_per_s) {
  return chirp_slope_hz_per_s * path_length_m / speed_of_light_m_per_s;
}

double echo_phase_at_chirp_start_rad(double path_length_m, const RadarDerived& derived) {
  const double delay_s = path_length_m / speed_of_light_m_per_s;
  return derived.sweep_sign * 2.0 * pi * delay_s * derived.start_frequency_hz -
         pi * derived.chirp_slope_hz_per_s * delay_s * delay_s;
}

double folded_velocity_m_per_s(double radial_velocity_m_per_s, double max_unambiguous_m_per_s) {
  const double period = 2.0 * max_unambiguous_m_per_s;
  return radial_velocity_m_per_s - period * std::round(radial_velocity_m_per_s / period);
}

double doppler_shift_hz(double radial_velocity_m_per_s, const RadarDerived& derived) {
  return derived.sweep_sign * 2.0 * radial_velocity_m_per_s / derived.wavelength_m;
}

double received_power_w(double tx_power_w, double tx_gain, double rx_gain, double wavelength_m,
                        double rcs_m2, double range_m) {
  const double four_pi_cubed = std::pow(4.0 * pi, 3);
  return tx_power_w * tx_gain * rx_gain * wavelength_m * wavelength_m * rcs_m2 /
         (four_pi_cubed * std::pow(range_m, 4));
}

double rcs_from_received_power_m2(double received_power_w, double tx_power_w, double tx_gain,
                                  double rx_gain, double wavelength_m, double range_m) {
  const double four_pi_cubed = std::pow(4.0 * pi, 3);
  return four_pi_cubed * std::pow(range_m, 4) * received_power_w /
         (tx_power_w * tx_gain * rx_gain * wavelength_m * wavelength_m);
}

double gaussian_beam_power(double off_axis_rad, double beamwidth_3db_rad) {
  const double u = off_axis_rad / beamwidth_3db_rad;
  return std::exp(-4.0 * std::log(2.0) * u * u);
}

double two_way_beam_solid_angle_sr(double azimuth_beamwidth_rad, double elevation_beamwidth_rad) {
  return pi * azimuth_beamwidth_rad * elevation_beamwidth_rad / (8.0 * std::log(2.0));
}

}  // namespace fogradar::radar
