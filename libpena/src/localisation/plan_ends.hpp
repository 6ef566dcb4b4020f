#pragma once
// The plan's free wall ends as references of the plan adaptation (internal; docs/localisation.md,
// "Plan adaptation"). A wall's line says nothing about the position along it, but where a wall
// stops at a door jamb or a corridor's end does. Where the walls across a corridor are drawn off
// they are the only references along it and the rounds match onto them; the corridor walls' own
// ends (door jambs, the corridor's end), when drawn right, pin that direction down.
//
// A drawn end is measured where the returns along its wall's line stop: the farthest return of a
// dense run towards the end, when the laser saw past it (the next returns beyond it in bearing lie
// well behind it) and it is not at the edge of the laser's field of view.

#include <Eigen/Core>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/localisation/plan_adaptation.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation::internal {

// One end measured in a round: the drawn end, the unit direction out of the wall through it, and
// how far beyond it (along `outward`) the returns along the wall's line stop; negative: short of it.
struct EndMeasurement {
  int segment = 0;
  Eigen::Vector2d end_m;
  Eigen::Vector2d outward;
  double residual_m = 0.0;
};

// The free ends of `plan`.
std::vector<SegmentEnds> FreeEnds(const std::vector<geometry::Segment2>& plan, double join_m);

// The ends of `plan` marked in `ends` that the returns `map_points` (map frame, beam order) of a
// round taken at `origin_m` facing `heading_rad` measure.
std::vector<EndMeasurement> MeasureEnds(const std::vector<geometry::Segment2>& plan,
                                        const std::vector<SegmentEnds>& ends,
                                        const scan_matching::Points2& map_points, const Eigen::Vector2d& origin_m,
                                        double heading_rad, const PlanEndOptions& options);

}  // namespace pena::localisation::internal
