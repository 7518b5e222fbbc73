#include "fogradar/sensor/sensor.hpp"

#include <functional>
#include <numeric>

namespace fogradar::sensor {

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
