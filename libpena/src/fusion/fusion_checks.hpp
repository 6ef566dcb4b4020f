#pragma once
// Input checks shared by the fusion's handlers: a refused input gets a message naming it and
// changes nothing. Internal to the fusion module.

#include <string>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/line_map/line_segment.hpp"

namespace pena::fusion::detail {

// Throws std::invalid_argument("<what>, got <value>") unless ok.
void Require(bool ok, const std::string& what, double value);
// True if every field is finite.
bool Finite(const geometry::Pose2& pose);
// Empty if the id is usable (non-empty, at most 64 bytes, no ':' which separates provenance).
std::string CheckEntityId(const std::string& entity_id);
// Empty if every segment has id > 0, finite coordinates within line_map::kMaxCoordinateM and
// non-negative finite counts; else what is wrong, naming `name` and the segment id.
std::string CheckSegments(const std::vector<line_map::LineSegment>& segments,
                          const std::string& name);

}  // namespace pena::fusion::detail
