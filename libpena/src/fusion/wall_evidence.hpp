#pragma once
// Which merged walls the global map publishes and how well each is supported (docs/fusion.md,
// "The global map", step 3): a wall is withheld on evidence that it is wrong (a dotted lone wall,
// a copy of a wall another entity saw better, a wall drifted entities left along a plan wall they
// do not confirm), never because one entity alone saw it. Internal to the fusion module.

#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "pena/fusion/global_map.hpp"

namespace pena::fusion::detail {

// What JudgeWalls found.
struct WallJudgement {
  std::map<std::string, EntityAgreement> agreement;  // GlobalMap::agreement()
  std::vector<WallSupport> support;  // one per wall left in `merged`, in its order
};

// Leaves out of `merged` (after the plan overlay gave the plan keys) the walls the evidence
// withholds; `source_by_key` is each source segment (map frame) by provenance key, `plan` the
// plan's walls. Deterministic: depends on the order of `merged` only through ties.
WallJudgement JudgeWalls(std::vector<line_map::LineSegment>& merged,
                         const std::unordered_map<std::string, geometry::Segment2>& source_by_key,
                         const std::vector<geometry::Segment2>& plan,
                         const GlobalMapOptions& options);

}  // namespace pena::fusion::detail
