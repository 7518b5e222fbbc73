// The fog chamber of the study (paper Fig. 1): sensor -> l_s -> n switchable fog layers of lengths
// f_i -> l_t -> target. Resolved at one radar frequency, it answers the two-way attenuation to any
// range and the fog backscatter inside any range interval, for any set of active layers.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "fogradar/propagation/fog.hpp"

namespace fogradar::propagation {

// A chamber of more layers than this is a typo, not a study (the study has 4,
// examples/long_chamber.toml 40); likewise a gap or layer longer than 10 km.
inline constexpr std::size_t max_chamber_layers = 1000;
inline constexpr double max_chamber_length_m = 1e4;

struct FogLayerSpec {
  double length_m = 1.0;
  FogSpec fog;
  bool operator==(const FogLayerSpec&) const = default;
};

struct ChamberSpec {
  double sensor_gap_m = 2.0;  // l_s, sensor to the first layer
  std::vector<FogLayerSpec> layers = std::vector<FogLayerSpec>(4);
  double target_gap_m = 4.0;  // l_t, last layer to the target
  void validate() const;
  double target_range_m() const;
};

// Which layers are switched on, one flag per layer.
using ActiveLayers = std::vector<bool>;
// The study's methodology: the first `count` layers (from the sensor) on, the rest off.
ActiveLayers first_layers_active(std::size_t count, std::size_t layer_count);
// The first `count` layers of `order` (layer indices, each at most once) on, the rest off.
ActiveLayers layers_switched_on(std::span<const std::size_t> order, std::size_t count,
                                std::size_t layer_count);

struct LayerOptics {
  double start_m;
  double end_m;
  double lwc_g_per_m3;
  FogOptics optics;
};

class Chamber {
 public:
  Chamber(const ChamberSpec& spec, double frequency_hz, const SegelsteinTable& table);

  std::size_t layer_count() const { return layers_.size(); }
  const LayerOptics& layer(std::size_t i) const { return layers_.at(i); }
  double target_range_m() const { return target_range_m_; }
  double frequency_hz() const { return frequency_hz_; }

  // Two-way (sensor -> range -> sensor) attenuation in dB through the active layers:
  //   A = 2 sum_i a_i * |[start_i, end_i] n [0, range]|,  a_i the layer's specific attenuation.
  double two_way_attenuation_db(double range_m, const ActiveLayers& active) const;
  // The corresponding power transmittance 10^(-A/10).
  double two_way_transmittance(double range_m, const ActiveLayers& active) const;

  // Fog backscattering cross section inside [r0, r1] for a beam of solid angle omega:
  //   sigma = sum_i eta_i omega (b^3 - a^3) / 3 over each active layer's overlap [a, b].
  double backscatter_cross_section_m2(double r0_m, double r1_m, double beam_solid_angle_sr,
                                      const ActiveLayers& active) const;

 private:
  void check_active(const ActiveLayers& active) const;

  std::vector<LayerOptics> layers_;
  double target_range_m_;
  double frequency_hz_;
};

}  // namespace fogradar::propagation
