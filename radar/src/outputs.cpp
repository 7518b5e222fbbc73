#include "fogradar/radar/outputs.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <string_view>
#include <variant>
#include <vector>

#include "fogradar/core/units.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/line_plot.hpp"
#include "fogradar/stats/svg_plot.hpp"

namespace fogradar::radar {
namespace {

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// Shortest text that reads back to exactly `value` (std::to_chars); NaN -> "" (docs/scenario.md).
std::string exact(double value) { return stats::format_number(value, 0); }

// Scenario numbers in captions: three significant digits ("0.2", "1e-06").
std::string num(double value) { return stats::format_number(value, 3); }

std::string micrometres(double metres) { return num(metres * 1e6) + " \u00b5m"; }

std::string target_name(const TargetSpec& target) {
  return (target.model == TargetModel::evt ? "EVT rear " : "point target ") + num(target.rcs_dbsm) +
         " dBsm";
}

// The fog density as the scenario gives it (one of beta_550, LWC, visibility).
std::string fog_density(const propagation::FogDensity& density) {
  struct Describe {
    std::string operator()(const propagation::OpticalExtinction& d) const {
      return "\u03b2(550 nm) = " + num(d.per_km) + " /km";
    }
    std::string operator()(const propagation::LiquidWaterContent& d) const {
      return "LWC = " + num(d.g_per_m3) + " g/m\u00b3";
    }
    std::string operator()(const propagation::Visibility& d) const {
      return "visibility " + num(d.m) + " m";
    }
  };
  return std::visit(Describe{}, density);
}

std::string droplets(const propagation::DropSizeDistribution& dsd) {
  struct Describe {
    std::string operator()(const propagation::Monodisperse& d) const {
      return "monodisperse droplets of " + micrometres(d.diameter_m);
    }
    std::string operator()(const propagation::Lognormal& d) const {
      return "lognormal droplets, median diameter " + micrometres(d.median_diameter_m) +
             ", \u03c3g = " + num(d.geometric_std);
    }
    std::string operator()(const propagation::ModifiedGamma& d) const {
      const std::string family = d == propagation::advection_fog()   ? "advection-fog "
                                 : d == propagation::radiation_fog() ? "radiation-fog "
                                                                     : "";
      return family + "modified-gamma droplets (\u03b1 = " + num(d.alpha) +
             ", \u03b3 = " + num(d.gamma) + ", b = " + num(d.b_per_um_gamma) + " \u00b5m^-\u03b3)";
    }
  };
  return std::visit(Describe{}, dsd);
}

bool one_fog(const propagation::ChamberSpec& c) {
  return std::all_of(c.layers.begin(), c.layers.end(),
                     [&c](const propagation::FogLayerSpec& l) { return l.fog == c.layers[0].fog; });
}

// "4 × 1 m fog layers", or each length where they differ.
std::string layer_lengths(const propagation::ChamberSpec& c) {
  const bool one_length = std::all_of(
      c.layers.begin(), c.layers.end(),
      [&c](const propagation::FogLayerSpec& l) { return l.length_m == c.layers[0].length_m; });
  if (one_length) {
    return std::to_string(c.layers.size()) + " \u00d7 " + num(c.layers[0].length_m) +
           " m fog layers";
  }
  std::string lengths;
  for (const propagation::FogLayerSpec& l : c.layers) {
    lengths += (lengths.empty() ? "" : ", ") + num(l.length_m);
  }
  return std::to_string(c.layers.size()) + " fog layers of " + lengths + " m";
}

std::string fog_words(const propagation::FogSpec& fog) {
  return fog_density(fog.density) + "; " + droplets(fog.droplets) + "; " + num(fog.temperature_c) +
         " \u00b0C";
}

// The fog of every layer, one sentence per layer where they differ (layer 0 at the radar).
std::string layer_fogs(const propagation::ChamberSpec& c) {
  if (one_fog(c)) return "Fog in each active layer: " + fog_words(c.layers[0].fog) + ".";
  std::string text;
  for (std::size_t i = 0; i < c.layers.size(); ++i) {
    if (!text.empty()) text += ' ';
    text += "Fog in layer " + std::to_string(i) + ": " + fog_words(c.layers[i].fog) + ".";
  }
  return text;
}

// The switching order where it is not the study's (from the radar).
std::string switching_words(const sensor::Context& context) {
  std::vector<std::size_t> study(context.chamber.layers.size());
  std::iota(study.begin(), study.end(), std::size_t{0});
  if (context.switching_order.empty() || context.switching_order == study) return "";
  std::string order;
  for (const std::size_t i : context.switching_order) {
    order += (order.empty() ? "" : ", ") + std::to_string(i);
  }
  return " Layers switched on in the order " + order + " (layer 0 at the radar).";
}

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// A window's name as a proper noun: "hann" -> "Hann", "blackman_harris" -> "Blackman-Harris".
std::string window_name(WindowType window) {
  std::string out(to_string(window));
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i] == '_') out[i] = '-';
    if (i == 0 || out[i - 1] == '-')
      out[i] = static_cast<char>(std::toupper(static_cast<unsigned char>(out[i])));
  }
  return out;
}

