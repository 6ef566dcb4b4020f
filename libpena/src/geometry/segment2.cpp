#include "pena/geometry/segment2.hpp"

#include <algorithm>
#include <cmath>

namespace pena::geometry {

double Length(const Segment2& segment) { return (segment.end_m - segment.start_m).norm(); }

double DistanceToSegment(const Segment2& segment, const Eigen::Vector2d& point_m) {
  const Eigen::Vector2d along = segment.end_m - segment.start_m;
  const double length_sq = along.squaredNorm();
  if (length_sq <= 0.0) return (point_m - segment.start_m).norm();
  const double t = std::clamp((point_m - segment.start_m).dot(along) / length_sq, 0.0, 1.0);
  return (point_m - (segment.start_m + t * along)).norm();
}

std::optional<double> RaySegmentIntersection(const Eigen::Vector2d& origin_m,
                                             const Eigen::Vector2d& direction_unit,
                                             const Segment2& segment) {
  // Solve origin + r * d = start + t * (end - start) with Cramer's rule (2D cross products).
  const Eigen::Vector2d edge = segment.end_m - segment.start_m;
  const double denom = direction_unit.x() * edge.y() - direction_unit.y() * edge.x();
  if (std::abs(denom) < 1e-12) return std::nullopt;  // parallel: a grazing ray sees no wall
  const Eigen::Vector2d to_start = segment.start_m - origin_m;
  const double range = (to_start.x() * edge.y() - to_start.y() * edge.x()) / denom;
  const double t = (to_start.x() * direction_unit.y() - to_start.y() * direction_unit.x()) / denom;
  if (range <= 0.0 || t < 0.0 || t > 1.0) return std::nullopt;
  return range;
}

std::vector<int> SegmentsInBox(const std::vector<Segment2>& segments, const Eigen::Vector2d& low_m,
                               const Eigen::Vector2d& high_m) {
  std::vector<int> inside;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment2& s = segments[i];
    if ((s.start_m.cwiseMin(s.end_m).array() <= high_m.array()).all() &&
        (s.start_m.cwiseMax(s.end_m).array() >= low_m.array()).all()) {
      inside.push_back(static_cast<int>(i));
    }
  }
  return inside;
}

}  // namespace pena::geometry
