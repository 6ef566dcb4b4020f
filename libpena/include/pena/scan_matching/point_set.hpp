#pragma once
// Scan points in the plane, the input of the correlation matcher.

#include <Eigen/Core>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::scan_matching {

// Points in one frame, metres.
using Points2 = std::vector<Eigen::Vector2d>;

// The scan's returns as points in the laser frame (no-returns, NaN and ranges under
// min_range_m dropped).
Points2 ScanToPoints(const sensors::LaserScan& scan, double min_range_m = 0.05);

// The same, in the laser frame at mid-sweep: a scan taken over geometry.sweep_s while the
// platform turns at rotation_rate_rad_s (CCW positive) has each beam's return rotated by the turn
// between its own time and the middle of the sweep. Translation during the sweep is not
// corrected (under 1 cm at 1.5 m/s over 1/150 s). With sweep_s = 0 it is ScanToPoints.
Points2 ScanToPointsAtMidSweep(const sensors::LaserScan& scan, double min_range_m,
                               double rotation_rate_rad_s);

// Every point mapped by a_from_b.
Points2 TransformPoints(const geometry::Pose2& a_from_b, const Points2& points_b);

}  // namespace pena::scan_matching