// Caption lines of at most this many characters fit the 960 px plot in a 12 px sans-serif face
// (measured in Chromium with Debian's fonts: 143 characters took 816 px).
constexpr std::size_t caption_line_chars = 140;

// Breaks `text` at spaces into lines of at most `width` characters (UTF-8 characters counted); a
// word longer than `width` gets a line of its own.
std::vector<std::string> wrap(std::string_view text, std::size_t width) {
  const auto chars = [](std::string_view s) {
    return static_cast<std::size_t>(std::count_if(
        s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
  };
  std::vector<std::string> lines;
  std::string current;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(' ', start), text.size());
    const std::string_view word = text.substr(start, end - start);
    if (!current.empty() && chars(current) + 1 + chars(word) > width) {
      lines.push_back(current);
      current.clear();
    }
    if (!current.empty()) current += ' ';
    current += word;
    start = end + 1;
  }
  if (!current.empty()) lines.push_back(current);
  return lines;
}

// "1 active layer", "3 active layers".
std::string counted(std::size_t count, std::string_view noun) {
  return std::to_string(count) + " " + std::string(noun) + (count == 1 ? "" : "s");
}

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

// A step where fewer than half the measurements detected the target, but some did: its RCS
// statistics describe the surviving detections only, a sample biased towards strong echoes.
bool survivors_only(const StepSummary& s) { return s.detections > 0 && s.detection_rate < 0.5; }

// The room besides its floor, for a caption: "Room: left wall 3 m (concrete); 4 objects
// (4 cylinders)."; empty for a floor-only hall.
std::string room_words(const propagation::RoomSpec& room) {
  std::vector<std::string> parts;
  const auto reflection = [](const propagation::SurfaceSpec& surface) {
    const auto* coefficient = std::get_if<propagation::ReflectionCoefficient>(&surface.reflection);
    return coefficient != nullptr
               ? "reflection " + num(coefficient->value)
               : std::string(to_string(std::get<propagation::Material>(surface.reflection)));
  };
  const struct {
    const char* name;
    const propagation::SurfaceSpec& surface;
    const char* how_far;
  } surfaces[] = {{"left wall", room.left_wall, " m to the left"},
                  {"right wall", room.right_wall, " m to the right"},
                  {"ceiling", room.ceiling, " m high"},
                  {"back wall", room.back_wall, " m ahead"}};
  for (const auto& s : surfaces) {
    if (s.surface.present)
      parts.push_back(std::string(s.name) + " " + num(s.surface.distance_m) + s.how_far + " (" +
                      reflection(s.surface) + ")");
  }
  if (!room.objects.empty()) {
    const auto cylinders = static_cast<std::size_t>(
        std::count_if(room.objects.begin(), room.objects.end(),
                      [](const auto& o) { return o.shape == propagation::ObjectShape::cylinder; }));
    std::string shapes;
    if (cylinders > 0) shapes = counted(cylinders, "cylinder");
    if (cylinders < room.objects.size())
      shapes += (shapes.empty() ? "" : ", ") + counted(room.objects.size() - cylinders, "plate");
    parts.push_back(counted(room.objects.size(), "object") + " (" + shapes + ")");
  }
  if (parts.empty()) return "";
  std::string words = "Room: ";
  for (std::size_t i = 0; i < parts.size(); ++i) words += (i == 0 ? "" : "; ") + parts[i];
  return words + ".";
}

