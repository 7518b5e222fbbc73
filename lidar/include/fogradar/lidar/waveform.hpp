// The received waveform of one lidar beam and the receiver's echo extraction, as small pure
// functions. Form (Rasshofer, Spies & Spies 2011, Adv. Radio Sci. 9, 49-60, eq. 1-3, the study's
// ref. [30]; the same single-scattering lidar equation as Measures 1984, Laser Remote Sensing):
//   P(t) = C [ sum_hard p(t - 2R/c) rho cos(i) / pi T^2(R) / R^2 O(R)
//            + integral p(t - 2r/c) beta_pi(r) T^2(r) / r^2 O(r) dr ],
// T^2(r) = exp(-2 integral_0^r alpha), p the pulse's power shape (peak 1), O the overlap function,
// C the system constant (transmitted peak power x receiver aperture x efficiencies). Waveforms here
// are in units of C (C = 1): m^-2 sr^-1, dimensionless reflectivity over m^2.
#pragma once

#include <array>
#include <cstddef>
#include <span>

namespace fogradar::lidar {

// Gaussian pulse of full width at half maximum `fwhm_s`, peak 1 at t = 0:
// p(t) = exp(-4 ln 2 t^2 / fwhm^2).
double pulse_shape(double t_s, double fwhm_s);

// Energy width integral p dt = fwhm sqrt(pi / (4 ln 2)) (Gaussian integral).
double pulse_energy_width_s(double fwhm_s);

// Overlap function O(r) = min(1, (r / r_full)^2): a coaxial receiver whose field of view fills with
// the beam by r_full (assumed form; Measures 1984, ch. 7, for the overlap of coaxial systems).
double overlap(double range_m, double full_overlap_range_m);

// Peak of a Lambertian hard target filling the beam (Rasshofer et al. 2011 eq. 1):
// rho cos(incidence) / pi * T^2 / R^2 (O = 1).
double hard_target_peak(double reflectivity, double cos_incidence, double two_way_transmittance,
                        double range_m);

// Sampling of a beam's waveform: sample k at round-trip time k dt, range c k dt / 2.
struct WaveformGrid {
  double sample_interval_s = 0.5e-9;
  double pulse_fwhm_s = 5e-9;
  double full_overlap_range_m = 0.5;
};

// waveform[k] += amplitude p(k dt - 2 R / c) O(R) for the samples within 2 fwhm of the echo's
// centre.
void add_hard_target(std::span<double> waveform, const WaveformGrid& grid, double range_m,
                     double amplitude);

// The receiver (docs/lidar.md §4).
struct EchoDetector {
  double threshold = 0.0;  // in waveform units
  double sample_interval_s = 0.5e-9;
  // Added to c t_cross / 2: the receiver is calibrated so that an echo whose peak is twice the
  // threshold (its threshold crossing at half maximum) reads its true range: c fwhm / 4.
  double range_offset_m = 0.0;
  double min_range_m = 0.1;
  double min_separation_m = 1.0;
  std::size_t max_echoes = 3;
};

struct DetectedEcho {
  double range_m = 0.0;          // leading-edge threshold crossing, linearly interpolated
  double peak = 0.0;             // largest sample from the crossing until the signal falls below
  std::size_t first_sample = 0;  // the leading edge's first sample at or above the threshold
  std::size_t last_sample = 0;   // the echo's last one, crossings merged into it included
};

struct DetectedEchoes {
  static constexpr std::size_t capacity = 8;
  std::array<DetectedEcho, capacity> echoes{};
  std::size_t count = 0;
};

// Echoes of a (noisy) waveform in range order: each upward threshold crossing starts an echo that
// lasts until the signal falls below the threshold again; a crossing within min_separation_m of the
// previous echo's range merges into it (the larger peak is kept); echoes closer than min_range_m
// are dropped, as is one already above the threshold at the record's first sample; at most
// max_echoes (<= capacity) are kept, the nearest.
DetectedEchoes extract_echoes(std::span<const double> waveform, const EchoDetector& detector);

// The sample an echo is attributed at (its origin, in the simulation's ground truth): the first
// local maximum of the noise-free return at or after the echo's leading edge, within the echo,
// found by climbing `noise_free` from echo.first_sample while it rises, up to echo.last_sample.
// The return whose leading edge made the echo is the one whose peak this reaches: a lone pulse's
// own peak; for a fog layer and a hard target merged into one echo (closer than the minimum
// separation), the fog's, where the echo's range is read. The echo's largest sample (its peak,
// the intensity) may belong to a later return.
std::size_t attribution_sample(std::span<const double> noise_free, const DetectedEcho& echo);

}  // namespace fogradar::lidar
