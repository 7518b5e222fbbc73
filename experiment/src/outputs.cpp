#include "fogradar/experiment/outputs.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>
#include <variant>
#include <vector>

#include "fogradar/camera/camera.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/lidar/outputs.hpp"
#include "fogradar/stats/format.hpp"
#include "fogradar/stats/svg_plot.hpp"

namespace fogradar::experiment {
namespace {

namespace fs = std::filesystem;

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// Shortest text that reads back to exactly `value` (std::to_chars); NaN -> "" (docs/scenario.md).
std::string exact(double value) { return stats::format_number(value, 0); }

std::string joined_outliers(const std::vector<double>& outliers) {
  std::string text;
  for (double v : outliers) {
    if (!text.empty()) text += ';';
    text += exact(v);
  }
  return text;
}

[[noreturn]] void refuse(const fs::path& path, const std::string& constraint) {
  throw_invalid("--out", path.string(), constraint);
}

std::string errno_text() { return std::strerror(errno); }

// Closes a file descriptor when it goes out of scope.
struct Descriptor {
  int fd;
  explicit Descriptor(int descriptor) : fd(descriptor) {}
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
};

// Writes `content` to a new file and fsyncs it, so the data is on disk before the rename that
// publishes it (a crash after the rename must not expose an empty file).
void write_file(const fs::path& path, const std::string& content) {
  const Descriptor file(::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
  if (file.fd < 0) refuse(path, "a writable location (" + errno_text() + ")");
  for (std::size_t written = 0; written < content.size();) {
    const ssize_t n = ::write(file.fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) refuse(path, "a writable location (" + errno_text() + ")");
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(file.fd) != 0) refuse(path, "a writable location (" + errno_text() + ")");
}

bool sync_directory(const fs::path& path) {
  const Descriptor directory(::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  return directory.fd >= 0 && ::fsync(directory.fd) == 0;
}

bool is_result_file(const fs::directory_entry& entry) {
  return is_result_file_name(entry.path().filename().string()) &&
         entry.symlink_status().type() == fs::file_type::regular;
}

// An existing `dir` must hold nothing but result files: it is replaced whole, and no file of the
// user's may go with it.
void require_only_result_files(const fs::path& dir, const fs::path& given) {
  std::error_code error;
  if (!fs::is_directory(fs::symlink_status(dir, error))) return;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (!is_result_file(entry)) {
      refuse(given, "a directory holding only fogradar's result files, as it is replaced whole ('" +
                        entry.path().filename().string() + "' is not one)");
    }
  }
}

// Scenario numbers in captions: three significant digits ("0.2", "1e-06").
std::string num(double value) { return stats::format_number(value, 3); }

std::string micrometres(double metres) { return num(metres * 1e6) + " \u00b5m"; }

std::string target_name(const TargetSpec& target) {
  return (target.model == TargetModel::evt ? "EVT rear " : "point target ") + num(target.rcs_dbsm) +
         " dBsm";
}

// The fog density as the scenario gives it (one of beta_550, LWC, visibility).
std::string fog_density(const propagation::FogDensity& density) {
  struct Describe {
    std::string operator()(const propagation::OpticalExtinction& d) const {
      return "\u03b2(550 nm) = " + num(d.per_km) + " /km";
    }
    std::string operator()(const propagation::LiquidWaterContent& d) const {
      return "LWC = " + num(d.g_per_m3) + " g/m\u00b3";
    }
    std::string operator()(const propagation::Visibility& d) const {
      return "visibility " + num(d.m) + " m";
    }
  };
  return std::visit(Describe{}, density);
}

std::string droplets(const propagation::DropSizeDistribution& dsd) {
  struct Describe {
    std::string operator()(const propagation::Monodisperse& d) const {
      return "monodisperse droplets of " + micrometres(d.diameter_m);
    }
    std::string operator()(const propagation::Lognormal& d) const {
      return "lognormal droplets, median diameter " + micrometres(d.median_diameter_m) +
             ", \u03c3g = " + num(d.geometric_std);
    }
    std::string operator()(const propagation::ModifiedGamma& d) const {
      const std::string family = d == propagation::advection_fog()   ? "advection-fog "
                                 : d == propagation::radiation_fog() ? "radiation-fog "
                                                                     : "";
      return family + "modified-gamma droplets (\u03b1 = " + num(d.alpha) +
             ", \u03b3 = " + num(d.gamma) + ", b = " + num(d.b_per_um_gamma) + " \u00b5m^-\u03b3)";
    }
  };
  return std::visit(Describe{}, dsd);
}

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// A window's name as a proper noun: "hann" -> "Hann", "blackman_harris" -> "Blackman-Harris".
std::string window_name(radar::WindowType window) {
  std::string out(radar::to_string(window));
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i] == '_') out[i] = '-';
    if (i == 0 || out[i - 1] == '-')
      out[i] = static_cast<char>(std::toupper(static_cast<unsigned char>(out[i])));
  }
  return out;
}

