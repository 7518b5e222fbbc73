#include "fogradar/lidar/outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string_view>
#include <utility>
#include <variant>

#include "fogradar/core/constants.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/svg_plot.hpp"

namespace fogradar::lidar {
namespace {

constexpr double degree_rad = pi / 180.0;

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// Shortest text that reads back to exactly `value`; NaN -> "".
std::string exact(double value) { return stats::format_number(value, 0); }

std::string px(double v) { return stats::format_fixed(v, 2); }

std::string layers_label(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " layer" : " layers");
}

// Clear-weather peak of the target's centre beam over the threshold: the datasheet margin.
double clear_margin(const Lidar& lidar) {
  const LidarParams& p = lidar.params();
  const double range_m = std::hypot(lidar.target_range_m(), p.target_offset_m);
  return hard_target_peak(p.target_reflectivity, 1.0, 1.0, range_m) *
         overlap(range_m, p.overlap_range_m) / lidar.threshold();
}

}  // namespace

std::string lidar_echoes_csv(const Lidar& lidar, const std::vector<LidarStepResult>& steps) {
  std::string out = "active_layers,item,angle_deg,echo,range_m,intensity,origin,layer\n";
  for (const LidarStepResult& step : steps) {
    const std::string step_text = std::to_string(step.active_layers) + ',';
    for (std::size_t s = 0; s < step.scans.size(); ++s) {
      const std::string prefix = step_text + std::to_string(s) + ',';
      for (const LidarEcho& e : step.scans[s].echoes) {
        out += prefix;
        out += exact(lidar.beam_angle_deg(e.beam));
        out += ',' + std::to_string(e.index) + ',' + stats::format_fixed(e.range_m, 4) + ',' +
               stats::format_fixed(e.intensity, 2) + ',';
        out += to_string(e.origin);
        out += ',' + std::to_string(e.layer) + '\n';
      }
    }
  }
  return out;
}

sensor::StepTable lidar_step_table(const LidarSummary& summary) {
  using S = LidarStepSummary;
  const std::vector<S>& steps = summary.steps;
  sensor::StepTable t(steps.size());
  t.integer("active_layers", "", steps, [](const S& s) { return s.active_layers; });
  t.integer("scans", "", steps, [](const S& s) { return s.scans; });
  t.integer("target_detections", "", steps, [](const S& s) { return s.target_detections; });
  t.number("target_detection_rate", "", steps, [](const S& s) { return s.target_detection_rate; });
  t.number("target_told_rate", "", steps, [](const S& s) { return s.target_told_rate; });
  // The target intensity's box plot: intensity_<statistic> in the CSV, one object in the JSON.
  using stats::BoxPlot;
  t.integer("intensity_n", "", steps, [](const S& s) { return s.target_intensity.n; })
      .in_csv(false)
      .in_json("/target_intensity/n");
  const std::pair<const char*, double BoxPlot::*> statistics[] = {
      {"mean", &BoxPlot::mean},
      {"std", &BoxPlot::std_dev},
      {"min", &BoxPlot::min},
      {"q1", &BoxPlot::q1},
      {"median", &BoxPlot::median},
      {"q3", &BoxPlot::q3},
      {"max", &BoxPlot::max},
      {"whisker_low", &BoxPlot::whisker_low},
      {"whisker_high", &BoxPlot::whisker_high}};
  for (const auto& [statistic, field] : statistics) {
    t.number(std::string("intensity_") + statistic, "", steps, [field = field](const S& s) {
       return s.target_intensity.*field;
     }).in_json(std::string("/target_intensity/") + statistic);
  }
  t.numbers("intensity_outliers", "", steps, [](const S& s) {
     return s.target_intensity.outliers;
   }).in_json("/target_intensity/outliers");
  t.number("eq4_intensity", "", steps, [](const S& s) { return s.eq4_intensity; });
  t.number("fog_echo_rate", "", steps, [](const S& s) { return s.fog_echo_rate; });
  t.number("median_first_echo_range", "m", steps,
           [](const S& s) { return s.median_first_echo_range_m; });
  t.integer("beams_through_fog", "", steps, [](const S& s) { return s.beams_through_fog; });
  t.integer("sensor_limit", "", steps, [&summary](const S& s) {
     return summary.sensor_limit_layers == s.active_layers;
   }).in_json("");

  // No beam crosses the fog at 0 active layers: the printed table shows neither fog figure when
  // either has no value.
  const auto fog_figure = [](double S::*figure) {
    return [figure](const S& s) {
      return std::isnan(s.fog_echo_rate) || std::isnan(s.median_first_echo_range_m)
                 ? std::numeric_limits<double>::quiet_NaN()
                 : s.*figure;
    };
  };
  t.number("printed_fog_echo_rate", "", steps, fog_figure(&S::fog_echo_rate)).printed_only();
  t.number("printed_first_echo_range", "m", steps, fog_figure(&S::median_first_echo_range_m))
      .printed_only();
  const auto intensity_head = [](const char* head) {
    return sensor::Printed{.heads = {head, "intens."}, .width = 9, .precision = 1};
  };
  t.print("active_layers", {.heads = {"layers", ""}, .width = 6});
  t.print("scans", {.heads = {"scans", ""}, .width = 5});
  t.print("target_detection_rate",
          {.heads = {"target", "det. %"}, .width = 8, .precision = 1, .scale = 100.0});
  t.print("target_told_rate", {.heads = {"told", "%"}, .width = 8, .precision = 1, .scale = 100.0});
  t.print("intensity_median", intensity_head("median"));
  t.print("eq4_intensity", intensity_head("eq. 4"));
  t.print("intensity_q1", intensity_head("q1"));
  t.print("intensity_q3", intensity_head("q3"));
  t.print("intensity_max", intensity_head("max"));
  t.print("printed_fog_echo_rate", {.heads = {"fog echo", "rate %"},
                                    .width = 9,
                                    .precision = 1,
                                    .scale = 100.0,
                                    .missing = "-"});
  t.print("printed_first_echo_range_m",
          {.heads = {"1st echo", "median m"}, .width = 10, .precision = 3, .missing = "-"});
  return t;
}

