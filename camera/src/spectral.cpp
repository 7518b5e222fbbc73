#include "fogradar/camera/spectral.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <string_view>
#include <system_error>

#include "fogradar/core/detail/text_fields.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::camera {
namespace detail {
std::string_view cie1931_2deg_xyz_text();  // generated from data/cie1931_2deg_xyz.txt
}  // namespace detail

namespace {

using fogradar::detail::parse_number;
using fogradar::detail::take_field;

// Layout of data/cie1931_2deg_xyz.txt: title, blank line, column titles, then rows of
// wavelength (nm), x_bar, y_bar, z_bar separated by tabs.
constexpr std::size_t cie_header_lines = 3;
constexpr std::size_t cie_row_count = 95;
constexpr double cie_step_nm = 5.0;

// IEC 61966-2-1 (sRGB) XYZ -> linear RGB matrix, rows R, G, B.
constexpr std::array<std::array<double, 3>, 3> xyz_to_linear_srgb{{
    {3.2406, -1.5372, -0.4986},
    {-0.9689, 1.8758, 0.0415},
    {0.0557, -0.2040, 1.0570},
}};

// Trapezoid weights of `sensitivity` on the table's uniform nodes, normalised to sum 1.
std::vector<double> trapezoid_weights(const std::vector<double>& sensitivity) {
  std::vector<double> weight(sensitivity.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < sensitivity.size(); ++k) {
    const bool end = k == 0 || k + 1 == sensitivity.size();
    weight[k] = std::max(sensitivity[k], 0.0) * (end ? 0.5 : 1.0);
    sum += weight[k];
  }
  FOGRADAR_CHECK(sum > 0.0);
  for (double& w : weight) w /= sum;
  return weight;
}

}  // namespace

ColourMatchingTable cie1931_table() {
  std::string_view text = detail::cie1931_2deg_xyz_text();
  for (std::size_t line = 0; line < cie_header_lines; ++line) take_field(text, '\n');
  ColourMatchingTable table;
  while (!text.empty()) {
    std::string_view line = take_field(text, '\n');
    if (line.empty()) continue;
    table.wavelength_nm.push_back(parse_number(take_field(line, '\t')));
    table.x_bar.push_back(parse_number(take_field(line, '\t')));
    table.y_bar.push_back(parse_number(take_field(line, '\t')));
    table.z_bar.push_back(parse_number(line));
  }
  // The table is compiled in: a malformed one is a build defect, not bad user input.
  FOGRADAR_CHECK(table.wavelength_nm.size() == cie_row_count);
  for (std::size_t k = 1; k < table.wavelength_nm.size(); ++k) {
    FOGRADAR_CHECK(table.wavelength_nm[k] - table.wavelength_nm[k - 1] == cie_step_nm);
  }
  return table;
}

BandQuadrature band_quadrature(Band band, double wavelength_nm, const ColourMatchingTable& table) {
  BandQuadrature quadrature;
  if (band == Band::monochromatic) {
    quadrature.wavelength_m = {wavelength_nm * 1e-9};
    quadrature.weight = {{1.0}};
    return quadrature;
  }
  for (double nm : table.wavelength_nm) quadrature.wavelength_m.push_back(nm * 1e-9);
  if (band == Band::photopic) {
    quadrature.weight = {trapezoid_weights(table.y_bar)};
    return quadrature;
  }
  for (const auto& row : xyz_to_linear_srgb) {
    std::vector<double> sensitivity(table.wavelength_nm.size());
    for (std::size_t k = 0; k < sensitivity.size(); ++k) {
      sensitivity[k] = row[0] * table.x_bar[k] + row[1] * table.y_bar[k] + row[2] * table.z_bar[k];
    }
    quadrature.weight.push_back(trapezoid_weights(sensitivity));
  }
  return quadrature;
}

std::vector<double> mie_wavelengths_m(Band band, double wavelength_nm, double step_nm) {
  if (band == Band::monochromatic) return {wavelength_nm * 1e-9};
  constexpr double first_nm = 400.0;
  constexpr double last_nm = 720.0;
  std::vector<double> nodes;
  for (int k = 0; first_nm + k * step_nm < last_nm; ++k)
    nodes.push_back((first_nm + k * step_nm) * 1e-9);
  nodes.push_back(last_nm * 1e-9);
  return nodes;
}

std::vector<double> interpolate_quadratic(const std::vector<double>& x,
                                          const std::vector<double>& y,
                                          const std::vector<double>& at) {
  FOGRADAR_CHECK(!x.empty() && x.size() == y.size());
  const std::size_t n = x.size();
  std::vector<double> out;
  out.reserve(at.size());
  for (const double raw : at) {
    const double v = std::clamp(raw, x.front(), x.back());
    if (n == 1) {
      out.push_back(y.front());
      continue;
    }
    // The nearest node, then the run of min(n, 3) nodes centred on it as far as the ends allow.
    const auto upper =
        static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), v) - x.begin());
    std::size_t nearest = std::min(upper, n - 1);
    if (nearest > 0 && v - x[nearest - 1] < x[nearest] - v) --nearest;
    const std::size_t count = std::min<std::size_t>(n, 3);
    const std::size_t first = std::min(nearest > 0 ? nearest - 1 : 0, n - count);
    double sum = 0.0;
    for (std::size_t i = first; i < first + count; ++i) {
      double basis = 1.0;
      for (std::size_t j = first; j < first + count; ++j) {
        if (j != i) basis *= (v - x[j]) / (x[i] - x[j]);
      }
      sum += basis * y[i];
    }
    out.push_back(sum);
  }
  return out;
}

}  // namespace fogradar::camera