// Caption lines of at most this many characters fit the 960 px plot in a 12 px sans-serif face
// (measured in Chromium with Debian's fonts: 143 characters took 816 px).
constexpr std::size_t caption_line_chars = 140;

// Breaks `text` at spaces into lines of at most `width` characters (UTF-8 characters counted); a
// word longer than `width` gets a line of its own.
std::vector<std::string> wrap(std::string_view text, std::size_t width) {
  const auto chars = [](std::string_view s) {
    return static_cast<std::size_t>(std::count_if(
        s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
  };
  std::vector<std::string> lines;
  std::string current;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(' ', start), text.size());
    const std::string_view word = text.substr(start, end - start);
    if (!current.empty() && chars(current) + 1 + chars(word) > width) {
      lines.push_back(current);
      current.clear();
    }
    if (!current.empty()) current += ' ';
    current += word;
    start = end + 1;
  }
  if (!current.empty()) lines.push_back(current);
  return lines;
}

// "1 active layer", "3 active layers".
std::string counted(std::size_t count, std::string_view noun) {
  return std::to_string(count) + " " + std::string(noun) + (count == 1 ? "" : "s");
}

std::vector<std::string> plot_caption(const Scenario& scenario, const ExperimentSummary& summary) {
  const TargetSpec& t = scenario.target;
  const ChamberLayout& c = scenario.chamber;
  const radar::RadarParams& r = scenario.radar;
  const double target_range_m =
      c.sensor_gap_m + static_cast<double>(c.layer_count) * c.layer_length_m + c.target_gap_m;
  std::string target = "Target: " + target_name(t);
  if (t.model == TargetModel::evt) {
    target += " (five scattering centres)";
  } else {
    target += ", Swerling " + std::string(radar::to_string(t.swerling)) + ", " + num(t.height_m) +
              " m high";
  }
  target += t.floor_multipath
                ? ", floor multipath (reflection " + num(t.floor_reflection_coefficient) + ")"
                : ", no floor multipath";
  target += "; " + num(target_range_m) + " m from the radar behind " +
            std::to_string(c.layer_count) + " \u00d7 " + num(c.layer_length_m) + " m fog layers";
  std::string cfar = "CFAR " + upper(radar::to_string(r.cfar.kind)) + " (" +
                     std::to_string(r.cfar.guard_cells) + " guard + " +
                     std::to_string(r.cfar.training_cells) + " training cells per side";
  if (r.cfar.kind == radar::CfarKind::os) {
    cfar += ", rank " + std::to_string(r.cfar.effective_os_rank());
  }
  cfar += "), P_fa = " + num(r.cfar.false_alarm_probability);
  const std::string limit =
      summary.sensor_limit_layers
          ? counted(*summary.sensor_limit_layers, "active layer")
          : "not reached within " + counted(scenario.experiment.max_active_layers, "active layer");
  const std::vector<std::string> paragraphs = {
      "Boxes: RCS of each measurement's associated target detection; "
      "detection rate = detections / n.",
      target + ".",
      "Fog in each active layer: " + fog_density(scenario.fog.density) + "; " +
          droplets(scenario.fog.droplets) + "; " + num(scenario.fog.temperature_c) + " \u00b0C.",
      "Radar: " + num(r.sweep_bandwidth_hz * 1e-9) + " GHz " +
          std::string(radar::to_string(r.sweep_direction)) + "-sweep centred on " +
          num(r.centre_frequency_hz * 1e-9) + " GHz, " + window_name(r.window) + " window; " +
          cfar + ".",
      "n = " + std::to_string(scenario.experiment.measurements_per_step) +
          " measurements per step, seed " + std::to_string(scenario.experiment.seed) + ".",
      "Sensor limit: " + limit + "; criterion: " + sensor_limit_criterion + ".",
  };
  std::vector<std::string> lines;
  for (const std::string& paragraph : paragraphs) {
    const std::vector<std::string> wrapped = wrap(paragraph, caption_line_chars);
    lines.insert(lines.end(), wrapped.begin(), wrapped.end());
  }
  return lines;
}