// The caption of the radar's plots: `what` (what the plot draws), then the scenario (target, room,
// chamber, fog, radar, n, seed, limit).
std::vector<std::string> plot_caption(const SensorParams& params, const sensor::Context& context,
                                      const RadarSummary& summary, std::string what) {
  const TargetSpec& t = params.target;
  const propagation::ChamberSpec& c = context.chamber;
  const RadarParams& r = params.radar;
  const double target_range_m = c.target_range_m();
  std::string target = "Target: " + target_name(t);
  if (t.model == TargetModel::evt) {
    target += " (five scattering centres)";
  } else {
    target +=
        ", Swerling " + std::string(to_string(t.swerling)) + ", " + num(t.height_m) + " m high";
  }
  const propagation::SurfaceSpec& floor = context.room.floor;
  const auto* floor_coefficient =
      std::get_if<propagation::ReflectionCoefficient>(&floor.reflection);
  target += !floor.present ? ", no floor multipath"
            : floor_coefficient != nullptr
                ? ", floor multipath (reflection " + num(floor_coefficient->value) + ")"
                : ", floor multipath (" +
                      std::string(to_string(std::get<propagation::Material>(floor.reflection))) +
                      ")";
  target += "; " + num(target_range_m) + " m from the radar behind " + layer_lengths(c);
  std::string cfar = "CFAR " + upper(to_string(r.cfar.kind)) + " (" +
                     std::to_string(r.cfar.guard_cells) + " guard + " +
                     std::to_string(r.cfar.training_cells) + " training cells per side";
  if (r.cfar.shape == CfarShape::range_doppler) {
    cfar += " in range, " + std::to_string(r.cfar.doppler_guard_cells) + " + " +
            std::to_string(r.cfar.doppler_training_cells) +
            " rows per side in Doppler: a ring of " +
            std::to_string(r.cfar.shape_reference_cells()) + " cells";
  }
  if (r.cfar.kind == CfarKind::os) {
    cfar += ", rank " + std::to_string(r.cfar.effective_os_rank());
  }
  cfar += "), P_fa = " + num(r.cfar.false_alarm_probability);
  const std::string limit =
      summary.sensor_limit_layers
          ? counted(*summary.sensor_limit_layers, "active layer")
          : "not reached within " + counted(context.steps - 1, "active layer");
  std::vector<std::string> paragraphs = {std::move(what), target + "."};
  if (const std::string room = room_words(context.room); !room.empty()) paragraphs.push_back(room);
  paragraphs.push_back(layer_fogs(c) + switching_words(context));
  paragraphs.push_back("Radar: " + num(r.sweep_bandwidth_hz * 1e-9) + " GHz " +
                       std::string(to_string(r.sweep_direction)) + "-sweep centred on " +
                       num(r.centre_frequency_hz * 1e-9) + " GHz, " + window_name(r.window) +
                       " window; " + cfar + ".");
  paragraphs.push_back("n = " + std::to_string(params.measurements_per_step) +
                       " measurements per step, seed " + std::to_string(context.seed) + ".");
  paragraphs.push_back("Sensor limit: " + limit + "; criterion: " + sensor_limit_criterion + ".");
  std::string survivors;
  for (const StepSummary& s : summary.steps) {
    if (!survivors_only(s)) continue;
    if (!survivors.empty()) survivors += ", ";
    survivors += std::to_string(s.active_layers);
  }
  if (!survivors.empty()) {
    paragraphs.push_back("Active layers " + survivors +
                         ": fewer than half the measurements detected the target; the box shows "
                         "the surviving detections only.");
  }
  std::vector<std::string> lines;
  for (const std::string& paragraph : paragraphs) {
    const std::vector<std::string> wrapped = wrap(paragraph, caption_line_chars);
    lines.insert(lines.end(), wrapped.begin(), wrapped.end());
  }
  return lines;
}

