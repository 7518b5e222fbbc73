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
  if (s.x.empty() || s.x.size() != s.y.size()) {
    throw_invalid(
        name + ".x", static_cast<double>(s.x.size()),
        "a non-empty list as long as " + name + ".y (" + std::to_string(s.y.size()) + ")");
  }
  for (const double v : s.x) require_finite(name + ".x", v);
  for (const double v : s.y) require_finite(name + ".y", v);
  if (s.marker_x) require_finite(name + ".marker_x", *s.marker_x);
}

}  // namespace

void LinePlotOptions::validate() const {
  require_finite("svg.width_px", width_px);
  if (width_px < 480.0) throw_invalid("svg.width_px", width_px, ">= 480");
  require_finite("svg.height_px", height_px);
  const double needed = plot_top + min_plot_height + below_plot_px(*this);
  if (height_px < needed) throw_invalid("svg.height_px", height_px, ">= " + format_number(needed));
}

std::string line_plot_svg(std::span<const LineSeries> series, const LinePlotOptions& options) {
  options.validate();
  if (series.empty())
    throw InvalidParameter("series", "series is empty: must contain at least one series");
  for (std::size_t i = 0; i < series.size(); ++i) require_drawable(series[i], i);

  double x_low = series[0].x[0];
  double x_high = x_low;
  double y_high = 0.0;
  double y_low = 0.0;
  for (const LineSeries& s : series) {
    for (const double v : s.x) {
      x_low = std::min(x_low, v);
      x_high = std::max(x_high, v);
    }
    for (const double v : s.y) {
      y_low = std::min(y_low, v);
      y_high = std::max(y_high, v);
    }
  }
  AxisTicks xt = nice_axis_ticks(x_low, x_high, 8);
  if (options.x_integer_ticks && xt.step < 1.0)
    xt = {std::floor(xt.first), std::ceil(xt.last), 1.0, 0};
  const AxisTicks yt = nice_axis_ticks(y_low, y_high, 6);

  const double width = options.width_px;
  const double height = options.height_px;
  const double left = margin_left;
  const double right = width - legend_column;
  const double bottom = height - below_plot_px(options);
  const double axis_x_low = options.x_axis_exact && x_high > x_low ? x_low : xt.first;
  const double axis_x_high = options.x_axis_exact && x_high > x_low ? x_high : xt.last;
  const auto to_x = [&](double v) {
    return left + (v - axis_x_low) / (axis_x_high - axis_x_low) * (right - left);
  };
  const auto to_y = [&](double v) {
    return bottom - (v - yt.first) / (yt.last - yt.first) * (bottom - plot_top);
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
  const auto x_ticks = std::lround((xt.last - xt.first) / xt.step);
  for (long i = 0; i <= x_ticks; ++i) {
    const double value = xt.first + static_cast<double>(i) * xt.step;
    if (value < axis_x_low - 1e-9 * xt.step || value > axis_x_high + 1e-9 * xt.step) continue;
    line(svg, to_x(value), bottom, to_x(value), bottom + 5.0,
         "stroke=\"#333333\" stroke-width=\"1\"");
    text(svg, to_x(value), bottom + tick_baseline, "middle", "class=\"tick\"",
         axis_tick_label(value, xt));
  }
  svg += "<rect class=\"frame\" x=\"" + px(left) + "\" y=\"" + px(plot_top) + "\" width=\"" +
         px(right - left) + "\" height=\"" + px(bottom - plot_top) +
         "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"/>\n";

  std::string labels;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const LineSeries& s = series[i];
    const std::string colour(palette[i % palette.size()]);
    svg += "<polyline class=\"series\" fill=\"none\" stroke=\"" + colour +
           "\" stroke-width=\"1.8\" points=\"";
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (k != 0) svg += ' ';
      svg += px(to_x(s.x[k]));
      svg += ',';
      svg += px(to_y(s.y[k]));
    }
    svg += "\"><title>" + escape_xml(s.label) + "</title></polyline>\n";
    if (s.marker_x) {
      const double x = to_x(*s.marker_x);
      line(svg, x, plot_top, x, bottom,
           "class=\"marker\" stroke=\"" + colour +
               "\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"");
      // Labels after every line (below), stacked downwards so that close markers stay readable.
      text(labels, x + 4.0, plot_top + 14.0 + 14.0 * static_cast<double>(i), "start",
           "class=\"marker-label\" fill=\"" + colour +
               "\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\"",
           s.marker_label);
    }
    const double ly = plot_top + 10.0 + legend_row * static_cast<double>(i);
    line(svg, right + 16.0, ly, right + 40.0, ly,
         "class=\"legend\" stroke=\"" + colour + "\" stroke-width=\"1.8\"");
    text(svg, right + 46.0, ly + 4.0, "start", "class=\"legend-text\"", s.label);
  }

  svg += labels;
  text(svg, 0.5 * (left + right), bottom + x_label_baseline, "middle", "class=\"x-label\"",
       options.x_label);
  svg +=
      "<text class=\"y-label\" x=\"0.00\" y=\"0.00\" text-anchor=\"middle\" "
      "transform=\"translate(" +
      px(22.0) + " " + px(0.5 * (plot_top + bottom)) + ") rotate(-90)\">" +
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
