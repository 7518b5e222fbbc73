#include "fogradar/stats/heat_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"
#include "svg_text.hpp"

namespace fogradar::stats {
namespace {

using detail::escape_xml;

constexpr double min_margin_left = 150.0;
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
  if (map.value_range) {
    const auto [range_low, range_high] = *map.value_range;
    if (!(std::isfinite(range_low) && std::isfinite(range_high) && range_low < range_high)) {
      throw_invalid("value_range", range_low,
                    "finite and below its high end (" + format_number(range_high) + ")");
    }
  }
  double low = 0.0, high = 0.0;
  bool any = false, any_missing = false;
  for (std::size_t r = 0; r < rows; ++r) {
    if (map.values[r].size() != columns) {
      throw_invalid("values", static_cast<double>(map.values[r].size()),
                    std::to_string(columns) + " columns in every row");
    }
    for (std::size_t c = 0; c < columns; ++c) {
      const std::optional<double>& v = map.values[r][c];
      if (!v) {
        any_missing = true;
        continue;
      }
      const std::string field = "values[" + std::to_string(r) + "][" + std::to_string(c) + "]";
      require_finite(field, *v);
      if (map.value_range && (*v < map.value_range->first || *v > map.value_range->second)) {
        throw_invalid(field, *v,
                      "inside value_range [" + format_number(map.value_range->first) + ", " +
                          format_number(map.value_range->second) + "]");
      }
      low = any ? std::min(low, *v) : *v;
      high = any ? std::max(high, *v) : *v;
      any = true;
    }
  }
  if (map.value_range) std::tie(low, high) = *map.value_range;
  // Room left of the cells for the longest row label, and for the y label written above them
  // (level: a few rows leave no height for it turned).
  std::size_t longest = 0;
  for (const std::string& label : map.row_labels) longest = std::max(longest, label.size());
  const double margin_left = std::max({min_margin_left, 24.0 + 7.5 * static_cast<double>(longest),
                                       24.0 + 8.5 * static_cast<double>(map.y_label.size())});
  const double cell_width = std::max(min_cell_width, 640.0 / static_cast<double>(columns));
  const double width = margin_left + cell_width * static_cast<double>(columns) + margin_right;
  const double plot_bottom = plot_top + cell_height * static_cast<double>(rows);
  std::vector<std::pair<double, std::string>> swatches;  // value, label; from the low end
  const bool scale_shown = any || map.value_range.has_value();
  if (scale_shown && map.integer_values) {
    const double first = std::ceil(low), last = std::floor(high);
    const double step = std::max(1.0, std::ceil((last - first) / 10.0));
    for (double v = first; v <= last; v += step) swatches.emplace_back(v, format_fixed(v, 0));
  } else if (scale_shown) {
    for (int i = 0; i < 5; ++i) {
      const double v = low + static_cast<double>(i) / 4.0 * (high - low);
      swatches.emplace_back(v, format_fixed(v, map.decimals + 1));
    }
  }
  const double key_rows = static_cast<double>(swatches.size() + (any_missing ? 1 : 0));
  const double height = std::max(
      plot_bottom + below_plot + caption_line * static_cast<double>(map.caption.size()) + 8.0,
      plot_top + 22.0 * key_rows + 8.0);
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
  text(svg, margin_left - 8.0, plot_top - 8.0, "end", "class=\"y-label\" font-size=\"14\"",
       map.y_label);
  // The colour key, darkest on top: five steps from the scale's low end to its high end, or a
  // swatch per whole number; then the missing cells' grey.
  const double key_x = plot_right + 24.0;
  text(svg, key_x, plot_top - 8.0, "start", "class=\"key-title\"", map.value_label);
  double key_y = plot_top;
  for (std::size_t i = swatches.size(); i-- > 0;) {
    rect(svg, key_x, key_y, 18.0, 18.0,
         "class=\"key\" fill=\"" + colour(scale(swatches[i].first)) + "\"");
    text(svg, key_x + 26.0, key_y + 13.0, "start", "class=\"key-text\"", swatches[i].second);
    key_y += 22.0;
  }
  if (any_missing) {
    rect(svg, key_x, key_y, 18.0, 18.0, "class=\"key\" fill=\"#d9d9d9\"");
    text(svg, key_x + 26.0, key_y + 13.0, "start", "class=\"key-text\"", map.missing_text);
    key_y += 22.0;
  }
  for (std::size_t i = 0; i < map.caption.size(); ++i) {
    text(svg, margin_left, plot_bottom + below_plot + caption_line * static_cast<double>(i) + 4.0,
         "start", "class=\"caption\" fill=\"#444444\"", map.caption[i]);
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace fogradar::stats
