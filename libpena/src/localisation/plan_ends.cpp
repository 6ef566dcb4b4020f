#include "plan_ends.hpp"

#include <algorithm>
#include <cmath>

#include "pena/geometry/pose2.hpp"

namespace pena::localisation::internal {
namespace {

// Distance from `point` to every segment but `skip`; the smallest.
double NearestOther(const std::vector<geometry::Segment2>& plan, std::size_t skip, const Eigen::Vector2d& point) {
  double nearest = INFINITY;
  for (std::size_t k = 0; k < plan.size(); ++k) {
    if (k != skip) nearest = std::min(nearest, geometry::DistanceToSegment(plan[k], point));
  }
  return nearest;
}

double Bearing(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  return std::atan2(to.y() - from.y(), to.x() - from.x());
}

struct Run {
  std::vector<double> along_m;  // beyond the end along `outward`, ascending
  std::vector<std::size_t> indices;
};

// The returns within across_m of the wall's line and within window_m of the end along it.
Run RunAtEnd(const scan_matching::Points2& points, const Eigen::Vector2d& end_m, const Eigen::Vector2d& outward,
             const PlanEndOptions& options) {
  const Eigen::Vector2d normal(-outward.y(), outward.x());
  std::vector<std::pair<double, std::size_t>> found;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d offset = points[i] - end_m;
    const double along = offset.dot(outward);
    if (std::abs(offset.dot(normal)) <= options.across_m && std::abs(along) <= options.window_m) {
      found.emplace_back(along, i);
    }
  }
  std::sort(found.begin(), found.end());
  Run run;
  for (const auto& [along, index] : found) {
    run.along_m.push_back(along);
    run.indices.push_back(index);
  }
  return run;
}

// Whether the last min_points returns of the run follow each other within max_gap_m: at grazing
// incidence far away the returns are sparse and the last one may stop well short of the end.
bool DenseAtItsEnd(const Run& run, const PlanEndOptions& options) {
  const std::size_t n = run.along_m.size();
  if (n < static_cast<std::size_t>(options.min_points)) return false;
  for (std::size_t k = n - static_cast<std::size_t>(options.min_points) + 1; k < n; ++k) {
    if (run.along_m[k] - run.along_m[k - 1] > options.max_gap_m) return false;
  }
  return true;
}

// Whether the laser saw past the run's last return: the nearest return beyond it in bearing
// (within past_rad, on the side the wall would go on) lies past_m farther away. Otherwise the
// wall may go on behind something in front of it, or where the plan stops drawing it (a line
// map's segment ending at clutter).
bool SeenPast(const scan_matching::Points2& points, const Run& run, const Eigen::Vector2d& origin_m,
              const Eigen::Vector2d& outward, const PlanEndOptions& options) {
  const Eigen::Vector2d& last = points[run.indices.back()];
  const double bearing = Bearing(origin_m, last);
  const double range_m = (last - origin_m).norm();
  // Which way the bearing turns along the wall beyond its last return.
  const double side = geometry::NormalizeAngle(Bearing(origin_m, last + 0.1 * outward) - bearing) >= 0.0 ? 1.0 : -1.0;
  double nearest_rad = INFINITY;
  double nearest_range_m = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const double turn = side * geometry::NormalizeAngle(Bearing(origin_m, p) - bearing);
    if (turn > 1e-6 && turn <= options.past_rad && turn < nearest_rad) {
      nearest_rad = turn;
      nearest_range_m = (p - origin_m).norm();
    }
  }
  return std::isfinite(nearest_rad) && nearest_range_m >= range_m + options.past_m;
}

// The bearings of the returns about the heading: lowest and highest (the scan's field of view).
std::pair<double, double> BearingSpan(const scan_matching::Points2& points, const Eigen::Vector2d& origin_m,
                                      double heading_rad) {
  double low = INFINITY, high = -INFINITY;
  for (const Eigen::Vector2d& p : points) {
    const double b = geometry::NormalizeAngle(Bearing(origin_m, p) - heading_rad);
    low = std::min(low, b);
    high = std::max(high, b);
  }
  return {low, high};
}

}  // namespace

std::vector<SegmentEnds> FreeEnds(const std::vector<geometry::Segment2>& plan, double join_m) {
  std::vector<SegmentEnds> ends(plan.size());
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (geometry::Length(plan[i]) < 1e-9) continue;
    ends[i].start = NearestOther(plan, i, plan[i].start_m) > join_m;
    ends[i].end = NearestOther(plan, i, plan[i].end_m) > join_m;
  }
  return ends;
}

std::vector<EndMeasurement> MeasureEnds(const std::vector<geometry::Segment2>& plan,
                                        const std::vector<SegmentEnds>& ends,
                                        const scan_matching::Points2& map_points, const Eigen::Vector2d& origin_m,
                                        double heading_rad, const PlanEndOptions& options) {
  std::vector<EndMeasurement> measured;
  if (!options.enabled || map_points.empty()) return measured;
  // Only ends near the returns can be measured: a large plan costs one box test per end.
  Eigen::Vector2d low = map_points.front(), high = map_points.front();
  for (const Eigen::Vector2d& p : map_points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const auto near = [&](const Eigen::Vector2d& end_m) {
    return (end_m.array() >= low.array() - options.window_m).all() &&
           (end_m.array() <= high.array() + options.window_m).all();
  };
  // A pair, not a structured binding: lambdas capture those only from clang 16 on.
  const std::pair<double, double> span_rad = BearingSpan(map_points, origin_m, heading_rad);
  // The laser must have been able to see past an end: its bearing inside the span by past_rad.
  const auto inside_view = [&](const Eigen::Vector2d& point) {
    const double b = geometry::NormalizeAngle(Bearing(origin_m, point) - heading_rad);
    return b >= span_rad.first + options.past_rad && b <= span_rad.second - options.past_rad;
  };
  for (std::size_t i = 0; i < plan.size() && i < ends.size(); ++i) {
    const geometry::Segment2& s = plan[i];
    const double length_m = geometry::Length(s);
    if (length_m < 2.0 * options.window_m) continue;  // a stub: both ends in one window
    const Eigen::Vector2d along = (s.end_m - s.start_m) / length_m;
    for (const bool at_end : {false, true}) {
      if (!(at_end ? ends[i].end : ends[i].start)) continue;
      const Eigen::Vector2d end_m = at_end ? s.end_m : s.start_m;
      if (!near(end_m)) continue;
      const Eigen::Vector2d outward = at_end ? along : Eigen::Vector2d(-along);
      const Run run = RunAtEnd(map_points, end_m, outward, options);
      if (!DenseAtItsEnd(run, options) || !inside_view(map_points[run.indices.back()]) ||
          !SeenPast(map_points, run, origin_m, outward, options)) {
        continue;
      }
      measured.push_back({static_cast<int>(i), end_m, outward, run.along_m.back()});
    }
  }
  return measured;
}

}  // namespace pena::localisation::internal
