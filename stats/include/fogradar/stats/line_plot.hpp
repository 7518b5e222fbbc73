// Line plots as standalone SVG 1.1 documents: several series of (x, y) points drawn as polylines in
// distinct colours over the same axes (1-2-5 ticks from nice_axis_ticks, gridlines), each with an
// optional vertical marker line (e.g. a histogram's mean) labelled with its value, a legend, a
// title and caption lines. Deterministic, locale-independent output; text XML-escaped.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace fogradar::stats {

struct LineSeries {
  std::string label;  // legend text
  std::vector<double> x;
  std::vector<double> y;           // same length as x
  std::optional<double> marker_x;  // a dashed vertical line in the series' colour
  std::string marker_label;        // written at the top of the marker line, e.g. "mean 46.1"
};

struct LinePlotOptions {
  std::string title;
  std::vector<std::string> caption;
  std::string x_label;
  std::string y_label;
  // The x axis spans the data exactly (e.g. grey levels 0-255), ticks at 1-2-5 steps inside it;
  // false: the axis is widened to the enclosing ticks.
  bool x_axis_exact = false;
  // x is a count (e.g. active fog layers): ticks only at whole numbers, never at 0.5 steps.
  bool x_integer_ticks = false;
  double width_px = 960;
  double height_px = 640;
  // Throws InvalidParameter naming "svg.width_px" (finite, >= 480) or "svg.height_px" (finite,
  // room for a 100 px plot area besides title, labels and caption).
  void validate() const;
};

// Throws InvalidParameter naming "series" (empty), "series[i].x" (empty, non-finite or a length
// other than y's), "series[i].y" (non-finite) or "series[i].marker_x" (non-finite), or an option.
std::string line_plot_svg(std::span<const LineSeries> series, const LinePlotOptions& options);

}  // namespace fogradar::stats
