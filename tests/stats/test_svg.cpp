// SVG box plot tests: well-formed standalone SVG 1.1 (checked by the small XML tokenizer of
// svg_check.hpp), one box per series with data, a legend entry for every symbol drawn, empty series
// shaded and crossed, the rate strip and the marked category at their categories, category labels
// thinned so that none overlap for up to 150 categories, escaping, byte-identical output, and 1-2-5
// axis ticks (hand-worked cases of Heckbert's rule, exact).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/heat_map.hpp"
#include "fogradar/stats/line_plot.hpp"
#include "fogradar/stats/svg_plot.hpp"
#include "rejected_field.hpp"
#include "svg_check.hpp"

namespace fogradar::stats {
namespace {

using test_support::count;
using test_support::elements_of_class;
using test_support::texts_of_class;
using test_support::xml_error;

std::vector<double> rcs_sample(std::uint64_t seed, std::size_t n, double median_dbsm) {
  RandomStream rng(seed);
  std::vector<double> v(n);
  for (double& x : v) x = median_dbsm + 10.0 * std::log10(rng.exponential() / std::log(2.0));
  return v;
}

BoxPlotSeries series_of(std::string label, BoxPlot box,
                        double rate = std::numeric_limits<double>::quiet_NaN()) {
  BoxPlotSeries s;
  s.label = std::move(label);
  s.box = std::move(box);
  s.rate = rate;
  return s;
}

std::vector<BoxPlotSeries> paper_like_series() {
  std::vector<BoxPlotSeries> series;
  for (int layers = 0; layers < 4; ++layers) {
    series.push_back(
        series_of(std::to_string(layers), box_plot(rcs_sample(100 + layers, 200, 15.0)), 1.0));
  }
  series.push_back(series_of("4", box_plot(std::vector<double>{}), 0.0));
  return series;
}

SvgPlotOptions paper_options() {
  SvgPlotOptions options;
  options.title = "RCS per active fog layers";
  options.x_label = "active fog layers";
  options.y_label = "RCS (dBsm)";
  return options;
}

// Every optional part on: caption, rate strip, a marked category, an empty-category label.
SvgPlotOptions full_options() {
  SvgPlotOptions options = paper_options();
  options.caption = {"first caption line", "second caption line"};
  options.rate_label = "rate";
  options.marked_category = 3;
  options.mark_label = "the mark";
  options.empty_label = "nothing here";
  return options;
}

double number(const std::string& text) { return std::stod(text); }

TEST(SvgPlot, WellFormedStandaloneSvg) {
  for (const SvgPlotOptions& options : {paper_options(), full_options()}) {
    const std::string svg = box_plot_svg(paper_like_series(), options);
    EXPECT_EQ(xml_error(svg), "");
    EXPECT_TRUE(svg.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\""));
    EXPECT_NE(
        svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"960.00\""),
        std::string::npos);
    EXPECT_TRUE(svg.ends_with("</svg>\n"));
  }
}

TEST(SvgPlot, TheCheckerRejectsBrokenXml) {  // the well-formedness check can fail
  EXPECT_NE(xml_error("<svg><g></svg></g>"), "");
  EXPECT_NE(xml_error("<svg><text>a < b</text></svg>"), "");
  EXPECT_NE(xml_error("<svg><text>A & B</text></svg>"), "");
  EXPECT_NE(xml_error("<svg x=1/>"), "");
  EXPECT_NE(xml_error("<svg/><svg/>"), "");
  EXPECT_NE(xml_error("<svg>"), "");
  EXPECT_EQ(xml_error("<svg a=\"1\"><t>A &amp; B</t></svg>"), "");
}

TEST(SvgPlot, OneBoxPerSeriesWithData) {
  const std::vector<BoxPlotSeries> series = paper_like_series();
  const std::string svg = box_plot_svg(series, paper_options());
  std::size_t outliers = 0;
  for (const BoxPlotSeries& s : series) outliers += s.box.outliers.size();
  ASSERT_GT(outliers, 0u);  // log-exponential RCS has a long low tail
  EXPECT_EQ(count(svg, "<g class=\"series\">"), 5u);
  EXPECT_EQ(count(svg, "class=\"box\""), 4u);
  EXPECT_EQ(count(svg, "class=\"median\""), 4u);
  EXPECT_EQ(count(svg, "class=\"whisker\""), 16u);  // two whiskers and two caps per box
  EXPECT_EQ(count(svg, "class=\"outlier\""), outliers);
  EXPECT_EQ(count(svg, "class=\"mean\""), 4u);
  for (const char* text :
       {">RCS (dBsm)</text>", ">active fog layers</text>", ">RCS per active fog layers</text>"}) {
    EXPECT_EQ(count(svg, text), 1u) << text;
  }

  SvgPlotOptions no_mean = paper_options();
  no_mean.show_mean = false;
  const std::string plain = box_plot_svg(series, no_mean);
  EXPECT_EQ(count(plain, "class=\"mean\""), 0u);
  EXPECT_EQ(count(plain, "class=\"legend-mean\""), 0u);
}

