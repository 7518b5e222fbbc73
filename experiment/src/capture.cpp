#include "fogradar/experiment/capture.hpp"

#include <algorithm>
#include <limits>

#include "fogradar/core/error.hpp"

namespace fogradar::experiment {

RawCapture::RawCapture(std::vector<sensor::RawKind> kinds, const std::vector<std::size_t>& wanted)
    : kinds_(std::move(kinds)) {
  for (const std::size_t k : wanted) {
    FOGRADAR_CHECK(k < kinds_.size());
    Kept kept;
    kept.kind = k;
    for (const sensor::RawColumn& c : kinds_[k].columns) {
      FOGRADAR_CHECK(c.labels.size() <= std::numeric_limits<std::int8_t>::max());
    }
    kept.columns.resize(kinds_[k].columns.size());
    kept_.push_back(std::move(kept));
  }
}

bool RawCapture::wants(std::size_t kind) const {
  return std::any_of(kept_.begin(), kept_.end(), [kind](const Kept& k) { return k.kind == kind; });
}

RawCapture::Kept& RawCapture::slot(std::size_t kind, sensor::RawElement element) {
  for (Kept& k : kept_) {
    if (k.kind != kind) continue;
    FOGRADAR_CHECK(kinds_[kind].element == element);
    return k;
  }
  check_failed("raw kind kept", __FILE__, __LINE__);
}

void RawCapture::write(std::size_t kind, std::span<const std::complex<double>> values) {
  Kept& k = slot(kind, sensor::RawElement::complex128);
  FOGRADAR_CHECK(values.size() == kinds_[kind].item_values());
  k.complex128.assign(values.begin(), values.end());
}

void RawCapture::write(std::size_t kind, std::span<const double> values) {
  Kept& k = slot(kind, sensor::RawElement::float64);
  FOGRADAR_CHECK(values.size() == kinds_[kind].item_values());
  k.float64.assign(values.begin(), values.end());
}

void RawCapture::write(std::size_t kind, std::span<const std::uint8_t> values) {
  Kept& k = slot(kind, sensor::RawElement::uint8);
  FOGRADAR_CHECK(values.size() == kinds_[kind].item_values());
  k.uint8.assign(values.begin(), values.end());
}

void RawCapture::write(std::size_t kind, std::span<const std::int16_t> values) {
  Kept& k = slot(kind, sensor::RawElement::int16);
  FOGRADAR_CHECK(values.size() == kinds_[kind].item_values());
  k.int16.assign(values.begin(), values.end());
}

void RawCapture::append_rows(std::size_t kind, std::span<const double> rows) {
  Kept& k = slot(kind, sensor::RawElement::table);
  const std::vector<sensor::RawColumn>& columns = kinds_[kind].columns;
  FOGRADAR_CHECK(!columns.empty() && rows.size() % columns.size() == 0);
  for (std::size_t r = 0; r < rows.size(); r += columns.size()) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double value = rows[r + c];
      if (!columns[c].labels.empty()) {
        k.columns[c].codes.push_back(static_cast<std::int8_t>(value));
      } else if (columns[c].integer) {
        k.columns[c].integers.push_back(static_cast<std::int64_t>(value));
      } else {
        k.columns[c].numbers.push_back(value);
      }
    }
    ++k.rows;
  }
}

}  // namespace fogradar::experiment
