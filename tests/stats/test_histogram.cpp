// Histogram statistics against the same statistics of the expanded sample (box_plot.hpp's type-7
// quantile and a two-pass standard deviation written here); the line plot's SVG is well formed
// (svg_check.hpp) and refuses bad series by name.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "fogradar/core/random.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/histogram.hpp"
#include "fogradar/stats/line_plot.hpp"
#include "rejected_field.hpp"
#include "svg_check.hpp"
#include "validation.hpp"

namespace fogradar::stats {
namespace {

using fogradar::testing::Tolerance;
using fogradar::testing::validate;

TEST(Histogram, MatchesTheExpandedSample) {
  RandomStream stream(3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::uint64_t> counts(256, 0);
    std::vector<double> sample;
    const std::size_t n = 1 + stream() % 500;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t v = 40 + stream() % 30;
      ++counts[v];
      sample.push_back(static_cast<double>(v));
    }
    std::sort(sample.begin(), sample.end());
    double mean = 0.0;
    for (const double v : sample) mean += v;
    mean /= static_cast<double>(n);
    double squares = 0.0;
    for (const double v : sample) squares += (v - mean) * (v - mean);
    const HistogramSummary summary = histogram_summary(counts);
    EXPECT_EQ(summary.n, n);
    const std::string conditions =
        "trial " + std::to_string(trial) + ": " + std::to_string(n) + " values in 40..69 (seed 3)";
    validate({.id = "stats.histogram.mean.trial" + std::to_string(trial),
              .group = "experiment: statistics",
              .quantity = "mean of a histogram",
              .unit = "1",
              .conditions = conditions,
              .reference = mean,
              .source = "second method: the mean of the expanded sample, summed here",
              .value = summary.mean,
              .tolerance = 1e-12,
              .kind = Tolerance::absolute});
    if (n > 1) {
      validate({.id = "stats.histogram.std_dev.trial" + std::to_string(trial),
                .group = "experiment: statistics",
                .quantity = "sample standard deviation of a histogram",
                .unit = "1",
                .conditions = conditions,
                .reference = std::sqrt(squares / static_cast<double>(n - 1)),
                .source = "second method: two-pass standard deviation of the expanded sample",
                .value = summary.std_dev,
                .tolerance = 1e-12,
                .kind = Tolerance::absolute});
    }
    for (const double p : {0.0, 0.05, 0.25, 0.5, 0.95, 1.0}) {
      EXPECT_NEAR(histogram_quantile_type7(counts, p), quantile_type7(sample, p), 1e-12) << p;
    }
  }
  const std::vector<std::uint64_t> empty(256, 0);
  EXPECT_EQ(test_support::rejected_field([&] { histogram_summary(empty); }), "counts");
  const std::vector<std::uint64_t> one{0, 1};
  EXPECT_EQ(test_support::rejected_field([&] { histogram_quantile_type7(one, 1.5); }), "p");
}

TEST(LinePlot, WellFormedWithMarkersAndRefusesBadSeries) {
  std::vector<LineSeries> series(2);
  series[0] = {"0 layers", {0, 1, 2}, {1, 5, 2}, 1.2, "mean 1.2"};
  series[1] = {"a < b & c", {0, 1, 2}, {0, 2, 9}, std::nullopt, ""};
  LinePlotOptions options;
  options.title = "t";
  options.caption = {"caption"};
  const std::string svg = line_plot_svg(series, options);
  EXPECT_EQ(test_support::xml_error(svg), "");
  EXPECT_NE(svg.find("mean 1.2"), std::string::npos);
  EXPECT_NE(svg.find("a &lt; b &amp; c"), std::string::npos);
  EXPECT_EQ(line_plot_svg(series, options), svg);  // deterministic
  series[1].y.pop_back();
  EXPECT_EQ(test_support::rejected_field([&] { line_plot_svg(series, options); }), "series[1].x");
  series[1].y.push_back(std::nan(""));
  EXPECT_EQ(test_support::rejected_field([&] { line_plot_svg(series, options); }), "series[1].y");
  EXPECT_EQ(test_support::rejected_field([&] { line_plot_svg({}, options); }), "series");
  options.width_px = 100;
  EXPECT_EQ(test_support::rejected_field([&] { line_plot_svg(series, options); }), "svg.width_px");
}

// Layer counts 0-4 give 1-2-5 ticks at 0.5 steps (Heckbert's rule allows 8 intervals); a count axis
// must show whole numbers only.
TEST(LinePlot, IntegerTicksForCountAxes) {
  const std::vector<LineSeries> series{{"metric", {0, 1, 2, 3, 4}, {1, 0.5, 0.2, 0.1, 0}, {}, ""}};
  LinePlotOptions options;
  options.title = "t";
  const auto has_tick = [](const std::string& svg, const std::string& label) {
    return svg.find("class=\"tick\">" + label + "<") != std::string::npos;
  };
  const std::string plain = line_plot_svg(series, options);
  EXPECT_TRUE(has_tick(plain, "0.5"));
  options.x_integer_ticks = true;
  const std::string counts = line_plot_svg(series, options);
  EXPECT_EQ(test_support::xml_error(counts), "");
  for (const char* label : {"0", "1", "2", "3", "4"}) EXPECT_TRUE(has_tick(counts, label)) << label;
  for (const char* label : {"0.5", "1.5", "3.5"}) EXPECT_FALSE(has_tick(counts, label)) << label;
}

}  // namespace
}  // namespace fogradar::stats