// Each symbol drawn has one legend entry with its meaning; symbols not drawn have none.
TEST(SvgPlot, LegendNamesEverySymbolDrawn) {
  const std::string svg = box_plot_svg(paper_like_series(), full_options());
  EXPECT_EQ(count(svg, "<g class=\"legend\">"), 1u);
  for (const char* symbol :
       {"class=\"legend-box\"", "class=\"legend-median\"", "class=\"legend-outlier\"",
        "class=\"legend-mean\"", "class=\"legend-empty\"", "class=\"legend-mark\"",
        "class=\"legend-rate\""}) {
    EXPECT_EQ(count(svg, symbol), 1u) << symbol;
  }
  EXPECT_EQ(count(svg, "class=\"legend-whisker\""), 3u);  // stem and two caps
  std::vector<std::string> texts;
  for (const auto& t : texts_of_class(svg, "legend-text")) texts.push_back(t.content);
  EXPECT_EQ(texts, (std::vector<std::string>{"box: quartiles Q1 to Q3", "median",
                                             "whiskers: Tukey, 1.5 IQR", "outlier beyond a whisker",
                                             "mean", "nothing here", "the mark", "rate"}));

  // No empty series, no mark, no strip: no legend entries for them.
  std::vector<BoxPlotSeries> full = paper_like_series();
  full.pop_back();
  const std::string plain = box_plot_svg(full, paper_options());
  EXPECT_EQ(texts_of_class(plain, "legend-text").size(), 5u);
  for (const char* symbol : {"legend-empty", "legend-mark", "legend-rate"})
    EXPECT_EQ(count(plain, symbol), 0u);
}

TEST(SvgPlot, EmptySeriesAreShadedAndCrossed) {
  const std::string svg = box_plot_svg(paper_like_series(), full_options());
  EXPECT_EQ(count(svg, "class=\"no-values-band\""), 1u);
  EXPECT_EQ(count(svg, "class=\"no-values\""), 2u);  // the two strokes of one cross
  // The band is the last category's: from the centre of category 3 plus half a band onwards.
  const auto labels = texts_of_class(svg, "category");
  ASSERT_EQ(labels.size(), 5u);
  const std::size_t band = elements_of_class(svg, "rect", "no-values-band").at(0);
  const double band_width = labels[4].x - labels[3].x;
  EXPECT_NEAR(number(test_support::attribute(svg, band, "x")), labels[4].x - 0.5 * band_width,
              0.01);
  EXPECT_NEAR(number(test_support::attribute(svg, band, "width")), band_width, 0.01);
  // A band of 127 px holds the written label; 100 bands of 6.36 px only the cross.
  EXPECT_EQ(count(svg, ">nothing here</text>"), 2u);  // in the plot and in the legend

  // Only empty series: still a valid plot with a default axis.
  const std::vector<BoxPlotSeries> none = {series_of("0", BoxPlot{}), series_of("1", BoxPlot{})};
  const std::string empty_svg = box_plot_svg(none, paper_options());
  EXPECT_EQ(xml_error(empty_svg), "");
  EXPECT_EQ(count(empty_svg, "class=\"no-values-band\""), 2u);
  EXPECT_EQ(count(empty_svg, "class=\"box\""), 0u);
}

TEST(SvgPlot, BoxGeometryFollowsTheQuartiles) {
  // One series 10..20 dBsm: axis 10..20 in steps of 2. A 960 x 640 plot without strip and caption
  // spans y = 52 (top) to 640 - 42 - 12 = 586 (bottom), x = 84 to 960 - 240 = 720; q3 = 17.5 maps
  // to 586 - 0.75 * 534 = 185.50, the box height is (17.5 - 12.5) / 10 * 534 = 267, its half width
  // is 40 (the maximum) about the centre 402.
  std::vector<double> v;
  for (int i = 0; i <= 20; ++i) v.push_back(10.0 + 0.5 * i);
  const std::vector<BoxPlotSeries> series = {series_of("a", box_plot(v))};
  const std::string svg = box_plot_svg(series, paper_options());
  EXPECT_NE(
      svg.find("<rect x=\"362.00\" y=\"185.50\" width=\"80.00\" height=\"267.00\" class=\"box\""),
      std::string::npos)
      << svg;
  for (const char* tick : {">10<", ">12<", ">14<", ">16<", ">18<", ">20<"}) {
    EXPECT_EQ(count(svg, tick), 1u) << tick;
  }
}

// Bars of the rate strip: height rate x 56 px (the strip's height), one per series with a rate.
TEST(SvgPlot, RateStripBars) {
  std::vector<BoxPlotSeries> series = paper_like_series();
  series[1].rate = 0.25;
  series[2].rate = std::numeric_limits<double>::quiet_NaN();
  const std::string svg = box_plot_svg(series, full_options());
  const auto bars = elements_of_class(svg, "rect", "rate");
  ASSERT_EQ(bars.size(), 4u);
  EXPECT_EQ(test_support::attribute(svg, bars[0], "height"), "56.00");
  EXPECT_EQ(test_support::attribute(svg, bars[1], "height"), "14.00");
  EXPECT_EQ(test_support::attribute(svg, bars[3], "height"), "0.00");
  const auto values = texts_of_class(svg, "rate-value");  // bands of 127 px are wide enough
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[1].content, "25 %");
  // Without a rate label there is no strip.
  EXPECT_EQ(count(box_plot_svg(series, paper_options()), "class=\"rate\""), 0u);
}

