#pragma once
// Which walls only one entity saw are published (docs/fusion.md, "The global map", step 3): lone
// weak walls, lone drifted copies of corroborated walls, and lone walls where the entity's walls
// around them are off the other sources' by more than the map promises. Internal to the fusion
// module.

#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "pena/fusion/global_map.hpp"

namespace pena::fusion::detail {

// Leaves out of `merged` (after the plan overlay gave the plan keys) the walls the options
// withhold; `source_by_key` is each source segment (map frame) by provenance key, `plan` the
// plan's walls. Returns each entity's agreement evidence (GlobalMap::agreement()).
std::map<std::string, EntityAgreement> DropLoneWalls(
    std::vector<line_map::LineSegment>& merged,
    const std::unordered_map<std::string, geometry::Segment2>& source_by_key,
    const std::vector<geometry::Segment2>& plan, const GlobalMapOptions& options);

}  // namespace pena::fusion::detail
