// Parameters of the FMCW radar and its processing chain, and the quantities derived from them in
// one place. Defaults are the paper scenario (examples/paper.toml): a typical 77 GHz long-range
// radar (1 GHz sweep, 512 x 64 samples per frame, 10 dBm, 25 dBi, 12 dB noise figure).
#pragma once

#include <cstddef>
#include <string_view>

#include "fogradar/core/enum_names.hpp"
#include "fogradar/core/keys.hpp"
#include "fogradar/radar/cfar.hpp"
#include "fogradar/radar/window.hpp"

namespace fogradar::radar {

// Direction of the linear frequency sweep of each chirp: up from f_c - B/2 to f_c + B/2, or down
// from f_c + B/2 to f_c - B/2 (docs/radar.md §3.2).
enum class SweepDirection { up, down };
inline constexpr auto sweep_direction_names =
    enum_names<SweepDirection>({{SweepDirection::up, "up"}, {SweepDirection::down, "down"}});
constexpr std::string_view to_string(SweepDirection direction) noexcept {
  return sweep_direction_names.name(direction);
}

// The linear polarisation of the radar's transmit and receive antennas (the same for both): the
// electric field horizontal (along y for a ray on boresight) or vertical (along z). It picks the
// Fresnel coefficient of each reflection off a material surface (docs/radar.md, the room).
enum class Polarisation { horizontal, vertical };
inline constexpr auto polarisation_names = enum_names<Polarisation>(
    {{Polarisation::horizontal, "horizontal"}, {Polarisation::vertical, "vertical"}});
constexpr std::string_view to_string(Polarisation polarisation) noexcept {
  return polarisation_names.name(polarisation);
}

// The radar's radome and the water film on its outer face (the study's water-covered sensor): flat
// slabs at normal incidence in the transfer-matrix model (propagation/water_film.hpp). Thickness 0:
// no radome. The permittivity defaults are an assumption of the order of polycarbonate's at W band,
// a common radome plastic (TI application note SWRA705, 2021; J. W. Lamb 1996, Int. J. IR MM Waves
// 17, 1997, tabulates mm-wave plastics): a user gives the radome's datasheet values.
struct Radome {
  double thickness_m = 0.0;
  double relative_permittivity = 2.9;  // real part eps_r'
  double loss_tangent = 0.01;          // eps_r'' / eps_r'
  double water_film_m = 0.0;           // on the outer face; the first layer's fog's water index
};

struct RadarParams {
  // Centre f_c of the swept band: lambda = c / f_c in the radar equation (paper eq. 7) and the
  // Doppler scale, and the phase with which echoes in one range cell interfere (docs/radar.md).
  double centre_frequency_hz = 77e9;
  // Up: most automotive FMCW front ends ramp up (docs/radar.md §3.2). Conjugates the beat signal.
  SweepDirection sweep_direction = SweepDirection::up;
  double sweep_bandwidth_hz = 1e9;
  double chirp_duration_s = 51.2e-6;
  double chirp_interval_s = 51.2e-6;  // chirp start to chirp start (>= duration)
  std::size_t samples_per_chirp = 512;
  double sample_rate_hz = 10e6;  // complex (I/Q) samples per second
  std::size_t chirps_per_frame = 64;
  double tx_power_dbm = 10.0;
  double tx_gain_dbi = 25.0;
  double rx_gain_dbi = 25.0;
  double azimuth_beamwidth_deg = 10.0;    // 3 dB, one way
  double elevation_beamwidth_deg = 10.0;  // 3 dB, one way
  // An assumption: the study names none (docs/radar.md).
  Polarisation polarisation = Polarisation::horizontal;
  double noise_figure_db = 12.0;
  double reference_temperature_k = 290.0;  // T0 of k T0 F fs
  bool thermal_noise = true;               // off only to check calibration without noise
  unsigned adc_bits = 0;                   // 0: ideal (no quantisation)
  double adc_full_scale_dbm = -20.0;       // power of a full-scale complex tone at the ADC input
  double phase_noise_rms_rad = 0.0;        // white phase noise per sample (0: off)
  WindowType window = WindowType::hann;    // range and Doppler
  CfarConfig cfar{.kind = CfarKind::ca,
                  .guard_cells = 2,
                  .training_cells = 8,
                  .false_alarm_probability = 1e-6,
                  .os_rank = 0};
  double association_gate_m = 0.5;  // |R_detected - R_expected| for the tracked target
  Radome radome;

