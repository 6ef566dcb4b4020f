#pragma once
// The a priori plan under the observed walls: observations are trusted over the plan,
// which is partial and partly wrong. Where an observed wall lies along a plan wall the observed
// geometry is published (carrying the plan's key when it confirms it); the plan wall's remainder
// is published as plan-only pieces. Internal to the fusion module.

#include <string>
#include <vector>

#include "pena/fusion/global_map.hpp"

namespace pena::fusion::detail {

// Adds `plan_key` to the observed walls that are the same wall as `plan_wall` (merge options)
// and returns the pieces of `plan_wall` no observed wall covers: an observed wall covers the part
// of the plan wall it overlaps if it is parallel (merge_angle_rad) and within plan_shadow_m.
// Pieces shorter than min_plan_piece_m are dropped; pieces are quantised, with provenance
// {plan_key} and no counts.
std::vector<line_map::LineSegment> OverlayPlanWall(const line_map::LineSegment& plan_wall,
                                                   const std::string& plan_key,
                                                   std::vector<line_map::LineSegment>& observed,
                                                   const GlobalMapOptions& options);

}  // namespace pena::fusion::detail
