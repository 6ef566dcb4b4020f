#pragma once
// The geometry behind placement: wall samples, the global map's distance field and corners.
// Internal to the fusion module.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "pena/fusion/placement.hpp"
#include "pena/geometry/pose2.hpp"
#include "pena/line_map/line_segment.hpp"

namespace pena::fusion::detail {

// Points along walls, each standing for `weight_m` metres of wall (entity frame).
struct Samples {
  std::vector<Eigen::Vector2d> points_m;
  std::vector<double> weight_m;
  std::vector<std::size_t> wall;  // index of the wall (in the sampled vector) of each point
  double length_m = 0.0;  // total wall length
};

// Points at most spacing_m apart at the centres of equal pieces of each wall.
Samples SampleWalls(const std::vector<line_map::LineSegment>& walls, double spacing_m);

// Distance from any point to the nearest wall of a map, on a grid (a distance transform).
class DistanceField {
 public:
  // The grid covers the walls' bounding box plus pad_m on each side.
  DistanceField(const std::vector<line_map::LineSegment>& walls, double resolution_m,
                double pad_m);
  // Fraction of the sampled wall length within `distance_m` of a wall after mapping by
  // map_from_entity, each sample weighted 1 - (d / distance_m)^2 (graded like the matcher);
  // every stride-th sample only. Samples off the grid count 0.
  double Score(const Samples& samples, const geometry::Pose2& map_from_entity, double distance_m,
               std::size_t stride) const;
  // Explained length (metres, graded as Score) of each sampled wall, indexed like the walls.
  std::vector<double> ExplainedPerWall(const Samples& samples, std::size_t walls,
                                       const geometry::Pose2& map_from_entity,
                                       double distance_m) const;

 private:
  // 1 - (d / distance_m)^2 for a point d from the nearest wall, 0 beyond or off the grid.
  double Explained(const Eigen::Vector2d& map_point_m, double distance_m) const;

  cv::Mat distance_cells_;  // CV_32F, distance to the nearest wall in cells
  Eigen::Vector2d origin_m_;
  double resolution_m_;
};

// Two walls meeting: the meeting point and the directions of the two walls away from it, the
// second counter-clockwise from the first by opening_rad in (0, pi).
struct Corner {
  Eigen::Vector2d point_m;
  double first_rad = 0.0;
  double second_rad = 0.0;
  double opening_rad = 0.0;
};

// Corners among the `max_segments` longest walls: pairs at least min_corner_angle_rad apart
// whose lines meet within corner_max_gap_m of an end of each (or inside a wall: a T, giving a
// corner on each side).
std::vector<Corner> FindCorners(const std::vector<line_map::LineSegment>& walls,
                                int max_segments, const PlacementOptions& options);

}  // namespace pena::fusion::detail