TEST(SvgPlot, MarkSitsAtTheMarkedCategory) {
  const std::string svg = box_plot_svg(paper_like_series(), full_options());
  const auto marks = elements_of_class(svg, "line", "mark");
  ASSERT_EQ(marks.size(), 2u);  // through the plot and through the rate strip
  const auto labels = texts_of_class(svg, "category");
  ASSERT_EQ(labels.size(), 5u);
  ASSERT_EQ(labels[3].content, "3");
  for (const std::size_t mark : marks) {
    EXPECT_NEAR(number(test_support::attribute(svg, mark, "x1")), labels[3].x, 0.005);
    EXPECT_NEAR(number(test_support::attribute(svg, mark, "x2")), labels[3].x, 0.005);
  }
  EXPECT_EQ(count(svg, "class=\"mark-head\""), 1u);
  EXPECT_EQ(count(box_plot_svg(paper_like_series(), paper_options()), "class=\"mark\""), 0u);
}

// Labels 0 .. n-1 for n up to 150 categories: never two overlapping, the first one written, every
// category within 10 of a labelled one (stride <= 10 up to 150 categories of 4.24 px and more).
TEST(SvgPlot, CategoryLabelsNeverOverlap) {
  for (const std::size_t n : {1u, 2u, 5u, 12u, 41u, 60u, 100u, 101u, 150u}) {
    std::vector<BoxPlotSeries> series;
    for (std::size_t i = 0; i < n; ++i) {
      series.push_back(series_of(std::to_string(i), box_plot(rcs_sample(i, 20, 10.0)), 0.5));
    }
    SvgPlotOptions options = full_options();
    options.marked_category = n / 2;
    const std::string svg = box_plot_svg(series, options);
    EXPECT_EQ(xml_error(svg), "") << n;
    EXPECT_EQ(test_support::text_overlap(svg, "category"), "") << n << " categories";
    const auto labels = texts_of_class(svg, "category");
    ASSERT_FALSE(labels.empty()) << n;
    EXPECT_EQ(labels.front().content, "0");
    const std::size_t stride = n == 1 ? 1 : std::stoul(labels[1].content);
    EXPECT_LE(stride, 10u) << n;
    EXPECT_EQ(labels.size(), (n + stride - 1) / stride) << n;
    EXPECT_EQ(count(svg, "class=\"category-tick\""), n);  // every category keeps its tick
  }
}

// Hand-worked: a label of c characters needs 0.7 x 12 c + 6 px (8.4 c + 6); the stride is the
// smallest 1-2-5 multiple of the band covering it.
TEST(SvgPlot, LabelStrideFromTheWidestLabel) {
  const std::vector<BoxPlotSeries> three = {series_of("0", BoxPlot{}), series_of("1", BoxPlot{}),
                                            series_of("100", BoxPlot{})};
  EXPECT_EQ(category_label_stride(three, 40.0), 1u);  // 31.2 px needed
  EXPECT_EQ(category_label_stride(three, 20.0), 2u);  // 2 x 20 >= 31.2 > 20
  EXPECT_EQ(category_label_stride(three, 10.0), 5u);  // 5 >= the count: only the first label
  std::vector<BoxPlotSeries> many(100, series_of("99", BoxPlot{}));  // 22.8 px needed
  EXPECT_EQ(category_label_stride(many, 6.36), 5u);                  // 2 x 6.36 < 22.8 <= 5 x 6.36
  EXPECT_EQ(category_label_stride(many, 2.0), 20u);                  // 10 x 2 < 22.8 <= 20 x 2
  EXPECT_EQ(test_support::rejected_field([&] { category_label_stride(many, 0.0); }), "band_px");
}

TEST(SvgPlot, EscapesText) {
  std::vector<BoxPlotSeries> series = {
      series_of("A & B <1>", box_plot(std::vector<double>{1, 2, 3}))};
  series[0].note = "note & <more>";
  SvgPlotOptions options = paper_options();
  options.title = "x < y & \"quoted\"";
  options.caption = {"caption's \u03b2 & co"};
  const std::string svg = box_plot_svg(series, options);
  EXPECT_EQ(xml_error(svg), "");
  EXPECT_NE(svg.find(">A &amp; B &lt;1&gt;</text>"), std::string::npos);
  EXPECT_NE(svg.find(">x &lt; y &amp; &quot;quoted&quot;</text>"), std::string::npos);
  EXPECT_NE(svg.find("<title>note &amp; &lt;more&gt;</title>"), std::string::npos);
  EXPECT_NE(svg.find(">caption&apos;s \u03b2 &amp; co</text>"), std::string::npos);
  EXPECT_EQ(svg.find("A & B"), std::string::npos);
}

