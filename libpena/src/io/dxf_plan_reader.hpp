#pragma once
// Private: the DXF half of ReadPlan (pena/io/plan_reader.hpp), in drawing units.

#include <filesystem>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::io::detail {

// LINE, LWPOLYLINE and POLYLINE/VERTEX entities of an ASCII DXF's ENTITIES section, in drawing
// units; bulged (arc) polyline spans are skipped. Throws InputError.
std::vector<geometry::Segment2> ReadDxfPlan(const std::filesystem::path& path);

}  // namespace pena::io::detail
