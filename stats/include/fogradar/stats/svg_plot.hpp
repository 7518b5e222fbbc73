// Box plots as standalone SVG 1.1 documents: one box per series (q1..q3 box, median line,
// whiskers with caps, outliers as circles, optional mean marker), category labels with the
// series size ("n = 200"), a y axis with 1-2-5 ticks and gridlines, axis labels and a title.
// A series with n = 0 is drawn as a "no detections" label. Output is deterministic: the same
// input gives byte-identical SVG (fixed-precision, locale-independent numbers).
#pragma once

#include <span>
#include <string>

#include "fogradar/stats/box_plot.hpp"

namespace fogradar::stats {

struct BoxPlotSeries {
  std::string label;  // category label under the box, e.g. "2"
  BoxPlot box;
};

struct SvgPlotOptions {
  std::string title;
  std::string x_label;  // with units where they apply, e.g. "active fog layers"
  std::string y_label;  // e.g. "RCS (dBsm)"
  double width_px = 720;
  double height_px = 480;
  bool show_mean = true;  // mean as a diamond marker, with a legend entry

  // Throws InvalidParameter naming "svg.width_px" or "svg.height_px" (finite, >= 200).
  void validate() const;
};

// Ticks first, first + step, ..., last covering [low, high], step in {1, 2, 5} x 10^k chosen as
// the smallest such step giving at most `max_intervals` intervals (after Heckbert, "Nice numbers
// for graph labels", Graphics Gems, 1990); `decimals` digits print every tick exactly.
struct AxisTicks {
  double first;
  double last;
  double step;
  int decimals;
};
// low == high is widened to [low - 1, high + 1]. Throws InvalidParameter naming "low", "high"
// (finite, high >= low) or "max_intervals" (>= 2).
AxisTicks nice_axis_ticks(double low, double high, int max_intervals = 6);

// Throws InvalidParameter naming "series" (empty list), "series[i].box" (n > 0 with a non-finite
// statistic other than std_dev) or an options field.
std::string box_plot_svg(std::span<const BoxPlotSeries> series, const SvgPlotOptions& options);

}  // namespace fogradar::stats
