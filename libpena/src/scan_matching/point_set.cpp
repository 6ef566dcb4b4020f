#include "pena/scan_matching/point_set.hpp"

#include <cmath>

namespace pena::scan_matching {

Points2 ScanToPoints(const sensors::LaserScan& scan, double min_range_m) {
  Points2 points;
  points.reserve(scan.ranges_m.size());
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!scan.IsReturn(i) || scan.ranges_m[i] < min_range_m) continue;
    const double angle = scan.BeamAngle(i);
    const double range = scan.ranges_m[i];
    points.emplace_back(range * std::cos(angle), range * std::sin(angle));
  }
  return points;
}

Points2 TransformPoints(const geometry::Pose2& a_from_b, const Points2& points_b) {
  Points2 points_a;
  points_a.reserve(points_b.size());
  for (const auto& point : points_b) points_a.push_back(geometry::TransformPoint(a_from_b, point));
  return points_a;
}

}  // namespace pena::scan_matching
