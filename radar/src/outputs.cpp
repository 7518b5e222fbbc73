#include "fogradar/radar/outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "fogradar/core/units.hpp"
#include "fogradar/stats/format.hpp"
#include "output_words.hpp"

namespace fogradar::radar {
namespace {

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// Shortest text that reads back to exactly `value` (std::to_chars); NaN -> "" (docs/scenario.md).
std::string exact(double value) { return stats::format_number(value, 0); }

// " 0.200 per frame at 0 active layers, 0.100 per frame at 1 active layer": `rate` of each step
// `shown` picks, for the notes under the printed table.
template <class Shown, class Rate>
std::string per_frame_at(const std::vector<StepSummary>& steps, Shown shown, Rate rate) {
  std::string text;
  char line[128];
  for (const StepSummary& s : steps) {
    if (!shown(s)) continue;
    std::snprintf(line, sizeof line, "%s%.3f per frame at %s", text.empty() ? " " : ", ", rate(s),
                  counted(s.active_layers, "active layer").c_str());
    text += line;
  }
  return text;
}

}  // namespace

std::string samples_csv(const std::vector<StepResult>& steps) {
  std::string out =
      "active_layers,item,detected,range_m,rcs_dbsm,snr_db,"
      "origin,fog_detections,false_alarms,velocity_m_per_s\n";
  for (const StepResult& step : steps) {
    for (std::size_t i = 0; i < step.records.size(); ++i) {
      const MeasurementRecord& r = step.records[i];
      out += std::to_string(step.active_layers) + ',' + std::to_string(i) + ',' +
             (r.detected ? "1," : "0,");
      if (r.associated) {
        out += exact(r.range_m) + ',' + exact(r.rcs_dbsm) + ',' + exact(r.snr_db) + ',' +
               std::string(to_string(r.associated_origin));
      } else {
        out += ",,,";
      }
      out += ',' + std::to_string(r.fog_detections) + ',' + std::to_string(r.false_alarms) + ',' +
             (r.associated ? exact(r.velocity_m_per_s) : "") + '\n';
    }
  }
  return out;
}

std::string detections_csv(const std::vector<StepResult>& steps) {
  std::string out =
      "active_layers,item,range_m,velocity_m_per_s,power_dbm,snr_db,rcs_dbsm,origin,in_gate,"
      "associated,layer\n";
  for (const StepResult& step : steps) {
    for (std::size_t i = 0; i < step.records.size(); ++i) {
      const std::string prefix = std::to_string(step.active_layers) + ',' + std::to_string(i) + ',';
      for (const DetectionRecord& d : step.records[i].detections) {
        out += prefix + exact(d.range_m) + ',' + exact(d.velocity_m_per_s) + ',' +
               exact(watt_to_dbm(d.received_power_w)) + ',' + exact(d.snr_db) + ',' +
               exact(d.rcs_dbsm) + ',' + std::string(to_string(d.origin)) +
               (d.in_gate ? ",1," : ",0,") + (d.associated ? "1," : "0,") +
               std::to_string(d.layer) + '\n';
      }
    }
  }
  return out;
}

sensor::StepTable step_table(const RadarSummary& summary) {
  const std::vector<StepSummary>& steps = summary.steps;
  sensor::StepTable t(steps.size());
  t.integer("active_layers", "", steps, [](const StepSummary& s) { return s.active_layers; });
  t.integer("n", "", steps, [](const StepSummary& s) { return s.n; });
  t.integer("detections", "", steps, [](const StepSummary& s) { return s.detections; });
  t.number("detection_rate", "", steps, [](const StepSummary& s) { return s.detection_rate; });
  t.number("mean", "dbsm", steps, [](const StepSummary& s) { return s.rcs.mean; });
  t.number("std", "db", steps, [](const StepSummary& s) { return s.rcs.std_dev; });
  t.number("min", "dbsm", steps, [](const StepSummary& s) { return s.rcs.min; });
  t.number("q1", "dbsm", steps, [](const StepSummary& s) { return s.rcs.q1; });
  t.number("median", "dbsm", steps, [](const StepSummary& s) { return s.rcs.median; });
  t.number("q3", "dbsm", steps, [](const StepSummary& s) { return s.rcs.q3; });
  t.number("max", "dbsm", steps, [](const StepSummary& s) { return s.rcs.max; });
  t.number("whisker_low", "dbsm", steps, [](const StepSummary& s) { return s.rcs.whisker_low; });
  t.number("whisker_high", "dbsm", steps, [](const StepSummary& s) { return s.rcs.whisker_high; });
  t.numbers("outliers", "", steps, [](const StepSummary& s) { return s.rcs.outliers; });
  t.number("median_shift", "db", steps, [](const StepSummary& s) { return s.median_shift_db; });
  t.number("p_value", "", steps, [](const StepSummary& s) { return s.p_value; });
  t.number("median_shift_ci95_low", "db", steps, [](const StepSummary& s) {
     return s.median_shift_ci95.low;
   }).in_json("/median_shift_ci95_db/0");
  t.number("median_shift_ci95_high", "db", steps, [](const StepSummary& s) {
     return s.median_shift_ci95.high;
   }).in_json("/median_shift_ci95_db/1");
  t.number("median_snr", "db", steps, [](const StepSummary& s) { return s.median_snr_db; });
  t.number("two_way_attenuation", "db", steps,
           [](const StepSummary& s) { return s.two_way_attenuation_db; });
  t.number("radome_two_way_loss", "db", steps,
           [](const StepSummary& s) { return s.radome_two_way_loss_db; });
  t.number("target_film_loss", "db", steps,
           [](const StepSummary& s) { return s.target_film_loss_db; });
  t.number("confusion_rate", "", steps, [](const StepSummary& s) { return s.confusion_rate; });
  t.number("false_association_rate", "", steps,
           [](const StepSummary& s) { return s.false_association_rate; });
  t.number("false_alarms_per_frame", "", steps,
           [](const StepSummary& s) { return s.false_alarms_per_frame; });
  t.number("fog_detections_per_frame", "", steps,
           [](const StepSummary& s) { return s.fog_detections_per_frame; });
  t.number("adc_clipped_fraction", "", steps,
           [](const StepSummary& s) { return s.adc_clipped_fraction; });
  t.number("clipping_detections_per_frame", "", steps,
           [](const StepSummary& s) { return s.clipping_detections_per_frame; });
  t.number("sidelobe_detections_per_frame", "", steps,
           [](const StepSummary& s) { return s.sidelobe_detections_per_frame; });
  t.number("multipath_detections_per_frame", "", steps,
           [](const StepSummary& s) { return s.multipath_detections_per_frame; });
  t.number("room_detections_per_frame", "", steps,
           [](const StepSummary& s) { return s.room_detections_per_frame; });

  // The printed table's own figures: the layer count starred where only the surviving detections
  // make the RCS statistics, the CFAR's design false alarms, the IQR and the total two-way loss.
  t.text("layers", "", steps, [](const StepSummary& s) {
     std::string layers = std::to_string(s.active_layers);
     if (survivors_only(s)) layers += '*';
     return layers;
   }).printed_only();
  t.number("design_per_frame", "", steps, [&summary](const StepSummary&) {
     return summary.expected_false_alarm_cells_per_frame;
   }).printed_only();
  t.number("iqr", "db", steps, [](const StepSummary& s) {
     return s.rcs.q3 - s.rcs.q1;
   }).printed_only();
  t.number("loss", "db", steps, [](const StepSummary& s) {
     return s.two_way_attenuation_db + s.radome_two_way_loss_db + s.target_film_loss_db;
   }).printed_only();
  // printf's output, an en dash where a statistic does not exist (a shift against 0 layers at 0
  // layers, a p-value of one sample): the terminal shows no "nan".
  const auto percent = [](const char* head, const char* unit) {
    return sensor::Printed{.heads = {head, unit}, .width = 8, .precision = 1, .scale = 100.0};
  };
  const auto fixed = [](const char* head, const char* unit) {
    return sensor::Printed{.heads = {head, unit}, .width = 9, .precision = 3};
  };
  const auto statistic = [](std::vector<std::string> heads) {
    return sensor::Printed{
        .heads = std::move(heads), .width = 9, .precision = 3, .missing = "\u2013"};
  };
  t.print("layers", {.heads = {"layers", ""}, .width = 6});
  t.print("n", {.heads = {"n", ""}, .width = 5});
  t.print("detection_rate", percent("target", "det. %"));
  t.print("confusion_rate", percent("confused", "%"));
  t.print("false_association_rate", percent("false", "assoc %"));
  t.print("fog_detections_per_frame", fixed("fog", "det./f"));
  t.print("false_alarms_per_frame", fixed("false", "alarms/f"));
  t.print("design_per_frame", fixed("design", "/frame"));
  t.print("median_dbsm", statistic({"median", "dBsm"}));
  t.print("iqr_db", statistic({"IQR", "dB"}));
  t.print("mean_dbsm", statistic({"mean", "dBsm"}));
  t.print("std_db", statistic({"std", "dB"}));
  t.print("median_shift_db", statistic({"shift", "HL dB"}));
  t.print("median_shift_ci95_low_db", statistic({"95 % interval", "dB"}));
  t.print("median_shift_ci95_high_db", statistic({}));
  sensor::Printed p = statistic({"p", ""});
  p.general = true;
  t.print("p_value", p);
  sensor::Printed loss = statistic({"loss", "dB 2-way"});
  loss.width = 8;
  loss.precision = 4;
  t.print("loss_db", loss);
  return t;
}

nlohmann::json summary_json(const RadarSummary& summary) {
  return {
      {"steps", step_table(summary).json()},
      {"sensor_limit_layers", summary.sensor_limit_layers
                                  ? nlohmann::json(*summary.sensor_limit_layers)
                                  : nlohmann::json(nullptr)},
      {"sensor_limit_criterion", sensor_limit_criterion},
      {"expected_false_alarm_cells_per_frame", summary.expected_false_alarm_cells_per_frame},
      {"velocity_fold",
       summary.velocity_fold
           ? nlohmann::json{{"set_m_per_s", summary.velocity_fold->set_m_per_s},
                            {"unambiguous_m_per_s", summary.velocity_fold->unambiguous_m_per_s},
                            {"reads_m_per_s", summary.velocity_fold->reads_m_per_s},
                            {"range_error_m", summary.velocity_fold->range_error_m}}
           : nlohmann::json(nullptr)},
      {"attenuation_margin_db", summary.attenuation_margin_db
                                    ? number_or_null(*summary.attenuation_margin_db)
                                    : nlohmann::json(nullptr)},
      {"statistics",
       {{"quantiles", "Hyndman & Fan (1996) type 7 (R's default)"},
        {"whiskers", "Tukey: most extreme values within 1.5 IQR of the quartiles"},
        {"shift", "Hodges-Lehmann: median of all pairwise differences against the 0-layer series"},
        {"shift_interval",
         "distribution-free 95 %: order statistics of the pairwise differences from the "
         "Mann-Whitney U null distribution (Bauer 1972)"},
        {"shift_test", "Mann-Whitney U (two-sided) against the 0-layer series"},
        {"detections",
         "target detections only: any other origin in the gate (fog, noise, a multipath ghost, the "
         "room) is a miss"}}},
  };
}

std::string velocity_fold_text(const VelocityFold& fold) {
  char text[400];
  std::snprintf(text, sizeof text,
                "the target's radial velocity %s m/s (target.radial_velocity_m_per_s) is beyond "
                "the radar's unambiguous \u00b1%.1f m/s (\u03bb/(4 T_i)): it reads as %.2f m/s, "
                "and the range-Doppler coupling correction made with that velocity moves its "
                "range by %+.3f m",
                stats::format_number(fold.set_m_per_s, 0).c_str(), fold.unambiguous_m_per_s,
                fold.reads_m_per_s, fold.range_error_m);
  return text;
}

std::string percent_of_samples(double fraction) {
  const std::string text = stats::format_number(100.0 * fraction, 3);
  return text == "100" && fraction < 1.0 ? ">99.9" : text;
}

std::string summary_table(const RadarSummary& summary) {
  std::ostringstream out;
  char line[320];
  out << step_table(summary).printed();
  out << "target det. %: a target-origin detection in the gate; confused %: no target detection\n"
         "or a fog detection at least as strong (the limit: the first step above 50 %); false\n"
         "assoc. %: another origin in the gate instead of the target (fog, noise, a multipath\n"
         "ghost, the room: a miss); fog det./f: fog-origin detections per frame; false alarms/f:\n"
         "noise-origin detections per frame; design /frame: P_fa x the cells the CFAR tests per\n"
         "frame; shift: Hodges-Lehmann shift against 0 layers with its distribution-free 95 %\n"
         "interval; p: Mann-Whitney U; \u2013: no such value\n";
  if (!summary.steps.empty() && (summary.steps.front().radome_two_way_loss_db != 0.0 ||
                                 summary.steps.front().target_film_loss_db != 0.0)) {
    std::snprintf(line, sizeof line,
                  "loss: the fog's, plus %.4f dB of the radome with its water film and %.4f dB "
                  "of the target's water film\n",
                  summary.steps.front().radome_two_way_loss_db,
                  summary.steps.front().target_film_loss_db);
    out << line;
  }
  if (std::any_of(summary.steps.begin(), summary.steps.end(), survivors_only)) {
    out << "*: fewer than half the measurements detected the target: the RCS statistics are the\n"
           "surviving detections' only\n";
  }
  if (std::any_of(summary.steps.begin(), summary.steps.end(),
                  [](const StepSummary& s) { return s.adc_clipped_fraction > 0.0; })) {
    // "ADC clipping: 12.3 % of the samples at 0 active layers, 0.5 % at 1 active layer".
    out << "ADC clipping:";
    bool first = true;
    for (const StepSummary& s : summary.steps) {
      if (s.adc_clipped_fraction <= 0.0) continue;
      out << (first ? " " : ", ") << percent_of_samples(s.adc_clipped_fraction)
          << (first ? " % of the samples at " : " % at ")
          << counted(s.active_layers, "active layer");
      first = false;
    }
    out << "\nclipping detections (its harmonics and intermodulation products, not false alarms):"
        << per_frame_at(
               summary.steps, [](const StepSummary& s) { return s.adc_clipped_fraction > 0.0; },
               [](const StepSummary& s) { return s.clipping_detections_per_frame; })
        << '\n';
  }
  if (std::any_of(summary.steps.begin(), summary.steps.end(),
                  [](const StepSummary& s) { return s.sidelobe_detections_per_frame > 0.0; })) {
    // "sidelobe false alarms (...): 0.200 per frame at 1 active layer, ...".
    out << "sidelobe false alarms (echoes' leakage outside their window main lobes):"
        << per_frame_at(
               summary.steps, [](const StepSummary&) { return true; },
               [](const StepSummary& s) { return s.sidelobe_detections_per_frame; })
        << '\n';
  }
  // "room echoes (...): 4.000 per frame at 0 active layers, ...", and the same for the ghosts.
  const auto origin_line = [&](const char* what, double StepSummary::*rate) {
    if (std::none_of(summary.steps.begin(), summary.steps.end(),
                     [rate](const StepSummary& s) { return s.*rate > 0.0; }))
      return;
    out << what
        << per_frame_at(
               summary.steps, [](const StepSummary&) { return true; },
               [rate](const StepSummary& s) { return s.*rate; })
        << '\n';
  };
  origin_line("room detections (its objects' and back wall's own echoes):",
              &StepSummary::room_detections_per_frame);
  origin_line("multipath detections (ghosts of the target via the room, misses in the gate):",
              &StepSummary::multipath_detections_per_frame);
  if (summary.velocity_fold)
    out << "velocity folded: " << velocity_fold_text(*summary.velocity_fold) << '\n';
  out << "sensor limit: ";
  if (summary.sensor_limit_layers)
    out << counted(*summary.sensor_limit_layers, "active layer") << "\n";
  else
    out << "not reached\n";
  if (summary.attenuation_margin_db) {
    std::snprintf(line, sizeof line, "attenuation margin at the last step: %.1f dB\n",
                  *summary.attenuation_margin_db);
    out << line;
  }
  return out.str();
}

}  // namespace fogradar::radar
