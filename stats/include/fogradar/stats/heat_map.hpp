// A heat map as a standalone SVG 1.1 document: a grid of cells coloured by value on a sequential
// scale (light to dark), each cell with its value written in it, labelled rows and columns, a
// colour key, a title and caption lines. A cell without a value is grey with its own text (e.g.
// "not reached"), and the key names it. Several maps compared side by side take one colour scale
// (value_range). Deterministic, locale-independent output; text XML-escaped.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace fogradar::stats {

struct HeatMap {
  std::vector<std::string> column_labels;                  // left to right (x)
  std::vector<std::string> row_labels;                     // bottom to top (y)
  std::vector<std::vector<std::optional<double>>> values;  // [row][column]
  std::string title;
  std::vector<std::string> caption;
  std::string x_label;
  std::string y_label;
  std::string value_label;   // the colour key's title
  std::string missing_text;  // written in a cell without a value
  int decimals = 0;          // of the values written in the cells
  // The colour scale's ends (lightest, darkest); default: the smallest and the largest value.
  std::optional<std::pair<double, double>> value_range;
  // The values are counts: the key shows whole numbers only, a swatch per count (at most 11).
  bool integer_values = false;
};

// Throws InvalidParameter naming "values" (not rows x columns, or no cell), "values[r][c]" (a
// non-finite value, or one outside value_range) or "value_range" (not finite with low < high).
std::string heat_map_svg(const HeatMap& map);

}  // namespace fogradar::stats
