// Line plots as standalone SVG 1.1 documents: several series of (x, y) points drawn as polylines in
// distinct colours over the same axes (1-2-5 ticks from nice_axis_ticks, gridlines), each with an
// optional vertical marker line (e.g. a histogram's mean) labelled with its value, a legend (with
// an optional title), a title and caption lines. Optionally each series also gets its own point
// marker and dash pattern (lines that coincide stay distinguishable), is drawn as steps, and has
// points beyond the top of the axis (e.g. a limit not reached) drawn as its marker in a labelled
// row above the plot. Deterministic, locale-independent output; text XML-escaped.
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
  // x of the points whose value lies beyond the top of the axis, drawn in the row named
  // LinePlotOptions::beyond_label above the plot; the line is broken there.
  std::vector<double> beyond_x = {};
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
  bool y_integer_ticks = false;
  // The y axis reaches at least this value (e.g. the last step a count can take).
  std::optional<double> y_reach;
  // Every series with its own hollow point marker (7 shapes) and dash pattern (4), both cycled, so
  // that no two of the first 28 series share both, and lines that coincide stay visible.
  bool point_markers = false;
  // Every series as steps: each value held halfway to its neighbours' x, not joined by slopes.
  bool steps = false;
  // Lines written above the legend's entries, e.g. the swept keys. The legend's column widens for
  // long titles and labels.
  std::vector<std::string> legend_title;
  std::string beyond_label;  // the row of LineSeries::beyond_x points, e.g. "not reached"
  double width_px = 960;
  double height_px = 640;
  // Throws InvalidParameter naming "svg.width_px" (finite, >= 480) or "svg.height_px" (finite,
  // room for a 100 px plot area besides title, labels and caption).
  void validate() const;
};

// Throws InvalidParameter naming "series" (empty), "series[i].x" (a length other than y's, or
// non-finite; empty only with points in beyond_x), "series[i].y" (non-finite),
// "series[i].marker_x" or "series[i].beyond_x" (non-finite), or an option.
std::string line_plot_svg(std::span<const LineSeries> series, const LinePlotOptions& options);

}  // namespace fogradar::stats