TEST(SvgPlot, DeterministicBytes) {
  const std::vector<BoxPlotSeries> series = paper_like_series();
  const std::vector<BoxPlotSeries> copy = series;
  EXPECT_EQ(box_plot_svg(series, full_options()), box_plot_svg(copy, full_options()));
}

TEST(NiceAxisTicks, OneTwoFiveSteps) {  // hand-worked: smallest 1-2-5 step with <= 6 intervals
  AxisTicks t = nice_axis_ticks(14.2, 15.9);  // 0.1 -> 17, 0.2 -> 9, 0.5 -> 4 intervals
  EXPECT_DOUBLE_EQ(t.first, 14.0);
  EXPECT_DOUBLE_EQ(t.last, 16.0);
  EXPECT_DOUBLE_EQ(t.step, 0.5);
  EXPECT_EQ(t.decimals, 1);
  t = nice_axis_ticks(0.3, 9.7);  // 1 -> 10, 2 -> 5 intervals
  EXPECT_DOUBLE_EQ(t.first, 0.0);
  EXPECT_DOUBLE_EQ(t.last, 10.0);
  EXPECT_DOUBLE_EQ(t.step, 2.0);
  EXPECT_EQ(t.decimals, 0);
  t = nice_axis_ticks(-37.2, 18.4);  // 5 -> 12, 10 -> 6 intervals
  EXPECT_DOUBLE_EQ(t.first, -40.0);
  EXPECT_DOUBLE_EQ(t.last, 20.0);
  EXPECT_DOUBLE_EQ(t.step, 10.0);
  t = nice_axis_ticks(5.0, 5.0);  // widened to [4, 6]: 0.5 -> 4 intervals
  EXPECT_DOUBLE_EQ(t.first, 4.0);
  EXPECT_DOUBLE_EQ(t.last, 6.0);
  EXPECT_DOUBLE_EQ(t.step, 0.5);
  t = nice_axis_ticks(1e-7, 3e-7);  // 5e-8 -> 4 intervals, 8 decimals
  EXPECT_DOUBLE_EQ(t.step, 5e-8);
  EXPECT_EQ(t.decimals, 8);
}

// Tick labels of any finite scale (a lidar.intensity_scale of 1e-20 made the box plot
// ask for 20 fixed-point decimals and fail after the run). Each label reads back to its tick within
// 1e-12 of the larger of the tick's magnitude and the step (labels round only the ticks' arithmetic
// residue, ~1e-16 relative), and no two ticks share a label.
void expect_labels_read_back(const AxisTicks& t) {
  const auto n = std::lround((t.last - t.first) / t.step);
  std::string previous;
  for (long i = 0; i <= n; ++i) {
    const double tick = t.first + static_cast<double>(i) * t.step;
    const std::string label = axis_tick_label(tick, t);
    EXPECT_NEAR(number(label), tick, 1e-12 * std::max(std::abs(tick), t.step))
        << label << ", step " << t.step;
    EXPECT_NE(label, previous) << "step " << t.step;
    previous = label;
  }
}

TEST(NiceAxisTicks, LabelsOfAnyFiniteStepReadBackToTheirTicks) {
  struct Case {
    double low, high, step;
    std::vector<std::string> labels;  // hand-worked
  };
  const Case cases[] = {
      {0.0, 3.7e-20, 1e-20, {"0", "1e-20", "2e-20", "3e-20", "4e-20"}},
      {0.0, 3.7e-300, 1e-300, {"0", "1e-300", "2e-300", "3e-300", "4e-300"}},
      {0.0, 3.7e12, 1e12, {"0", "1e+12", "2e+12", "3e+12", "4e+12"}},
      // Digits down to the step's decade; zero without a rounding residue's sign or exponent.
      {-2.2e-20, 2.8e-20, 1e-20, {"-3e-20", "-2e-20", "-1e-20", "0", "1e-20", "2e-20", "3e-20"}},
      {1.01e12,
       1.29e12,
       5e10,
       {"1.00e+12", "1.05e+12", "1.10e+12", "1.15e+12", "1.20e+12", "1.25e+12", "1.30e+12"}},
      // Steps in [1e-6, 1e9] keep their fixed-point labels.
      {14.2, 15.9, 0.5, {"14.0", "14.5", "15.0", "15.5", "16.0"}},
      {0.0, 3.7e-6, 1e-6, {"0.000000", "0.000001", "0.000002", "0.000003", "0.000004"}},
      {0.0, 3.7e9, 1e9, {"0", "1000000000", "2000000000", "3000000000", "4000000000"}},
  };
  for (const Case& c : cases) {
    const AxisTicks t = nice_axis_ticks(c.low, c.high);
    EXPECT_DOUBLE_EQ(t.step, c.step) << c.low << " to " << c.high;
    std::vector<std::string> labels;
    for (long i = 0; i <= std::lround((t.last - t.first) / t.step); ++i) {
      labels.push_back(axis_tick_label(t.first + static_cast<double>(i) * t.step, t));
    }
    EXPECT_EQ(labels, c.labels) << c.low << " to " << c.high;
    // At most 10 characters: the tick-label margin's width.
    for (const std::string& label : labels) EXPECT_LE(label.size(), 10u) << label;
    expect_labels_read_back(t);
  }
  // Spans near the smallest normal double and the largest; a tiny step far from zero, down to
  // 17 significant digits.
  for (const auto& [low, high] :
       std::vector<std::pair<double, double>>{{0.0, 1e-305},
                                              {-1e307, 1e307},
                                              {1.0, 1.0 + 1e-12},
                                              {-7.5e-12, -7.4e-12},
                                              {123456789.0, 123456789.0 + 1e-7}}) {
    expect_labels_read_back(nice_axis_ticks(low, high));
  }
}

