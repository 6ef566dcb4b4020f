#include "placement_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

namespace pena::fusion::detail {
namespace {

// Directions (angles) of the wall's rays away from `point`: one if the point is near an end,
// two if it lies inside the wall (a T junction), none otherwise.
std::vector<double> RaysFrom(const geometry::Segment2& wall, const Eigen::Vector2d& point,
                             double max_gap_m) {
  const Eigen::Vector2d along = wall.end_m - wall.start_m;
  const double length = along.norm();
  const Eigen::Vector2d unit = along / length;
  const double s = (point - wall.start_m).dot(unit);
  const double angle = std::atan2(unit.y(), unit.x());
  if (std::abs(s) <= max_gap_m) return {angle};
  if (std::abs(s - length) <= max_gap_m) return {geometry::NormalizeAngle(angle + std::numbers::pi)};
  if (s > max_gap_m && s < length - max_gap_m) {
    return {angle, geometry::NormalizeAngle(angle + std::numbers::pi)};
  }
  return {};
}

void AddCorners(const geometry::Segment2& a, const geometry::Segment2& b,
                const PlacementOptions& options, std::vector<Corner>& corners) {
  const Eigen::Vector2d da = (a.end_m - a.start_m).normalized();
  const Eigen::Vector2d db = (b.end_m - b.start_m).normalized();
  const double cross = da.x() * db.y() - da.y() * db.x();
  if (std::abs(cross) < std::sin(options.min_corner_angle_rad)) return;
  // a.start + s da = b.start + u db, solved for s by Cramer's rule.
  const Eigen::Vector2d w = b.start_m - a.start_m;
  const double s = (w.x() * db.y() - w.y() * db.x()) / cross;
  const Eigen::Vector2d point = a.start_m + s * da;
  for (const double ray_a : RaysFrom(a, point, options.corner_max_gap_m)) {
    for (const double ray_b : RaysFrom(b, point, options.corner_max_gap_m)) {
      double opening = geometry::NormalizeAngle(ray_b - ray_a);
      const bool ccw = opening > 0.0;
      if (!ccw) opening = -opening;
      if (opening < options.min_corner_angle_rad ||
          opening > std::numbers::pi - options.min_corner_angle_rad) {
        continue;
      }
      corners.push_back({point, ccw ? ray_a : ray_b, ccw ? ray_b : ray_a, opening});
    }
  }
}

}  // namespace

Samples SampleWalls(const std::vector<line_map::LineSegment>& walls, double spacing_m) {
  Samples samples;
  for (std::size_t index = 0; index < walls.size(); ++index) {
    const line_map::LineSegment& wall = walls[index];
    const double length = geometry::Length(wall.segment);
    if (length <= 0.0) continue;
    const int pieces = std::max(1, static_cast<int>(std::ceil(length / spacing_m)));
    for (int i = 0; i < pieces; ++i) {
      const double fraction = (i + 0.5) / pieces;
      samples.points_m.push_back(wall.segment.start_m +
                                 fraction * (wall.segment.end_m - wall.segment.start_m));
      samples.weight_m.push_back(length / pieces);
      samples.wall.push_back(index);
    }
    samples.length_m += length;
  }
  return samples;
}

DistanceField::DistanceField(const std::vector<line_map::LineSegment>& walls,
                             double resolution_m, double pad_m)
    : resolution_m_(resolution_m) {
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_m = Eigen::Vector2d::Zero();
  if (!walls.empty()) min_m = max_m = walls.front().segment.start_m;
  for (const line_map::LineSegment& wall : walls) {
    for (const Eigen::Vector2d& p : {wall.segment.start_m, wall.segment.end_m}) {
      min_m = min_m.cwiseMin(p);
      max_m = max_m.cwiseMax(p);
    }
  }
  origin_m_ = min_m - Eigen::Vector2d::Constant(pad_m);
  const Eigen::Vector2d size = (max_m - min_m).array() + 2.0 * pad_m;
  const int cols = static_cast<int>(std::ceil(size.x() / resolution_m)) + 1;
  const int rows = static_cast<int>(std::ceil(size.y() / resolution_m)) + 1;
  cv::Mat free_cells(rows, cols, CV_8UC1, cv::Scalar(255));
  const auto cell = [this](const Eigen::Vector2d& p) {
    const Eigen::Vector2d c = (p - origin_m_) / resolution_m_;
    return cv::Point(static_cast<int>(std::floor(c.x())), static_cast<int>(std::floor(c.y())));
  };
  for (const line_map::LineSegment& wall : walls) {
    cv::line(free_cells, cell(wall.segment.start_m), cell(wall.segment.end_m), cv::Scalar(0), 1,
             cv::LINE_8);
  }
  cv::distanceTransform(free_cells, distance_cells_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
}

double DistanceField::Explained(const Eigen::Vector2d& map_point_m, double distance_m) const {
  const Eigen::Vector2d p = map_point_m - origin_m_;
  const int col = static_cast<int>(std::floor(p.x() / resolution_m_));
  const int row = static_cast<int>(std::floor(p.y() / resolution_m_));
  if (col < 0 || row < 0 || col >= distance_cells_.cols || row >= distance_cells_.rows) return 0.0;
  const double d = distance_cells_.at<float>(row, col) * resolution_m_ / distance_m;
  return d < 1.0 ? 1.0 - d * d : 0.0;
}

double DistanceField::Score(const Samples& samples, const geometry::Pose2& map_from_entity,
                            double distance_m, std::size_t stride) const {
  const double c = std::cos(map_from_entity.theta_rad);
  const double s = std::sin(map_from_entity.theta_rad);
  const Eigen::Vector2d t(map_from_entity.x_m, map_from_entity.y_m);
  double explained = 0.0;
  double total = 0.0;
  for (std::size_t i = 0; i < samples.points_m.size(); i += stride) {
    const Eigen::Vector2d& p = samples.points_m[i];
    total += samples.weight_m[i];
    explained += samples.weight_m[i] *
                 Explained(Eigen::Vector2d(c * p.x() - s * p.y(), s * p.x() + c * p.y()) + t,
                           distance_m);
  }
  return total > 0.0 ? explained / total : 0.0;
}

std::vector<double> DistanceField::ExplainedPerWall(const Samples& samples, std::size_t walls,
                                                    const geometry::Pose2& map_from_entity,
                                                    double distance_m) const {
  std::vector<double> explained_m(walls, 0.0);
  for (std::size_t i = 0; i < samples.points_m.size(); ++i) {
    explained_m[samples.wall[i]] +=
        samples.weight_m[i] *
        Explained(geometry::TransformPoint(map_from_entity, samples.points_m[i]), distance_m);
  }
  return explained_m;
}

std::vector<Corner> FindCorners(const std::vector<line_map::LineSegment>& walls, int max_segments,
                                const PlacementOptions& options) {
  std::vector<geometry::Segment2> longest;
  for (const line_map::LineSegment& wall : walls) {
    if (geometry::Length(wall.segment) > options.corner_max_gap_m) longest.push_back(wall.segment);
  }
  std::stable_sort(longest.begin(), longest.end(), [](const auto& a, const auto& b) {
    return geometry::Length(a) > geometry::Length(b);
  });
  if (longest.size() > static_cast<std::size_t>(max_segments)) {
    longest.resize(static_cast<std::size_t>(max_segments));
  }
  std::vector<Corner> corners;
  for (std::size_t i = 0; i < longest.size(); ++i) {
    for (std::size_t j = i + 1; j < longest.size(); ++j) {
      AddCorners(longest[i], longest[j], options, corners);
    }
  }
  return corners;
}

}  // namespace pena::fusion::detail
