#pragma once
// Private: the SVG half of ReadPlan (pena/io/plan_reader.hpp), in drawing units.

#include <filesystem>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::io::detail {

// Straight strokes of an SVG drawing in user units after all transforms, y negated (so the
// drawing's up is +y). Curves and arcs are skipped (the pen moves to their end). Throws InputError.
std::vector<geometry::Segment2> ReadSvgPlan(const std::filesystem::path& path);

}  // namespace pena::io::detail