// The category's tooltip: the table's numbers for this step.
std::string step_note(const StepSummary& s) {
  std::string note = counted(s.active_layers, "active layer") + ": n = " + std::to_string(s.n) +
                     " measurements, " + std::to_string(s.detections) +
                     " with an associated target detection (" +
                     stats::format_fixed(100.0 * s.detection_rate, 1) + " %)";
  if (s.rcs.n > 0) note += ", median RCS " + stats::format_fixed(s.rcs.median, 2) + " dBsm";
  return note + ", two-way fog loss " + stats::format_fixed(s.two_way_attenuation_db, 3) + " dB";
}

}  // namespace

std::string samples_csv(const ExperimentResult& result) {
  std::string out =
      "active_layers,measurement,detected,range_m,rcs_dbsm,snr_db,"
      "origin,fog_detections,false_alarms\n";
  for (const StepResult& step : result.steps) {
    for (std::size_t i = 0; i < step.records.size(); ++i) {
      const MeasurementRecord& r = step.records[i];
      out += std::to_string(step.active_layers) + ',' + std::to_string(i) + ',' +
             (r.detected ? "1," : "0,");
      if (r.associated) {
        out += exact(r.range_m) + ',' + exact(r.rcs_dbsm) + ',' + exact(r.snr_db) + ',' +
               std::string(radar::to_string(r.associated_origin));
      } else {
        out += ",,,";
      }
      out += ',' + std::to_string(r.fog_detections) + ',' + std::to_string(r.false_alarms) + '\n';
    }
  }
  return out;
}

std::string summary_csv(const ExperimentSummary& summary) {
  std::string out =
      "active_layers,n,detections,detection_rate,mean_dbsm,std_db,min_dbsm,q1_dbsm,median_dbsm,"
      "q3_dbsm,max_dbsm,whisker_low_dbsm,whisker_high_dbsm,outliers,median_shift_db,p_value,"
      "median_shift_ci95_low_db,median_shift_ci95_high_db,median_snr_db,two_way_attenuation_db,"
      "confusion_rate,false_association_rate,false_alarms_per_frame,fog_detections_per_frame\n";
  for (const StepSummary& s : summary.steps) {
    const stats::BoxPlot& b = s.rcs;
    const double numbers[] = {s.detection_rate, b.mean, b.std_dev, b.min,         b.q1,
                              b.median,         b.q3,   b.max,     b.whisker_low, b.whisker_high};
    const double after_outliers[] = {s.median_shift_db,        s.p_value,
                                     s.median_shift_ci95.low,  s.median_shift_ci95.high,
                                     s.median_snr_db,          s.two_way_attenuation_db,
                                     s.confusion_rate,         s.false_association_rate,
                                     s.false_alarms_per_frame, s.fog_detections_per_frame};
    out += std::to_string(s.active_layers) + ',' + std::to_string(s.n) + ',' +
           std::to_string(s.detections);
    for (double v : numbers) out += ',' + exact(v);
    out += ',' + joined_outliers(b.outliers);
    for (double v : after_outliers) out += ',' + exact(v);
    out += '\n';
  }
  return out;
}

const std::vector<std::string>& result_file_names() {
  static const std::vector<std::string> names = {
      "samples.csv",         "summary.csv",           "summary.json",
      "rcs_boxplot.svg",     "scenario.toml",         "lidar_echoes.csv",
      "lidar_summary.csv",   "lidar_summary.json",    "lidar_intensity_boxplot.svg",
      "lidar_scans.svg",     "camera_histograms.csv", "camera_summary.csv",
      "camera_summary.json", "camera_histograms.svg", "benchmark.svg"};
  return names;
}

bool is_result_file_name(const std::string& name) {
  const std::vector<std::string>& names = result_file_names();
  if (std::find(names.begin(), names.end(), name) != names.end()) return true;
  // camera_roi_<step>.pgm, one per step when camera.write_roi_images.
  const std::string prefix = "camera_roi_", suffix = ".pgm";
  if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return false;
  }
  const std::string digits =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  return digits.size() <= 7 &&
         std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string camera_roi_name(std::size_t step) {
  return "camera_roi_" + std::to_string(step) + ".pgm";
}

