#include "fogradar/propagation/chamber.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::propagation {
namespace {

// Length of [a, b] n [c, d].
double overlap_m(double a, double b, double c, double d) {
  return std::max(0.0, std::min(b, d) - std::max(a, c));
}

}  // namespace

void ChamberSpec::validate() const {
  require_in_range("chamber.sensor_gap_m", sensor_gap_m, 0.0, max_chamber_length_m);
  require_in_range("chamber.target_gap_m", target_gap_m, 0.0, max_chamber_length_m);
  if (layers.empty() || layers.size() > max_chamber_layers) {
    throw_invalid("chamber.layers", static_cast<double>(layers.size()),
                  "a layer count in [1, " + std::to_string(max_chamber_layers) + "]");
  }
  const KeyTable<FogSpec> fog_table = fog_keys("fog.");  // FogSpec::validate's, made once
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const std::string field = "chamber.layers[" + std::to_string(i) + "].length_m";
    if (!(layers[i].length_m > 0.0 && layers[i].length_m <= max_chamber_length_m)) {
      std::ostringstream range;
      range << "in (0, " << max_chamber_length_m << "]";
      throw_invalid(field, layers[i].length_m, range.str());
    }
    fog_table.check(layers[i].fog);
  }
}

double ChamberSpec::target_range_m() const {
  double range_m = sensor_gap_m + target_gap_m;
  for (const FogLayerSpec& layer : layers) range_m += layer.length_m;
  return range_m;
}

ActiveLayers first_layers_active(std::size_t count, std::size_t layer_count) {
  if (count > layer_count) {
    throw_invalid("active_layers", static_cast<double>(count),
                  "in [0, " + std::to_string(layer_count) + "] (the chamber's layer count)");
  }
  ActiveLayers active(layer_count, false);
  std::fill_n(active.begin(), count, true);
  return active;
}

ActiveLayers layers_switched_on(std::span<const std::size_t> order, std::size_t count,
                                std::size_t layer_count) {
  if (count > order.size()) {
    throw_invalid("active_layers", static_cast<double>(count),
                  "in [0, " + std::to_string(order.size()) + "] (the switching order's length)");
  }
  ActiveLayers active(layer_count, false);
  for (std::size_t k = 0; k < count; ++k) {
    if (order[k] >= layer_count || active[order[k]]) {
      throw_invalid("switching_order", static_cast<double>(order[k]),
                    "a layer index in [0, " + std::to_string(layer_count) + "), each once");
    }
    active[order[k]] = true;
  }
  return active;
}

Chamber::Chamber(const ChamberSpec& spec, double frequency_hz, const SegelsteinTable& table)
    : target_range_m_(spec.target_range_m()), frequency_hz_(frequency_hz) {
  spec.validate();
  require_positive("frequency_hz", frequency_hz);
  double start_m = spec.sensor_gap_m;
  layers_.reserve(spec.layers.size());
  for (std::size_t i = 0; i < spec.layers.size(); ++i) {
    const FogLayerSpec& layer_spec = spec.layers[i];
    LayerOptics layer{.start_m = start_m,
                      .end_m = start_m + layer_spec.length_m,
                      .lwc_g_per_m3 = 0.0,
                      .optics = {}};
    // A layer filled with the same fog as an earlier one (the study's chamber: one fog in all four)
    // takes its results: resolving a density given at 550 nm sums a Mie series for every drop size
    // of the quadrature, most of a run's start-up, and would only repeat the same arithmetic.
    std::size_t same = 0;
    while (same < i && spec.layers[same].fog != layer_spec.fog) ++same;
    if (same < i) {
      layer.lwc_g_per_m3 = layers_[same].lwc_g_per_m3;
      layer.optics = layers_[same].optics;
    } else {
      const Fog fog(layer_spec.fog, table);
      layer.lwc_g_per_m3 = fog.lwc_g_per_m3();
      layer.optics = fog.at_frequency(frequency_hz);
    }
    layers_.push_back(layer);
    start_m += layer_spec.length_m;
  }
}

void Chamber::check_active(const ActiveLayers& active) const {
  if (active.size() != layers_.size()) {
    throw_invalid("active_layers", static_cast<double>(active.size()),
                  "one flag per layer (" + std::to_string(layers_.size()) + ")");
  }
}

// A = 2 sum_i a_i |[start_i, end_i] n [0, R]|.
double Chamber::two_way_attenuation_db(double range_m, const ActiveLayers& active) const {
  check_active(active);
  require_non_negative("range_m", range_m);
  double one_way_db = 0.0;
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    if (!active[i]) continue;
    const LayerOptics& layer = layers_[i];
    one_way_db += layer.optics.specific_attenuation_db_per_km * 1e-3 *
                  overlap_m(layer.start_m, layer.end_m, 0.0, range_m);
  }
  return 2.0 * one_way_db;
}

double Chamber::two_way_transmittance(double range_m, const ActiveLayers& active) const {
  return db_to_power_ratio(-two_way_attenuation_db(range_m, active));
}

// sigma = sum_i eta_i omega integral_a^b r^2 dr = eta_i omega (b^3 - a^3) / 3.
double Chamber::backscatter_cross_section_m2(double r0_m, double r1_m, double beam_solid_angle_sr,
                                             const ActiveLayers& active) const {
  check_active(active);
  require_non_negative("range_m", r0_m);
  if (!(r1_m >= r0_m)) throw_invalid("range_m", r1_m, ">= the interval's start");
  require_positive("beam_solid_angle_sr", beam_solid_angle_sr);
  double sigma_m2 = 0.0;
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    if (!active[i]) continue;
    const LayerOptics& layer = layers_[i];
    const double a = std::max(r0_m, layer.start_m);
    const double b = std::min(r1_m, layer.end_m);
    if (b <= a) continue;
    sigma_m2 += layer.optics.volume_backscatter_m2_per_m3 * beam_solid_angle_sr *
                (b * b * b - a * a * a) / 3.0;
  }
  return sigma_m2;
}

}  // namespace fogradar::propagation
