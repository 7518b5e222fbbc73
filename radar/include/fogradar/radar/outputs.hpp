// The radar's result files as strings (experiment/ writes them into the run's result set) and its
// terminal table.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fogradar/radar/results.hpp"
#include "fogradar/radar/sensor.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::radar {

// radar_samples.csv: one row per measurement, "active_layers,item,detected,range_m,rcs_dbsm,snr_db,
// origin,fog_detections,false_alarms,velocity_m_per_s" (item: the measurement's index in its step);
// numbers in shortest round-trip form.
std::string samples_csv(const std::vector<StepResult>& steps);
// radar_detections.csv: every detection of every measurement, "active_layers,item,range_m,
// velocity_m_per_s,power_dbm,snr_db,rcs_dbsm,origin,in_gate,associated" (the received power at the
// receiver input; in_gate and associated 0 or 1).
std::string detections_csv(const std::vector<StepResult>& steps);
// The per-step statistics as typed columns: radar_summary.csv (step_table(s).csv()), the steps of
// summary_json, and the columns of summary_table with the figures only it prints.
sensor::StepTable step_table(const RadarSummary& summary);
// radar_summary.json (and summary.json's sensors.radar.summary): the steps, the limit with its
// criterion, the CFAR's design false alarms, the attenuation margin and the statistics used.
nlohmann::json summary_json(const RadarSummary& summary);
// radar_rcs_boxplot.svg: RCS box plots per step with the detection rate under them, the sensor
// limit marked, and title and caption from the scenario (target, chamber, fog as given, droplets,
// CFAR, n, seed).
std::string rcs_boxplot_svg(const SensorParams& params, const sensor::Context& context,
                            const RadarSummary& summary);
// radar_origins.svg: the detections per measurement of each origin against active layers (the
// target's associated share, and multipath, room, fog, noise, sidelobe and clipping detections
// anywhere in the map; an origin never detected is named in the caption, not drawn), with the
// box plot's caption.
std::string origins_svg(const SensorParams& params, const sensor::Context& context,
                        const RadarSummary& summary);
// A fraction in [0, 1] as a percentage of 3 significant digits ("12.3", "0.05"): "100" only when
// it is 1, ">99.9" when it is less but would round to 100.
std::string percent_of_samples(double fraction);

// "the target's radial velocity 25 m/s (target.radial_velocity_m_per_s) is beyond the radar's
// unambiguous ±19.0 m/s (λ/(4 T_i)): it reads as -13.0 m/s, and the range-Doppler coupling
// correction made with that velocity moves its range by 0.150 m": the run's warning and the
// table's line.
std::string velocity_fold_text(const VelocityFold& fold);
// The per-layer table `fogradar run` prints for the radar.
std::string summary_table(const RadarSummary& summary);

}  // namespace fogradar::radar
