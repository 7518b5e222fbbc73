#include "fogradar/stats/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::stats {

namespace {

// Layout in px: margins hold the title and legend (top), tick labels and the y label (left),
// category labels, "n = ..." notes and the x label (bottom).
constexpr double margin_left = 80.0;
constexpr double margin_right = 24.0;
constexpr double margin_top = 60.0;
constexpr double margin_bottom = 90.0;
constexpr double max_box_half_width = 40.0;
constexpr double outlier_radius = 3.0;
constexpr double mean_marker_half = 4.5;

// Coordinates with two decimals: 0.01 px is far below any rendering resolution.
std::string px(double v) { return format_fixed(v, 2); }

// XML character data and attribute values: the five predefined entities; control characters
// that XML 1.0 forbids become spaces.
std::string escape_xml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out +=
            (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') ? ' ' : c;
    }
  }
  return out;
}

void line(std::string& svg, double x1, double y1, double x2, double y2, std::string_view style) {
  svg += "<line x1=\"" + px(x1) + "\" y1=\"" + px(y1) + "\" x2=\"" + px(x2) + "\" y2=\"" + px(y2) +
         "\" " + std::string(style) + "/>\n";
}

void text(std::string& svg, double x, double y, std::string_view anchor, std::string_view style,
          std::string_view content) {
  svg += "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" text-anchor=\"" + std::string(anchor) +
         "\" " + std::string(style) + ">" + escape_xml(content) + "</text>\n";
}

void diamond(std::string& svg, double x, double y, std::string_view class_name) {
  const double h = mean_marker_half;
  svg += "<path class=\"" + std::string(class_name) + "\" d=\"M " + px(x) + " " + px(y - h) +
         " L " + px(x + h) + " " + px(y) + " L " + px(x) + " " + px(y + h) + " L " + px(x - h) +
         " " + px(y) + " Z\" fill=\"#333333\"/>\n";
}

void require_drawable(const BoxPlot& box, std::size_t index) {
  if (box.n == 0) return;
  const double stats[] = {box.mean, box.min, box.q1,          box.median,
                          box.q3,   box.max, box.whisker_low, box.whisker_high};
  const bool finite =
      std::all_of(std::begin(stats), std::end(stats), [](double v) { return std::isfinite(v); }) &&
      std::all_of(box.outliers.begin(), box.outliers.end(),
                  [](double v) { return std::isfinite(v); });
  if (!finite) {
    const std::string field = "series[" + std::to_string(index) + "].box";
    throw InvalidParameter(field, field + " has n = " + std::to_string(box.n) +
                                      " and a non-finite statistic: must be finite when n > 0");
  }
}

// One series: whiskers with caps, q1..q3 box, median line, outliers, mean; or "no detections".
void draw_series(std::string& svg, const BoxPlotSeries& s, double cx, double half_width,
                 double plot_top, double plot_bottom, bool show_mean, auto&& to_y) {
  svg += "<g class=\"series\">\n<title>" + escape_xml(s.label) + "</title>\n";
  const BoxPlot& b = s.box;
  if (b.n == 0) {
    text(svg, cx, 0.5 * (plot_top + plot_bottom), "middle",
         "class=\"no-detections\" font-style=\"italic\" fill=\"#888888\"", "no detections");
  } else {
    constexpr std::string_view whisker =
        "class=\"whisker\" stroke=\"#1f4e79\" stroke-width=\"1.5\"";
    const double cap = 0.5 * half_width;
    line(svg, cx, to_y(b.q3), cx, to_y(b.whisker_high), whisker);
    line(svg, cx, to_y(b.q1), cx, to_y(b.whisker_low), whisker);
    line(svg, cx - cap, to_y(b.whisker_high), cx + cap, to_y(b.whisker_high), whisker);
    line(svg, cx - cap, to_y(b.whisker_low), cx + cap, to_y(b.whisker_low), whisker);
    svg += "<rect class=\"box\" x=\"" + px(cx - half_width) + "\" y=\"" + px(to_y(b.q3)) +
           "\" width=\"" + px(2.0 * half_width) + "\" height=\"" + px(to_y(b.q1) - to_y(b.q3)) +
           "\" fill=\"#cfe2f3\" stroke=\"#1f4e79\" stroke-width=\"1.5\"/>\n";
    line(svg, cx - half_width, to_y(b.median), cx + half_width, to_y(b.median),
         "class=\"median\" stroke=\"#1f4e79\" stroke-width=\"3\"");
    for (const double v : b.outliers) {
      svg += "<circle class=\"outlier\" cx=\"" + px(cx) + "\" cy=\"" + px(to_y(v)) + "\" r=\"" +
             px(outlier_radius) + "\" fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.2\"/>\n";
    }
    if (show_mean) diamond(svg, cx, to_y(b.mean), "mean");
  }
  text(svg, cx, plot_bottom + 20.0, "middle", "class=\"category\" font-size=\"13\"", s.label);
  text(svg, cx, plot_bottom + 36.0, "middle", "class=\"count\" font-size=\"11\" fill=\"#555555\"",
       "n = " + std::to_string(b.n));
  svg += "</g>\n";
}

}  // namespace

