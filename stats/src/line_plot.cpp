#include "fogradar/stats/line_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/svg_plot.hpp"
#include "svg_text.hpp"

namespace fogradar::stats {
namespace {

using detail::escape_xml;

// Layout in px, as box_plot_svg's: tick labels and y label on the left, the legend on the right.
constexpr double margin_left = 84.0;
constexpr double legend_column = 220.0;
constexpr double title_baseline = 28.0;
constexpr double plot_top = 52.0;
constexpr double min_plot_height = 100.0;
constexpr double tick_baseline = 18.0;
constexpr double x_label_baseline = 40.0;
constexpr double caption_gap = 8.0;
constexpr double caption_line = 16.0;
constexpr double bottom_padding = 12.0;
constexpr double legend_row = 22.0;
constexpr double beyond_row = 30.0;

// Colour-blind-safe qualitative palette (Okabe & Ito 2008), cycled.
constexpr std::array<std::string_view, 7> palette{"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                  "#E69F00", "#56B4E9", "#000000"};

std::string px(double v) { return format_fixed(v, 2); }

void line(std::string& svg, double x1, double y1, double x2, double y2,
          std::string_view attributes) {
  svg += "<line x1=\"" + px(x1) + "\" y1=\"" + px(y1) + "\" x2=\"" + px(x2) + "\" y2=\"" + px(y2) +
         "\" " + std::string(attributes) + "/>\n";
}

void text(std::string& svg, double x, double y, std::string_view anchor,
          std::string_view attributes, std::string_view content) {
  svg += "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" text-anchor=\"" + std::string(anchor) +
         "\" " + std::string(attributes) + ">" + escape_xml(content) + "</text>\n";
}

double below_plot_px(const LinePlotOptions& options) {
  return x_label_baseline + caption_gap +
         caption_line * static_cast<double>(options.caption.size()) + bottom_padding;
}

void require_drawable(const LineSeries& s, std::size_t i) {
  const std::string name = "series[" + std::to_string(i) + "]";
  if ((s.x.empty() && s.beyond_x.empty()) || s.x.size() != s.y.size()) {
    throw_invalid(
        name + ".x", static_cast<double>(s.x.size()),
        "a non-empty list as long as " + name + ".y (" + std::to_string(s.y.size()) + ")");
  }
  for (const double v : s.x) require_finite(name + ".x", v);
  for (const double v : s.y) require_finite(name + ".y", v);
  for (const double v : s.beyond_x) require_finite(name + ".beyond_x", v);
  if (s.marker_x) require_finite(name + ".marker_x", *s.marker_x);
}

// Hollow point markers (SVG path data centred on the point) and dash patterns; 7 and 4 are coprime,
// so series i and j < 28 differ in shape or dash.
constexpr double marker_radius = 4.5;
constexpr std::array<std::string_view, 7> shape_names{
    "circle", "square", "triangle-up", "diamond", "triangle-down", "plus", "cross"};
constexpr std::array<std::string_view, 4> dashes{"", "7 3", "2 2.5", "9 3 2 3"};

std::string marker_path(std::size_t shape, double x, double y) {
  const double r = marker_radius;
  const auto at = [&](double dx, double dy) { return px(x + dx) + "," + px(y + dy); };
  switch (shape) {
    case 0:  // circle: two arcs
      return "M" + at(-r, 0) + " A" + px(r) + "," + px(r) + " 0 1,0 " + at(r, 0) + " A" + px(r) +
             "," + px(r) + " 0 1,0 " + at(-r, 0) + " Z";
    case 1:
      return "M" + at(-0.85 * r, -0.85 * r) + " L" + at(0.85 * r, -0.85 * r) + " L" +
             at(0.85 * r, 0.85 * r) + " L" + at(-0.85 * r, 0.85 * r) + " Z";
    case 2:
      return "M" + at(0, -1.15 * r) + " L" + at(r, 0.75 * r) + " L" + at(-r, 0.75 * r) + " Z";
    case 3:
      return "M" + at(0, -1.2 * r) + " L" + at(1.2 * r, 0) + " L" + at(0, 1.2 * r) + " L" +
             at(-1.2 * r, 0) + " Z";
    case 4:
      return "M" + at(0, 1.15 * r) + " L" + at(r, -0.75 * r) + " L" + at(-r, -0.75 * r) + " Z";
    case 5:
      return "M" + at(-1.2 * r, 0) + " L" + at(1.2 * r, 0) + " M" + at(0, -1.2 * r) + " L" +
             at(0, 1.2 * r);
    default:
      return "M" + at(-r, -r) + " L" + at(r, r) + " M" + at(-r, r) + " L" + at(r, -r);
  }
}

void point_marker(std::string& svg, std::size_t shape, double x, double y, std::string_view cls,
                  std::string_view colour) {
  svg += "<path class=\"" + std::string(cls) + "-" + std::string(shape_names[shape]) + "\" d=\"" +
         marker_path(shape, x, y) + "\" fill=\"#ffffff\" fill-opacity=\"0\" stroke=\"" +
         std::string(colour) + "\" stroke-width=\"1.6\"/>\n";
}

// A series' points with those beyond the axis (no y); in x order where runs and steps need it.
struct Point {
  double x;
  std::optional<double> y;
};

std::vector<Point> ordered_points(const LineSeries& s, bool steps) {
  std::vector<Point> points;
  for (std::size_t k = 0; k < s.x.size(); ++k) points.push_back({s.x[k], s.y[k]});
  for (const double x : s.beyond_x) points.push_back({x, std::nullopt});
  if (steps || !s.beyond_x.empty()) {
    std::stable_sort(points.begin(), points.end(),
                     [](const Point& a, const Point& b) { return a.x < b.x; });
  }
  return points;
}

// The vertices of each unbroken run of points (as given, or as steps that change halfway between
// neighbours, the ends held to the outermost points).
std::vector<std::vector<std::pair<double, double>>> runs_of(const std::vector<Point>& points,
                                                            bool steps) {
  std::vector<std::vector<std::pair<double, double>>> runs;
  bool open = false;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!points[k].y) {
      open = false;
      continue;
    }
    if (!open) runs.emplace_back();
    open = true;
    const double y = *points[k].y;
    if (!steps) {
      runs.back().emplace_back(points[k].x, y);
      continue;
    }
    const double from = k == 0 ? points[k].x : 0.5 * (points[k - 1].x + points[k].x);
    const double to = k + 1 == points.size() ? points[k].x : 0.5 * (points[k].x + points[k + 1].x);
    runs.back().emplace_back(from, y);
    runs.back().emplace_back(to, y);
  }
  return runs;
}

double beyond_row_px(const LinePlotOptions& options) {
  return options.beyond_label.empty() ? 0.0 : beyond_row;
}

}  // namespace

