#pragma once
// A simulated rescue mission: the building, its a priori plan, hazards and who walks where.
// Text format and the built-in scenarios: docs/scenarios.md.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/sensors/entity.hpp"

namespace pena::sim {

// An axis-aligned rectangle in the mission frame, metres.
struct Box {
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_m = Eigen::Vector2d::Zero();
  bool Contains(const Eigen::Vector2d& point_m) const {
    return (point_m.array() >= min_m.array()).all() && (point_m.array() <= max_m.array()).all();
  }
};

// Smoke where the laser's maximum range drops to max_range_m.
struct SmokeZone {
  Box area;
  double max_range_m = 3.0;
};

// A magnetic disturbance near steel structures: the compass reading is offset by up to
// peak_offset_rad at the centre, fading linearly to zero at radius_m.
struct MagneticDisturbance {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double radius_m = 2.0;
  double peak_offset_rad = 0.5;
};

// A point of an entity's route: walk (or drive) there, then stay pause_s seconds.
struct Waypoint {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double pause_s = 0.0;
};

// One team member and its route; the route is followed `laps` times (a closed route ends where
// it starts).
struct EntitySpec {
  std::string id;
  sensors::EntityKind kind = sensors::EntityKind::kHuman;
  geometry::Pose2 start;         // known start pose in the mission frame
  double start_time_s = 0.0;     // when it enters the mission
  double cruise_speed_m_s = 1.0; // mean speed while walking or driving
  std::vector<Waypoint> route;
  int laps = 1;
};

// A whole scenario.
struct Scenario {
  std::string name;
  double ceiling_height_m = 2.6;
  std::vector<geometry::Segment2> walls;          // the true building
  std::optional<std::vector<geometry::Segment2>> apriori;  // the (partial, partly wrong) plan
  std::vector<SmokeZone> smoke;
  std::vector<MagneticDisturbance> magnetic;
  std::vector<EntitySpec> entities;
};

// Parses the scenario text format; throws io-style errors "origin:line: what" as
// std::invalid_argument. `origin` names the text in messages (a path or "builtin:office").
Scenario ParseScenario(std::string_view text, const std::string& origin);

// Names of the built-in scenarios: "loop170", "office", "team".
std::vector<std::string> BuiltinScenarioNames();

// The scenario text of a built-in scenario, or nullopt for an unknown name.
std::optional<std::string_view> BuiltinScenarioText(std::string_view name);

// Checks that the scenario is usable: every route leg is clear of walls by at least
// clearance_m, entities have routes, numbers are in range. Returns "" or a message naming the
// entity and waypoint.
std::string ValidateScenario(const Scenario& scenario, double clearance_m = 0.3);

}  // namespace pena::sim