// The plots draw those labels: box plot and line plot at scales of 1e-20, 1e-300 and 1e12.
TEST(NiceAxisTicks, PlotsOfExtremeScalesDrawTheirTicks) {
  for (const double scale : {1e-20, 1e-300, 1e12}) {
    std::vector<BoxPlotSeries> series = paper_like_series();
    for (BoxPlotSeries& s : series) {
      std::vector<double> sample = rcs_sample(7, 50, 30.0);
      for (double& v : sample) v *= scale;
      s.box = box_plot(sample);
    }
    std::string svg;
    ASSERT_NO_THROW(svg = box_plot_svg(series, full_options())) << scale;
    EXPECT_EQ(xml_error(svg), "");
    std::vector<LineSeries> lines(1);
    lines[0] = {"a", {0.0, scale, 2.0 * scale}, {0.0, 2.5 * scale, 4.0 * scale}, std::nullopt, ""};
    std::string line_svg;
    ASSERT_NO_THROW(line_svg = line_plot_svg(lines, LinePlotOptions{})) << scale;
    EXPECT_EQ(xml_error(line_svg), "");
    for (const std::string* doc : {&svg, &line_svg}) {
      const std::vector<test_support::SvgText> ticks = texts_of_class(*doc, "tick");
      ASSERT_GE(ticks.size(), 3u);
      for (const test_support::SvgText& tick : ticks) {
        const double value = number(tick.content);
        EXPECT_TRUE(value == 0.0 ||
                    (std::abs(value) >= 0.1 * scale && std::abs(value) <= 1e4 * scale))
            << tick.content << " at scale " << scale;
      }
    }
  }
}

TEST(SvgConfig, EveryInvalidInputNamesItsField) {
  const std::vector<BoxPlotSeries> series = paper_like_series();
  const auto expect_field = [](auto&& f, const std::string& field) {
    EXPECT_EQ(test_support::rejected_field(f), field);
  };
  expect_field([&] { box_plot_svg(std::span<const BoxPlotSeries>{}, paper_options()); }, "series");
  SvgPlotOptions narrow = paper_options();
  narrow.width_px = 10;
  expect_field([&] { box_plot_svg(series, narrow); }, "svg.width_px");
  SvgPlotOptions flat = paper_options();
  flat.height_px = std::numeric_limits<double>::quiet_NaN();
  expect_field([&] { box_plot_svg(series, flat); }, "svg.height_px");
  SvgPlotOptions wordy = full_options();
  wordy.caption.assign(30,
                       "a caption line");  // 30 x 16 px of caption leave no 100 px plot in 640 px
  expect_field([&] { box_plot_svg(series, wordy); }, "svg.height_px");
  std::vector<BoxPlotSeries> broken = series;
  broken[1].box.median = std::numeric_limits<double>::infinity();
  expect_field([&] { box_plot_svg(broken, paper_options()); }, "series[1].box");
  std::vector<BoxPlotSeries> above_one = series;
  above_one[2].rate = 1.5;
  expect_field([&] { box_plot_svg(above_one, full_options()); }, "series[2].rate");
  SvgPlotOptions off_the_end = full_options();
  off_the_end.marked_category = series.size();
  expect_field([&] { box_plot_svg(series, off_the_end); }, "marked_category");
  expect_field([] { nice_axis_ticks(2.0, 1.0); }, "high");
  expect_field([] { nice_axis_ticks(std::numeric_limits<double>::quiet_NaN(), 1.0); }, "low");
  expect_field([] { nice_axis_ticks(0.0, 1.0, 1); }, "max_intervals");
  std::vector<BoxPlotSeries> reversed_band = series;
  reversed_band[0].band_low = 5.0;
  reversed_band[0].band_high = 4.0;
  expect_field([&] { box_plot_svg(reversed_band, paper_options()); }, "series[0].band_low");
  std::vector<BoxPlotSeries> half_band = series;
  half_band[3].inner_band_high = 4.0;
  expect_field([&] { box_plot_svg(half_band, paper_options()); }, "series[3].inner_band_low");
  std::vector<BoxPlotSeries> endless = series;
  endless[2].references = {std::numeric_limits<double>::infinity()};
  expect_field([&] { box_plot_svg(endless, paper_options()); }, "series[2].references");
}

