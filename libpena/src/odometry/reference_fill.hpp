#pragma once
// Densifies a keyframe scan for use as a reference: points are added along the surface between
// neighbouring returns, so that eq. 2's nearest-neighbour test measures the distance to the wall
// and not to the nearest beam's sample (at 10 m, 1 deg beams are 17 cm apart, far more than the
// 6 cm threshold).

#include "pena/geometry/pose2.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::odometry::internal {

// When two consecutive returns (in beam order) are at most max_gap_m apart and their segment is
// not nearly along the beam (a depth jump between a foreground edge and the wall behind), and at
// most max_gap_beam_spacings times the spacing of neighbouring beams at that range (0: no such
// limit), points every spacing_m are added between them. Input and output in the world frame;
// world_from_sensor is where the scan was taken. spacing_m <= 0 returns the points unchanged.
scan_matching::Points2 FillReference(const scan_matching::Points2& points_world,
                                     const geometry::Pose2& world_from_sensor, double spacing_m,
                                     double max_gap_m, double max_gap_beam_spacings = 3.0);

}  // namespace pena::odometry::internal
