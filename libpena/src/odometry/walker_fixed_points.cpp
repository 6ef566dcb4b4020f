#include "walker_fixed_points.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "pena/geometry/segment2.hpp"
#include "pena/options_check.hpp"

namespace pena::odometry::internal {
namespace {

void Require(bool ok, const char* field, const char* rule, double value) {
  RequireOption(ok, "walker_fixed_points", field, rule, value);
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Whether the bearing of `point` (from the laser) lies between those of a and b.
bool BetweenBearings(const Eigen::Vector2d& point, const Eigen::Vector2d& a,
                     const Eigen::Vector2d& b) {
  const double ab = Cross(a, b);
  return Cross(a, point) * ab >= 0.0 && Cross(point, b) * ab >= 0.0 && point.dot(a + b) > 0.0;
}

// Whether `point` lies within tolerance_m of the outline through `outline` (laser frame, beam
// order): of one of its points, or of the segment between two consecutive ones that are at most
// max_gap_m apart or whose bearings bracket the point's. The second joins a wall seen at grazing
// incidence, its returns metres apart far down a corridor (0.5 deg beams: 2-3 m at 15-20 m);
// across a depth jump it joins a surface that is not there, which can only keep a return. A scan
// has a few hundred returns, so the plain loop costs well under a millisecond.
bool NearOutline(const Eigen::Vector2d& point, const scan_matching::Points2& outline,
                 double tolerance_m, double max_gap_m) {
  for (std::size_t i = 0; i < outline.size(); ++i) {
    if ((point - outline[i]).norm() <= tolerance_m) return true;
    if (i + 1 == outline.size()) break;
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d& b = outline[i + 1];
    if (((b - a).norm() <= max_gap_m || BetweenBearings(point, a, b)) &&
        geometry::DistanceToSegment({a, b}, point) <= tolerance_m) {
      return true;
    }
  }
  return false;
}

// Whether a previous return lies within the box along_m x across_m around `point` (laser frame).
bool NearInBodyFrame(const Eigen::Vector2d& point, const scan_matching::Points2& previous,
                     double along_m, double across_m) {
  return std::any_of(previous.begin(), previous.end(), [&](const Eigen::Vector2d& p) {
    return std::abs(p.x() - point.x()) <= along_m && std::abs(p.y() - point.y()) <= across_m;
  });
}

// Unmarks the runs of fewer than min_run consecutive marks; returns the marks left.
std::size_t KeepRuns(int min_run, std::vector<bool>& marks) {
  std::size_t left = 0;
  for (std::size_t begin = 0; begin < marks.size();) {
    if (!marks[begin]) {
      ++begin;
      continue;
    }
    std::size_t end = begin;
    while (end < marks.size() && marks[end]) ++end;
    if (end - begin < static_cast<std::size_t>(min_run)) {
      std::fill(marks.begin() + static_cast<std::ptrdiff_t>(begin),
                marks.begin() + static_cast<std::ptrdiff_t>(end), false);
    } else {
      left += end - begin;
    }
    begin = end;
  }
  return left;
}

}  // namespace

WalkerFixedPoints::WalkerFixedPoints(const WalkerFixedPointsOptions& o) : options_(o) {
  Require(o.static_m > 0.0, "static_m", "> 0 m", o.static_m);
  // A body-fixed return lies min_forward_m from its motion-compensated position: within static_m
  // it would pass for static, and the test could never tell the two apart.
  Require(o.min_forward_m > o.static_m, "min_forward_m", "> static_m (m)", o.min_forward_m);
  Require(o.body_along_m > 0.0, "body_along_m", "> 0 m", o.body_along_m);
  Require(o.body_across_m > 0.0, "body_across_m", "> 0 m", o.body_across_m);
  Require(o.static_per_range_m >= 0.0, "static_per_range_m", ">= 0 m per m", o.static_per_range_m);
  Require(o.max_turn_rad > 0.0, "max_turn_rad", "> 0 rad", o.max_turn_rad);
  Require(o.min_run_points >= 1, "min_run_points", ">= 1 points", o.min_run_points);
  Require(o.outline_max_gap_m >= 0.0, "outline_max_gap_m", ">= 0 m (0: points only)",
          o.outline_max_gap_m);
  Require(o.max_fraction > 0.0 && o.max_fraction <= 1.0, "max_fraction", "in (0, 1]",
          o.max_fraction);
}

std::vector<bool> WalkerFixedPoints::Find(const scan_matching::Points2& previous,
                                          const scan_matching::Points2& current,
                                          const geometry::Pose2& previous_from_current) const {
  std::vector<bool> moving(current.size(), false);
  if (previous.empty() || std::abs(previous_from_current.x_m) < options_.min_forward_m ||
      std::abs(previous_from_current.theta_rad) > options_.max_turn_rad) {
    return moving;
  }
  // Where the previous returns should be now if they are static.
  const scan_matching::Points2 compensated =
      scan_matching::TransformPoints(geometry::Inverse(previous_from_current), previous);
  for (std::size_t i = 0; i < current.size(); ++i) {
    const Eigen::Vector2d& point = current[i];
    const double static_m = options_.static_m + options_.static_per_range_m * point.norm();
    if (NearOutline(point, compensated, static_m, options_.outline_max_gap_m)) continue;
    // Not static, but also not seen before (a corner coming into view): kept.
    if (!NearInBodyFrame(point, previous, options_.body_along_m, options_.body_across_m)) continue;
    moving[i] = true;
  }
  const std::size_t marked = KeepRuns(options_.min_run_points, moving);
  if (static_cast<double>(marked) > options_.max_fraction * static_cast<double>(current.size())) {
    std::fill(moving.begin(), moving.end(), false);  // the prior is more likely wrong
  }
  return moving;
}

scan_matching::Points2 WithoutMarked(const scan_matching::Points2& points,
                                     const std::vector<bool>& moving) {
  scan_matching::Points2 kept;
  kept.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!moving[i]) kept.push_back(points[i]);
  }
  return kept;
}

}  // namespace pena::odometry::internal
