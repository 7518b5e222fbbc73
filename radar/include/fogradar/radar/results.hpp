// What the radar finds in one run of the study's methodology: one record per measurement (what a
// tracker associates, with the simulation's ground truth beside it), and per step the statistics
// of the target detections' RCS (Tukey box plot, shift against the 0-layer series) and the sensor
// limit: the number of active layers at which the radar can no longer tell the target from the fog.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/origin.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/median_interval.hpp"

namespace fogradar::radar {

// One detection of a measured frame as the result files keep it (radar_detections.csv), with its
// ground truth.
struct DetectionRecord {
  double range_m = 0.0;  // Doppler-corrected (Detection::range_m)
  double velocity_m_per_s = 0.0;
  double received_power_w = 0.0;
  double snr_db = 0.0;
  double rcs_dbsm = 0.0;
  Origin origin = Origin::noise;
  bool in_gate = false;        // within the association gate of the chamber's target range
  bool associated = false;     // the gate's strongest: the one the record associates
  std::size_t range_cell = 0;  // the peak cell the attribution looked at (Detection)
  std::size_t doppler_cell = 0;
  std::int16_t layer = -1;  // for a fog origin, the dominant chamber layer (Detection::layer)
};

// What the tracker reports for one measurement, with the simulation's ground truth beside it.
struct MeasurementRecord {
  // A detection inside the association gate (the strongest there): what a tracker associates.
  bool associated = false;
  Origin associated_origin = Origin::noise;  // only meaningful when associated
  // A target detection: associated, and the associated detection's origin is target. Any other
  // detection the gate takes (fog, noise, a ghost of the target via the room, the room's own echo,
  // a sidelobe or clipping product) is a false association and counts as a miss.
  bool detected = false;
  double range_m = 0.0;  // of the associated detection; only meaningful when associated
  double velocity_m_per_s = 0.0;
  double rcs_dbsm = 0.0;
  double snr_db = 0.0;
  // A fog-origin detection echoes at least as strongly (received power) as the target detection,
  // or there is no target detection at all: the sensor cannot tell target from fog.
  bool fog_rivals_target = false;
  std::size_t fog_detections = 0;           // fog-origin detections anywhere in the map
  std::size_t false_alarms = 0;             // noise-origin detections anywhere in the map
  std::size_t clipping_detections = 0;      // clipping-origin detections anywhere in the map
  std::size_t sidelobe_detections = 0;      // sidelobe-origin detections anywhere in the map
  std::size_t multipath_detections = 0;     // ghosts of the target via the room, anywhere
  std::size_t room_detections = 0;          // the room's own echoes (objects, back wall), anywhere
  std::vector<DetectionRecord> detections;  // every detection of the map, in the chain's order
  // The frame's samples and those with an I or Q rail clipped by the ADC (SynthesisReport); not
  // written per measurement, summed per step (StepSummary::adc_clipped_fraction).
  std::size_t samples = 0;
  std::size_t clipped_samples = 0;
};

// The record of one measured frame; the gate is |range - target_range_m| <= gate_m, as
// RadarChain::measure associates.
MeasurementRecord record_of(const Measurement& measurement, double target_range_m, double gate_m);

struct StepResult {
  std::size_t active_layers = 0;
  double two_way_attenuation_db = 0.0;  // to the target through the active layers
  double radome_two_way_loss_db = 0.0;  // the radome and its water film, out and back
  double target_film_loss_db = 0.0;     // the water film on the target
  std::vector<MeasurementRecord> records;
};

struct StepSummary {
  std::size_t active_layers = 0;
  std::size_t n = 0;           // measurements
  std::size_t detections = 0;  // with a target detection (target origin, in the gate)
  double detection_rate = 0.0;
  // Measurements whose gate association is not a target detection: fog, noise, a ghost, the room
  // (counted as misses).
  double false_association_rate = 0.0;
  double false_alarms_per_frame = 0.0;    // mean noise-origin detections per measurement
  double fog_detections_per_frame = 0.0;  // mean fog-origin detections per measurement
  // Mean clipping-origin detections per measurement: the ADC's harmonics and intermodulation
  // products (attribution.hpp), not counted as false alarms.
  double clipping_detections_per_frame = 0.0;
  // Mean sidelobe-origin detections per measurement: sidelobe false alarms, echoes' leakage outside
  // their window main lobes (attribution.hpp), not counted with the noise's false alarms.
  double sidelobe_detections_per_frame = 0.0;
  // Mean multipath-origin (ghosts of the target via the room) and room-origin (the room's own
  // echoes: its objects, the back wall) detections per measurement, anywhere in the map.
  double multipath_detections_per_frame = 0.0;
  double room_detections_per_frame = 0.0;
  stats::BoxPlot rcs;  // of the target detections' rcs_dbsm values
  // Against the 0-layer series: the Hodges-Lehmann shift (median of all pairwise differences
  // x_i - y_j), its distribution-free 95 % interval (the inverted Mann-Whitney test) and the
  // Mann-Whitney U p-value; shift 0 and interval and p NaN for the baseline itself, all NaN when
  // either series has no target detection.
  double median_shift_db = 0.0;
  stats::Interval median_shift_ci95;
  double p_value = 0.0;
  double median_snr_db = 0.0;  // of the target detections
  double two_way_attenuation_db = 0.0;
  double radome_two_way_loss_db = 0.0;
  double target_film_loss_db = 0.0;
  double confusion_rate = 0.0;  // measurements without a target detection or with fog rivalling it
  // Samples of the step's frames with an I or Q rail clipped by the ADC, over all their samples
  // (sums of integers: the same for any thread count); 0 without an ADC (radar.adc_bits = 0).
  double adc_clipped_fraction = 0.0;
};

// A target whose set radial velocity lies beyond the unambiguous +-v_max (|v| > v_max): the
// velocity it reads as and the range error that the range-Doppler coupling correction, made with
// that velocity, leaves (measured - true).
struct VelocityFold {
  double set_m_per_s = 0.0;
  double unambiguous_m_per_s = 0.0;  // v_max = lambda / (4 T_i)
  double reads_m_per_s = 0.0;        // folded_velocity_m_per_s
  double range_error_m = 0.0;        // (f_D(v) - f_D(folded)) c / (2 S)
};

// The fold of the target's velocity, or none when |v| <= v_max.
std::optional<VelocityFold> velocity_fold(double radial_velocity_m_per_s,
                                          const RadarDerived& derived);

struct RadarSummary {
  std::vector<StepSummary> steps;
  // First layer count at which fewer than half the measurements detect the target (target origin:
  // a ghost never counts) with no fog-origin detection at least as strong (docs/scenario.md); empty
  // if never reached.
  std::optional<std::size_t> sensor_limit_layers;
  // At the last step: median target SNR minus the CFAR threshold factor (dB), i.e. roughly how
  // much more two-way attenuation the median echo could take before it drops below the threshold.
  // Empty when the last step's ADC clipped: a clipped echo's level is not what it measures, and
  // its clipping products raise the map, so the SNR says nothing of the margin.
  std::optional<double> attenuation_margin_db;
  // The CFAR's design: P_fa times the cells it tests per frame (every cell of the map). Counts
  // cells; a detection is an 8-connected object of cells, so noise detections per frame come out
  // at most this (fewer where the window correlates neighbouring cells).
  double expected_false_alarm_cells_per_frame = 0.0;
  // The target's velocity folded by the Doppler FFT (set by the sensor from its parameters).
  std::optional<VelocityFold> velocity_fold;
};

inline constexpr double sensor_limit_success_fraction = 0.5;

inline constexpr const char* sensor_limit_criterion =
    "first active-layer count at which fewer than 50 % of the measurements detect the target "
    "(a target-origin detection within the association gate) with no fog-origin detection echoing "
    "at least as strongly";

inline constexpr const char* sensor_limit_criterion_short =
    "target detected (no fog detection as strong) in < 50 % of the measurements";

// The steps' statistics and the limit; `cfar_threshold_db` = 10 log10(alpha), the SNR a detection
// needs, for the attenuation margin.
RadarSummary summarize(const std::vector<StepResult>& steps, double cfar_threshold_db,
                       double expected_false_alarm_cells_per_frame);

}  // namespace fogradar::radar
