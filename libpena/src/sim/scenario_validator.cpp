// ValidateScenario: a scenario is usable when every route keeps clear of the walls and its
// numbers are in range (docs/scenarios.md, "Checking a scenario").

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "pena/sim/scenario.hpp"

namespace pena::sim {
namespace {

constexpr double kClosedRouteTolerance_m = 0.5;
constexpr double kMaxSpeed_m_s = 5.0;

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), format, a, b, c, d);
  return buffer;
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// True when two non-collinear segments share a point (cross or touch). Collinear overlaps are
// caught by the endpoint distances in SegmentDistance.
bool SegmentsIntersect(const geometry::Segment2& p, const geometry::Segment2& q) {
  const Eigen::Vector2d r = p.end_m - p.start_m, s = q.end_m - q.start_m;
  const double d1 = Cross(r, q.start_m - p.start_m), d2 = Cross(r, q.end_m - p.start_m);
  const double d3 = Cross(s, p.start_m - q.start_m), d4 = Cross(s, p.end_m - q.start_m);
  auto straddles = [](double a, double b) {
    return (a <= 0.0 && b >= 0.0) || (a >= 0.0 && b <= 0.0);
  };
  if (d1 == 0.0 && d2 == 0.0) return false;
  return straddles(d1, d2) && straddles(d3, d4);
}

// Shortest distance between two segments: zero if they cross, else an endpoint-to-segment distance.
double SegmentDistance(const geometry::Segment2& p, const geometry::Segment2& q) {
  if (SegmentsIntersect(p, q)) return 0.0;
  return std::min(
      {geometry::DistanceToSegment(q, p.start_m), geometry::DistanceToSegment(q, p.end_m),
       geometry::DistanceToSegment(p, q.start_m), geometry::DistanceToSegment(p, q.end_m)});
}

std::string PointName(std::size_t index) {
  return index == 0 ? std::string("the start") : "waypoint " + std::to_string(index);
}

// Checks one leg between route points `from` and `to` (0 = start pose, i = waypoint i, 1-based).
std::string CheckLeg(const Scenario& scenario, const std::vector<Eigen::Vector2d>& points,
                     std::size_t from, std::size_t to, double clearance_m) {
  const geometry::Segment2 leg{points[from], points[to]};
  for (std::size_t w = 0; w < scenario.walls.size(); ++w) {
    const geometry::Segment2& wall = scenario.walls[w];
    const double distance_m = SegmentDistance(leg, wall);
    if (distance_m >= clearance_m) continue;
    const std::string wall_name = "wall " + std::to_string(w) +
                                  Format(" (%.2f %.2f %.2f %.2f)", wall.start_m.x(),
                                         wall.start_m.y(), wall.end_m.x(), wall.end_m.y());
    const std::string leg_name = "leg from " + PointName(from) + " to " + PointName(to);
    if (distance_m == 0.0) return leg_name + " crosses " + wall_name;
    return leg_name + " passes " + Format("%.2f m", distance_m) + " from " + wall_name +
           Format(" (clearance_m %.2f)", clearance_m);
  }
  return "";
}

std::string CheckEntityNumbers(const EntitySpec& entity) {
  if (entity.id.empty()) return "an entity has an empty id";
  const std::string prefix = "entity " + entity.id + ": ";
  const auto& start = entity.start;
  if (!std::isfinite(start.x_m) || !std::isfinite(start.y_m) || !std::isfinite(start.theta_rad)) {
    return prefix + "start pose must be finite";
  }
  if (!(entity.start_time_s >= 0.0) || !std::isfinite(entity.start_time_s))
    return prefix + "start_time_s must be >= 0";
  if (!(entity.cruise_speed_m_s > 0.0 && entity.cruise_speed_m_s <= kMaxSpeed_m_s)) {
    return prefix + Format("cruise_speed_m_s must be in (0, %.1f], got %g", kMaxSpeed_m_s,
                           entity.cruise_speed_m_s);
  }
  if (entity.laps < 1) return prefix + "laps must be >= 1, got " + std::to_string(entity.laps);
  if (entity.route.empty()) return prefix + "has no waypoints";
  for (std::size_t i = 0; i < entity.route.size(); ++i) {
    const Waypoint& waypoint = entity.route[i];
    if (!waypoint.position_m.allFinite() || !(waypoint.pause_s >= 0.0) ||
        !std::isfinite(waypoint.pause_s)) {
      return prefix + "waypoint " + std::to_string(i + 1) +
             " needs a finite position and pause_s >= 0";
    }
  }
  return "";
}

