// One item's raw data kept in memory (docs/python.md): the Python module's arrays. A RawSink that
// keeps the kinds asked for, each in a buffer of its own element type, and a table column by
// column (numbers as float64, integer columns as int64, enumerations as int8 codes), so that every
// array and every table column is one contiguous buffer a NumPy array can view without a copy.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fogradar/sensor/sensor.hpp"

namespace fogradar::experiment {

class RawCapture : public sensor::RawSink {
 public:
  struct Column {
    std::vector<double> numbers;         // a number column
    std::vector<std::int64_t> integers;  // an integer column
    std::vector<std::int8_t> codes;      // an enumeration: the index of its label
  };
  struct Kept {
    std::size_t kind = 0;  // index into the sensor's raw kinds
    std::vector<std::complex<double>> complex128;
    std::vector<double> float64;
    std::vector<std::uint8_t> uint8;
    std::vector<std::int16_t> int16;
    std::vector<Column> columns;  // table kinds, in the kind's column order
    std::size_t rows = 0;
  };

  // Keeps the kinds at `wanted` (indices into `kinds`) of one item. Throws InternalError for an
  // enumeration of more than 127 labels.
  RawCapture(std::vector<sensor::RawKind> kinds, const std::vector<std::size_t>& wanted);

  bool wants(std::size_t kind) const override;
  void write(std::size_t kind, std::span<const std::complex<double>> values) override;
  void write(std::size_t kind, std::span<const double> values) override;
  void write(std::size_t kind, std::span<const std::uint8_t> values) override;
  void write(std::size_t kind, std::span<const std::int16_t> values) override;
  void append_rows(std::size_t kind, std::span<const double> rows) override;

  const std::vector<sensor::RawKind>& kinds() const { return kinds_; }
  const std::vector<Kept>& kept() const { return kept_; }

 private:
  Kept& slot(std::size_t kind, sensor::RawElement element);

  std::vector<sensor::RawKind> kinds_;
  std::vector<Kept> kept_;
};

}  // namespace fogradar::experiment