// An envelope and a measured value beside the boxes: each drawn, in the legend, and inside the
// y axis even where they lie beyond every box.
TEST(BoxPlotSvg, DrawsBandsAndReferencesInsideTheAxis) {
  std::vector<BoxPlotSeries> series = paper_like_series();
  series[0].band_low = 9.0;
  series[0].band_high = 60.0;  // above every box (the boxes lie near 15 dBsm)
  series[0].inner_band_low = 12.0;
  series[0].inner_band_high = 18.0;
  series[1].references = {-60.0};  // below every box and outlier
  SvgPlotOptions options = paper_options();
  options.band_label = "5-95 %";
  options.inner_band_label = "25-75 %";
  options.reference_label = "the study";
  const std::string svg = box_plot_svg(series, options);
  EXPECT_EQ(count(svg, "class=\"band\""), 1u);
  EXPECT_EQ(count(svg, "class=\"inner-band\""), 1u);
  EXPECT_EQ(count(svg, "class=\"reference\""), 2u);  // a cross: two lines
  EXPECT_NE(svg.find(">5-95 %<"), std::string::npos);
  EXPECT_NE(svg.find(">the study<"), std::string::npos);
  // The axis reaches both: tick labels at 60 and at -60.
  EXPECT_NE(svg.find(">60<"), std::string::npos);
  EXPECT_NE(svg.find(">-60<"), std::string::npos);
  // Without them the axis stops at the boxes.
  const std::string plain = box_plot_svg(paper_like_series(), paper_options());
  EXPECT_EQ(plain.find(">-60<"), std::string::npos);
  EXPECT_EQ(plain.find(">60<"), std::string::npos);
  EXPECT_EQ(count(plain, "class=\"band\""), 0u);
}

// A heat map: a cell per row x column with its value written in it, the missing ones grey with
// their text, the darkest colour on the largest value; a grid of another shape is refused.
TEST(HeatMapSvg, DrawsEveryCellAndRefusesAGridOfAnotherShape) {
  HeatMap map;
  map.column_labels = {"300", "900", "2000"};
  map.row_labels = {"0.1", "0.3"};
  map.values = {{1.0, 1.0, std::nullopt}, {3.0, 1.0, 1.0}};
  map.missing_text = "not reached";
  map.title = "lidar: layers to failure";
  const std::string svg = heat_map_svg(map);
  EXPECT_EQ(count(svg, "class=\"cell\""), 6u);
  EXPECT_EQ(count(svg, ">not reached<"), 2u);     // the missing cell and the key
  EXPECT_EQ(count(svg, "fill=\"#d9d9d9\""), 2u);  // the missing cell and its key swatch
  EXPECT_EQ(count(svg, "fill=\"#08519c\""), 2u);  // the largest value's cell and its key swatch
  EXPECT_NE(svg.find(">lidar: layers to failure<"), std::string::npos);
  HeatMap ragged = map;
  ragged.values[1].pop_back();
  EXPECT_EQ(test_support::rejected_field([&] { heat_map_svg(ragged); }), "values");
  HeatMap endless = map;
  endless.values[0][1] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(test_support::rejected_field([&] { heat_map_svg(endless); }), "values[0][1]");
}

// The number in the first `attribute="..."` of the element starting at `tag`.
double number_at(std::string_view svg, std::size_t tag, std::string_view attribute) {
  return std::stod(test_support::attribute(svg, tag, attribute));
}

// Start positions of the <path> elements whose class attribute begins with `prefix`.
std::vector<std::size_t> elements_with_class_prefix(std::string_view svg, std::string_view prefix) {
  std::vector<std::size_t> found;
  for (auto tag = svg.find("<path "); tag != std::string_view::npos;
       tag = svg.find("<path ", tag + 1)) {
    if (test_support::attribute(svg, tag, "class").starts_with(prefix)) found.push_back(tag);
  }
  return found;
}

// Lines that lie on top of each other stay visible: with point markers, each of 28 identical series
// has its own pair of mark shape and dash pattern (7 shapes and 4 dashes, cycled), every point is
// marked, the legend shows both and its title; without the option nothing changes.
TEST(LinePlotSvg, CoincidingLinesEachHaveTheirOwnMarkAndDash) {
  std::vector<LineSeries> series(28);
  for (std::size_t i = 0; i < series.size(); ++i) {
    series[i].label = std::to_string(i);
    series[i].x = {0, 1, 2, 3, 4};
    series[i].y = {1.0, 0.96, 0.96, 0.87, 0.9};
  }
  LinePlotOptions options;
  options.point_markers = true;
  options.legend_title = {"fog.extinction_per_km"};
  options.height_px = 1100;
  const std::string svg = line_plot_svg(series, options);
  EXPECT_EQ(xml_error(svg), "");
  const auto lines = elements_of_class(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), series.size());
  std::vector<std::pair<std::string, std::string>> styles;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    // The series' marks follow its line; the first names its shape.
    const std::size_t mark = svg.find("<path class=\"point-", lines[i]);
    ASSERT_NE(mark, std::string::npos);
    styles.emplace_back(test_support::attribute(svg, mark, "class"),
                        test_support::attribute(svg, lines[i], "stroke-dasharray"));
  }
  for (std::size_t i = 0; i < styles.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_NE(styles[i], styles[j]) << "series " << i << " and " << j;
    }
  }
  EXPECT_EQ(elements_with_class_prefix(svg, "point-").size(), 28u * 5u);
  EXPECT_EQ(elements_with_class_prefix(svg, "legend-point-").size(), 28u);
  EXPECT_EQ(texts_of_class(svg, "legend-title").at(0).content, "fog.extinction_per_km");
  options.point_markers = false;
  options.legend_title.clear();
  const std::string plain = line_plot_svg(series, options);
  EXPECT_EQ(elements_with_class_prefix(plain, "point-").size(), 0u);
  EXPECT_EQ(count(plain, "stroke-dasharray"), 0u);
}

