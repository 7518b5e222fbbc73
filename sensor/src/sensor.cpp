#include "fogradar/sensor/sensor.hpp"

#include <functional>
#include <numeric>

namespace fogradar::sensor {

KeyTable<TargetWorld> target_world_keys() {
  KeyTable<TargetWorld> keys("target.");
  keys.retired("floor_multipath",
               "the floor is the room's: chamber.room.floor = false for none, or a table "
               "[chamber.room.floor] for one");
  keys.retired("floor_reflection_coefficient",
               "the floor is the room's: chamber.room.floor.reflection_coefficient");
  keys.number("micro_motion_std_m", FOGRADAR_KEY_FIELD(micro_motion_std_m), closed(0.0, 0.1),
              "rms line-of-sight jitter of each scattering centre per measurement (the radar's)");
  keys.number(
      "radial_velocity_m_per_s", FOGRADAR_KEY_FIELD(radial_velocity_m_per_s), closed(-300.0, 300.0),
      "the whole target's radial velocity, + receding; beyond a radar's unambiguous velocity "
      "λ/(4 T_i) (19.0 m/s for the paper radar) its estimate folds into it and the run warns");
  keys.number("water_film_m", FOGRADAR_KEY_FIELD(water_film_m), closed(0.0, 0.01),
              "water film on the target's metal surfaces (the study's water-covered target), with "
              "the water model and temperature of the last layer's fog (the radar's echo)");
  return keys;
}

propagation::ActiveLayers Context::active(std::size_t step) const {
  if (switching_order.empty()) return propagation::first_layers_active(step, chamber.layers.size());
  return propagation::layers_switched_on(switching_order, step, chamber.layers.size());
}

std::size_t RawKind::item_values() const {
  return std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>());
}

std::size_t RawKind::item_bytes() const {
  switch (element) {
    case RawElement::complex128:
      return item_values() * sizeof(std::complex<double>);
    case RawElement::float64:
      return item_values() * sizeof(double);
    case RawElement::uint8:
      return item_values();
    case RawElement::int16:
      return item_values() * sizeof(std::int16_t);
    case RawElement::table:
      return rows_per_item * columns.size() * sizeof(double);
  }
  return 0;
}

}  // namespace fogradar::sensor