std::vector<SensorVerdict> sensor_verdicts(const ExperimentSummary& summary) {
  std::vector<SensorVerdict> verdicts;
  for (SensorId sensor : summary.sensors) {
    SensorVerdict v;
    v.sensor = sensor;
    if (sensor == SensorId::radar) {
      v.criterion = radar_criterion_short;
      v.sensor_limit_layers = summary.sensor_limit_layers;
      if (v.sensor_limit_layers) {
        v.margin.clear();
      } else if (summary.attenuation_margin_db) {
        v.margin = "median target SNR " + stats::format_fixed(*summary.attenuation_margin_db, 1) +
                   " dB above the CFAR threshold at " +
                   counted(summary.steps.empty() ? 0 : summary.steps.back().active_layers, "layer");
      } else {
        v.margin = "no target detection at the last step";
      }
    } else if (sensor == SensorId::lidar && summary.lidar) {
      v.criterion = lidar::lidar_sensor_limit_criterion;
      v.sensor_limit_layers = summary.lidar->sensor_limit_layers;
      if (!v.sensor_limit_layers && !summary.lidar->steps.empty()) {
        const lidar::LidarStepSummary& last = summary.lidar->steps.back();
        v.margin = "target told from fog in " +
                   stats::format_fixed(100.0 * last.target_told_rate, 1) + " % of the scans at " +
                   counted(last.active_layers, "layer") + " (fails below 50 %)";
      }
    } else if (sensor == SensorId::camera && summary.camera) {
      v.criterion = summary.camera->criterion;
      v.sensor_limit_layers = summary.camera->sensor_limit_layers;
      if (!v.sensor_limit_layers && !summary.camera->steps.empty()) {
        const camera::CameraStepSummary& last = summary.camera->steps.back();
        v.margin = "target contrast " + stats::format_fixed(last.target_contrast, 3) + " (" +
                   stats::format_fixed(100.0 * last.relative_contrast, 1) +
                   " % of clear weather) at " + counted(last.active_layers, "layer");
      }
    }
    verdicts.push_back(std::move(v));
  }
  return verdicts;
}

std::string sensor_tables(const ExperimentSummary& summary) {
  std::string out;
  for (SensorId sensor : summary.sensors) {
    out += std::string(sensor_name(sensor)) + '\n';
    if (sensor == SensorId::radar) out += summary_table(summary);
    if (sensor == SensorId::lidar && summary.lidar)
      out += lidar::lidar_summary_table(*summary.lidar);
    if (sensor == SensorId::camera && summary.camera) out += camera::step_table(*summary.camera);
    out += '\n';
  }
  return out;
}

std::string benchmark_table(const ExperimentSummary& summary) {
  std::string out = "benchmark (the study's criterion: active fog layers until the sensor fails)\n";
  for (const SensorVerdict& v : sensor_verdicts(summary)) {
    std::string name(sensor_name(v.sensor));
    name.resize(7, ' ');
    out += name + "layers to failure: " +
           (v.sensor_limit_layers ? std::to_string(*v.sensor_limit_layers)
                                  : "not reached (" + v.margin + ")") +
           "\n       criterion: " + v.criterion + "\n";
  }
  return out;
}

