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

std::string pad(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : std::string(width - text.size(), ' ') + text;
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

std::string summary_csv(const CameraSummary& summary) {
  std::string csv =
      "active_layers,frames,mean_grey,std_grey,p05_grey,p95_grey,tonal_range,target_contrast,"
      "relative_contrast,edges_above_threshold,clear_edges,transmittance\n";
  for (const CameraStepSummary& s : summary.steps) {
    csv += std::to_string(s.active_layers) + "," + std::to_string(s.frames) + "," +
           format_number(s.mean_grey) + "," + format_number(s.std_grey) + "," +
           format_number(s.p05_grey) + "," + format_number(s.p95_grey) + "," +
           format_number(s.tonal_range) + "," + format_number(s.target_contrast) + "," +
           format_number(s.relative_contrast) + "," + format_number(s.edges_above_threshold) + "," +
           std::to_string(s.clear_edges) + "," + format_number(s.transmittance) + "\n";
  }
  return csv;
}

nlohmann::json summary_json(const CameraSummary& summary) {
  nlohmann::json steps = nlohmann::json::array();
  for (const CameraStepSummary& s : summary.steps) {
    steps.push_back({{"active_layers", s.active_layers},
                     {"frames", s.frames},
                     {"mean_grey", json_number(s.mean_grey)},
                     {"std_grey", json_number(s.std_grey)},
                     {"p05_grey", json_number(s.p05_grey)},
                     {"p95_grey", json_number(s.p95_grey)},
                     {"tonal_range", json_number(s.tonal_range)},
                     {"target_contrast", json_number(s.target_contrast)},
                     {"relative_contrast", json_number(s.relative_contrast)},
                     {"edges_above_threshold", json_number(s.edges_above_threshold)},
                     {"clear_edges", s.clear_edges},
                     {"transmittance", json_number(s.transmittance)}});
  }
  nlohmann::json object = {{"criterion", summary.criterion},
                           {"clear_contrast", json_number(summary.clear_contrast)},
                           {"steps", steps}};
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

std::string step_table(const CameraSummary& summary) {
  std::string table =
      "        layers   mean    std  p05-p95  contrast  rel.contrast  edges>thr (clear)\n";
  for (const CameraStepSummary& s : summary.steps) {
    table += "        " + pad(std::to_string(s.active_layers), 6) +
             pad(format_fixed(s.mean_grey, 1), 7) + pad(format_fixed(s.std_grey, 1), 7) +
             pad(format_fixed(s.p05_grey, 0) + "-" + format_fixed(s.p95_grey, 0), 9) +
             pad(format_fixed(s.target_contrast, 3), 10) +
             pad(format_fixed(s.relative_contrast, 3), 14) +
             pad(format_fixed(s.edges_above_threshold, 1), 11) + " (" +
             std::to_string(s.clear_edges) + ")\n";
  }
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