void LinePlotOptions::validate() const {
  require_finite("svg.width_px", width_px);
  if (width_px < 480.0) throw_invalid("svg.width_px", width_px, ">= 480");
  require_finite("svg.height_px", height_px);
  const double needed = plot_top + beyond_row_px(*this) + min_plot_height + below_plot_px(*this);
  if (height_px < needed) throw_invalid("svg.height_px", height_px, ">= " + format_number(needed));
  if (y_reach) require_finite("svg.y_reach", *y_reach);
}

std::string line_plot_svg(std::span<const LineSeries> series, const LinePlotOptions& options) {
  options.validate();
  if (series.empty())
    throw InvalidParameter("series", "series is empty: must contain at least one series");
  for (std::size_t i = 0; i < series.size(); ++i) require_drawable(series[i], i);

  const double first_x = series[0].x.empty() ? series[0].beyond_x[0] : series[0].x[0];
  double x_low = first_x;
  double x_high = first_x;
  double y_high = options.y_reach.value_or(0.0);
  double y_low = std::min(0.0, y_high);
  bool any_beyond = false;
  for (const LineSeries& s : series) {
    for (const auto* xs : {&s.x, &s.beyond_x}) {
      for (const double v : *xs) {
        x_low = std::min(x_low, v);
        x_high = std::max(x_high, v);
      }
    }
    for (const double v : s.y) {
      y_low = std::min(y_low, v);
      y_high = std::max(y_high, v);
    }
    any_beyond = any_beyond || !s.beyond_x.empty();
  }
  AxisTicks xt = nice_axis_ticks(x_low, x_high, 8);
  if (options.x_integer_ticks && xt.step < 1.0)
    xt = {std::floor(xt.first), std::ceil(xt.last), 1.0, 0};
  AxisTicks yt = nice_axis_ticks(y_low, y_high, 6);
  if (options.y_integer_ticks && yt.step < 1.0)
    yt = {std::floor(yt.first), std::ceil(yt.last), 1.0, 0};

  const double width = options.width_px;
  const double height = options.height_px;
  const double left = margin_left;
  // The legend's column: wide enough for its longest text (12 px sans-serif, about 0.6 em a
  // character, bold titles 0.65 em), never narrower than the default.
  double legend_width = legend_column;
  for (const std::string& t : options.legend_title)
    legend_width = std::max(legend_width, 28.0 + 7.8 * static_cast<double>(t.size()));
  for (const LineSeries& s : series)
    legend_width = std::max(legend_width, 58.0 + 7.2 * static_cast<double>(s.label.size()));
  legend_width = std::min(legend_width, 0.5 * width);
  const double right = width - legend_width;
  const double bottom = height - below_plot_px(options);
  // With points beyond the axis, a row for them between the title and the plot area.
  const double beyond_y = plot_top + 0.5 * beyond_row;
  const double frame_top = plot_top + (any_beyond ? beyond_row_px(options) : 0.0);
  const double axis_x_low = options.x_axis_exact && x_high > x_low ? x_low : xt.first;
  const double axis_x_high = options.x_axis_exact && x_high > x_low ? x_high : xt.last;
  const auto to_x = [&](double v) {
    return left + (v - axis_x_low) / (axis_x_high - axis_x_low) * (right - left);
  };
  const auto to_y = [&](double v) {
    return bottom - (v - yt.first) / (yt.last - yt.first) * (bottom - frame_top);
  };

  std::string svg;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(width) +
         "\" height=\"" + px(height) + "\" viewBox=\"0 0 " + px(width) + " " + px(height) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect x=\"0.00\" y=\"0.00\" width=\"" + px(width) + "\" height=\"" + px(height) +
         "\" fill=\"#ffffff\"/>\n";
  text(svg, 0.5 * width, title_baseline, "middle",
       "class=\"title\" font-size=\"16\" font-weight=\"bold\"", options.title);

  const auto y_ticks = std::lround((yt.last - yt.first) / yt.step);
  for (long i = 0; i <= y_ticks; ++i) {
    const double value = yt.first + static_cast<double>(i) * yt.step;
    line(svg, left, to_y(value), right, to_y(value),
         "class=\"grid\" stroke=\"#dddddd\" stroke-width=\"1\"");
    text(svg, left - 8.0, to_y(value) + 4.0, "end", "class=\"tick\"", axis_tick_label(value, yt));
  }
  if (any_beyond) {
    line(svg, left, beyond_y, right, beyond_y,
         "class=\"grid\" stroke=\"#dddddd\" stroke-width=\"1\" stroke-dasharray=\"3 3\"");
    text(svg, left - 8.0, beyond_y + 4.0, "end", "class=\"beyond-label\" font-style=\"italic\"",
         options.beyond_label);
  }
  const auto x_ticks = std::lround((xt.last - xt.first) / xt.step);
  for (long i = 0; i <= x_ticks; ++i) {
    const double value = xt.first + static_cast<double>(i) * xt.step;
    if (value < axis_x_low - 1e-9 * xt.step || value > axis_x_high + 1e-9 * xt.step) continue;
    line(svg, to_x(value), bottom, to_x(value), bottom + 5.0,
         "stroke=\"#333333\" stroke-width=\"1\"");
    text(svg, to_x(value), bottom + tick_baseline, "middle", "class=\"tick\"",
         axis_tick_label(value, xt));
  }
  svg += "<rect class=\"frame\" x=\"" + px(left) + "\" y=\"" + px(frame_top) + "\" width=\"" +
         px(right - left) + "\" height=\"" + px(bottom - frame_top) +
         "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"/>\n";

  std::string labels;
  const double legend_top =
      plot_top + legend_row * static_cast<double>(options.legend_title.size());
  for (std::size_t i = 0; i < options.legend_title.size(); ++i) {
    text(svg, right + 16.0, plot_top + 4.0 + legend_row * static_cast<double>(i), "start",
         "class=\"legend-title\" font-weight=\"bold\"", options.legend_title[i]);
  }
  for (std::size_t i = 0; i < series.size(); ++i) {
    const LineSeries& s = series[i];
    const std::string colour(palette[i % palette.size()]);
    const std::size_t shape = i % shape_names.size();
    const std::string_view dash = options.point_markers ? dashes[i % dashes.size()] : "";
    const std::string dash_attribute =
        dash.empty() ? std::string() : " stroke-dasharray=\"" + std::string(dash) + "\"";
    const std::vector<Point> points = ordered_points(s, options.steps);
    for (const auto& run : runs_of(points, options.steps)) {
      svg += "<polyline class=\"series\" fill=\"none\" stroke=\"" + colour +
             "\" stroke-width=\"1.8\"" + dash_attribute + " points=\"";
      for (std::size_t k = 0; k < run.size(); ++k) {
        if (k != 0) svg += ' ';
        svg += px(to_x(run[k].first));
        svg += ',';
        svg += px(to_y(run[k].second));
      }
      svg += "\"><title>" + escape_xml(s.label) + "</title></polyline>\n";
    }
    for (const Point& p : points) {
      if (p.y && options.point_markers) {
        point_marker(svg, shape, to_x(p.x), to_y(*p.y), "point", colour);
      } else if (!p.y) {
        // Series stacked within the row, so that marks at one x stay apart.
        const double dodge =
            std::min(8.0, (beyond_row - 2.0 * marker_radius) / static_cast<double>(series.size()));
        const double offset =
            (static_cast<double>(i) - 0.5 * static_cast<double>(series.size() - 1)) * dodge;
        point_marker(svg, shape, to_x(p.x), beyond_y + offset, "beyond", colour);
      }
    }
    if (s.marker_x) {
      const double x = to_x(*s.marker_x);
      line(svg, x, frame_top, x, bottom,
           "class=\"marker\" stroke=\"" + colour +
               "\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"");
      // Labels after every line (below), stacked downwards so that close markers stay readable.
      text(labels, x + 4.0, frame_top + 14.0 + 14.0 * static_cast<double>(i), "start",
           "class=\"marker-label\" fill=\"" + colour +
               "\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\"",
           s.marker_label);
    }
    const double ly = legend_top + 10.0 + legend_row * static_cast<double>(i);
    line(svg, right + 16.0, ly, right + 40.0, ly,
         "class=\"legend\" stroke=\"" + colour + "\" stroke-width=\"1.8\"" + dash_attribute);
    if (options.point_markers || any_beyond)
      point_marker(svg, shape, right + 28.0, ly, "legend-point", colour);
    text(svg, right + 46.0, ly + 4.0, "start", "class=\"legend-text\"", s.label);
  }
  if (any_beyond) {
    const double ly = legend_top + 10.0 + legend_row * static_cast<double>(series.size());
    text(svg, right + 16.0, ly + 4.0, "start", "class=\"legend-beyond\" font-style=\"italic\"",
         "top row: " + options.beyond_label);
  }

  svg += labels;
  text(svg, 0.5 * (left + right), bottom + x_label_baseline, "middle", "class=\"x-label\"",
       options.x_label);
  svg +=
      "<text class=\"y-label\" x=\"0.00\" y=\"0.00\" text-anchor=\"middle\" "
      "transform=\"translate(" +
      px(22.0) + " " + px(0.5 * (frame_top + bottom)) + ") rotate(-90)\">" +
      escape_xml(options.y_label) + "</text>\n";
  for (std::size_t i = 0; i < options.caption.size(); ++i) {
    text(svg, left,
         bottom + x_label_baseline + caption_gap + caption_line * static_cast<double>(i + 1),
         "start", "class=\"caption\" fill=\"#555555\"", options.caption[i]);
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace fogradar::stats