// The category's tooltip: the table's numbers for this step.
std::string step_note(const StepSummary& s) {
  std::string note = counted(s.active_layers, "active layer") + ": n = " + std::to_string(s.n) +
                     " measurements, " + std::to_string(s.detections) +
                     " with an associated target detection (" +
                     stats::format_fixed(100.0 * s.detection_rate, 1) + " %)";
  if (s.rcs.n > 0) note += ", median RCS " + stats::format_fixed(s.rcs.median, 2) + " dBsm";
  return note + ", two-way fog loss " + stats::format_fixed(s.two_way_attenuation_db, 3) + " dB";
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

std::string rcs_boxplot_svg(const SensorParams& params, const sensor::Context& context,
                            const RadarSummary& summary) {
  std::vector<stats::BoxPlotSeries> series;
  stats::SvgPlotOptions options;
  for (std::size_t i = 0; i < summary.steps.size(); ++i) {
    const StepSummary& s = summary.steps[i];
    stats::BoxPlotSeries& step = series.emplace_back();
    step.label = std::to_string(s.active_layers);
    step.box = s.rcs;
    step.rate = s.detection_rate;
    step.note = step_note(s);
    if (summary.sensor_limit_layers == s.active_layers) options.marked_category = i;
  }
  options.title = "Target RCS against active fog layers: " + target_name(params.target) + ", fog " +
                  (one_fog(context.chamber) ? fog_density(context.chamber.layers[0].fog.density)
                                            : "per layer (caption)");
  options.caption = plot_caption(params, context, summary,
                                 "Boxes: RCS of each measurement's associated target detection; "
                                 "detection rate = detections / n.");
  options.x_label = "active fog layers";
  options.y_label = "RCS of the associated target detection (dBsm)";
  // The plot area keeps its 406 px however many caption lines there are.
  options.height_px = 604.0 + 16.0 * static_cast<double>(options.caption.size());
  options.empty_label = "no target detection";
  options.rate_label = "detection rate";
  if (summary.sensor_limit_layers) {
    options.mark_label = "sensor limit: " + counted(*summary.sensor_limit_layers, "layer");
  }
  return stats::box_plot_svg(series, options);
}

std::string origins_svg(const SensorParams& params, const sensor::Context& context,
                        const RadarSummary& summary) {
  const struct {
    const char* label;
    double StepSummary::*per_frame;
  } origins[] = {
      {"target (associated, in the gate)", &StepSummary::detection_rate},
      {"multipath (ghosts of the target via the room)",
       &StepSummary::multipath_detections_per_frame},
      {"room (its objects, the back wall)", &StepSummary::room_detections_per_frame},
      {"fog", &StepSummary::fog_detections_per_frame},
      {"noise (false alarms)", &StepSummary::false_alarms_per_frame},
      {"sidelobe", &StepSummary::sidelobe_detections_per_frame},
      {"clipping (ADC)", &StepSummary::clipping_detections_per_frame},
  };
  std::vector<stats::LineSeries> series;
  std::string absent;
  for (const auto& origin : origins) {
    stats::LineSeries line;
    line.label = origin.label;
    bool any = false;
    for (const StepSummary& s : summary.steps) {
      line.x.push_back(static_cast<double>(s.active_layers));
      line.y.push_back(s.*origin.per_frame);
      any = any || s.*origin.per_frame > 0.0;
    }
    // The target is drawn even where it is never detected: its line at 0 is the finding.
    if (any || series.empty()) {
      series.push_back(std::move(line));
    } else {
      absent += (absent.empty() ? "" : ", ") + std::string(origin.label);
    }
  }
  std::string what =
      "Lines: detections per measurement of each origin (the target: the share of measurements "
      "whose associated detection in the gate is the target's; the others: detections anywhere in "
      "the map, counted by the simulation's ground truth).";
  if (!absent.empty()) what += " No detection at any step: " + absent + ".";
  stats::LinePlotOptions options;
  options.title =
      "Radar detections by origin against active fog layers: " + target_name(params.target);
  options.caption = plot_caption(params, context, summary, std::move(what));
  options.x_label = "active fog layers";
  options.y_label = "detections per measurement";
  options.x_integer_ticks = true;
  options.point_markers = true;
  options.y_reach = 1.0;
  options.legend_title = {"origin"};
  options.height_px = 604.0 + 16.0 * static_cast<double>(options.caption.size());
  return stats::line_plot_svg(series, options);
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