// Limits as the integers they are: steps that change halfway between points (no slopes), a mark at
// each point, whole-number ticks up to the last step, and a value beyond the axis ("not reached")
// as the series' mark in a row above the last step, named in the legend, breaking the line.
TEST(LinePlotSvg, StepsAndPointsBeyondTheAxisInTheirOwnRow) {
  std::vector<LineSeries> series(2);
  series[0] = {.label = "lidar",
               .x = {300, 900, 2000},
               .y = {3, 1, 1},
               .marker_x = {},
               .marker_label = {},
               .beyond_x = {100}};
  series[1] = {.label = "radar",
               .x = {},
               .y = {},
               .marker_x = {},
               .marker_label = {},
               .beyond_x = {100, 300, 900, 2000}};
  LinePlotOptions options;
  options.point_markers = true;
  options.steps = true;
  options.y_integer_ticks = true;
  options.y_reach = 4.0;
  options.beyond_label = "not reached";
  const std::string svg = line_plot_svg(series, options);
  EXPECT_EQ(xml_error(svg), "");
  // Whole-number ticks 0..4, the last step at the top of the frame.
  std::vector<std::string> ticks;
  double last_step_y = 0.0;
  for (const auto& t : texts_of_class(svg, "tick")) {
    if (t.x < 84.0) {  // the y axis's, left of the plot
      ticks.push_back(t.content);
      if (t.content == "4") last_step_y = t.y - 4.0;
    }
  }
  EXPECT_EQ(ticks, (std::vector<std::string>{"0", "1", "2", "3", "4"}));
  // Five marks beyond, each above the last step's gridline and the frame.
  const auto beyond = elements_with_class_prefix(svg, "beyond-");
  ASSERT_EQ(beyond.size(), 5u);
  const double frame_top = number_at(svg, elements_of_class(svg, "rect", "frame").at(0), "y");
  EXPECT_NEAR(frame_top, last_step_y, 0.01);
  for (const std::size_t tag : beyond) {
    const std::string d = test_support::attribute(svg, tag, "d");
    double lowest = 0.0;  // the mark's largest y in px (its bottom)
    for (std::size_t comma = d.find(','); comma != std::string::npos;
         comma = d.find(',', comma + 1))
      lowest = std::max(lowest, std::stod(d.substr(comma + 1)));
    EXPECT_LT(lowest, frame_top) << d;
  }
  EXPECT_EQ(texts_of_class(svg, "beyond-label").at(0).content, "not reached");
  EXPECT_EQ(texts_of_class(svg, "legend-beyond").at(0).content, "top row: not reached");
  // One line for the lidar (the radar has no point on the axis), horizontal and vertical pieces.
  const auto lines = elements_of_class(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), 1u);
  std::vector<std::pair<double, double>> vertices;
  std::istringstream points(test_support::attribute(svg, lines[0], "points"));
  for (std::string pair; points >> pair;) {
    const std::size_t comma = pair.find(',');
    vertices.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
  }
  ASSERT_EQ(vertices.size(), 6u);  // three steps
  for (std::size_t k = 1; k < vertices.size(); ++k) {
    EXPECT_TRUE(vertices[k].first == vertices[k - 1].first ||
                vertices[k].second == vertices[k - 1].second)
        << "a slope from vertex " << k - 1 << " to " << k;
  }
  // The line starts halfway between the point beyond (100) and the first on the axis (300).
  const auto x_of = [&](double v) { return 84.0 + (v - 0.0) / 2000.0 * (960.0 - 220.0 - 84.0); };
  EXPECT_NEAR(vertices.front().first, x_of(200.0), 0.01);
  EXPECT_NEAR(vertices.back().first, x_of(2000.0), 0.01);
}

