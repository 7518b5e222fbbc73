// Text shared by the SVG writers of stats/ (svg_plot.cpp, line_plot.cpp); not installed.
#pragma once

#include <string>
#include <string_view>

namespace fogradar::stats::detail {

// XML character data and attribute values: the five predefined entities; control characters
// that XML 1.0 forbids become spaces.
std::string escape_xml(std::string_view text);

}  // namespace fogradar::stats::detail