std::string summary_json(const Scenario& scenario, const ExperimentSummary& summary) {
  std::ostringstream scenario_json;
  scenario_json << toml::json_formatter{toml::parse(to_toml(scenario))};
  nlohmann::json steps = nlohmann::json::array();
  for (const StepSummary& s : summary.steps) {
    const stats::BoxPlot& b = s.rcs;
    steps.push_back(
        {{"active_layers", s.active_layers},
         {"n", s.n},
         {"detections", s.detections},
         {"detection_rate", s.detection_rate},
         {"mean_dbsm", number_or_null(b.mean)},
         {"std_db", number_or_null(b.std_dev)},
         {"min_dbsm", number_or_null(b.min)},
         {"q1_dbsm", number_or_null(b.q1)},
         {"median_dbsm", number_or_null(b.median)},
         {"q3_dbsm", number_or_null(b.q3)},
         {"max_dbsm", number_or_null(b.max)},
         {"whisker_low_dbsm", number_or_null(b.whisker_low)},
         {"whisker_high_dbsm", number_or_null(b.whisker_high)},
         {"outliers", b.outliers},
         {"median_shift_db", number_or_null(s.median_shift_db)},
         {"median_shift_ci95_db",
          {number_or_null(s.median_shift_ci95.low), number_or_null(s.median_shift_ci95.high)}},
         {"p_value", number_or_null(s.p_value)},
         {"median_snr_db", number_or_null(s.median_snr_db)},
         {"two_way_attenuation_db", s.two_way_attenuation_db},
         {"confusion_rate", s.confusion_rate},
         {"false_association_rate", s.false_association_rate},
         {"false_alarms_per_frame", s.false_alarms_per_frame},
         {"fog_detections_per_frame", s.fog_detections_per_frame}});
  }
  nlohmann::json sensors = nlohmann::json::object();
  for (const SensorVerdict& v : sensor_verdicts(summary)) {
    nlohmann::json entry = {
        {"sensor_limit_layers",
         v.sensor_limit_layers ? nlohmann::json(*v.sensor_limit_layers) : nlohmann::json(nullptr)},
        {"criterion", v.criterion},
        {"margin", v.margin}};
    if (v.sensor == SensorId::lidar && summary.lidar && summary.lidar_sensor) {
      entry["summary"] = lidar::lidar_summary_json(*summary.lidar_sensor, *summary.lidar);
    } else if (v.sensor == SensorId::camera && summary.camera) {
      entry["summary"] = camera::summary_json(*summary.camera);
    }
    sensors[std::string(sensor_name(v.sensor))] = std::move(entry);
  }
  nlohmann::json out = {
      {"scenario", nlohmann::json::parse(scenario_json.str())},
      {"steps", steps},
      {"sensor_limit_layers", summary.sensor_limit_layers
                                  ? nlohmann::json(*summary.sensor_limit_layers)
                                  : nlohmann::json(nullptr)},
      {"sensor_limit_criterion", sensor_limit_criterion},
      {"expected_false_alarm_cells_per_frame", summary.expected_false_alarm_cells_per_frame},
      {"attenuation_margin_db", summary.attenuation_margin_db
                                    ? number_or_null(*summary.attenuation_margin_db)
                                    : nlohmann::json(nullptr)},
      {"statistics",
       {{"quantiles", "Hyndman & Fan (1996) type 7 (R's default)"},
        {"whiskers", "Tukey: most extreme values within 1.5 IQR of the quartiles"},
        {"shift", "Hodges-Lehmann: median of all pairwise differences against the 0-layer series"},
        {"shift_interval",
         "distribution-free 95 %: order statistics of the pairwise differences from the "
         "Mann-Whitney U null distribution (Bauer 1972)"},
        {"shift_test", "Mann-Whitney U (two-sided) against the 0-layer series"},
        {"detections",
         "target detections only: a fog- or noise-origin detection in the gate is a miss"}}},
  };
  if (!std::count(summary.sensors.begin(), summary.sensors.end(), SensorId::radar)) {
    for (const char* radar_key :
         {"steps", "sensor_limit_layers", "sensor_limit_criterion",
          "expected_false_alarm_cells_per_frame", "attenuation_margin_db", "statistics"}) {
      out.erase(radar_key);
    }
  }
  out["sensors"] = std::move(sensors);
  return out.dump(2) + '\n';
}

std::string rcs_boxplot_svg(const Scenario& scenario, const ExperimentSummary& summary) {
  std::vector<stats::BoxPlotSeries> series;
  stats::SvgPlotOptions options;
  for (std::size_t i = 0; i < summary.steps.size(); ++i) {
    const StepSummary& s = summary.steps[i];
    series.push_back({std::to_string(s.active_layers), s.rcs, s.detection_rate, step_note(s)});
    if (summary.sensor_limit_layers == s.active_layers) options.marked_category = i;
  }
  options.title = "Target RCS against active fog layers: " + target_name(scenario.target) +
                  ", fog " + fog_density(scenario.fog.density);
  options.caption = plot_caption(scenario, summary);
  options.x_label = "active fog layers";
  options.y_label = "RCS of the associated target detection (dBsm)";
  // The plot area keeps its 406 px however many caption lines there are.
  options.height_px = 604.0 + 16.0 * static_cast<double>(options.caption.size());
  options.empty_label = "no target detection";
  options.rate_label = "detection rate";
  if (summary.sensor_limit_layers) {
    options.mark_label = "sensor limit: " + counted(*summary.sensor_limit_layers, "layer");
  }
  return stats::box_plot_svg(series, options);
}

