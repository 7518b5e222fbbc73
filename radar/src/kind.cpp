// The radar as a sensor kind (sensor/sensor.hpp): its keys and checks, and the radar configured
// for a scenario: its memory and time, its raw data kinds, its view of the fog; its files.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/propagation/water.hpp"
#include "fogradar/radar/costs.hpp"
#include "fogradar/radar/scene.hpp"
#include "fogradar/radar/sensor.hpp"
#include "radar_sensor.hpp"

namespace fogradar::radar {
namespace {

// The CPU time of a frame, measured by bench/estimate_calibration (docs/scenario.md, "Time limit"):
// synthesis, the two transforms and the CFAR cost about cells x log2(cells) together (the FFTs'
// n log n, and a map that outgrows the caches); each object's peak search (the scene's few plus
// about P_fa x cells false alarms) sums over the whole map, so a frame grows as cells squared once
// P_fa x cells passes a few.
constexpr double frame_seconds_per_cell_log2_cell = 2.16e-10;
constexpr double frame_seconds_per_cell_and_object = 3.22e-10;
// Each static tone (a scene path, a fog clutter scatterer) is synthesised once per frame over one
// chirp's samples (synthesis.cpp), so the fog's clutter adds per tone and sample.
constexpr double frame_seconds_per_tone_sample = 3.38e-10;

// Wide CFAR windows (bench/estimate_calibration does not reach them; measured with profiles of
// 4096-65536 cells and n = 1000-32767, GO and OS, Blackman-Harris): CA, GO and SO add the N
// reference cells of each of a row's 2 (guard + n) edge cells one by one (cfar_kernels.cpp,
// edge_halves), 21 s for 10 rows of 4.3e9 additions; OS moves up to N sorted values per cell as its
// window slides (a memmove per cell), ~0.05 s per row of 65536 cells with N = 65534.
constexpr double frame_seconds_per_edge_reference = 4.9e-10;
constexpr double frame_seconds_per_sorted_reference = 1.3e-11;
// The range_doppler ring adds each cell's N reference cells one by one (OS: a selection over them),
// bench/cfar_clutter: 7.9 and 44 ms per map of 512 x 64 cells with N = 132.
constexpr double frame_seconds_per_ring_reference = 1.8e-9;
constexpr double frame_seconds_per_ring_selected_reference = 1.0e-8;

// The fog clutter's tones of a frame, averaged over the steps: clutter_scatterers_per_bin in every
// range bin of every active layer that holds water (scene.cpp, add_fog_clutter).
double mean_clutter_tones(const SensorParams& p, const sensor::Context& context) {
  const double bin_m = derive(p.radar).range_bin_m;
  const auto wet = [](const propagation::FogSpec& fog) {
    if (const auto* lwc = std::get_if<propagation::LiquidWaterContent>(&fog.density))
      return lwc->g_per_m3 > 0.0;
    if (const auto* beta = std::get_if<propagation::OpticalExtinction>(&fog.density))
      return beta->per_km > 0.0;
    return true;
  };
  double tones = 0.0;
  for (std::size_t k = 0; k < context.steps; ++k) {
    const propagation::ActiveLayers active = context.active(k);
    for (std::size_t i = 0; i < context.chamber.layers.size(); ++i) {
      const propagation::FogLayerSpec& layer = context.chamber.layers[i];
      if (!active[i] || !wet(layer.fog)) continue;
      tones += std::ceil(layer.length_m / bin_m) * p.clutter_scatterers_per_bin;
    }
  }
  return tones / static_cast<double>(std::max<std::size_t>(context.steps, 1));
}
constexpr double scene_objects_per_frame = 3.0;

double mib(std::size_t bytes) {
  return static_cast<double>(bytes) / static_cast<double>(std::size_t{1} << 20);
}

// The radar for one scenario: its parameters, checked against the chamber, and the context.
class Configured : public sensor::ConfiguredSensor {
 public:
  Configured(const SensorParams& params, const sensor::Context& context)
      : p_(params), context_(context) {}

  std::size_t items_per_step() const override { return p_.measurements_per_step; }

  sensor::MemoryPart memory(unsigned threads) const override {
    const MemoryEstimate e = memory_estimate(p_, context_.steps * p_.measurements_per_step);
    std::ostringstream detail;
    detail.precision(6);
    detail << "radar.samples_per_chirp = " << p_.radar.samples_per_chirp
           << " x radar.chirps_per_frame = " << p_.radar.chirps_per_frame << ": " << threads
           << " x " << mib(e.per_thread_bytes)
           << " MiB frame workspace; radar.measurements_per_step = " << p_.measurements_per_step
           << ": " << mib(e.records_bytes) << " MiB per-measurement records; "
           << mib(e.shared_bytes) << " MiB windows and plans";
    return {.bytes = threads * e.per_thread_bytes + e.shared_bytes + e.records_bytes,
            .detail = detail.str(),
            .key = "radar.samples_per_chirp"};
  }

