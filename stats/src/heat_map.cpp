#include "fogradar/stats/heat_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"
#include "svg_text.hpp"

namespace fogradar::stats {
namespace {

using detail::escape_xml;

constexpr double margin_left = 150.0;
constexpr double margin_right = 150.0;
constexpr double plot_top = 56.0;
constexpr double cell_height = 36.0;
constexpr double min_cell_width = 64.0;
constexpr double below_plot = 56.0;
constexpr double caption_line = 16.0;

std::string px(double v) { return format_fixed(v, 2); }

void text(std::string& svg, double x, double y, std::string_view anchor,
          std::string_view attributes, std::string_view content) {
  svg += "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" text-anchor=\"" + std::string(anchor) +
         "\" " + std::string(attributes) + ">" + escape_xml(content) + "</text>\n";
}

void rect(std::string& svg, double x, double y, double w, double h, std::string_view attributes) {
  svg += "<rect x=\"" + px(x) + "\" y=\"" + px(y) + "\" width=\"" + px(w) + "\" height=\"" + px(h) +
         "\" " + std::string(attributes) + "/>\n";
}

// Sequential blue scale, t in [0, 1] from light (#eff3ff) to dark (#08519c) (ColorBrewer Blues).
std::string colour(double t) {
  const double light[3] = {239.0, 243.0, 255.0}, dark[3] = {8.0, 81.0, 156.0};
  char out[8];
  int rgb[3];
  for (int i = 0; i < 3; ++i) {
    rgb[i] = static_cast<int>(std::lround(light[i] + t * (dark[i] - light[i])));
  }
  std::snprintf(out, sizeof out, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return out;
}

}  // namespace

std::string heat_map_svg(const HeatMap& map) {
  const std::size_t rows = map.row_labels.size(), columns = map.column_labels.size();
  if (rows == 0 || columns == 0 || map.values.size() != rows) {
    throw_invalid("values", static_cast<double>(map.values.size()),
                  "rows x columns of the labels (" + std::to_string(rows) + " x " +
                      std::to_string(columns) + ", at least one cell)");
  }
  double low = 0.0, high = 0.0;
  bool any = false;
  for (std::size_t r = 0; r < rows; ++r) {
    if (map.values[r].size() != columns) {
      throw_invalid("values", static_cast<double>(map.values[r].size()),
                    std::to_string(columns) + " columns in every row");
    }
    for (std::size_t c = 0; c < columns; ++c) {
      const std::optional<double>& v = map.values[r][c];
      if (!v) continue;
      require_finite("values[" + std::to_string(r) + "][" + std::to_string(c) + "]", *v);
      low = any ? std::min(low, *v) : *v;
      high = any ? std::max(high, *v) : *v;
      any = true;
    }
  }
  const double cell_width = std::max(min_cell_width, 640.0 / static_cast<double>(columns));
  const double width = margin_left + cell_width * static_cast<double>(columns) + margin_right;
  const double plot_bottom = plot_top + cell_height * static_cast<double>(rows);
  const double height =
      plot_bottom + below_plot + caption_line * static_cast<double>(map.caption.size()) + 8.0;
  const auto scale = [&](double v) { return high > low ? (v - low) / (high - low) : 0.5; };

  std::string svg;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(width) +
         "\" height=\"" + px(height) + "\" viewBox=\"0 0 " + px(width) + " " + px(height) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  rect(svg, 0.0, 0.0, width, height, "fill=\"#ffffff\"");
  text(svg, 0.5 * width, 28.0, "middle", "class=\"title\" font-size=\"16\" font-weight=\"bold\"",
       map.title);
  for (std::size_t r = 0; r < rows; ++r) {
    const double y = plot_bottom - cell_height * static_cast<double>(r + 1);
    text(svg, margin_left - 8.0, y + 0.5 * cell_height + 4.0, "end", "class=\"row\"",
         map.row_labels[r]);
    for (std::size_t c = 0; c < columns; ++c) {
      const double x = margin_left + cell_width * static_cast<double>(c);
      const std::optional<double>& v = map.values[r][c];
      const double t = v ? scale(*v) : 0.0;
      rect(svg, x, y, cell_width, cell_height,
           "class=\"cell\" fill=\"" + (v ? colour(t) : std::string("#d9d9d9")) +
               "\" stroke=\"#ffffff\" stroke-width=\"2\"");
      text(svg, x + 0.5 * cell_width, y + 0.5 * cell_height + 4.0, "middle",
           std::string("class=\"cell-text\" fill=\"") + (t > 0.55 ? "#ffffff" : "#1a1a1a") + "\"",
           v ? format_fixed(*v, map.decimals) : map.missing_text);
    }
  }
  for (std::size_t c = 0; c < columns; ++c) {
    text(svg, margin_left + cell_width * (static_cast<double>(c) + 0.5), plot_bottom + 18.0,
         "middle", "class=\"column\"", map.column_labels[c]);
  }
  const double plot_right = margin_left + cell_width * static_cast<double>(columns);
  text(svg, 0.5 * (margin_left + plot_right), plot_bottom + 40.0, "middle",
       "class=\"x-label\" font-size=\"14\"", map.x_label);
  const double mid_y = 0.5 * (plot_top + plot_bottom);
  svg += "<text x=\"22\" y=\"" + px(mid_y) +
         "\" text-anchor=\"middle\" transform=\"rotate(-90 22 " + px(mid_y) +
         ")\" class=\"y-label\" font-size=\"14\">" + escape_xml(map.y_label) + "</text>\n";
  // The colour key: five steps from the lowest value to the highest.
  const double key_x = plot_right + 24.0;
  text(svg, key_x, plot_top - 8.0, "start", "class=\"key-title\"", map.value_label);
  for (int i = 0; i < (any ? 5 : 0); ++i) {
    const double t = static_cast<double>(i) / 4.0;
    const double y = plot_top + 22.0 * (4 - i);
    rect(svg, key_x, y, 18.0, 18.0, "class=\"key\" fill=\"" + colour(t) + "\"");
    text(svg, key_x + 26.0, y + 13.0, "start", "class=\"key-text\"",
         format_fixed(low + t * (high - low), map.decimals + 1));
  }
  if (!any) {
    rect(svg, key_x, plot_top, 18.0, 18.0, "class=\"key\" fill=\"#d9d9d9\"");
    text(svg, key_x + 26.0, plot_top + 13.0, "start", "class=\"key-text\"", map.missing_text);
  }
  for (std::size_t i = 0; i < map.caption.size(); ++i) {
    text(svg, margin_left, plot_bottom + below_plot + caption_line * static_cast<double>(i) + 4.0,
         "start", "class=\"caption\" fill=\"#444444\"", map.caption[i]);
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace fogradar::stats