std::string summary_table(const ExperimentSummary& summary) {
  std::ostringstream out;
  char line[320];
  constexpr const char* header = "%6s %5s %8s %8s %9s %9s %9s %9s %9s %9s %9s %19s %9s %8s\n";
  std::snprintf(line, sizeof line, header, "layers", "n", "target", "false", "false", "design",
                "median", "IQR", "mean", "std", "shift", "95 % interval", "p", "loss");
  out << line;
  std::snprintf(line, sizeof line, header, "", "", "det. %", "assoc %", "alarms/f", "/frame",
                "dBsm", "dB", "dBsm", "dB", "HL dB", "dB", "", "dB 2-way");
  out << line;
  for (const StepSummary& s : summary.steps) {
    std::snprintf(
        line, sizeof line,
        "%6zu %5zu %8.1f %8.1f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3g %8.4f\n",
        s.active_layers, s.n, 100.0 * s.detection_rate, 100.0 * s.false_association_rate,
        s.false_alarms_per_frame, summary.expected_false_alarm_cells_per_frame, s.rcs.median,
        s.rcs.q3 - s.rcs.q1, s.rcs.mean, s.rcs.std_dev, s.median_shift_db, s.median_shift_ci95.low,
        s.median_shift_ci95.high, s.p_value, s.two_way_attenuation_db);
    out << line;
  }
  out << "target det. %: a target-origin detection in the gate; false assoc. %: a fog or noise\n"
         "detection there instead (a miss); false alarms/f: noise-origin detections per frame;\n"
         "design /frame: P_fa x the cells the CFAR tests per frame; shift: Hodges-Lehmann shift\n"
         "against 0 layers with its distribution-free 95 % interval; p: Mann-Whitney U\n";
  out << "sensor limit: ";
  if (summary.sensor_limit_layers)
    out << counted(*summary.sensor_limit_layers, "active layer") << "\n";
  else
    out << "not reached\n";
  if (summary.attenuation_margin_db) {
    std::snprintf(line, sizeof line, "attenuation margin at the last step: %.1f dB\n",
                  *summary.attenuation_margin_db);
    out << line;
  }
  return out.str();
}

std::vector<std::pair<std::string, std::string>> result_files(const Scenario& scenario,
                                                              const ExperimentResult& result,
                                                              const ExperimentSummary& summary) {
  std::vector<std::pair<std::string, std::string>> files;
  if (scenario.runs(SensorId::radar)) {
    files.emplace_back("samples.csv", samples_csv(result));
    files.emplace_back("summary.csv", summary_csv(summary));
  }
  files.emplace_back("summary.json", summary_json(scenario, summary));
  if (scenario.runs(SensorId::radar))
    files.emplace_back("rcs_boxplot.svg", rcs_boxplot_svg(scenario, summary));
  files.emplace_back("scenario.toml", to_toml(scenario));
  if (result.lidar && summary.lidar) {
    const lidar::Lidar& sensor = *result.lidar;
    files.emplace_back("lidar_echoes.csv", lidar::lidar_echoes_csv(sensor, result.lidar_steps));
    files.emplace_back("lidar_summary.csv", lidar::lidar_summary_csv(*summary.lidar));
    files.emplace_back("lidar_summary.json",
                       lidar::lidar_summary_json(sensor, *summary.lidar).dump(2) + '\n');
    files.emplace_back("lidar_intensity_boxplot.svg",
                       lidar::lidar_intensity_boxplot_svg(sensor, *summary.lidar));
    files.emplace_back("lidar_scans.svg", lidar::lidar_scans_svg(sensor, result.lidar_steps));
  }
  if (result.camera && summary.camera) {
    files.emplace_back("camera_histograms.csv", camera::histograms_csv(*summary.camera));
    files.emplace_back("camera_summary.csv", camera::summary_csv(*summary.camera));
    files.emplace_back("camera_summary.json", camera::summary_json(*summary.camera).dump(2) + '\n');
    files.emplace_back("camera_histograms.svg", camera::histograms_svg(*summary.camera));
    if (scenario.camera.write_roi_images) {
      for (const camera::CameraStepResult& step : result.camera_steps) {
        if (step.frames.empty() || step.frames.front().pixels.empty()) continue;
        files.emplace_back(camera_roi_name(step.active_layers),
                           camera::roi_pgm(scenario.camera, step.frames.front()));
      }
    }
  }
  files.emplace_back("benchmark.svg", benchmark_svg(scenario, summary));
  return files;
}

