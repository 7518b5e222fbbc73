#include <cmath>
#include <cstdio>

#include "fogradar/camera/camera.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/histogram.hpp"
#include "fogradar/stats/line_plot.hpp"

namespace fogradar::camera {
namespace {

using stats::format_fixed;
using stats::format_number;

// JSON numbers: NaN (no value) as null.
nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

// "3 layers", or "not reached" with the last step's contrast.
std::string limit_verdict(const CameraSummary& summary) {
  if (summary.sensor_limit_layers) {
    return std::to_string(*summary.sensor_limit_layers) +
           (*summary.sensor_limit_layers == 1 ? " layer" : " layers");
  }
  if (summary.steps.empty()) return "not reached";
  return "not reached (|contrast| " +
         format_fixed(std::abs(summary.steps.back().target_contrast), 3) + " at the last step)";
}

}  // namespace

CameraSummary summarize(const CameraParams& params, const std::vector<CameraStepResult>& steps) {
  params.validate();
  CameraSummary summary;
  summary.criterion = "first step at which |target contrast| < " +
                      format_number(params.contrast_threshold) +
                      " (CIE, Weber contrast of the ROI's target vs background, linearised grey)";
  for (const CameraStepResult& step : steps) {
    if (step.frames.empty()) {
      throw InvalidParameter("steps", "a camera step holds no frames: must hold at least one");
    }
    CameraStepSummary s;
    s.active_layers = step.active_layers;
    s.frames = step.frames.size();
    double contrast = 0.0;
    double edges = 0.0;
    for (const CameraFrame& frame : step.frames) {
      for (std::size_t g = 0; g < grey_levels; ++g) s.histogram[g] += frame.histogram[g];
      contrast += frame.target_contrast;
      edges += static_cast<double>(frame.edges_above_threshold);
    }
    const stats::HistogramSummary h = stats::histogram_summary(s.histogram);
    s.mean_grey = h.mean;
    s.std_grey = h.std_dev;
    s.p05_grey = stats::histogram_quantile_type7(s.histogram, 0.05);
    s.p95_grey = stats::histogram_quantile_type7(s.histogram, 0.95);
    s.tonal_range = s.p95_grey - s.p05_grey;
    s.target_contrast = contrast / static_cast<double>(s.frames);
    s.relative_contrast = s.target_contrast / step.optics.clear_contrast;
    s.edges_above_threshold = edges / static_cast<double>(s.frames);
    s.clear_edges = step.optics.clear_edges;
    s.transmittance = step.optics.transmittance.empty() ? 1.0 : step.optics.transmittance[0];
    summary.clear_contrast = step.optics.clear_contrast;
    if (!summary.sensor_limit_layers && std::abs(s.target_contrast) < params.contrast_threshold) {
      summary.sensor_limit_layers = s.active_layers;
    }
    summary.steps.push_back(s);
  }
  return summary;
}

std::string histograms_csv(const CameraSummary& summary) {
  std::string csv = "active_layers,grey_level,count\n";
  for (const CameraStepSummary& s : summary.steps) {
    for (std::size_t g = 0; g < grey_levels; ++g) {
      csv += std::to_string(s.active_layers) + "," + std::to_string(g) + "," +
             std::to_string(s.histogram[g]) + "\n";
    }
  }
  return csv;
}

sensor::StepTable step_table(const CameraSummary& summary) {
  using S = CameraStepSummary;
  const std::vector<S>& steps = summary.steps;
  sensor::StepTable t(steps.size());
  t.integer("active_layers", "", steps, [](const S& s) { return s.active_layers; });
  t.integer("frames", "", steps, [](const S& s) { return s.frames; });
  // The CSV writes its numbers to 10 significant digits.
  const auto number = [&t, &steps](const char* name, double S::*field) {
    t.number(name, "", steps, [field](const S& s) { return s.*field; }).csv_digits(10);
  };
  number("mean_grey", &S::mean_grey);
  number("std_grey", &S::std_grey);
  number("p05_grey", &S::p05_grey);
  number("p95_grey", &S::p95_grey);
  number("tonal_range", &S::tonal_range);
  number("target_contrast", &S::target_contrast);
  number("relative_contrast", &S::relative_contrast);
  number("edges_above_threshold", &S::edges_above_threshold);
  t.integer("clear_edges", "", steps, [](const S& s) { return s.clear_edges; });
  number("transmittance", &S::transmittance);
  t.text("grey_range", "", steps, [](const S& s) {
     return format_fixed(s.p05_grey, 0) + "-" + format_fixed(s.p95_grey, 0);
   }).printed_only();

  const auto fixed = [](const char* head, std::size_t width, int decimals) {
    return sensor::Printed{
        .heads = {head}, .width = width, .precision = decimals, .signless_zero = true};
  };
  t.print_layout("        ", "");
  t.print("active_layers", {.heads = {"layers"}, .width = 6});
  t.print("mean_grey", fixed("mean", 7, 1));
  t.print("std_grey", fixed("std", 7, 1));
  t.print("grey_range", {.heads = {"p05-p95"}, .width = 9});
  t.print("target_contrast", fixed("contrast", 10, 3));
  t.print("relative_contrast", fixed("rel.contrast", 14, 3));
  t.print("edges_above_threshold", fixed("edges>thr", 11, 1));
  t.print("clear_edges", {.heads = {" (clear)"}, .width = 0, .prefix = " (", .suffix = ")"});
  return t;
}

nlohmann::json summary_json(const CameraSummary& summary) {
  nlohmann::json object = {{"criterion", summary.criterion},
                           {"clear_contrast", json_number(summary.clear_contrast)},
                           {"steps", step_table(summary).json()}};
  object["sensor_limit_layers"] =
      summary.sensor_limit_layers ? nlohmann::json(*summary.sensor_limit_layers) : nlohmann::json();
  return object;
}

std::string histograms_svg(const CameraSummary& summary) {
  std::vector<stats::LineSeries> series;
  for (const CameraStepSummary& s : summary.steps) {
    stats::LineSeries line;
    line.label = std::to_string(s.active_layers) + (s.active_layers == 1 ? " layer" : " layers") +
                 ", mean " + format_fixed(s.mean_grey, 1);
    // Fraction of pixels per grey level, so that steps with different frame counts compare.
    double total = 0.0;
    for (const std::uint64_t c : s.histogram) total += static_cast<double>(c);
    for (std::size_t g = 0; g < grey_levels; ++g) {
      line.x.push_back(static_cast<double>(g));
      line.y.push_back(100.0 * static_cast<double>(s.histogram[g]) / total);
    }
    line.marker_x = s.mean_grey;
    line.marker_label = "mean " + format_fixed(s.mean_grey, 1);
    series.push_back(std::move(line));
  }
  stats::LinePlotOptions options;
  options.title = "Camera ROI grey histograms per active fog layers (cf. paper Fig. 7)";
  options.x_label = "grey level (8 bit)";
  options.y_label = "pixels (% of ROI)";
  options.x_axis_exact = true;
  options.caption = {
      "Dashed lines: each step's mean grey. Histograms summed over the step's frames.",
      "Camera limit: " + limit_verdict(summary) + " (" + summary.criterion + ")."};
  return stats::line_plot_svg(series, options);
}

std::string roi_pgm(const CameraParams& params, const CameraFrame& frame) {
  if (frame.pixels.size() != params.roi.width_px * params.roi.height_px) {
    throw InvalidParameter("camera.write_roi_images",
                           "the frame holds no ROI image: camera.write_roi_images must be true");
  }
  std::string pgm = "P5\n" + std::to_string(params.roi.width_px) + " " +
                    std::to_string(params.roi.height_px) + "\n255\n";
  pgm.append(reinterpret_cast<const char*>(frame.pixels.data()), frame.pixels.size());
  return pgm;
}

std::string summary_table(const CameraSummary& summary) {
  std::string table = step_table(summary).printed();
  table += "camera limit (" + summary.criterion + "): " + limit_verdict(summary) + "\n";
  return table;
}

std::size_t memory_bytes(const CameraParams& params, std::size_t step_count) {
  const std::size_t per_frame =
      sizeof(CameraFrame) +
      (params.write_roi_images ? params.roi.width_px * params.roi.height_px : std::size_t{0});
  // The frames of every step, plus one frame's working buffers (cell means).
  const std::size_t cells = (params.roi.width_px / params.roi.cell_px + 1) *
                            (params.roi.height_px / params.roi.cell_px + 1);
  return step_count * (sizeof(CameraStepResult) + params.frames_per_step * per_frame) +
         cells * (sizeof(double) + 48);
}

}  // namespace fogradar::camera