nlohmann::json lidar_summary_json(const Lidar& lidar, const LidarSummary& summary) {
  nlohmann::json layers = nlohmann::json::array();
  for (std::size_t i = 0; i < lidar.layer_count(); ++i) {
    layers.push_back({{"start_m", lidar.layer_start_m(i)},
                      {"end_m", lidar.layer_end_m(i)},
                      {"extinction_per_m", lidar.layer_extinction_per_m(i)},
                      {"backscatter_per_m_sr", lidar.layer_backscatter_per_m_sr(i)},
                      {"lidar_ratio_sr", lidar.layer_backscatter_per_m_sr(i) > 0.0
                                             ? number_or_null(lidar.layer_extinction_per_m(i) /
                                                              lidar.layer_backscatter_per_m_sr(i))
                                             : nlohmann::json(nullptr)}});
  }
  return {
      {"sensor", "lidar"},
      {"wavelength_m", lidar.params().wavelength_m},
      {"beams_per_scan", lidar.beam_count()},
      {"target_beam_angle_deg", lidar.beam_angle_deg(lidar.target_beam())},
      {"threshold", lidar.threshold()},
      {"noise_std", lidar.noise_std()},
      {"window_two_way_transmittance", lidar.window_two_way_transmittance()},
      {"clear_weather_margin", clear_margin(lidar)},
      {"layers", layers},
      {"steps", lidar_step_table(summary).json()},
      {"sensor_limit_layers", summary.sensor_limit_layers
                                  ? nlohmann::json(*summary.sensor_limit_layers)
                                  : nlohmann::json(nullptr)},
      {"sensor_limit_criterion", lidar_sensor_limit_criterion},
  };
}