void SvgPlotOptions::validate() const {
  if (!(std::isfinite(width_px) && width_px >= 200.0)) {
    throw_invalid("svg.width_px", width_px, "finite and >= 200");
  }
  if (!(std::isfinite(height_px) && height_px >= 200.0)) {
    throw_invalid("svg.height_px", height_px, "finite and >= 200");
  }
}

AxisTicks nice_axis_ticks(double low, double high, int max_intervals) {
  require_finite("low", low);
  require_finite("high", high);
  if (high < low) throw_invalid("high", high, "finite and >= low = " + format_number(low));
  if (max_intervals < 2) throw_invalid("max_intervals", max_intervals, ">= 2");
  if (high == low) {
    low -= 1.0;
    high += 1.0;
  }
  // Candidates 1, 2, 5 x 10^e upwards from the largest power of ten below the raw step;
  // at most two intervals once the step exceeds the span, so the loop ends.
  int exponent = static_cast<int>(std::floor(std::log10((high - low) / max_intervals)));
  for (;; ++exponent) {
    for (const int factor : {1, 2, 5}) {
      const double step = factor * std::pow(10.0, exponent);
      const double k_first = std::floor(low / step);
      const double k_last = std::ceil(high / step);
      if (k_last - k_first <= max_intervals) {
        return {k_first * step, k_last * step, step, std::max(0, -exponent)};
      }
    }
  }
}

std::string box_plot_svg(std::span<const BoxPlotSeries> series, const SvgPlotOptions& options) {
  options.validate();
  if (series.empty()) {
    throw InvalidParameter("series", "series is empty: must contain at least one series");
  }
  for (std::size_t i = 0; i < series.size(); ++i) require_drawable(series[i].box, i);

  // Value range over the non-empty series; min and max bound whiskers, outliers and mean.
  double low = 0.0;
  double high = 1.0;
  bool any_data = false;
  for (const BoxPlotSeries& s : series) {
    if (s.box.n == 0) continue;
    low = any_data ? std::min(low, s.box.min) : s.box.min;
    high = any_data ? std::max(high, s.box.max) : s.box.max;
    any_data = true;
  }
  const AxisTicks ticks = nice_axis_ticks(low, high);

  const double width = options.width_px;
  const double height = options.height_px;
  const double plot_left = margin_left;
  const double plot_right = width - margin_right;
  const double plot_top = margin_top;
  const double plot_bottom = height - margin_bottom;
  const auto to_y = [&](double v) {
    return plot_bottom - (v - ticks.first) / (ticks.last - ticks.first) * (plot_bottom - plot_top);
  };

  std::string svg;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(width) +
         "\" height=\"" + px(height) + "\" viewBox=\"0 0 " + px(width) + " " + px(height) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + px(width) + "\" height=\"" + px(height) +
         "\" fill=\"#ffffff\"/>\n";
  text(svg, 0.5 * width, 26.0, "middle", "class=\"title\" font-size=\"16\" font-weight=\"bold\"",
       options.title);
  if (options.show_mean && any_data) {
    diamond(svg, plot_right - 48.0, 46.0, "legend-mean");
    text(svg, plot_right - 38.0, 50.0, "start", "class=\"legend\"", "mean");
  }

  // Gridlines and tick labels at the 1-2-5 ticks.
  const auto tick_count = std::lround((ticks.last - ticks.first) / ticks.step);
  for (long i = 0; i <= tick_count; ++i) {
    const double value = ticks.first + static_cast<double>(i) * ticks.step;
    const double y = to_y(value);
    line(svg, plot_left, y, plot_right, y, "class=\"grid\" stroke=\"#dddddd\" stroke-width=\"1\"");
    line(svg, plot_left - 5.0, y, plot_left, y, "stroke=\"#333333\" stroke-width=\"1\"");
    text(svg, plot_left - 8.0, y + 4.0, "end", "class=\"tick\"",
         format_fixed(value, ticks.decimals));
  }
  svg += "<rect class=\"frame\" x=\"" + px(plot_left) + "\" y=\"" + px(plot_top) + "\" width=\"" +
         px(plot_right - plot_left) + "\" height=\"" + px(plot_bottom - plot_top) +
         "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"/>\n";

  // One category band per series.
  const double band = (plot_right - plot_left) / static_cast<double>(series.size());
  const double half_width = std::min(0.25 * band, max_box_half_width);
  for (std::size_t i = 0; i < series.size(); ++i) {
    const double cx = plot_left + (static_cast<double>(i) + 0.5) * band;
    draw_series(svg, series[i], cx, half_width, plot_top, plot_bottom, options.show_mean, to_y);
  }

  // Axis labels.
  text(svg, 0.5 * (plot_left + plot_right), height - 16.0, "middle",
       "class=\"x-label\" font-size=\"14\"", options.x_label);
  const double y_mid = 0.5 * (plot_top + plot_bottom);
  text(svg, 20.0, y_mid, "middle",
       "class=\"y-label\" font-size=\"14\" transform=\"rotate(-90 20.00 " + px(y_mid) + ")\"",
       options.y_label);
  svg += "</svg>\n";
  return svg;
}

}  // namespace fogradar::stats
