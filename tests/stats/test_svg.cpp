// SVG box plot tests: well-formed standalone SVG 1.1 (checked by a small XML tokenizer written
// here: balanced tags, quoted attributes, only predefined entities), one box per series with
// data, escaping, byte-identical output, the "no detections" series, and 1-2-5 axis ticks
// (hand-worked cases of Heckbert's rule, exact).
#include <gtest/gtest.h>

#include "rejected_field.hpp"

#include <cctype>
#include <string>
#include <string_view>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/svg_plot.hpp"

namespace fogradar::stats {
namespace {

std::size_t count(std::string_view haystack, std::string_view needle) {
  std::size_t n = 0;
  for (auto pos = haystack.find(needle); pos != std::string_view::npos;
       pos = haystack.find(needle, pos + needle.size())) {
    ++n;
  }
  return n;
}

// Character data or an attribute value: no '<', every '&' starts a predefined entity.
bool valid_text(std::string_view text) {
  if (text.find('<') != std::string_view::npos) return false;
  for (auto pos = text.find('&'); pos != std::string_view::npos; pos = text.find('&', pos + 1)) {
    const std::string_view rest = text.substr(pos);
    bool known = false;
    for (const std::string_view entity : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"}) {
      known = known || rest.starts_with(entity);
    }
    if (!known) return false;
  }
  return true;
}

bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == ':' || c == '_';
}

// Minimal XML well-formedness check: one root element, balanced and properly nested tags,
// double-quoted unique attributes, valid character data. Returns "" or a description.
std::string xml_error(std::string_view doc) {
  std::size_t pos = 0;
  if (doc.starts_with("<?xml")) pos = doc.find("?>") + 2;
  std::vector<std::string> open;
  int roots = 0;
  while (true) {
    const std::size_t lt = doc.find('<', pos);
    const std::string_view text =
        doc.substr(pos, lt == std::string_view::npos ? doc.npos : lt - pos);
    if (!valid_text(text)) return "bad character data near " + std::to_string(pos);
    if (open.empty() && text.find_first_not_of(" \n\t\r") != std::string_view::npos) {
      return "text outside the root element";
    }
    if (lt == std::string_view::npos) break;
    pos = lt + 1;
    if (doc.substr(pos).starts_with("/")) {  // end tag
      const std::size_t gt = doc.find('>', pos);
      const std::string name(doc.substr(pos + 1, gt - pos - 1));
      if (open.empty() || open.back() != name) return "mismatched </" + name + ">";
      open.pop_back();
      pos = gt + 1;
      continue;
    }
    std::size_t end = pos;
    while (end < doc.size() && is_name_char(doc[end])) ++end;
    if (end == pos) return "missing element name at " + std::to_string(pos);
    const std::string name(doc.substr(pos, end - pos));
    if (open.empty() && ++roots > 1) return "second root element <" + name + ">";
    std::vector<std::string> attributes;
    pos = end;
    while (true) {
      while (pos < doc.size() && std::isspace(static_cast<unsigned char>(doc[pos]))) ++pos;
      if (doc.substr(pos).starts_with("/>")) {
        pos += 2;
        break;
      }
      if (doc.substr(pos).starts_with(">")) {
        open.push_back(name);
        pos += 1;
        break;
      }
      end = pos;
      while (end < doc.size() && is_name_char(doc[end])) ++end;
      const std::string attribute(doc.substr(pos, end - pos));
      if (attribute.empty() || doc.substr(end, 2) != "=\"")
        return "bad attribute in <" + name + ">";
      for (const std::string& seen : attributes) {
        if (seen == attribute) return "duplicate attribute " + attribute;
      }
      attributes.push_back(attribute);
      const std::size_t close = doc.find('"', end + 2);
      if (close == std::string_view::npos) return "unterminated attribute " + attribute;
      if (!valid_text(doc.substr(end + 2, close - end - 2))) return "bad value of " + attribute;
      pos = close + 1;
    }
  }
  if (!open.empty()) return "unclosed <" + open.back() + ">";
  return roots == 1 ? "" : "no root element";
}

std::vector<double> rcs_sample(std::uint64_t seed, std::size_t n, double median_dbsm) {
  RandomStream rng(seed);
  std::vector<double> v(n);
  for (double& x : v) x = median_dbsm + 10.0 * std::log10(rng.exponential() / std::log(2.0));
  return v;
}

std::vector<BoxPlotSeries> paper_like_series() {
  std::vector<BoxPlotSeries> series;
  for (int layers = 0; layers < 4; ++layers) {
    series.push_back({std::to_string(layers), box_plot(rcs_sample(100 + layers, 200, 15.0))});
  }
  series.push_back({"4", box_plot(std::vector<double>{})});
  return series;
}

SvgPlotOptions paper_options() {
  SvgPlotOptions options;
  options.title = "RCS per active fog layers";
  options.x_label = "active fog layers";
  options.y_label = "RCS (dBsm)";
  return options;
}

TEST(SvgPlot, WellFormedStandaloneSvg) {
  const std::string svg = box_plot_svg(paper_like_series(), paper_options());
  EXPECT_EQ(xml_error(svg), "");
  EXPECT_TRUE(svg.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\""));
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"720.00\""),
            std::string::npos);
  EXPECT_TRUE(svg.ends_with("</svg>\n"));
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
  EXPECT_EQ(count(svg, "class=\"legend-mean\""), 1u);
  EXPECT_EQ(count(svg, ">n = 200</text>"), 4u);
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