std::string lidar_intensity_boxplot_svg(const Lidar& lidar, const LidarSummary& summary) {
  const LidarParams& p = lidar.params();
  std::vector<stats::BoxPlotSeries> series;
  stats::SvgPlotOptions options;
  for (std::size_t i = 0; i < summary.steps.size(); ++i) {
    const LidarStepSummary& s = summary.steps[i];
    stats::BoxPlotSeries& step = series.emplace_back();
    step.label = std::to_string(s.active_layers);
    step.box = s.target_intensity;
    step.rate = s.target_detection_rate;
    step.note = layers_label(s.active_layers) + ": target in " +
                std::to_string(s.target_detections) + " of " + std::to_string(s.scans) + " scans";
    if (summary.sensor_limit_layers == s.active_layers) options.marked_category = i;
  }
  options.title = "Lidar: target intensity against active fog layers (the study's Fig. 6)";
  options.caption = {"One value per scan from the beam through the target's centre (" +
                         stats::format_number(lidar.beam_angle_deg(lidar.target_beam()), 6) +
                         " deg); a scan without a target echo counts as 0, as the study plots it.",
                     stats::format_number(p.wavelength_m * 1e9, 4) + " nm, pulse " +
                         stats::format_number(p.pulse_width_ns, 4) + " ns FWHM, threshold from " +
                         stats::format_number(p.threshold_range_m, 4) + " m at reflectivity " +
                         stats::format_number(p.threshold_reflectivity, 3) +
                         "; target reflectivity " + stats::format_number(p.target_reflectivity, 3) +
                         " at " + stats::format_number(lidar.target_range_m(), 4) +
                         " m; clear-weather margin " +
                         stats::format_number(clear_margin(lidar), 3) + " x threshold.",
                     "Intensity = " + stats::format_number(p.intensity_scale, 6) +
                         " x peak / threshold (a unit choice), saturating at " +
                         stats::format_number(p.intensity_saturation, 6) + "."};
  options.x_label = "active fog layers";
  options.y_label = "target intensity (relative)";
  options.height_px = 604.0 + 16.0 * static_cast<double>(options.caption.size());
  options.empty_label = "no scans";
  options.rate_label = "target detection rate";
  if (summary.sensor_limit_layers) {
    options.mark_label = "sensor limit: " + layers_label(*summary.sensor_limit_layers);
  }
  return stats::box_plot_svg(series, options);
}

