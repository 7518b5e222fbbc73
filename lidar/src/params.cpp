#include "fogradar/lidar/params.hpp"

#include <cmath>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/propagation/water_film.hpp"
#include "fogradar/stats/format.hpp"

namespace fogradar::lidar {
namespace {

// Scene coordinates are bounded by the largest chamber a scenario describes (propagation's 1e4 m).
constexpr double max_coordinate_m = 1e4;

}  // namespace

KeyTable<BackgroundSegment> background_segment_keys(std::string prefix) {
  KeyTable<BackgroundSegment> keys(prefix);
  struct Required {
    std::string name;
    std::function<double(const BackgroundSegment&)> get;
    Interval range;
  };
  std::vector<Required> required;
  // Every key is required (BackgroundSegment: NaN is "not given"). A missing key is refused only
  // after every given key's own check, so that a value the user wrote out of range is named first,
  // at its line; the range check alone would say "= nan: must be in ...", not that the key is
  // missing.
  const auto add = [&](std::string_view name, auto field, Interval range,
                       const std::string& meaning) -> Key<BackgroundSegment>& {
    Key<BackgroundSegment>& key = keys.number(name, field, range, "required; " + meaning);
    key.check = [get = key.get_number,
                 in_range = std::move(key.check)](const BackgroundSegment& s) {
      if (!std::isnan(get(s))) in_range(s);
    };
    required.push_back({key.name, key.get_number, range});
    return key;
  };
  const Interval coordinate = closed(-max_coordinate_m, max_coordinate_m);
  add("x0_m", FOGRADAR_KEY_FIELD(x0_m), coordinate, "segment start, along boresight");
  add("y0_m", FOGRADAR_KEY_FIELD(y0_m), coordinate, "segment start, lateral (+ right)");
  add("x1_m", FOGRADAR_KEY_FIELD(x1_m), coordinate, "segment end, along boresight")
      .with_check([key = prefix + "x1_m"](const BackgroundSegment& s) {
        if (s.x0_m == s.x1_m && s.y0_m == s.y1_m) {
          throw_invalid(key, s.x1_m, "a point distinct from (x0_m, y0_m): a segment of length > 0");
        }
      })
      .documented_as(coordinate.doc() + ", (x1, y1) ≠ (x0, y0)");
  add("y1_m", FOGRADAR_KEY_FIELD(y1_m), coordinate, "segment end, lateral");
  add("reflectivity", FOGRADAR_KEY_FIELD(reflectivity), closed(0.0, 1.0),
      "Lambertian reflectivity at the wavelength")
      .with_check([required](const BackgroundSegment& s) {
        for (const Required& key : required) {
          if (!std::isnan(key.get(s))) continue;
          throw InvalidParameter(key.name, key.name +
                                               " is missing: every [[lidar.background]] segment "
                                               "must give it, a number " +
                                               key.range.constraint());
        }
      });
  return keys;
}

KeyTable<LidarParams> lidar_keys() {
  KeyTable<LidarParams> keys("lidar.");
  // 400 nm - 2 um: the optical window of the Segelstein water index the fog is resolved with.
  keys.number("wavelength_m", FOGRADAR_KEY_FIELD(wavelength_m), closed(400e-9, 2e-6),
              "datasheet: 905 nm pulsed laser diode");
  keys.number("field_of_view_deg", FOGRADAR_KEY_FIELD(field_of_view_deg), closed(0.0, 360.0),
              "assumption: the part of the datasheet's 270° the study plots (fog, EVT, wall, "
              "barrels); keeps the paper run's lidar files at 2.2 MB");
  keys.number("angular_step_deg", FOGRADAR_KEY_FIELD(angular_step_deg), closed(0.01, 10.0),
              "datasheet")
      .with_check([](const LidarParams& p) {
        if (p.beam_count() > 100000) {
          throw_invalid("lidar.angular_step_deg", p.angular_step_deg,
                        "such that lidar.field_of_view_deg / step + 1 <= 100000 beams");
        }
      })
      .documented_as("[0.01, 10], at most 100000 beams");
  keys.number("scan_rate_hz", FOGRADAR_KEY_FIELD(scan_rate_hz), closed(0.1, 1000.0),
              "datasheet; sets the fluctuation's scan-to-scan correlation");
  keys.integer("scans_per_step", FOGRADAR_KEY_FIELD(scans_per_step), 1, 100000,
               "the study (40 scans per box of Fig. 6)");
  keys.number("min_range_m", FOGRADAR_KEY_FIELD(min_range_m), closed(0.0, 100.0),
              "datasheet (0.1–30 m)");
  keys.number(
      "max_range_m", FOGRADAR_KEY_FIELD(max_range_m), "(min_range_m, 1000]",
      [](const LidarParams& p) {
        if (!(p.max_range_m > p.min_range_m && p.max_range_m <= 1000.0)) {
          throw_invalid(
              "lidar.max_range_m", p.max_range_m,
              "in (lidar.min_range_m = " + stats::format_number(p.min_range_m) + ", 1000]");
        }
      },
      "datasheet guaranteed range; end of the recorded waveform");
  keys.number(
      "pulse_width_ns", FOGRADAR_KEY_FIELD(pulse_width_ns), closed(0.1, 1000.0),
      "assumption: pulsed 905 nm laser diodes in scanning rangefinders emit pulses of a few "
      "ns (FWHM of a Gaussian pulse); Hokuyo publishes none");
  keys.number(
      "sample_interval_ns", FOGRADAR_KEY_FIELD(sample_interval_ns), "[0.01, pulse_width_ns/2]",
      [](const LidarParams& p) {
        if (!(p.sample_interval_ns >= 0.01 && p.sample_interval_ns <= 0.5 * p.pulse_width_ns)) {
          throw_invalid("lidar.sample_interval_ns", p.sample_interval_ns,
                        "in [0.01, lidar.pulse_width_ns / 2 = " +
                            stats::format_number(0.5 * p.pulse_width_ns) +
                            "] (at least two samples per pulse width)");
        }
        // A record of more than 1e6 samples per beam is a typo, not a receiver.
        if (2.0 * p.max_range_m / 299792458.0 / (p.sample_interval_ns * 1e-9) > 1e6) {
          throw_invalid("lidar.sample_interval_ns", p.sample_interval_ns,
                        "such that 2 lidar.max_range_m / c / interval <= 1e6 samples per beam");
        }
      },
      "assumption: 10 samples per FWHM, so the leading-edge interpolation is exact to ~1 mm");
  keys.number("overlap_range_m", FOGRADAR_KEY_FIELD(overlap_range_m), closed(0.0, 100.0),
              "full overlap of the receiver's field of view with the beam from this range on, "
              "O(r) = min(1, (r/r_full)²); assumption: a coaxial design measuring from 0.1 m has "
              "full overlap within tens of cm; every surface and layer of the paper scene is "
              "beyond 2 m");
  keys.number("threshold_range_m", FOGRADAR_KEY_FIELD(threshold_range_m), closed(0.1, 1000.0),
              "the threshold is the noise-free peak of a Lambertian target of "
              "`threshold_reflectivity` at this range in clear air; datasheet: 30 m guaranteed on "
              "white Kent sheet");
  keys.number("threshold_reflectivity", FOGRADAR_KEY_FIELD(threshold_reflectivity),
              open_closed(0.0, 1.0),
              "assumption: white Kent sheet (drawing paper) ≈ 0.9 in the near infrared");
  keys.number("false_alarm_probability", FOGRADAR_KEY_FIELD(false_alarm_probability),
              open_closed(0.0, 0.1),
              "per range sample, noise alone (noise std = threshold / Φ⁻¹(1 − p)); assumption: a "
              "threshold 4.75 σ above the noise, a usual design for a pulse detector");
  keys.integer("max_echoes", FOGRADAR_KEY_FIELD(max_echoes), 1, 8,
               "datasheet (multi-echo, up to 3)");
  keys.number("min_echo_separation_m", FOGRADAR_KEY_FIELD(min_echo_separation_m),
              closed(0.0, 100.0),
              "leading edges closer than this merge into one echo; assumption: a little more than "
              "the pulse's range length c τ/2 = 0.75 m");
  keys.number("intensity_scale", FOGRADAR_KEY_FIELD(intensity_scale), positive(),
              "reported intensity = min(saturation, scale · peak / threshold); unit choice: the "
              "noise-free clear-weather EVT peak (M = 3.0 thresholds) reads 540, the study's "
              "value; it fixes units only");
  keys.number("intensity_saturation", FOGRADAR_KEY_FIELD(intensity_saturation), positive(),
              "assumption: a 16-bit intensity field; not reached in the paper scenario");
  keys.number("target_width_m", FOGRADAR_KEY_FIELD(target_width_m), closed(0.0, 100.0),
              "the EVT's rear at the chamber's target range; assumption: a car rear's width (the "
              "EVT's is not given)");
  keys.number("target_offset_m", FOGRADAR_KEY_FIELD(target_offset_m), closed(-100.0, 100.0),
              "lateral position of the EVT's centre; the study: the EVT on boresight");
  keys.number("target_reflectivity", FOGRADAR_KEY_FIELD(target_reflectivity), closed(0.0, 1.0),
              "at the wavelength, Lambertian; assumption: a mid value of car body panels at 905 nm "
              "(dark paints ~0.05, white ~0.8)");
  keys.number("fog_width_m", FOGRADAR_KEY_FIELD(fog_width_m), closed(0.0, max_coordinate_m),
              "lateral width of the fog bank, centred on boresight; assumption: the fog bank "
              "between the barrels of Fig. 2; the study gives no width");
  keys.number("height_m", FOGRADAR_KEY_FIELD(height_m), closed(0.0, 100.0),
              "the scan plane's height above the floor, where it cuts the room's objects "
              "([[chamber.objects]]); assumption: the study gives none: 0.5 m, radar.height_m's "
              "default, the two sensors side by side; below a rain barrel's top, as Fig. 5's "
              "barrel points need");
  keys.number(
      "window_water_film_m", FOGRADAR_KEY_FIELD(window_water_film_m), "0, or [1e-6, 0.01]",
      [](const LidarParams& p) {
        propagation::require_window_film("lidar.window_water_film_m", p.window_water_film_m);
      },
      "flat water film on the window (the study's water-covered sensor): Fresnel and "
      "absorption, out and back, against the dry window; droplets' scattering not modelled");
  keys.table_array("background", FOGRADAR_KEY_FIELD(background), &background_segment_keys, 1000,
                   "≤ 1000 segments",
                   "static reflecting segments `[[lidar.background]]` besides the room "
                   "([chamber.room] walls, [[chamber.objects]]), for what it does not describe; "
                   "each with every key below "
                   "(none has a default; a segment that lacks one is refused); none by default: "
                   "the study's wall and rain barrels are the paper scenario's room");
  keys.number("fog_fluctuation.log_std", FOGRADAR_KEY_FIELD(fog_fluctuation.log_std),
              closed(0.0, 2.0),
              "scan-to-scan fluctuation of each layer's optical depth (lognormal, unit mean); "
              "assumption: ±20 % variation of a fogger-fed layer's optical depth");
  keys.number("fog_fluctuation.correlation_time_s",
              FOGRADAR_KEY_FIELD(fog_fluctuation.correlation_time_s), positive(),
              "AR(1) correlation time of the fluctuation; assumption: eddies of ~0.5 m carried at "
              "~1 m/s by the barrels' fans")
      .when([](const LidarParams& p) { return p.fog_fluctuation.log_std > 0.0; },
            "with lidar.fog_fluctuation.log_std > 0 (0: no fluctuation to correlate)");
  return keys;
}

void LidarParams::validate() const { lidar_keys().check(*this); }

double LidarParams::beam_angle_deg(std::size_t beam) const {
  return -0.5 * field_of_view_deg + static_cast<double>(beam) * angular_step_deg;
}

std::size_t LidarParams::samples_per_beam() const {
  return static_cast<std::size_t>(
             std::floor(2.0 * max_range_m / speed_of_light_m_per_s / (sample_interval_ns * 1e-9))) +
         1;
}

std::size_t LidarParams::beam_count() const {
  return static_cast<std::size_t>(std::floor(field_of_view_deg / angular_step_deg + 1e-9)) + 1;
}

}  // namespace fogradar::lidar