TEST(SvgPlot, NoDetectionsSeries) {
  const std::string svg = box_plot_svg(paper_like_series(), paper_options());
  EXPECT_EQ(count(svg, ">no detections</text>"), 1u);
  EXPECT_EQ(count(svg, ">n = 0</text>"), 1u);

  // Only empty series: still a valid plot with a default axis.
  const std::vector<BoxPlotSeries> none = {{"0", BoxPlot{}}, {"1", BoxPlot{}}};
  const std::string empty_svg = box_plot_svg(none, paper_options());
  EXPECT_EQ(xml_error(empty_svg), "");
  EXPECT_EQ(count(empty_svg, ">no detections</text>"), 2u);
  EXPECT_EQ(count(empty_svg, "class=\"box\""), 0u);
}

TEST(SvgPlot, BoxGeometryFollowsTheQuartiles) {
  // One series 10..20 dBsm: axis 10..20 in steps of 2, plot from y = 60 (top) to 390 (bottom);
  // q3 = 17.5 maps to 390 - 0.75 * 330 = 142.50 and the box height is (17.5 - 12.5) * 33 = 165.
  std::vector<double> v;
  for (int i = 0; i <= 20; ++i) v.push_back(10.0 + 0.5 * i);
  const std::vector<BoxPlotSeries> series = {{"a", box_plot(v)}};
  const std::string svg = box_plot_svg(series, paper_options());
  EXPECT_NE(svg.find("class=\"box\" x=\"348.00\" y=\"142.50\" width=\"80.00\" height=\"165.00\""),
            std::string::npos)
      << svg;
  for (const char* tick : {">10<", ">12<", ">14<", ">16<", ">18<", ">20<"}) {
    EXPECT_EQ(count(svg, tick), 1u) << tick;
  }
}

TEST(SvgPlot, EscapesText) {
  std::vector<BoxPlotSeries> series = {{"A & B <1>", box_plot(std::vector<double>{1, 2, 3})}};
  SvgPlotOptions options = paper_options();
  options.title = "x < y & \"quoted\"";
  const std::string svg = box_plot_svg(series, options);
  EXPECT_EQ(xml_error(svg), "");
  EXPECT_NE(svg.find(">A &amp; B &lt;1&gt;</text>"), std::string::npos);
  EXPECT_NE(svg.find(">x &lt; y &amp; &quot;quoted&quot;</text>"), std::string::npos);
  EXPECT_EQ(svg.find("A & B"), std::string::npos);
}

TEST(SvgPlot, DeterministicBytes) {
  const std::vector<BoxPlotSeries> series = paper_like_series();
  const std::vector<BoxPlotSeries> copy = series;
  EXPECT_EQ(box_plot_svg(series, paper_options()), box_plot_svg(copy, paper_options()));
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

TEST(SvgConfig, EveryInvalidInputNamesItsField) {
  const std::vector<BoxPlotSeries> series = paper_like_series();
  const auto expect_field = [](auto&& f, const std::string& field) { EXPECT_EQ(test_support::rejected_field(f), field); };
  expect_field([&] { box_plot_svg(std::span<const BoxPlotSeries>{}, paper_options()); }, "series");
  SvgPlotOptions narrow = paper_options();
  narrow.width_px = 10;
  expect_field([&] { box_plot_svg(series, narrow); }, "svg.width_px");
  SvgPlotOptions flat = paper_options();
  flat.height_px = std::numeric_limits<double>::quiet_NaN();
  expect_field([&] { box_plot_svg(series, flat); }, "svg.height_px");
  std::vector<BoxPlotSeries> broken = series;
  broken[1].box.median = std::numeric_limits<double>::infinity();
  expect_field([&] { box_plot_svg(broken, paper_options()); }, "series[1].box");
  expect_field([] { nice_axis_ticks(2.0, 1.0); }, "high");
  expect_field([] { nice_axis_ticks(std::numeric_limits<double>::quiet_NaN(), 1.0); }, "low");
  expect_field([] { nice_axis_ticks(0.0, 1.0, 1); }, "max_intervals");
}

}  // namespace
}  // namespace fogradar::stats
