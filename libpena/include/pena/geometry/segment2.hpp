#pragma once
// Line segments in the plane: walls of floor plans and line maps.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace pena::geometry {

// A straight segment between two points, metres, in the frame of its container.
struct Segment2 {
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d end_m = Eigen::Vector2d::Zero();
};

// Length in metres.
double Length(const Segment2& segment);

// Distance in metres from a point to the closest point of the segment.
double DistanceToSegment(const Segment2& segment, const Eigen::Vector2d& point_m);

// Distance along a ray (origin, unit direction) to where it crosses the segment, if it does (> 0).
std::optional<double> RaySegmentIntersection(const Eigen::Vector2d& origin_m,
                                             const Eigen::Vector2d& direction_unit,
                                             const Segment2& segment);

// Indices of the segments whose bounding boxes overlap the box [low_m, high_m].
std::vector<int> SegmentsInBox(const std::vector<Segment2>& segments, const Eigen::Vector2d& low_m,
                               const Eigen::Vector2d& high_m);

}  // namespace pena::geometry
