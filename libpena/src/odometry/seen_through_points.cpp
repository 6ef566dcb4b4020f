#include "seen_through_points.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pena::odometry::internal {

double SeenThroughPoints::SeenRange(const View& view, const Eigen::Vector2d& point) {
  const double increment = view.geometry.angle_increment_rad;
  if (!(increment > 0.0) || view.ranges_m.empty()) return -1.0;
  const double beam = (std::atan2(point.y(), point.x()) - view.geometry.angle_min_rad) / increment;
  const auto last = static_cast<long>(view.ranges_m.size()) - 1;
  const long centre = std::lround(beam);
  if (centre < 0 || centre > last) return -1.0;
  // A no-return says nothing (smoke ends a beam without a return as well as open space does).
  double seen = std::numeric_limits<double>::infinity();
  for (long i = std::max(0L, centre - 1); i <= std::min(last, centre + 1); ++i) {
    const float r = view.ranges_m[static_cast<std::size_t>(i)];
    if (std::isfinite(r)) seen = std::min(seen, static_cast<double>(r));
  }
  return std::isfinite(seen) ? seen : -1.0;
}

std::vector<bool> SeenThroughPoints::Find(const scan_matching::Points2& points,
                                          const geometry::Pose2& world_from_laser) const {
  std::vector<bool> marked(points.size(), false);
  for (const View& view : views_) {
    const geometry::Pose2 view_from_laser = geometry::Compose(view.laser_from_world, world_from_laser);
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (marked[i]) continue;
      const Eigen::Vector2d p = geometry::TransformPoint(view_from_laser, points[i]);
      const double range = p.norm();
      if (range < options_.min_range_m) continue;
      const double seen = SeenRange(view, p);
      marked[i] = seen > range + options_.margin_m + options_.margin_per_m * range;
    }
  }
  return marked;
}

void SeenThroughPoints::Remember(const sensors::LaserScan& scan, const geometry::Pose2& world_from_laser) {
  views_.push_back({geometry::Inverse(world_from_laser), scan.geometry, scan.ranges_m});
  while (static_cast<int>(views_.size()) > options_.history_scans) views_.pop_front();
}

}  // namespace pena::odometry::internal
