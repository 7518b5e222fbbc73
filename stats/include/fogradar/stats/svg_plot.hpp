// Box plots as standalone SVG 1.1 documents, for reports: one box per category (q1..q3 box, median
// line, whiskers with caps, outliers as circles, optional mean marker), a y axis with 1-2-5 ticks
// and gridlines, an optional strip of per-category rates (0..1) under the boxes, an optional marked
// category (dashed line), a legend naming every symbol drawn, a title and caption lines. Category
// labels are thinned (every 1st, 2nd, 5th, 10th, ... label) so that they never overlap, for any
// number of categories. A category without values is shaded and crossed, not left as a gap.
// Output is deterministic: the same input gives byte-identical SVG (fixed-precision,
// locale-independent numbers). Text is written as given (UTF-8), XML-escaped.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fogradar/stats/box_plot.hpp"

namespace fogradar::stats {

struct BoxPlotSeries {
  std::string label;  // category label under the box, e.g. "2"
  BoxPlot box;        // n = 0: drawn as an empty category (SvgPlotOptions::empty_label)
  // Drawn as a bar in the rate strip when SvgPlotOptions::rate_label is set; NaN: no bar.
  double rate = std::numeric_limits<double>::quiet_NaN();
  std::string note;  // the category's tooltip (SVG <title>); empty: the label
  // An envelope behind the box (e.g. the 5-95 % and 25-75 % points of a statistic across the
  // setups a study allows), drawn as two shaded bars; NaN: none.
  double band_low = std::numeric_limits<double>::quiet_NaN();
  double band_high = std::numeric_limits<double>::quiet_NaN();
  double inner_band_low = std::numeric_limits<double>::quiet_NaN();
  double inner_band_high = std::numeric_limits<double>::quiet_NaN();
  // Reference values marked at this category (e.g. a measurement's), as red crosses.
  std::vector<double> references;
};

struct SvgPlotOptions {
  std::string title;
  std::vector<std::string> caption;  // lines under the x label, e.g. what the data are
  std::string x_label;               // with units where they apply, e.g. "active fog layers"
  std::string y_label;               // e.g. "RCS (dBsm)"
  double width_px = 960;
  double height_px = 640;
  bool show_mean = true;                       // mean as a diamond marker
  std::string empty_label = "no values";       // legend text of the empty-category symbol
  std::string rate_label;                      // title of the rate strip (0-100 %); empty: no strip
  std::optional<std::size_t> marked_category;  // index of a category marked by a dashed line
  std::string mark_label;                      // legend text of that mark
  std::string band_label;                      // legend text of the bands (BoxPlotSeries::band_*)
  std::string inner_band_label;
  std::string reference_label;  // legend text of the reference crosses
  // Non-empty: every category holds one value (min = max, e.g. one run's statistic), drawn as a
  // bar and named in the legend by this text instead of the box plot's symbols.
  std::string value_label;
  // The y axis reaches beyond the values by this fraction of their range at both ends (in [0, 1]),
  // so that none lies on the frame.
  double axis_padding = 0.0;

  // Throws InvalidParameter naming "svg.width_px" (finite, >= 480), "svg.height_px" (finite and
  // tall enough for a 100 px plot area besides title, strip, labels and caption) or
  // "svg.axis_padding".
  void validate() const;
};

// Ticks first, first + step, ..., last covering [low, high], step in {1, 2, 5} x 10^k chosen as
// the smallest such step giving at most `max_intervals` intervals (after Heckbert, "Nice numbers
// for graph labels", Graphics Gems, 1990); `decimals` digits print every tick exactly in
// fixed-point, which axis_tick_label uses for moderate steps.
struct AxisTicks {
  double first;
  double last;
  double step;
  int decimals;
};
// low == high is widened to [low - 1, high + 1]. Throws InvalidParameter naming "low", "high"
// (finite, high >= low) or "max_intervals" (>= 2).
AxisTicks nice_axis_ticks(double low, double high, int max_intervals = 6);

// The label of tick `value` of `ticks`: fixed-point with ticks.decimals digits ("14.5") while the
// step is in [1e-6, 1e9]; beyond, scientific with the significant digits that reach the step's
// decade ("2.5e-20", "1.5e+12", at most 17), so that any finite scale plots with labels no longer
// than its ticks need (a value within half a step of zero is "0"). Every label reads back to its
// tick within 1e-12 of the larger of the tick's magnitude and the step.
std::string axis_tick_label(double value, const AxisTicks& ticks);

// Every how many categories a label is written: the smallest stride in 1, 2, 5, 10, 20, 50, ...
// with stride * band_px >= the widest label's estimated width plus a gap. Throws InvalidParameter
// naming "band_px" (finite, > 0).
std::size_t category_label_stride(std::span<const BoxPlotSeries> series, double band_px);

// Throws InvalidParameter naming "series" (empty list), "series[i].box" (n > 0 with a non-finite
// statistic other than std_dev), "series[i].rate" (not NaN and outside [0, 1] while the strip is
// drawn), "series[i].band_low" (a band whose ends are not both finite with low <= high),
// "series[i].references" (a non-finite value), "marked_category" (not an index of `series`) or an
// options field.
std::string box_plot_svg(std::span<const BoxPlotSeries> series, const SvgPlotOptions& options);

}  // namespace fogradar::stats
