#pragma once
// Line maps and floor plans rendered as SVG for people: metres as user units, y up, a scale bar
// and a legend. Readable by browsers and CAD tools (Inkscape, LibreCAD import).

#include <filesystem>
#include <string>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::io {

// One group of segments drawn in one style; `name` is the SVG group id and the legend text.
struct SvgLayer {
  std::string name;
  std::string colour = "#000000";  // any SVG colour
  double stroke_width_m = 0.05;
  std::vector<geometry::Segment2> segments;
};

// Writes the layers (first drawn first) with a margin around their bounding box.
// Throws std::runtime_error naming the path if it cannot be written.
void WriteLineSvg(const std::filesystem::path& path, const std::vector<SvgLayer>& layers,
                  double margin_m = 1.0);

}  // namespace pena::io