  sensor::Cost cost() const override { return {.item = item_time(), .setup = setup_time()}; }

  std::vector<sensor::RawKind> raw_kinds() const override { return radar_raw_kinds(p_); }

  // The fog at the radar's sweep centre: specific attenuation, backscatter, and the two-way loss
  // through one layer, 2 A L.
  sensor::FogReport fog_report(const propagation::FogSpec& spec, double layer_length_m,
                               const propagation::SegelsteinTable& water) const override {
    const propagation::Fog fog(spec, water);
    const propagation::FogOptics o = fog.at_frequency(p_.radar.centre_frequency_hz);
    const double loss_db = 2.0 * o.specific_attenuation_db_per_km * layer_length_m * 1e-3;
    std::ostringstream line;
    line << "  radar (" << o.frequency_hz * 1e-9 << " GHz)         2-way loss " << loss_db << " dB";
    return {.json = {{"frequency_hz", o.frequency_hz},
                     {"specific_attenuation_db_per_km", o.specific_attenuation_db_per_km},
                     {"volume_backscatter_m2_per_m3", o.volume_backscatter_m2_per_m3},
                     {"two_way_loss_db_per_layer", loss_db}},
            .line = line.str()};
  }

  std::shared_ptr<const sensor::Sensor> make(const propagation::SegelsteinTable& water,
                                             const StopToken& stop) const override {
    return std::make_shared<RadarSensor>(p_, context_, water, stop);
  }

 private:
  sensor::TimePart item_time() const {
    const RadarParams& p = p_.radar;
    const double cells = static_cast<double>(p.samples_per_chirp * p.chirps_per_frame);
    const double tones = mean_clutter_tones(p_, context_);
    const double objects = scene_objects_per_frame + p.cfar.false_alarm_probability * cells;
    const double reference_cells = static_cast<double>(p.cfar.reference_cells());
    const double edge_references =
        p.cfar.kind == CfarKind::os
            ? 0.0
            : static_cast<double>(p.chirps_per_frame) * 2.0 *
                  static_cast<double>(std::size_t{p.cfar.guard_cells} + p.cfar.training_cells) *
                  reference_cells;
    const double ring_references = cells * static_cast<double>(p.cfar.shape_reference_cells());
    const double edge_seconds =
        p.cfar.shape == CfarShape::range_doppler
            ? ring_references * (p.cfar.kind == CfarKind::os
                                     ? frame_seconds_per_ring_selected_reference
                                     : frame_seconds_per_ring_reference)
        : p.cfar.kind == CfarKind::os ? cells * reference_cells * frame_seconds_per_sorted_reference
                                      : edge_references * frame_seconds_per_edge_reference;
    std::ostringstream detail;
    detail.precision(6);
    detail << "radar.samples_per_chirp = " << p.samples_per_chirp
           << " x radar.chirps_per_frame = " << p.chirps_per_frame << " cells, about " << objects
           << " objects (" << scene_objects_per_frame
           << " + radar.processing.cfar.false_alarm_probability = "
           << p.cfar.false_alarm_probability << " x cells), about " << tones
           << " fog clutter tones (fog.clutter_scatterers_per_bin = "
           << p_.clutter_scatterers_per_bin << " per range bin of the active layers), "
           << edge_references
           << " CFAR edge-cell additions (2 x (radar.processing.cfar.guard_cells + training_cells) "
              "x N "
              "per Doppler row)";
    if (p.cfar.shape == CfarShape::range_doppler) {
      detail << ", " << ring_references
             << " CFAR ring reference cells (cells x the ring's N, radar.processing.cfar.shape = "
                "\"range_doppler\")";
    }
    const double rest =
        cells * (std::log2(cells) * frame_seconds_per_cell_log2_cell +
                 objects * frame_seconds_per_cell_and_object) +
        tones * static_cast<double>(p.samples_per_chirp) * frame_seconds_per_tone_sample;
    return {.item_seconds = rest + edge_seconds,
            .detail = detail.str(),
            .key = edge_seconds > rest ? "radar.processing.cfar.training_cells"
                   : p.samples_per_chirp >= p.chirps_per_frame ? "radar.samples_per_chirp"
                                                               : "radar.chirps_per_frame",
            .items_key = "radar.measurements_per_step"};
  }

  sensor::SetupTime setup_time() const {
    const SetupCost c = setup_cost(p_, context_);
    std::ostringstream detail;
    detail.precision(3);
    detail << "fog optics " << c.fog_seconds << " s, chain " << c.chain_seconds
           << " s, CFAR design (radar.processing.cfar.kind = " << to_string(p_.radar.cfar.kind)
           << ", radar.processing.cfar.threshold_design = "
           << to_string(p_.radar.cfar.threshold_design) << ") " << c.cfar_design_seconds << " s";
    const double largest = std::max({c.fog_seconds, c.chain_seconds, c.cfar_design_seconds});
    return {.make_seconds = c.fog_seconds + c.chain_seconds + c.cfar_design_seconds,
            .run_seconds = c.summary_seconds,
            .report_seconds = c.report_seconds,
            .detail = detail.str(),
            .key = largest == c.cfar_design_seconds ? "radar.processing.cfar.threshold_design"
                   : largest == c.chain_seconds     ? "radar.samples_per_chirp"
                                                    : "fog.droplets"};
  }