std::string lidar_scans_svg(const Lidar& lidar, const std::vector<LidarStepResult>& steps) {
  const LidarParams& p = lidar.params();
  // Scene extent: the fog, the target and the background near them, plus a metre of margin.
  double half_width_m =
      std::max(0.5 * p.fog_width_m, std::abs(p.target_offset_m) + 0.5 * p.target_width_m);
  const double depth_m = lidar.target_range_m() + 2.0;
  for (const Shape& shape : lidar.shapes()) {
    if (const auto* s = std::get_if<SegmentShape>(&shape.geometry)) {
      if (std::min(s->x0_m, s->x1_m) < depth_m) {
        half_width_m = std::max({half_width_m, std::abs(s->y0_m), std::abs(s->y1_m)});
      }
    } else if (const auto* c = std::get_if<CircleShape>(&shape.geometry)) {
      if (c->centre_x_m - c->radius_m < depth_m) {
        half_width_m = std::max(half_width_m, std::abs(c->centre_y_m) + c->radius_m);
      }
    } else if (const auto* l = std::get_if<LineShape>(&shape.geometry)) {
      // A side wall (a line along x) in view.
      if (l->direction_y == 0.0) half_width_m = std::max(half_width_m, std::abs(l->y_m));
    }
  }
  half_width_m = std::min(half_width_m + 1.0, depth_m);
  const double panel_w = 220.0;
  const double scale = panel_w / (2.0 * half_width_m);  // px per metre
  const double panel_h = depth_m * scale;
  const double left = 50.0, top = 60.0, gap = 20.0;
  const std::size_t n = std::max<std::size_t>(steps.size(), 1);
  const double width = left + static_cast<double>(n) * (panel_w + gap) + 10.0;
  const double height = top + panel_h + 90.0;

  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(width) +
         "\" height=\"" + px(height) + "\" viewBox=\"0 0 " + px(width) + " " + px(height) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + px(left) +
         "\" y=\"22\" font-size=\"15\">Lidar: one scan per step, top "
         "view, sensor at the bottom (the study's Fig. 5)</text>\n";
  svg += "<text x=\"" + px(left) +
         "\" y=\"40\" fill=\"#444\">First scan of each step; echoes by "
         "ground-truth origin. Blue bands: active fog layers (dashed: off); grey bar: the "
         "target (EVT).</text>\n";
  struct Style {
    Origin origin;
    const char* colour;
    const char* name;
  };
  constexpr Style styles[] = {{Origin::target, "#d62728", "target"},
                              {Origin::fog, "#1f77b4", "fog"},
                              {Origin::background, "#555555", "background"},
                              {Origin::noise, "#ff7f0e", "noise"}};
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const LidarStepResult& step = steps[i];
    const double x0 = left + static_cast<double>(i) * (panel_w + gap);
    // Scene (x forward, y right) to panel pixels: y -> right, x -> up from the bottom.
    const auto sx = [&](double y_m) { return x0 + (y_m + half_width_m) * scale; };
    const auto sy = [&](double x_m) { return top + panel_h - x_m * scale; };
    svg += "<g>\n<rect x=\"" + px(x0) + "\" y=\"" + px(top) + "\" width=\"" + px(panel_w) +
           "\" height=\"" + px(panel_h) + "\" fill=\"#fafafa\" stroke=\"#999\"/>\n";
    for (std::size_t l = 0; l < lidar.layer_count(); ++l) {
      const bool on = l < step.active_layers;
      const double fog_half = std::min(0.5 * p.fog_width_m, half_width_m);
      svg += "<rect x=\"" + px(sx(-fog_half)) + "\" y=\"" + px(sy(lidar.layer_end_m(l))) +
             "\" width=\"" + px(2.0 * fog_half * scale) + "\" height=\"" +
             px((lidar.layer_end_m(l) - lidar.layer_start_m(l)) * scale) + "\" " +
             (on ? "fill=\"#cfe3f5\" stroke=\"#9cc3e6\""
                 : "fill=\"none\" stroke=\"#9cc3e6\" stroke-dasharray=\"4 3\"") +
             "/>\n";
    }
    const double half_target = 0.5 * p.target_width_m;
    svg += "<rect x=\"" + px(sx(p.target_offset_m - half_target)) + "\" y=\"" +
           px(sy(lidar.target_range_m()) - 10.0) + "\" width=\"" + px(p.target_width_m * scale) +
           "\" height=\"8\" fill=\"#999\"><title>target region</title></rect>\n";
    const auto line = [&](double xa, double ya, double xb, double yb, const char* title) {
      svg += "<line x1=\"" + px(sx(ya)) + "\" y1=\"" + px(sy(xa)) + "\" x2=\"" + px(sx(yb)) +
             "\" y2=\"" + px(sy(xb)) + "\" stroke=\"#ccc\" stroke-width=\"3\"><title>" + title +
             "</title></line>\n";
    };
    for (const Shape& shape : lidar.shapes()) {
      if (const auto* s = std::get_if<SegmentShape>(&shape.geometry)) {
        line(s->x0_m, s->y0_m, s->x1_m, s->y1_m, "background segment");
      } else if (const auto* c = std::get_if<CircleShape>(&shape.geometry)) {
        svg += "<circle cx=\"" + px(sx(c->centre_y_m)) + "\" cy=\"" + px(sy(c->centre_x_m)) +
               "\" r=\"" + px(c->radius_m * scale) +
               "\" fill=\"none\" stroke=\"#ccc\" "
               "stroke-width=\"3\"><title>cylinder</title></circle>\n";
      } else if (const auto* l = std::get_if<LineShape>(&shape.geometry)) {
        // The line clipped to the panel, x in [0, depth], y in [-half width, half width]: the range
        // of its parameter t (point = p + t d) inside each slab.
        double t0 = -std::numeric_limits<double>::infinity();
        double t1 = std::numeric_limits<double>::infinity();
        const auto slab = [&t0, &t1](double start, double direction, double low, double high) {
          if (direction == 0.0) {
            if (start < low || start > high) t1 = t0 - 1.0;
            return;
          }
          const double a = (low - start) / direction;
          const double b = (high - start) / direction;
          t0 = std::max(t0, std::min(a, b));
          t1 = std::min(t1, std::max(a, b));
        };
        slab(l->x_m, l->direction_x, 0.0, depth_m);
        slab(l->y_m, l->direction_y, -half_width_m, half_width_m);
        if (t1 > t0) {
          line(l->x_m + t0 * l->direction_x, l->y_m + t0 * l->direction_y,
               l->x_m + t1 * l->direction_x, l->y_m + t1 * l->direction_y, "wall");
        }
      }
    }
    if (!step.scans.empty()) {
      for (const LidarEcho& e : step.scans.front().echoes) {
        const double angle = lidar.beam_angle_deg(e.beam) * degree_rad;
        const double x_m = e.range_m * std::cos(angle);
        const double y_m = e.range_m * std::sin(angle);
        if (x_m < 0.0 || x_m > depth_m || std::abs(y_m) > half_width_m) continue;
        const char* colour = "#000";
        for (const Style& style : styles) {
          if (style.origin == e.origin) colour = style.colour;
        }
        svg += "<circle cx=\"" + px(sx(y_m)) + "\" cy=\"" + px(sy(x_m)) + "\" r=\"1.6\" fill=\"" +
               colour + "\"/>\n";
      }
    }
    svg += "<path d=\"M " + px(sx(0.0)) + " " + px(sy(0.0) - 8.0) + " L " + px(sx(0.0) - 6.0) +
           " " + px(sy(0.0)) + " L " + px(sx(0.0) + 6.0) + " " + px(sy(0.0)) +
           " Z\" fill=\"#222\"><title>sensor</title></path>\n";
    svg += "<text x=\"" + px(x0 + panel_w / 2.0) + "\" y=\"" + px(top + panel_h + 18.0) +
           "\" text-anchor=\"middle\">" + layers_label(step.active_layers) + "</text>\n</g>\n";
  }
  // Range axis on the left, 2 m ticks.
  for (double x_m = 0.0; x_m <= depth_m + 1e-9; x_m += 2.0) {
    const double y = top + panel_h - x_m * scale;
    svg += "<line x1=\"" + px(left - 5.0) + "\" y1=\"" + px(y) + "\" x2=\"" + px(left) +
           "\" y2=\"" + px(y) + "\" stroke=\"#333\"/>\n";
    svg += "<text x=\"" + px(left - 8.0) + "\" y=\"" + px(y + 4.0) + "\" text-anchor=\"end\">" +
           stats::format_number(x_m, 4) + "</text>\n";
  }
  svg += "<text transform=\"translate(14 " + px(top + panel_h / 2.0) +
         ") rotate(-90)\" text-anchor=\"middle\">range along boresight (m)</text>\n";
  double legend_x = left;
  const double legend_y = top + panel_h + 45.0;
  for (const Style& style : styles) {
    svg += "<circle cx=\"" + px(legend_x + 5.0) + "\" cy=\"" + px(legend_y - 4.0) +
           "\" r=\"4\" fill=\"" + style.colour + "\"/>\n";
    svg += "<text x=\"" + px(legend_x + 14.0) + "\" y=\"" + px(legend_y) + "\">" + style.name +
           " echo</text>\n";
    legend_x += 120.0;
  }
  svg += "<text x=\"" + px(left) + "\" y=\"" + px(legend_y + 22.0) +
         "\" fill=\"#444\">Panel width " + stats::format_number(2.0 * half_width_m, 4) +
         " m (lateral, sensor's right to the right); scale 1:1.</text>\n";
  svg += "</svg>\n";
  return svg;
}