// Panels compared side by side share one colour scale: a value has the same colour in each, the
// key is the same, with whole numbers for counts, and names the missing cells' grey.
TEST(HeatMapSvg, PanelsOnOneColourScaleWithWholeNumbersForCounts) {
  HeatMap a;
  a.column_labels = {"100", "900"};
  a.row_labels = {"24 GHz", "77 GHz"};
  a.values = {{std::nullopt, 1.0}, {std::nullopt, 1.0}};
  a.missing_text = "not reached";
  a.value_range = {{0.0, 4.0}};
  a.integer_values = true;
  HeatMap b = a;
  b.values = {{std::nullopt, 3.0}, {1.0, 1.0}};
  const std::string sa = heat_map_svg(a), sb = heat_map_svg(b);
  EXPECT_EQ(xml_error(sa), "");
  const auto fill_of_value = [](const std::string& svg, std::string_view value) {
    for (const std::size_t cell : elements_of_class(svg, "rect", "cell")) {
      const std::size_t label = svg.find("class=\"cell-text\"", cell);
      const std::size_t open = svg.find('>', label) + 1;
      if (svg.substr(open, svg.find('<', open) - open) == value)
        return test_support::attribute(svg, cell, "fill");
    }
    return std::string();
  };
  EXPECT_EQ(fill_of_value(sa, "1"), fill_of_value(sb, "1"));
  EXPECT_NE(fill_of_value(sb, "3"), fill_of_value(sb, "1"));
  // Without the shared range, each panel would stretch its own values over the whole scale.
  HeatMap own = a;
  own.value_range.reset();
  EXPECT_NE(fill_of_value(heat_map_svg(own), "1"), fill_of_value(sb, "1"));
  const auto keys = [](const std::string& svg) {
    std::vector<std::string> out;
    for (const auto& t : texts_of_class(svg, "key-text")) out.push_back(t.content);
    return out;
  };
  EXPECT_EQ(keys(sa), (std::vector<std::string>{"4", "3", "2", "1", "0", "not reached"}));
  EXPECT_EQ(keys(sa), keys(sb));
  HeatMap outside = a;
  outside.values[0][0] = 5.0;
  EXPECT_EQ(test_support::rejected_field([&] { heat_map_svg(outside); }), "values[0][0]");
  HeatMap reversed = a;
  reversed.value_range = {{4.0, 0.0}};
  EXPECT_EQ(test_support::rejected_field([&] { heat_map_svg(reversed); }), "value_range");
}

// One statistic on one axis: single values drawn as bars and named alone in the legend (no box,
// whisker or outlier symbols); a band of no width still drawn; the axis padded so that a reference
// next to a 1-2-5 tick (the study's 14.97 dBsm) does not sit on the frame.
TEST(SvgPlot, SingleValuesBandsAndAPaddedAxis) {
  std::vector<BoxPlotSeries> series(2);
  for (std::size_t i = 0; i < series.size(); ++i) {
    BoxPlotSeries& s = series[i];
    s.label = std::to_string(i);
    const double v = 11.0 - static_cast<double>(i);
    s.box.n = 1;
    s.box.min = s.box.q1 = s.box.median = s.box.mean = s.box.q3 = s.box.max = v;
    s.box.whisker_low = s.box.whisker_high = v;
    s.band_low = 10.2;
    s.band_high = 13.4;
  }
  series[0].references = {14.97};
  series[1].band_low = series[1].band_high = 10.0;  // every setup alike
  SvgPlotOptions options;
  options.show_mean = false;
  options.value_label = "the nominal run";
  options.band_label = "5-95 % of the setups";
  options.reference_label = "the study";
  const auto top_gap = [](const std::string& svg) {
    // Distance of the reference from the frame's top, as a fraction of the frame's height.
    const std::size_t frame = elements_of_class(svg, "rect", "frame").at(0);
    const double top = number_at(svg, frame, "y"), height = number_at(svg, frame, "height");
    const auto crosses = elements_of_class(svg, "line", "reference");
    const double y =
        0.5 * (number_at(svg, crosses.at(0), "y1") + number_at(svg, crosses.at(0), "y2"));
    return (y - top) / height;
  };
  const std::string unpadded = box_plot_svg(series, options);
  EXPECT_LT(top_gap(unpadded), 0.01);  // the case to avoid: ticks end at 15
  options.axis_padding = 0.06;
  const std::string svg = box_plot_svg(series, options);
  EXPECT_EQ(xml_error(svg), "");
  EXPECT_GT(top_gap(svg), 0.05);
  std::vector<std::string> legend;
  for (const auto& t : texts_of_class(svg, "legend-text")) legend.push_back(t.content);
  EXPECT_EQ(legend,
            (std::vector<std::string>{"the nominal run", "5-95 % of the setups", "the study"}));
  EXPECT_EQ(elements_of_class(svg, "line", "value").size(), 2u);
  EXPECT_EQ(elements_of_class(svg, "rect", "box").size(), 0u);
  const auto bands = elements_of_class(svg, "rect", "band");
  ASSERT_EQ(bands.size(), 2u);
  EXPECT_GE(number_at(svg, bands[1], "height"), 2.0);
  // Box plots without outliers do not list the outlier symbol.
  options.value_label.clear();
  EXPECT_EQ(box_plot_svg(series, options).find("outlier beyond a whisker"), std::string::npos);
  series[0].box.outliers = {9.0};
  series[0].box.whisker_low = 10.0;
  EXPECT_NE(box_plot_svg(series, options).find("outlier beyond a whisker"), std::string::npos);
  options.axis_padding = -0.1;
  EXPECT_EQ(test_support::rejected_field([&] { box_plot_svg(series, options); }),
            "svg.axis_padding");
}

}  // namespace
}  // namespace fogradar::stats