  SensorParams p_;
  sensor::Context context_;
};

class Kind : public sensor::Kind<SensorParams> {
 public:
  Kind()
      : sensor::Kind<SensorParams>({.name = "radar",
                                    .stream_key = radar::stream_key,
                                    .band = sensor::Band::radio,
                                    .item_noun = "radar measurements",
                                    .curve_caption = "median target RCS as a power ratio"},
                                   sensor_keys()) {}

 protected:
  std::shared_ptr<const sensor::ConfiguredSensor> configured(
      const SensorParams& p, const sensor::Context& context) const override {
    // The CFAR's window against the range profile is one of the keys' checks
    // (radar_param_keys).
    const Scene scene = make_scene(p.target, context.target, context.room,
                                   p.clutter_scatterers_per_bin, p.radar.centre_frequency_hz);
    scene.validate();
    const double target_range_m = context.chamber.target_range_m();
    scene.check_room(target_range_m);
    // Every echo's beat must lie inside [0, fs) with the 1 m margin RadarChain keeps
    // (docs/radar.md).
    const FarthestEcho farthest = farthest_echo(scene, target_range_m);
    const double limit_m = derive(p.radar).max_range_m - 1.0;
    if (farthest.range_m > limit_m) {
      std::ostringstream constraint;
      constraint.precision(10);
      const bool target = farthest.key == "chamber.target_gap_m";
      constraint << "such that "
                 << (target ? "the target's farthest echo, chamber.sensor_gap_m + "
                              "chamber.layer_count x chamber.layer_length_m + "
                              "chamber.target_gap_m (+ the EVT's depth)"
                            : "the farthest echo of the room's own (a wall's or an object's)")
                 << " = " << farthest.range_m
                 << " m, lies within the unambiguous range minus 1 m, c x radar.sample_rate_hz x "
                    "radar.chirp_duration_s / (2 x radar.sweep_bandwidth_hz) - 1 = "
                 << limit_m << " m";
      throw_invalid(farthest.key, target ? context.chamber.target_gap_m : farthest.value,
                    constraint.str());
    }
    return std::make_shared<Configured>(p, context);
  }
};

}  // namespace

KeyTable<SensorParams> sensor_keys() {
  KeyTable<SensorParams> keys;
  keys.include(radar_param_keys(), FOGRADAR_KEY_FIELD(radar));
  keys.include(target_keys(), FOGRADAR_KEY_FIELD(target));
  keys.integer("radar.measurements_per_step", FOGRADAR_KEY_FIELD(measurements_per_step), 1, 1000000,
               "the study's series length: measurements (frames) per step");
  keys.number("radar.height_m", FOGRADAR_KEY_FIELD(target.sensor_height_m), closed(0.0, 100.0),
              "radar height above the floor; boresight is horizontal");
  keys.integer("radar.clutter_scatterers_per_bin", FOGRADAR_KEY_FIELD(clutter_scatterers_per_bin),
               1, 64, "random point scatterers per range bin that make up the radar's fog clutter");
  // Keys a scenario gave before the radar's own view of the target, its chain and its series moved
  // under [radar]: each is refused with its new place.
  for (const char* name : {"processing.window", "processing.association_gate_m"}) {
    keys.retired(name, std::string("it is radar.") + name + " now, in the radar's own section");
  }
  for (const char* name : {"kind", "guard_cells", "training_cells", "false_alarm_probability",
                           "os_rank", "threshold_design"}) {
    keys.retired(
        std::string("processing.cfar.") + name,
        std::string("it is radar.processing.cfar.") + name + " now, in the radar's own section");
  }
  for (const char* name : {"model", "rcs_dbsm", "swerling", "height_m"}) {
    keys.retired(std::string("target.") + name, std::string("it is radar.target.") + name +
                                                    " now: the radar's own view of the target");
  }
  keys.retired("target.sensor_height_m", "it is radar.height_m now, in the radar's own section");
  keys.retired("fog.clutter_scatterers_per_bin",
               "it is radar.clutter_scatterers_per_bin now, in the radar's own section");
  keys.retired("experiment.measurements_per_step",
               "each sensor counts its own items now: radar.measurements_per_step (the radar's "
               "series), lidar.scans_per_step, camera.frames_per_step");
  return keys;
}

std::shared_ptr<const sensor::SensorKind> sensor_kind() { return std::make_shared<Kind>(); }

}  // namespace fogradar::radar
