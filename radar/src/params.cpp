#include "fogradar/radar/params.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::radar {
namespace {

constexpr double degree_rad = pi / 180.0;

void require_count(const char* field, std::size_t value, std::size_t low, std::size_t high) {
  require_in_range(field, static_cast<double>(value), static_cast<double>(low), static_cast<double>(high));
}

constexpr std::array<std::pair<SweepDirection, std::string_view>, 2> kDirectionNames{{
    {SweepDirection::up, "up"},
    {SweepDirection::down, "down"},
}};

}  // namespace

std::string_view to_string(SweepDirection direction) noexcept {
  for (const auto& [value, name] : kDirectionNames) {
    if (value == direction) return name;
  }
  return "?";
}

SweepDirection parse_sweep_direction(std::string_view text, std::string_view field) {
  for (const auto& [value, name] : kDirectionNames) {
    if (name == text) return value;
  }
  throw_invalid(field, text, "one of up, down");
}

void RadarParams::validate() const {
  // 1-300 GHz: the radar bands the water models cover (Liebe ends at 1 THz).
  require_in_range("radar.centre_frequency_hz", centre_frequency_hz, 1e9, 300e9);
  // B <= f_c / 2 keeps the whole sweep above 3 f_c / 4.
  if (!(sweep_bandwidth_hz >= 1e6 && sweep_bandwidth_hz <= 0.5 * centre_frequency_hz)) {
    std::ostringstream range;
    range.precision(10);
    range << "in [1e6, radar.centre_frequency_hz / 2 = " << 0.5 * centre_frequency_hz << "]";
    throw_invalid("radar.sweep_bandwidth_hz", sweep_bandwidth_hz, range.str());
  }
  require_in_range("radar.chirp_duration_s", chirp_duration_s, 1e-7, 1e-2);
  if (!(chirp_interval_s >= chirp_duration_s && chirp_interval_s <= 1.0)) {
    std::ostringstream range;
    range.precision(10);
    range << "in [radar.chirp_duration_s = " << chirp_duration_s << ", 1]";
    throw_invalid("radar.chirp_interval_s", chirp_interval_s, range.str());
  }
  require_count("radar.samples_per_chirp", samples_per_chirp, 16, 1 << 16);
  require_in_range("radar.sample_rate_hz", sample_rate_hz, 1e5, 1e10);
  // The samples must fit inside the chirp: N / fs <= T_c.
  const double sampling_time_s = static_cast<double>(samples_per_chirp) / sample_rate_hz;
  if (sampling_time_s > chirp_duration_s * (1.0 + 1e-12)) {
    throw_invalid("radar.samples_per_chirp", static_cast<double>(samples_per_chirp),
                  "an integer <= radar.chirp_duration_s x radar.sample_rate_hz = " +
                      std::to_string(chirp_duration_s * sample_rate_hz) + " (samples fit in the chirp)");
  }
  require_count("radar.chirps_per_frame", chirps_per_frame, 1, 1 << 14);
  require_in_range("radar.tx_power_dbm", tx_power_dbm, -30.0, 50.0);
  require_in_range("radar.tx_gain_dbi", tx_gain_dbi, 0.0, 60.0);
  require_in_range("radar.rx_gain_dbi", rx_gain_dbi, 0.0, 60.0);
  require_in_range("radar.azimuth_beamwidth_deg", azimuth_beamwidth_deg, 0.1, 180.0);
  require_in_range("radar.elevation_beamwidth_deg", elevation_beamwidth_deg, 0.1, 180.0);
  require_in_range("radar.noise_figure_db", noise_figure_db, 0.0, 40.0);
  require_in_range("radar.reference_temperature_k", reference_temperature_k, 1.0, 1000.0);
  require_in_range("radar.adc_bits", adc_bits, 0.0, 24.0);
  require_in_range("radar.adc_full_scale_dbm", adc_full_scale_dbm, -100.0, 30.0);
  require_in_range("radar.phase_noise_rms_rad", phase_noise_rms_rad, 0.0, pi);
  require_in_range("radar.association_gate_m", association_gate_m, 0.0, 1e3);
  cfar.validate();
  // CFAR slides along range, one Doppler bin at a time.
  cfar.validate_profile_length(samples_per_chirp);
}

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
  // Thermal noise k T0 F B with B = fs for complex sampling (noise figure definition, IEEE Std 100).
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
