#pragma once
// Line maps and plans as AutoCAD R12 ASCII DXF (LINE entities on named layers), the drawing
// exchange format fire brigades' CAD plans use. Drawing units are metres, mission frame.

#include <filesystem>
#include <string>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::io {

// One layer of LINE entities; `name` is 1-31 characters of A-Z a-z 0-9 _ - $ (R12's rule).
struct DxfLayer {
  std::string name = "WALLS";
  int colour = 7;  // AutoCAD colour index 1-255 (1 red, 5 blue, 7 black/white)
  std::vector<geometry::Segment2> segments;
};

// Writes the layers (a LAYER table entry each) and their segments as LINE entities (z = 0).
// Throws std::invalid_argument for a bad layer name, colour or non-finite coordinate (naming it),
// std::runtime_error naming the path if it cannot be written.
void WriteLineDxf(const std::filesystem::path& path, const std::vector<DxfLayer>& layers);

// One layer named `layer` (default "WALLS").
void WriteLineDxf(const std::filesystem::path& path,
                  const std::vector<geometry::Segment2>& segments,
                  const std::string& layer = "WALLS");

}  // namespace pena::io
