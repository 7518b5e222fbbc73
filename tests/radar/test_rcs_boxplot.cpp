// The radar's RCS box plot of a run (radar_rcs_boxplot.svg) from a hand-made summary: well-formed
// XML, scenario text in the title and caption, "n" the measurements per step as in the printed
// table (detections stated separately), the detection-rate strip, the sensor-limit mark at its
// step, steps without a target detection marked, legend entries, no "tracked" wording, labels of a
// 41-step and a 101-step chamber that do not overlap; the printed table's fog detections and
// dashes; its ADC clipping line.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "fogradar/radar/outputs.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "radar_sensor.hpp"
#include "svg_check.hpp"

namespace fogradar::experiment {
namespace {

using radar::RadarSummary;
using radar::StepSummary;
using test_support::count;
using test_support::elements_of_class;
using test_support::texts_of_class;

// Steps 0 .. steps-1 with 200 measurements each; `detections(k)` of them detect the target with the
// RCS values 10 - k + 0.01 j, j = 0 .. detections - 1.
template <class Detections>
RadarSummary summary_of(std::size_t steps, Detections&& detections) {
  RadarSummary summary;
  for (std::size_t k = 0; k < steps; ++k) {
    StepSummary s{};
    s.active_layers = k;
    s.n = 200;
    s.detections = detections(k);
    s.detection_rate = static_cast<double>(s.detections) / static_cast<double>(s.n);
    std::vector<double> rcs;
    for (std::size_t j = 0; j < s.detections; ++j)
      rcs.push_back(10.0 - static_cast<double>(k) + 0.01 * static_cast<double>(j));
    s.rcs = stats::box_plot(rcs);
    summary.steps.push_back(s);
  }
  return summary;
}

// The box plot of `summary` as the radar of scenario `s` draws it.
std::string rcs_boxplot_svg(const Scenario& s, const RadarSummary& summary) {
  return radar::rcs_boxplot_svg(radar_of(s), s.context(), summary);
}

// The paper scenario's five steps: detections 200, 150, 50, 0, 0; the limit at 2 layers.
RadarSummary losing_summary() {
  const std::size_t detections[] = {200, 150, 50, 0, 0};
  RadarSummary summary = summary_of(5, [&](std::size_t k) { return detections[k]; });
  summary.sensor_limit_layers = 2;
  return summary;
}

TEST(RcsBoxplot, WellFormedWithScenarioTitleAndCaption) {
  const std::string svg = rcs_boxplot_svg(paper_scenario(), losing_summary());
  EXPECT_EQ(test_support::xml_error(svg), "");
  EXPECT_EQ(svg.find("tracked"), std::string::npos);
  const auto title = texts_of_class(svg, "title");
  ASSERT_EQ(title.size(), 1u);
  EXPECT_NE(title[0].content.find("EVT rear 10 dBsm"), std::string::npos) << title[0].content;
  EXPECT_NE(title[0].content.find("\u03b2(550 nm) = 900 /km"), std::string::npos)
      << title[0].content;
  std::string caption;
  for (const auto& line : texts_of_class(svg, "caption")) {
    // Long paragraphs are broken at spaces into lines that fit the plot's width.
    EXPECT_LE(line.content.size(), 140u + 20u) << line.content;  // UTF-8: up to 20 extra bytes
    caption += line.content + " ";
  }
  for (const char* part :
       {"4 \u00d7 1 m fog layers", "lognormal droplets, median diameter 1 \u00b5m", "\u03c3g = 1.5",
        "CFAR CA", "P_fa = 1e-06", "n = 200 measurements per step", "seed 1",
        "detection rate = detections / n", "Sensor limit: 2 active layers; criterion: first"}) {
    EXPECT_NE(caption.find(part), std::string::npos) << part << " not in\n" << caption;
  }

  // The fog density as given: LWC or visibility instead of beta_550.
  Scenario lwc = paper_scenario();
  lwc.fog.density = propagation::LiquidWaterContent{0.25};
  lwc.fog.droplets = propagation::Monodisperse{200e-6};
  const std::string lwc_svg = rcs_boxplot_svg(lwc, losing_summary());
  EXPECT_NE(lwc_svg.find("LWC = 0.25 g/m\u00b3"), std::string::npos);
  EXPECT_NE(lwc_svg.find("monodisperse droplets of 200 \u00b5m"), std::string::npos);
  EXPECT_EQ(lwc_svg.find("\u03b2(550 nm)"), std::string::npos);
}

// n is the number of measurements (200), as in the printed table, not the number of detections.
TEST(RcsBoxplot, NCountsMeasurementsAndDetectionsAreSeparate) {
  const std::string svg = rcs_boxplot_svg(paper_scenario(), losing_summary());
  EXPECT_NE(
      svg.find(
          "<title>1 active layer: n = 200 measurements, 150 with an associated target detection "
          "(75.0 %)"),
      std::string::npos);
  EXPECT_NE(
      svg.find(
          "<title>3 active layers: n = 200 measurements, 0 with an associated target detection"),
      std::string::npos);
  EXPECT_EQ(svg.find("n = 150"), std::string::npos);
  EXPECT_EQ(svg.find("n = 50"), std::string::npos);
  EXPECT_NE(summary_table(losing_summary()).find("     1   200     75.0"), std::string::npos);
}

// The printed table shows the confusion rate (the limit's criterion) and the fog detections per
// frame, and an en dash, never "nan", for a value that does not exist.
TEST(RcsBoxplot, TableShowsConfusionFogDetectionsAndNoNan) {
  RadarSummary summary = losing_summary();
  summary.steps[2].fog_detections_per_frame = 12.5;
  summary.steps[2].confusion_rate = 0.805;
  summary.steps[0].median_shift_ci95 = {std::nan(""), std::nan("")};
  summary.steps[0].p_value = std::nan("");
  summary.steps[3].rcs.median = std::nan("");
  const std::string table = summary_table(summary);
  EXPECT_EQ(table.find("nan"), std::string::npos) << table;
  EXPECT_NE(table.find("det./f"), std::string::npos) << table;
  EXPECT_NE(table.find("confused %: no target detection"), std::string::npos) << table;
  std::istringstream lines(table);
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(lines, line)) rows.push_back(line);
  ASSERT_GE(rows.size(), 7u);
  // Row of step 2: layers, n, target det. %, confused %, false assoc. %, fog det./f.
  std::istringstream step2(rows[4]);
  std::string layers, n, target, confused, assoc, fog;
  step2 >> layers >> n >> target >> confused >> assoc >> fog;
  EXPECT_EQ(layers, "2*");  // fewer than half detected (SurvivorsOnlyStepsSaySo)
  EXPECT_EQ(confused, "80.5");
  EXPECT_EQ(fog, "12.500");
  // Step 0: the shift's interval and p are the last numbers but the loss, each an en dash.
  EXPECT_NE(rows[2].find("\u2013         \u2013         \u2013"), std::string::npos) << rows[2];
  // The columns stay aligned: an en dash takes one column, as a digit does.
  const auto columns = [](const std::string& text) {
    std::size_t count = 0;
    for (const unsigned char c : text) count += (c & 0xC0) != 0x80;
    return count;
  };
  EXPECT_EQ(columns(rows[2]), columns(rows[3])) << rows[2] << "\n" << rows[3];
  EXPECT_EQ(columns(rows[5]), columns(rows[3])) << rows[5] << "\n" << rows[3];
}

// A step where some but fewer than half the measurements detected the target (step 2: 50 of 200)
// is marked in the table and the box plot's caption as the surviving detections' statistics;
// steps at 100 % and 75 % (0, 1) and without a detection (3, 4) are not.
TEST(RcsBoxplot, SurvivorsOnlyStepsSaySo) {
  const std::string table = summary_table(losing_summary());
  EXPECT_NE(table.find("\n    2*   200     25.0"), std::string::npos) << table;
  for (const char* unmarked : {"\n     0   200", "\n     1   200", "\n     3   200"}) {
    EXPECT_NE(table.find(unmarked), std::string::npos) << unmarked << "\n" << table;
  }
  EXPECT_NE(table.find("*: fewer than half the measurements detected the target"),
            std::string::npos);
  std::string caption;
  for (const auto& line :
       texts_of_class(rcs_boxplot_svg(paper_scenario(), losing_summary()), "caption")) {
    caption += line.content + " ";
  }
  EXPECT_NE(caption.find("Active layers 2: fewer than half the measurements detected the target; "
                         "the box shows the surviving detections only."),
            std::string::npos)
      << caption;
  RadarSummary all_detected = losing_summary();
  for (auto& step : all_detected.steps) {
    step.detections = step.n;
    step.detection_rate = 1.0;
  }
  EXPECT_EQ(summary_table(all_detected).find('*'), std::string::npos);
}

// The table states ADC clipping after its footnotes, only when a step clipped and only for the
// steps that did (steps 0 and 3 here); without clipping there is no such line.
TEST(RcsBoxplot, TableStatesAdcClippingOnlyWhenAStepClipped) {
  EXPECT_EQ(summary_table(losing_summary()).find("ADC clipping"), std::string::npos);
  RadarSummary summary = losing_summary();
  summary.steps[0].adc_clipped_fraction = 0.123;
  summary.steps[3].adc_clipped_fraction = 0.005;
  const std::string table = summary_table(summary);
  const std::string line =
      "\nADC clipping: 12.3 % of the samples at 0 active layers, 0.5 % at 3 active layers\n";
  EXPECT_NE(table.find(line), std::string::npos) << table;
  EXPECT_GT(table.find("ADC clipping"), table.find("\u2013: no such value"));
  EXPECT_GT(table.find("ADC clipping"), table.find("*: fewer than half"));
  EXPECT_EQ(table.find("at 1 active layer"), std::string::npos) << table;
  // The detections the clipping made, per frame, for the same steps.
  summary.steps[0].clipping_detections_per_frame = 15.5;
  EXPECT_NE(summary_table(summary).find(
                "\nclipping detections (its harmonics and intermodulation products, not false "
                "alarms): 15.500 per frame at 0 active layers, 0.000 per frame at 3 active "
                "layers\n"),
            std::string::npos)
      << summary_table(summary);
  summary.steps[0].adc_clipped_fraction = 0.0;
  summary.steps[3].adc_clipped_fraction = 0.0;
  summary.steps[1].adc_clipped_fraction = 1.0;
  summary.steps[2].adc_clipped_fraction = 0.9999;
  EXPECT_NE(summary_table(summary).find(">99.9 % at 2 active layers\n"), std::string::npos)
      << summary_table(summary);
  summary.steps[2].adc_clipped_fraction = 0.0;
  const std::string all = summary_table(summary);
  EXPECT_NE(all.find("\nADC clipping: 100 % of the samples at 1 active layer\n"), std::string::npos)
      << all;
}

// Rate bars of 56 px full height: 200/200, 150/200, 50/200, 0, 0 -> 56, 42, 14, 0, 0 px.
TEST(RcsBoxplot, DetectionRateStrip) {
  const std::string svg = rcs_boxplot_svg(paper_scenario(), losing_summary());
  const auto bars = elements_of_class(svg, "rect", "rate");
  ASSERT_EQ(bars.size(), 5u);
  const char* heights[] = {"56.00", "42.00", "14.00", "0.00", "0.00"};
  for (std::size_t k = 0; k < bars.size(); ++k) {
    EXPECT_EQ(test_support::attribute(svg, bars[k], "height"), heights[k]) << k;
  }
  EXPECT_EQ(count(svg, ">detection rate</text>"), 2u);  // strip title and legend
}

TEST(RcsBoxplot, SensorLimitMarkedAtItsStep) {
  const std::string svg = rcs_boxplot_svg(paper_scenario(), losing_summary());
  const auto labels = texts_of_class(svg, "category");
  ASSERT_EQ(labels.size(), 5u);
  ASSERT_EQ(labels[2].content, "2");
  const auto marks = elements_of_class(svg, "line", "mark");
  ASSERT_FALSE(marks.empty());
  for (const std::size_t mark : marks) {
    EXPECT_NEAR(std::stod(test_support::attribute(svg, mark, "x1")), labels[2].x, 0.005);
  }
  EXPECT_EQ(count(svg, ">sensor limit: 2 layers</text>"), 1u);

  RadarSummary unlimited = losing_summary();
  unlimited.sensor_limit_layers.reset();
  const std::string plain = rcs_boxplot_svg(paper_scenario(), unlimited);
  EXPECT_EQ(count(plain, "class=\"mark\""), 0u);
  EXPECT_NE(plain.find("not reached within 4 active layers"), std::string::npos);
}

TEST(RcsBoxplot, StepsWithoutDetectionAreMarked) {
  const std::string svg = rcs_boxplot_svg(paper_scenario(), losing_summary());
  const auto bands = elements_of_class(svg, "rect", "no-values-band");
  ASSERT_EQ(bands.size(), 2u);  // steps 3 and 4
  const auto labels = texts_of_class(svg, "category");
  ASSERT_EQ(labels.size(), 5u);
  for (std::size_t i = 0; i < 2; ++i) {
    const double x = std::stod(test_support::attribute(svg, bands[i], "x"));
    const double width = std::stod(test_support::attribute(svg, bands[i], "width"));
    EXPECT_NEAR(x + 0.5 * width, labels[3 + i].x, 0.01);
  }
  EXPECT_EQ(count(svg, "class=\"box\""), 3u);
  EXPECT_EQ(count(svg, ">no target detection</text>"), 3u);  // two wide bands and the legend
  for (const char* symbol : {"legend-box", "legend-median", "legend-whisker", "legend-empty",
                             "legend-mark", "legend-rate"}) {
    EXPECT_NE(svg.find(symbol), std::string::npos) << symbol;
  }
  // The legend names only symbols drawn: these boxes have no outliers.
  EXPECT_EQ(count(svg, "class=\"outlier\""), 0u);
  EXPECT_EQ(svg.find("legend-outlier"), std::string::npos);
}

TEST(RcsBoxplot, LongChambersKeepLabelsApart) {
  for (const std::size_t steps : {41u, 101u}) {
    const RadarSummary summary =
        summary_of(steps, [&](std::size_t k) { return k < steps / 2 ? 20u : 0u; });
    Scenario s = paper_scenario();
    s.chamber.layer_count = steps - 1;
    s.experiment.max_active_layers = steps - 1;
    const std::string svg = rcs_boxplot_svg(s, summary);
    EXPECT_EQ(test_support::xml_error(svg), "") << steps;
    EXPECT_EQ(test_support::text_overlap(svg, "category"), "") << steps;
    EXPECT_GE(texts_of_class(svg, "category").size(), 11u) << steps;  // every 10th or denser
    EXPECT_EQ(elements_of_class(svg, "rect", "no-values-band").size(), steps - steps / 2) << steps;
  }
}

// The origins plot (radar_origins.svg): one line per origin detected at some step, drawn at its
// per-measurement rate at each step, the target's always; an origin never detected named in the
// caption; the room beside the floor in both plots' captions, the floor-only hall's caption as
// before.
TEST(OriginsPlot, LinesForDetectedOriginsAndTheRoomInTheCaption) {
  RadarSummary summary = losing_summary();
  summary.steps[1].room_detections_per_frame = 2.0;
  summary.steps[4].multipath_detections_per_frame = 0.5;
  summary.steps[2].false_alarms_per_frame = 0.25;
  Scenario s = paper_scenario();
  const std::string svg = radar::origins_svg(radar_of(s), s.context(), summary);
  EXPECT_EQ(test_support::xml_error(svg), "");
  std::vector<std::string> legend;
  for (const auto& text : texts_of_class(svg, "legend-text")) legend.push_back(text.content);
  EXPECT_EQ(legend,
            (std::vector<std::string>{
                "target (associated, in the gate)", "multipath (ghosts of the target via the room)",
                "room (its objects, the back wall)", "noise (false alarms)"}));
  EXPECT_EQ(count(svg, "class=\"series\""), 4u);
  std::string caption;
  for (const auto& line : texts_of_class(svg, "caption")) caption += line.content + " ";
  for (const char* part : {"No detection at any step: fog, sidelobe, clipping (ADC).",
                           "Room: left wall 3 m to the left (concrete); 4 objects (4 cylinders).",
                           "floor multipath (concrete)", "CFAR CA", "seed 1"}) {
    EXPECT_NE(caption.find(part), std::string::npos) << part << " not in\n" << caption;
  }

  // A floor-only hall: no room line in either caption; a back wall and a plate are named.
  Scenario bare = paper_scenario();
  bare.chamber.room.left_wall.present = false;
  bare.chamber.room.objects.clear();
  for (const std::string& plot : {radar::origins_svg(radar_of(bare), bare.context(), summary),
                                  rcs_boxplot_svg(bare, summary)}) {
    EXPECT_EQ(plot.find("Room:"), std::string::npos);
  }
  Scenario walled = bare;
  walled.chamber.room.back_wall = {
      .present = true, .reflection = propagation::ReflectionCoefficient{-1.0}, .distance_m = 14.0};
  walled.chamber.room.objects.push_back({.shape = propagation::ObjectShape::plate});
  std::string walled_caption;
  for (const auto& line : texts_of_class(rcs_boxplot_svg(walled, summary), "caption"))
    walled_caption += line.content + " ";
  EXPECT_NE(walled_caption.find("Room: back wall 14 m ahead (reflection -1); 1 object (1 plate)."),
            std::string::npos)
      << walled_caption;
}

// A 41-step chamber (40 layers): one marker per step on the one line drawn (the target's, the
// others never detected), and the caption's 40 layers.
TEST(OriginsPlot, LongChamberHasAMarkerPerStep) {
  const RadarSummary summary = summary_of(41, [](std::size_t k) { return k < 20 ? 20u : 0u; });
  Scenario s = paper_scenario();
  s.chamber.layer_count = 40;
  s.experiment.max_active_layers = 40;
  const std::string svg = radar::origins_svg(radar_of(s), s.context(), summary);
  EXPECT_EQ(test_support::xml_error(svg), "");
  EXPECT_EQ(count(svg, "class=\"series\""), 1u);
  EXPECT_EQ(count(svg, "class=\"point-"), 41u);
  std::string caption;
  for (const auto& line : texts_of_class(svg, "caption")) caption += line.content + " ";
  EXPECT_NE(caption.find("40 \u00d7 1 m fog layers"), std::string::npos) << caption;
}

}  // namespace
}  // namespace fogradar::experiment