OutputDirectory::OutputDirectory(fs::path dir) {
  const fs::path given = dir;
  std::error_code error;
  dir_ = fs::absolute(dir, error).lexically_normal();
  if (!dir_.has_filename()) dir_ = dir_.parent_path();  // "out/" names "out"
  const std::string name = dir_.filename().string();
  if (error || given.empty() || name.empty() || name == "." || name == "..") {
    refuse(given, "a directory name");
  }
  // Swapping the working directory away would leave this process and its shell in a deleted one.
  if (dir_ == fs::current_path(error).lexically_normal()) {
    refuse(given, "a directory other than the current one (it is replaced whole)");
  }
  parent_ = dir_.parent_path();
  const fs::file_status status = fs::symlink_status(dir_, error);
  if (fs::is_symlink(status))
    refuse(given, "a directory, not a symbolic link (it is replaced whole)");
  if (fs::exists(status) && !fs::is_directory(status)) refuse(given, "a directory");
  fs::create_directories(parent_, error);
  if (error) refuse(given, "a directory that can be created (" + error.message() + ")");

  // The lock file is unlinked by its holder before it lets go, so a run that locked a file someone
  // has since unlinked holds nothing: it checks that the name still leads to its file, else
  // retries.
  lock_path_ = parent_ / ("." + name + ".lock");
  for (;;) {
    lock_fd_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd_ < 0) refuse(given, "a directory whose parent is writable (" + errno_text() + ")");
    if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
      const bool busy = errno == EWOULDBLOCK;
      const std::string why = errno_text();
      ::close(lock_fd_);
      lock_fd_ = -1;
      if (busy)
        refuse(given, "a directory no other fogradar run is writing to (" + lock_path_.string() +
                          " is locked)");
      refuse(given, "a directory that can be locked (" + why + ")");
    }
    struct stat held {
    }, named{};
    if (::fstat(lock_fd_, &held) == 0 && ::stat(lock_path_.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino) {
      break;
    }
    ::close(lock_fd_);
    lock_fd_ = -1;
  }

  try {
    require_only_result_files(dir_, given);
    std::string staging =
        (parent_ / ("." + name + ".tmp-" + std::to_string(::getpid()) + "-XXXXXX")).string();
    if (::mkdtemp(staging.data()) == nullptr) {
      refuse(given, "a directory whose parent is writable (" + errno_text() + ")");
    }
    staging_ = staging;
  } catch (...) {
    ::unlink(lock_path_.c_str());
    ::close(lock_fd_);
    throw;
  }
}

OutputDirectory::~OutputDirectory() {
  std::error_code ignored;
  if (!staging_.empty()) fs::remove_all(staging_, ignored);
  ::unlink(lock_path_.c_str());
  ::close(lock_fd_);
}

bool OutputDirectory::replace(const std::vector<std::pair<std::string, std::string>>& files,
                              const std::function<bool()>& abandon) {
  for (const auto& [name, content] : files) write_file(staging_ / name, content);
  if (!sync_directory(staging_))
    refuse(staging_, "a directory that can be synced (" + errno_text() + ")");
  if (abandon && abandon()) return false;
  if (fs::exists(fs::symlink_status(dir_))) {
    // Checked again: a file put into `dir` while the run measured must not go with the old set.
    require_only_result_files(dir_, dir_);
    // Readers see the old set or the new one, never a mixture and never no directory at all.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, dir_.c_str(), RENAME_EXCHANGE) != 0) {
      refuse(dir_, "a directory that can be replaced (renameat2: " + errno_text() + ")");
    }
  } else if (::rename(staging_.c_str(), dir_.c_str()) != 0) {
    refuse(dir_, "a directory that can be created (" + errno_text() + ")");
  } else {
    staging_.clear();
  }
  // The set is in place; a failed sync of the rename is the kernel's to retry, not the run's
  // failure.
  sync_directory(parent_);
  // The previous set, now under the staging name: its result files by name, then the directory if
  // that left it empty (only a file put into `dir` in the instant of the swap would keep it).
  if (!staging_.empty()) {
    std::error_code ignored;
    for (const fs::directory_entry& entry : fs::directory_iterator(staging_, ignored)) {
      if (is_result_file(entry)) fs::remove(entry.path(), ignored);
    }
    fs::remove(staging_, ignored);
  }
  staging_.clear();
  return true;
}

}  // namespace fogradar::experiment
