#include "fogradar/stats/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"
#include "svg_text.hpp"

namespace fogradar::stats {

namespace detail {

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

}  // namespace detail

namespace {

using detail::escape_xml;

// Layout in px. Left margin: tick labels and the y label; right: the legend column. Below the
// plot, top to bottom: the rate strip (with its title above it), category labels, the x label and
// the caption lines.
constexpr double margin_left = 84.0;
constexpr double legend_column = 240.0;
constexpr double title_baseline = 28.0;
constexpr double plot_top = 52.0;
constexpr double min_plot_height = 100.0;
constexpr double strip_gap = 28.0;          // plot bottom to strip top, holds the strip's title
constexpr double strip_height = 56.0;       // 0..100 %
constexpr double category_baseline = 18.0;  // below the lowest panel
constexpr double x_label_baseline = 42.0;   // below the lowest panel
constexpr double caption_gap = 8.0;
constexpr double caption_line = 16.0;
constexpr double bottom_padding = 12.0;
constexpr double max_box_half_width = 40.0;
constexpr double outlier_radius = 3.0;
constexpr double mean_marker_half = 4.5;
constexpr double legend_row = 22.0;
// Label width estimate: 0.7 em per character is wider than any digit or Latin letter but 'm'/'W'
// of common sans-serif faces (DejaVu Sans digits 0.636 em), so estimated labels never touch.
constexpr double category_font_px = 12.0;
constexpr double label_em_per_char = 0.7;
constexpr double label_gap_px = 6.0;
// Wide enough bands get a written value: the empty label in the plot, the rate above its bar.
constexpr double band_for_empty_text = 110.0;
constexpr double band_for_rate_text = 40.0;

constexpr std::string_view box_style = "fill=\"#cfe2f3\" stroke=\"#1f4e79\" stroke-width=\"1.5\"";
constexpr std::string_view whisker_style = "stroke=\"#1f4e79\" stroke-width=\"1.5\"";
constexpr std::string_view median_style = "stroke=\"#1f4e79\" stroke-width=\"3\"";
constexpr std::string_view outlier_style = "fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.2\"";
constexpr std::string_view empty_fill = "fill=\"#ececec\"";
constexpr std::string_view cross_style = "stroke=\"#7f7f7f\" stroke-width=\"1.5\"";
constexpr std::string_view mark_style =
    "stroke=\"#d35400\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"";
constexpr std::string_view rate_fill = "fill=\"#8fb3d9\"";
constexpr std::string_view band_style = "fill=\"#f5cba7\" fill-opacity=\"0.7\"";
constexpr std::string_view inner_band_style = "fill=\"#e59866\" fill-opacity=\"0.7\"";
constexpr std::string_view value_style = "stroke=\"#1f4e79\" stroke-width=\"4\"";
constexpr std::string_view reference_style = "stroke=\"#c0392b\" stroke-width=\"2.5\"";

// Coordinates with two decimals: 0.01 px is far below any rendering resolution.
std::string px(double v) { return format_fixed(v, 2); }

// Characters of UTF-8 text: every byte but continuation bytes (10xxxxxx).
std::size_t utf8_length(std::string_view text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

void line(std::string& svg, double x1, double y1, double x2, double y2,
          std::string_view attributes) {
  svg += "<line x1=\"" + px(x1) + "\" y1=\"" + px(y1) + "\" x2=\"" + px(x2) + "\" y2=\"" + px(y2) +
         "\" " + std::string(attributes) + "/>\n";
}

void rect(std::string& svg, double x, double y, double w, double h, std::string_view attributes,
          std::string_view tooltip = {}) {
  svg += "<rect x=\"" + px(x) + "\" y=\"" + px(y) + "\" width=\"" + px(w) + "\" height=\"" + px(h) +
         "\" " + std::string(attributes);
  svg += tooltip.empty() ? "/>\n" : "><title>" + escape_xml(tooltip) + "</title></rect>\n";
}

void text(std::string& svg, double x, double y, std::string_view anchor,
          std::string_view attributes, std::string_view content) {
  svg += "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" text-anchor=\"" + std::string(anchor) +
         "\" " + std::string(attributes) + ">" + escape_xml(content) + "</text>\n";
}

void diamond(std::string& svg, double x, double y, std::string_view class_name,
             double h = mean_marker_half) {
  svg += "<path class=\"" + std::string(class_name) + "\" d=\"M " + px(x) + " " + px(y - h) +
         " L " + px(x + h) + " " + px(y) + " L " + px(x) + " " + px(y + h) + " L " + px(x - h) +
         " " + px(y) + " Z\" fill=\"#333333\"/>\n";
}

void cross(std::string& svg, double x, double y, double half, std::string_view class_name) {
  const std::string attributes =
      "class=\"" + std::string(class_name) + "\" " + std::string(cross_style);
  line(svg, x - half, y - half, x + half, y + half, attributes);
  line(svg, x - half, y + half, x + half, y - half, attributes);
}

void circle(std::string& svg, double x, double y, std::string_view class_name,
            double radius = outlier_radius) {
  svg += "<circle class=\"" + std::string(class_name) + "\" cx=\"" + px(x) + "\" cy=\"" + px(y) +
         "\" r=\"" + px(radius) + "\" " + std::string(outlier_style) + "/>\n";
}

// A downward triangle above the plot frame at the marked category.
void mark_triangle(std::string& svg, double x, double bottom, std::string_view class_name) {
  svg += "<path class=\"" + std::string(class_name) + "\" d=\"M " + px(x - 5.0) + " " +
         px(bottom - 9.0) + " L " + px(x + 5.0) + " " + px(bottom - 9.0) + " L " + px(x) + " " +
         px(bottom) + " Z\" fill=\"#d35400\"/>\n";
}

// A measured value: an x-shaped cross.
void reference_cross(std::string& svg, double x, double y, std::string_view class_name) {
  const std::string style =
      "class=\"" + std::string(class_name) + "\" " + std::string(reference_style);
  line(svg, x - 6.0, y - 6.0, x + 6.0, y + 6.0, style);
  line(svg, x - 6.0, y + 6.0, x + 6.0, y - 6.0, style);
}

std::string with_class(std::string_view class_name, std::string_view style) {
  return "class=\"" + std::string(class_name) + "\" " + std::string(style);
}

bool has_strip(const SvgPlotOptions& options) { return !options.rate_label.empty(); }

// Height of everything below the plot area.
double below_plot_px(const SvgPlotOptions& options) {
  const double caption =
      options.caption.empty()
          ? 0.0
          : caption_gap + caption_line * static_cast<double>(options.caption.size());
  return (has_strip(options) ? strip_gap + strip_height : 0.0) + x_label_baseline + caption +
         bottom_padding;
}

bool has_band(double low, double high) { return !std::isnan(low) || !std::isnan(high); }

void require_band(double low, double high, const std::string& field) {
  if (!has_band(low, high)) return;
  if (!(std::isfinite(low) && std::isfinite(high) && low <= high)) {
    throw_invalid(field, low, "finite and <= its high end (" + format_number(high) + ")");
  }
}

void require_drawable(const BoxPlotSeries& s, std::size_t index, bool strip) {
  const BoxPlot& box = s.box;
  const std::string name = "series[" + std::to_string(index) + "]";
  if (strip && !std::isnan(s.rate) && !(s.rate >= 0.0 && s.rate <= 1.0)) {
    throw_invalid(name + ".rate", s.rate, "in [0, 1], or NaN for no bar");
  }
  require_band(s.band_low, s.band_high, name + ".band_low");
  require_band(s.inner_band_low, s.inner_band_high, name + ".inner_band_low");
  for (const double v : s.references) require_finite(name + ".references", v);
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

struct Layout {
  double width;
  double height;
  double plot_left;
  double plot_right;
  double plot_bottom;
  double strip_top;
  double strip_bottom;
  double axis_bottom;  // bottom of the lowest panel, where the category labels hang
  double band;
  double half_width;
  double center(std::size_t i) const { return plot_left + (static_cast<double>(i) + 0.5) * band; }
};

// Box, whiskers with caps, median, outliers, mean; or the empty-category cross; and the rate bar.
void draw_series(std::string& svg, const BoxPlotSeries& s, double cx, const Layout& at,
                 const SvgPlotOptions& options, auto&& to_y) {
  svg += "<g class=\"series\">\n<title>" + escape_xml(s.note.empty() ? s.label : s.note) +
         "</title>\n";
  const BoxPlot& b = s.box;
  const double half_width = at.half_width;
  // A band is at least 2 px tall, so that one of no width (every setup alike) stays visible.
  const auto band = [&](double low, double high, std::string_view cls, std::string_view style) {
    const double top = std::min(to_y(high), 0.5 * (to_y(low) + to_y(high)) - 1.0);
    const double bottom = std::max(to_y(low), 0.5 * (to_y(low) + to_y(high)) + 1.0);
    rect(svg, cx - 0.42 * at.band, top, 0.84 * at.band, bottom - top, with_class(cls, style));
  };
  if (has_band(s.band_low, s.band_high)) band(s.band_low, s.band_high, "band", band_style);
  if (has_band(s.inner_band_low, s.inner_band_high))
    band(s.inner_band_low, s.inner_band_high, "inner-band", inner_band_style);
  if (b.n == 0) {
    cross(svg, cx, at.plot_bottom - 14.0, std::min(5.0, 0.4 * at.band), "no-values");
    if (at.band >= band_for_empty_text) {
      text(svg, cx, 0.5 * (plot_top + at.plot_bottom), "middle",
           "class=\"no-values-text\" font-style=\"italic\" fill=\"#666666\"", options.empty_label);
    }
  } else if (!options.value_label.empty()) {
    line(svg, cx - half_width, to_y(b.median), cx + half_width, to_y(b.median),
         with_class("value", value_style));
  } else {
    const std::string whisker = with_class("whisker", whisker_style);
    const double cap = 0.5 * half_width;
    line(svg, cx, to_y(b.q3), cx, to_y(b.whisker_high), whisker);
    line(svg, cx, to_y(b.q1), cx, to_y(b.whisker_low), whisker);
    line(svg, cx - cap, to_y(b.whisker_high), cx + cap, to_y(b.whisker_high), whisker);
    line(svg, cx - cap, to_y(b.whisker_low), cx + cap, to_y(b.whisker_low), whisker);
    rect(svg, cx - half_width, to_y(b.q3), 2.0 * half_width, to_y(b.q1) - to_y(b.q3),
         with_class("box", box_style));
    line(svg, cx - half_width, to_y(b.median), cx + half_width, to_y(b.median),
         with_class("median", median_style));
    // Markers shrink with narrow boxes (many categories) so that they stay inside their band.
    const double radius = std::clamp(0.6 * half_width, 1.5, outlier_radius);
    for (const double v : b.outliers) circle(svg, cx, to_y(v), "outlier", radius);
    if (options.show_mean) {
      diamond(svg, cx, to_y(b.mean), "mean", std::clamp(0.8 * half_width, 2.5, mean_marker_half));
    }
  }
  for (const double v : s.references) reference_cross(svg, cx, to_y(v), "reference");
  if (has_strip(options) && !std::isnan(s.rate)) {
    const double bar = s.rate * strip_height;
    rect(svg, cx - half_width, at.strip_bottom - bar, 2.0 * half_width, bar,
         with_class("rate", rate_fill));
    if (at.band >= band_for_rate_text) {
      // Inside a tall bar, above a short one.
      const bool inside = bar >= 18.0;
      text(svg, cx, inside ? at.strip_bottom - bar + 13.0 : at.strip_bottom - bar - 3.0, "middle",
           "class=\"rate-value\" font-size=\"11\" fill=\"#1a1a1a\"",
           format_fixed(100.0 * s.rate, 0) + " %");
    }
  }
  svg += "</g>\n";
}

// One row per symbol drawn: its sample on the left, its meaning on the right.
void draw_legend(std::string& svg, const Layout& at, const SvgPlotOptions& options, bool any_data,
                 bool any_outlier, bool any_empty, bool any_band, bool any_inner_band,
                 bool any_reference) {
  const double left = at.plot_right + 16.0;
  const double right = at.width - 12.0;
  const double sx = left + 18.0;  // symbol centre
  const double tx = left + 36.0;  // text start
  double y = plot_top + 18.0;     // row centre
  svg += "<g class=\"legend\">\n";
  const bool values_only = !options.value_label.empty();
  const std::size_t data_rows =
      values_only ? 1u : 3u + (any_outlier ? 1u : 0u) + (options.show_mean ? 1u : 0u);
  const std::size_t rows = (any_data ? data_rows : 0u) + (any_empty ? 1u : 0u) +
                           (options.marked_category ? 1u : 0u) + (has_strip(options) ? 1u : 0u) +
                           (any_band ? 1u : 0u) + (any_inner_band ? 1u : 0u) +
                           (any_reference ? 1u : 0u);
  rect(svg, left, plot_top, right - left, 8.0 + legend_row * static_cast<double>(rows),
       "class=\"legend-frame\" fill=\"#ffffff\" stroke=\"#bbbbbb\" stroke-width=\"1\"");
  const auto label = [&](std::string_view content) {
    text(svg, tx, y + 4.0, "start", "class=\"legend-text\"", content);
    y += legend_row;
  };
  if (any_data && values_only) {
    line(svg, sx - 8.0, y, sx + 8.0, y, with_class("legend-value", value_style));
    label(options.value_label);
  } else if (any_data) {
    rect(svg, sx - 8.0, y - 6.0, 16.0, 12.0, with_class("legend-box", box_style));
    label("box: quartiles Q1 to Q3");
    line(svg, sx - 8.0, y, sx + 8.0, y, with_class("legend-median", median_style));
    label("median");
    const std::string whisker = with_class("legend-whisker", whisker_style);
    line(svg, sx, y - 8.0, sx, y + 8.0, whisker);
    line(svg, sx - 4.0, y - 8.0, sx + 4.0, y - 8.0, whisker);
    line(svg, sx - 4.0, y + 8.0, sx + 4.0, y + 8.0, whisker);
    label("whiskers: Tukey, 1.5 IQR");
    if (any_outlier) {
      circle(svg, sx, y, "legend-outlier");
      label("outlier beyond a whisker");
    }
    if (options.show_mean) {
      diamond(svg, sx, y, "legend-mean");
      label("mean");
    }
  }
  if (any_empty) {
    rect(svg, sx - 8.0, y - 8.0, 16.0, 16.0, "class=\"legend-empty\" " + std::string(empty_fill));
    cross(svg, sx, y, 5.0, "legend-no-values");
    label(options.empty_label);
  }
  if (options.marked_category) {
    line(svg, sx, y - 9.0, sx, y + 9.0, with_class("legend-mark", mark_style));
    label(options.mark_label);
  }
  if (has_strip(options)) {
    rect(svg, sx - 5.0, y - 4.0, 10.0, 12.0, with_class("legend-rate", rate_fill));
    label(options.rate_label);
  }
  if (any_band) {
    rect(svg, sx - 8.0, y - 6.0, 16.0, 12.0, with_class("legend-band", band_style));
    label(options.band_label);
  }
  if (any_inner_band) {
    rect(svg, sx - 8.0, y - 6.0, 16.0, 12.0, with_class("legend-inner-band", inner_band_style));
    label(options.inner_band_label);
  }
  if (any_reference) {
    reference_cross(svg, sx, y, "legend-reference");
    label(options.reference_label);
  }
  svg += "</g>\n";
}

}  // namespace

void SvgPlotOptions::validate() const {
  if (!(std::isfinite(axis_padding) && axis_padding >= 0.0 && axis_padding <= 1.0)) {
    throw_invalid("svg.axis_padding", axis_padding, "in [0, 1]");
  }
  if (!(std::isfinite(width_px) && width_px >= 480.0)) {
    throw_invalid("svg.width_px", width_px, "finite and >= 480");
  }
  const double min_height = plot_top + min_plot_height + below_plot_px(*this);
  if (!(std::isfinite(height_px) && height_px >= min_height)) {
    throw_invalid("svg.height_px", height_px,
                  "finite and >= " + format_number(min_height) +
                      " (a 100 px plot area with this caption and strip)");
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

namespace {

// Fixed-point labels of finer steps need more than 6 decimals, of coarser ones 10 or more digits:
// wider than the tick-label margin, and past 17 decimals not printable at all.
constexpr double min_fixed_step = 1e-6;
constexpr double max_fixed_step = 1e9;

// floor(log10(v)) for v > 0; the nudge keeps an exact power of ten that log10 rounds down
// (1e-20 -> -20.000000000000004) in its own decade.
int decade(double v) { return static_cast<int>(std::floor(std::log10(v) + 1e-9)); }

}  // namespace

std::string axis_tick_label(double value, const AxisTicks& ticks) {
  if (ticks.step >= min_fixed_step && ticks.step <= max_fixed_step) {
    return format_fixed(value, ticks.decimals);
  }
  // first + i step leaves a rounding residue (1e-36) where the tick is zero.
  if (std::abs(value) < 0.5 * ticks.step) return "0";
  const int digits = std::clamp(decade(std::abs(value)) - decade(ticks.step) + 1, 1, 17);
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::scientific, digits - 1);
  FOGRADAR_CHECK(result.ec == std::errc());
  return std::string(buffer.data(), result.ptr);
}

std::size_t category_label_stride(std::span<const BoxPlotSeries> series, double band_px) {
  if (!(std::isfinite(band_px) && band_px > 0.0))
    throw_invalid("band_px", band_px, "finite and > 0");
  std::size_t widest = 0;
  for (const BoxPlotSeries& s : series) widest = std::max(widest, utf8_length(s.label));
  const double needed =
      static_cast<double>(widest) * label_em_per_char * category_font_px + label_gap_px;
  // 1, 2, 5, 10, 20, 50, ...; a stride beyond the series count writes only the first label.
  for (std::size_t decade = 1;; decade *= 10) {
    for (const std::size_t factor : {1u, 2u, 5u}) {
      const std::size_t stride = factor * decade;
      if (static_cast<double>(stride) * band_px >= needed || stride >= series.size()) return stride;
    }
  }
}

std::string box_plot_svg(std::span<const BoxPlotSeries> series, const SvgPlotOptions& options) {
  options.validate();
  if (series.empty()) {
    throw InvalidParameter("series", "series is empty: must contain at least one series");
  }
  for (std::size_t i = 0; i < series.size(); ++i)
    require_drawable(series[i], i, has_strip(options));
  if (options.marked_category && *options.marked_category >= series.size()) {
    throw_invalid("marked_category", std::to_string(*options.marked_category),
                  "an index of the series, < " + std::to_string(series.size()));
  }

  // Value range over the non-empty series; min and max bound whiskers, outliers and mean.
  double low = 0.0;
  double high = 1.0;
  bool any_data = false;
  bool any_empty = false;
  bool any_outlier = false;
  bool any_value = false, any_band = false, any_inner_band = false, any_reference = false;
  const auto cover = [&](double v) {
    low = any_value ? std::min(low, v) : v;
    high = any_value ? std::max(high, v) : v;
    any_value = true;
  };
  for (const BoxPlotSeries& s : series) {
    if (has_band(s.band_low, s.band_high)) {
      cover(s.band_low);
      cover(s.band_high);
      any_band = true;
    }
    if (has_band(s.inner_band_low, s.inner_band_high)) {
      cover(s.inner_band_low);
      cover(s.inner_band_high);
      any_inner_band = true;
    }
    for (const double v : s.references) cover(v);
    any_reference = any_reference || !s.references.empty();
    if (s.box.n == 0) {
      any_empty = true;
      continue;
    }
    cover(s.box.min);
    cover(s.box.max);
    any_data = true;
    any_outlier = any_outlier || !s.box.outliers.empty();
  }
  const double pad = options.axis_padding * (high - low);
  const AxisTicks ticks = nice_axis_ticks(low - pad, high + pad);

  Layout at{};
  at.width = options.width_px;
  at.height = options.height_px;
  at.plot_left = margin_left;
  at.plot_right = at.width - legend_column;
  at.plot_bottom = at.height - below_plot_px(options);
  at.strip_top = at.plot_bottom + strip_gap;
  at.strip_bottom = at.strip_top + strip_height;
  at.axis_bottom = has_strip(options) ? at.strip_bottom : at.plot_bottom;
  at.band = (at.plot_right - at.plot_left) / static_cast<double>(series.size());
  at.half_width = std::min(0.3 * at.band, max_box_half_width);
  const auto to_y = [&](double v) {
    return at.plot_bottom -
           (v - ticks.first) / (ticks.last - ticks.first) * (at.plot_bottom - plot_top);
  };

  std::string svg;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(at.width) +
         "\" height=\"" + px(at.height) + "\" viewBox=\"0 0 " + px(at.width) + " " + px(at.height) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  rect(svg, 0.0, 0.0, at.width, at.height, "fill=\"#ffffff\"");
  text(svg, 0.5 * at.width, title_baseline, "middle",
       "class=\"title\" font-size=\"16\" font-weight=\"bold\"", options.title);

  // Empty categories shaded over the plot's height, under the gridlines.
  for (std::size_t i = 0; i < series.size(); ++i) {
    if (series[i].box.n != 0) continue;
    rect(svg, at.center(i) - 0.5 * at.band, plot_top, at.band, at.plot_bottom - plot_top,
         "class=\"no-values-band\" " + std::string(empty_fill),
         series[i].note.empty() ? series[i].label : series[i].note);
  }

  // Gridlines and tick labels at the 1-2-5 ticks.
  const auto tick_count = std::lround((ticks.last - ticks.first) / ticks.step);
  for (long i = 0; i <= tick_count; ++i) {
    const double value = ticks.first + static_cast<double>(i) * ticks.step;
    const double y = to_y(value);
    line(svg, at.plot_left, y, at.plot_right, y,
         "class=\"grid\" stroke=\"#dddddd\" stroke-width=\"1\"");
    line(svg, at.plot_left - 5.0, y, at.plot_left, y, "stroke=\"#333333\" stroke-width=\"1\"");
    text(svg, at.plot_left - 8.0, y + 4.0, "end", "class=\"tick\"", axis_tick_label(value, ticks));
  }
  rect(svg, at.plot_left, plot_top, at.plot_right - at.plot_left, at.plot_bottom - plot_top,
       "class=\"frame\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"");

  if (has_strip(options)) {
    text(svg, at.plot_left, at.strip_top - 8.0, "start", "class=\"rate-title\"",
         options.rate_label);
    for (const int percent : {0, 50, 100}) {
      const double y = at.strip_bottom - 0.01 * percent * strip_height;
      line(svg, at.plot_left, y, at.plot_right, y,
           "class=\"grid\" stroke=\"#dddddd\" stroke-width=\"1\"");
      line(svg, at.plot_left - 5.0, y, at.plot_left, y, "stroke=\"#333333\" stroke-width=\"1\"");
      text(svg, at.plot_left - 8.0, y + 4.0, "end", "class=\"rate-tick\"",
           std::to_string(percent) + " %");
    }
    rect(svg, at.plot_left, at.strip_top, at.plot_right - at.plot_left, strip_height,
         "class=\"frame\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"");
  }

  if (options.marked_category) {
    const double x = at.center(*options.marked_category);
    line(svg, x, plot_top, x, at.plot_bottom, with_class("mark", mark_style));
    if (has_strip(options))
      line(svg, x, at.strip_top, x, at.strip_bottom, with_class("mark", mark_style));
    mark_triangle(svg, x, plot_top - 2.0, "mark-head");
  }

  for (std::size_t i = 0; i < series.size(); ++i)
    draw_series(svg, series[i], at.center(i), at, options, to_y);

  // Category ticks on the lowest panel; labels on every stride-th, which gets a longer tick.
  const std::size_t stride = category_label_stride(series, at.band);
  for (std::size_t i = 0; i < series.size(); ++i) {
    const bool labelled = i % stride == 0;
    const double x = at.center(i);
    line(svg, x, at.axis_bottom, x, at.axis_bottom + (labelled ? 6.0 : 3.0),
         "class=\"category-tick\" stroke=\"#333333\" stroke-width=\"1\"");
    if (labelled) {
      text(svg, x, at.axis_bottom + category_baseline, "middle", "class=\"category\"",
           series[i].label);
    }
  }

  text(svg, 0.5 * (at.plot_left + at.plot_right), at.axis_bottom + x_label_baseline, "middle",
       "class=\"x-label\" font-size=\"14\"", options.x_label);
  const double y_mid = 0.5 * (plot_top + at.plot_bottom);
  text(svg, 22.0, y_mid, "middle",
       "class=\"y-label\" font-size=\"14\" transform=\"rotate(-90 22.00 " + px(y_mid) + ")\"",
       options.y_label);
  for (std::size_t i = 0; i < options.caption.size(); ++i) {
    text(
        svg, 16.0,
        at.axis_bottom + x_label_baseline + caption_gap + caption_line * static_cast<double>(i + 1),
        "start", "class=\"caption\" fill=\"#333333\"", options.caption[i]);
  }
  draw_legend(svg, at, options, any_data, any_outlier, any_empty, any_band, any_inner_band,
              any_reference);
  svg += "</svg>\n";
  return svg;
}

}  // namespace fogradar::stats
