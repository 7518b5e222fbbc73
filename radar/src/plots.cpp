// The radar's plots: the RCS box plot (radar_rcs_boxplot.svg) and the detections by origin
// (radar_origins.svg), with the caption that states the scenario they come from.
#include <algorithm>
#include <cctype>
#include <numeric>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "fogradar/radar/outputs.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/line_plot.hpp"
#include "fogradar/stats/svg_plot.hpp"
#include "output_words.hpp"

namespace fogradar::radar {
namespace {

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

}  // namespace fogradar::radar