// Route legs: start -> waypoint 1 -> ... -> waypoint N. With laps > 1 the route must be closed
// (waypoint N within kClosedRouteTolerance_m of the start) and the next lap walks N -> 1.
std::string CheckRoute(const Scenario& scenario, const EntitySpec& entity, double clearance_m) {
  const std::string prefix = "entity " + entity.id + ": ";
  std::vector<Eigen::Vector2d> points{{entity.start.x_m, entity.start.y_m}};
  for (const Waypoint& waypoint : entity.route) points.push_back(waypoint.position_m);
  for (std::size_t w = 0; w < scenario.walls.size(); ++w) {
    const double distance_m = geometry::DistanceToSegment(scenario.walls[w], points[0]);
    if (distance_m < clearance_m) {
      return prefix + "the start is " +
             Format("%.2f m from wall %.0f", distance_m, static_cast<double>(w));
    }
  }
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (std::string error = CheckLeg(scenario, points, i - 1, i, clearance_m); !error.empty()) {
      return prefix + error;
    }
  }
  if (entity.laps > 1) {
    const double gap_m = (points.back() - points.front()).norm();
    if (gap_m > kClosedRouteTolerance_m) {
      return prefix + "laps=" + std::to_string(entity.laps) +
             " needs a closed route: " + PointName(points.size() - 1) +
             Format(" ends %.2f m from the start (max %.2f m)", gap_m, kClosedRouteTolerance_m);
    }
    if (std::string error = CheckLeg(scenario, points, points.size() - 1, 1, clearance_m);
        !error.empty()) {
      return prefix + error + " (next lap)";
    }
  }
  return "";
}

std::string CheckBuilding(const Scenario& scenario) {
  if (!(scenario.ceiling_height_m > 0.0) || !std::isfinite(scenario.ceiling_height_m)) {
    return "ceiling_height_m must be > 0";
  }
  auto finite = [](const geometry::Segment2& s) {
    return s.start_m.allFinite() && s.end_m.allFinite();
  };
  if (!std::all_of(scenario.walls.begin(), scenario.walls.end(), finite))
    return "walls must be finite";
  if (scenario.apriori &&
      !std::all_of(scenario.apriori->begin(), scenario.apriori->end(), finite)) {
    return "a priori walls must be finite";
  }
  for (const SmokeZone& smoke : scenario.smoke) {
    if (!(smoke.area.max_m.array() > smoke.area.min_m.array()).all() ||
        !(smoke.max_range_m > 0.0)) {
      return "smoke zones need min_m < max_m and max_range_m > 0";
    }
  }
  for (const MagneticDisturbance& magnetic : scenario.magnetic) {
    if (!magnetic.center_m.allFinite() || !(magnetic.radius_m > 0.0) ||
        !(std::abs(magnetic.peak_offset_rad) <= std::numbers::pi)) {
      return "magnetic disturbances need radius_m > 0 and |peak_offset_rad| <= pi";
    }
  }
  return "";
}

}  // namespace

std::string ValidateScenario(const Scenario& scenario, double clearance_m) {
  if (!(clearance_m >= 0.0) || !std::isfinite(clearance_m)) return "clearance_m must be >= 0";
  if (std::string error = CheckBuilding(scenario); !error.empty()) return error;
  if (scenario.entities.empty()) return "the scenario has no entities";
  std::set<std::string> ids;
  for (const EntitySpec& entity : scenario.entities) {
    if (std::string error = CheckEntityNumbers(entity); !error.empty()) return error;
    if (!ids.insert(entity.id).second) return "duplicate entity id " + entity.id;
    if (std::string error = CheckRoute(scenario, entity, clearance_m); !error.empty()) return error;
  }
  return "";
}

}  // namespace pena::sim