std::string lidar_summary_table(const LidarSummary& summary) {
  std::ostringstream out;
  out << lidar_step_table(summary).printed();
  out << "target det. %: scans with a target-origin echo in the beam through the target's centre;\n"
         "told %: and no fog echo there at least as intense; intensity: that echo's, 0 when\n"
         "missing (the study's Fig. 6); eq. 4: the study's eq. 4 for that echo, the clear\n"
         "noise-free echo times tau^2 of each active layer; fog echo rate: beams through the fog\n"
         "with a fog echo; 1st echo: median first-echo range of the beams through the fog\n";
  out << "lidar sensor limit: ";
  if (summary.sensor_limit_layers)
    out << layers_label(*summary.sensor_limit_layers) << "\n";
  else
    out << "not reached\n";
  return out.str();
}

std::size_t lidar_memory_bytes(const LidarParams& params, std::size_t steps, unsigned threads) {
  const std::size_t beams = params.beam_count();
  const std::size_t scans = steps * params.scans_per_step;
  // Per scan: at most max_echoes echoes and one first-echo range per beam, plus the struct.
  const std::size_t per_scan =
      beams * (params.max_echoes * sizeof(LidarEcho) + sizeof(double)) + sizeof(LidarScan);
  const std::size_t samples =
      static_cast<std::size_t>(2.0 * params.max_range_m / speed_of_light_m_per_s /
                               (params.sample_interval_ns * 1e-9)) +
      2;
  // Per thread: five real waveforms, the complex noise buffer and the fog's shares by layer (about
  // one record).
  const std::size_t per_thread = 8 * samples * sizeof(double);
  // lidar_echoes.csv: at most ~64 characters a row; the SVGs and the summary are small.
  const std::size_t files = scans * beams * params.max_echoes * 64 + (1u << 20);
  return scans * per_scan + threads * per_thread + files;
}

}  // namespace fogradar::lidar