  // Throws InvalidParameter naming the scenario key (radar_param_keys: "radar.<field>",
  // "radar.processing.window", "radar.processing.association_gate_m",
  // "radar.processing.cfar.<field>") and the
  // allowed range.
  void validate() const;
};

// The scenario keys of the radar and its processing chain: [radar], [radar.radome],
// [radar.processing] and [radar.processing.cfar] (docs/scenario.md). thermal_noise is no key (tests
// switch it off).
KeyTable<RadarParams> radar_param_keys();

// Everything the chain derives from RadarParams.
struct RadarDerived {
  double wavelength_m;                      // c / f_c, f_c the sweep centre
  double start_frequency_hz;                // f_0 = f_c - eps B / 2
  double sweep_sign;                        // eps: +1 up, -1 down
  double chirp_slope_hz_per_s;              // S = B / T_c (magnitude; the sweep runs at eps S)
  double range_resolution_m;                // c / (2 B)
  double range_bin_m;                       // c fs / (2 S N): one range-FFT bin
  double max_range_m;                       // c fs / (2 S): complex sampling, beat in [0, fs)
  double velocity_resolution_m_per_s;       // lambda / (2 N_c T_i)
  double max_unambiguous_velocity_m_per_s;  // lambda / (4 T_i)
  double noise_power_w;                     // k T0 F fs, per complex sample
  double tx_power_w;
  double tx_gain;  // linear
  double rx_gain;
  double beam_solid_angle_sr;  // two-way equivalent, Probert-Jones 1962
};

RadarDerived derive(const RadarParams& params);

// Beat frequency of a path of two-way length L (m): f_b = S L / c (= 2 S R / c monostatic).
double beat_frequency_hz(double path_length_m, double chirp_slope_hz_per_s);

// Phase of the dechirped echo of a path of two-way length L at the first sample of a chirp,
// tau = L / c: eps 2 pi tau f_0 - pi S tau^2 (the echo phase at the transmit frequency of t =
// -tau/2, i.e. eps 2 pi tau f_tx(t - tau/2) at t = 0; derivation and mixing convention in
// docs/radar.md §3.2).
double echo_phase_at_chirp_start_rad(double path_length_m, const RadarDerived& derived);

// Beat-frequency shift of a path of radial velocity v (+ receding): f_D = eps 2 v / lambda (a
// receding target raises the beat frequency of an up-chirp and lowers that of a down-chirp).
double doppler_shift_hz(double radial_velocity_m_per_s, const RadarDerived& derived);

// The velocity a radial velocity v reads as after the Doppler FFT, which holds only
// [-v_max, v_max) with v_max = lambda / (4 T_i): v - 2 v_max round(v / (2 v_max)) (aliasing of the
// chirp-to-chirp phase 4 pi v T_i / lambda, Richards, Fundamentals of Radar Signal Processing,
// 2nd ed., §5.3).
double folded_velocity_m_per_s(double radial_velocity_m_per_s, double max_unambiguous_m_per_s);

// Radar equation (paper eq. 7 solved for P_r): P_r = P_t G_t G_r lambda^2 sigma / ((4 pi)^3 R^4).
double received_power_w(double tx_power_w, double tx_gain, double rx_gain, double wavelength_m,
                        double rcs_m2, double range_m);

// Paper eq. 7: sigma = (4 pi)^3 R^4 P_r / (P_t G_t G_r lambda^2).
double rcs_from_received_power_m2(double received_power_w, double tx_power_w, double tx_gain,
                                  double rx_gain, double wavelength_m, double range_m);

// One-way power pattern of a Gaussian beam with 3 dB width theta_3dB (rad), per axis:
// g(theta) = exp(-4 ln 2 (theta / theta_3dB)^2) (e.g. Skolnik, Radar Handbook 3rd ed., ch. 2).
double gaussian_beam_power(double off_axis_rad, double beamwidth_3db_rad);

// Probert-Jones (1962, QJRMS 88, 485) two-way equivalent solid angle of a Gaussian beam:
// Omega = pi theta_az theta_el / (8 ln 2), angles in rad; fog clutter volume = Omega R^2 dR.
double two_way_beam_solid_angle_sr(double azimuth_beamwidth_rad, double elevation_beamwidth_rad);

}  // namespace fogradar::radar
