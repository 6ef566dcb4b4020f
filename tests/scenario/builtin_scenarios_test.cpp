#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/sim/scenario.hpp"

namespace pena::sim {
namespace {

// Every route must clear walls by this much: with the walker on a door's centre line, every door
// walked through is at least 0.9 m wide.
constexpr double kDoorClearance_m = 0.45;

Scenario LoadBuiltin(const std::string& name) {
  const auto text = BuiltinScenarioText(name);
  if (!text) throw std::invalid_argument("no built-in " + name);
  return ParseScenario(*text, "builtin:" + name);
}

std::vector<Eigen::Vector2d> RoutePoints(const EntitySpec& entity) {
  std::vector<Eigen::Vector2d> points{{entity.start.x_m, entity.start.y_m}};
  for (const Waypoint& waypoint : entity.route) points.push_back(waypoint.position_m);
  return points;
}

double RouteLength_m(const EntitySpec& entity) {
  const auto points = RoutePoints(entity);
  double length_m = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length_m += (points[i] - points[i - 1]).norm();
  return length_m;
}

double PauseTotal_s(const EntitySpec& entity) {
  double total_s = 0.0;
  for (const Waypoint& waypoint : entity.route) total_s += waypoint.pause_s;
  return total_s;
}

double NearestWall_m(const std::vector<geometry::Segment2>& walls, const Eigen::Vector2d& point_m) {
  double best_m = std::numeric_limits<double>::infinity();
  for (const auto& wall : walls)
    best_m = std::min(best_m, geometry::DistanceToSegment(wall, point_m));
  return best_m;
}

Box BoundingBox(const std::vector<geometry::Segment2>& walls) {
  Box box{Eigen::Vector2d::Constant(1e9), Eigen::Vector2d::Constant(-1e9)};
  for (const auto& wall : walls) {
    box.min_m = box.min_m.cwiseMin(wall.start_m).cwiseMin(wall.end_m);
    box.max_m = box.max_m.cwiseMax(wall.start_m).cwiseMax(wall.end_m);
  }
  return box;
}

TEST(BuiltinScenarios, ListsLoop170OfficeAndTeam) {
  EXPECT_EQ(BuiltinScenarioNames(), (std::vector<std::string>{"loop170", "office", "team"}));
  EXPECT_FALSE(BuiltinScenarioText("warehouse").has_value());
}

TEST(BuiltinScenarios, EveryBuiltinParsesAndValidatesWithDoorClearance) {
  for (const std::string& name : BuiltinScenarioNames()) {
    const Scenario scenario = LoadBuiltin(name);
    EXPECT_EQ(scenario.name, name);
    EXPECT_GT(scenario.walls.size(), 40u) << name;
    EXPECT_EQ(ValidateScenario(scenario, kDoorClearance_m), "") << name;
  }
}

TEST(BuiltinScenarios, EveryRouteIsClosedSoSeveralLapsWork) {
  for (const std::string& name : BuiltinScenarioNames()) {
    Scenario scenario = LoadBuiltin(name);
    for (EntitySpec& entity : scenario.entities) {
      EXPECT_LT((RoutePoints(entity).back() - RoutePoints(entity).front()).norm(), 0.01)
          << name << " " << entity.id;
      entity.laps = 3;
    }
    EXPECT_EQ(ValidateScenario(scenario, kDoorClearance_m), "") << name;
  }
}

TEST(BuiltinScenarios, Loop170IsA170mWalkOfAbout231s) {
  const Scenario scenario = LoadBuiltin("loop170");
  ASSERT_EQ(scenario.entities.size(), 1u);
  const EntitySpec& ff1 = scenario.entities[0];
  EXPECT_EQ(ff1.id, "ff1");
  EXPECT_EQ(ff1.kind, sensors::EntityKind::kHuman);
  EXPECT_EQ(ff1.laps, 1);
  const double length_m = RouteLength_m(ff1);
  EXPECT_NEAR(length_m, 170.0, 0.05 * 170.0);
  // The simulator's random stops add to the cruise time; the planned time leaves room for them.
  const double planned_s = length_m / ff1.cruise_speed_m_s + PauseTotal_s(ff1);
  EXPECT_GT(planned_s, 0.85 * 231.0);
  EXPECT_LT(planned_s, 231.0);
  EXPECT_NEAR(scenario.ceiling_height_m, 2.6, 0.2);
  EXPECT_GE(scenario.magnetic.size(), 2u);
  EXPECT_FALSE(scenario.apriori.has_value());
}

// Overlap in metres of two parallel axis-aligned walls that face each other across a corridor.
double CorridorOverlap_m(const geometry::Segment2& a, const geometry::Segment2& b) {
  const int along = a.start_m.y() == a.end_m.y() ? 0 : 1;  // horizontal walls run along x
  const int across = 1 - along;
  if (a.start_m[across] != a.end_m[across] || b.start_m[across] != b.end_m[across]) return 0.0;
  const double gap_m = std::abs(a.start_m[across] - b.start_m[across]);
  if (gap_m < 1.5 || gap_m > 2.5) return 0.0;
  const double low = std::max(std::min(a.start_m[along], a.end_m[along]),
                              std::min(b.start_m[along], b.end_m[along]));
  const double high = std::min(std::max(a.start_m[along], a.end_m[along]),
                               std::max(b.start_m[along], b.end_m[along]));
  return high - low;
}

TEST(BuiltinScenarios, Loop170KeepsAPlainCorridorOf20m) {
  const Scenario scenario = LoadBuiltin("loop170");
  double longest_m = 0.0;
  for (const auto& a : scenario.walls) {
    for (const auto& b : scenario.walls) longest_m = std::max(longest_m, CorridorOverlap_m(a, b));
  }
  EXPECT_GE(longest_m, 20.0);
}

TEST(BuiltinScenarios, OfficeAprioriLacksFourRoomsAndHasShiftedWalls) {
  const Scenario scenario = LoadBuiltin("office");
  ASSERT_TRUE(scenario.apriori.has_value());
  const auto& apriori = *scenario.apriori;
  const Box mapped = BoundingBox(apriori);
  // True walls without an a priori counterpart, by where the missing rooms are.
  int missing_below = 0, missing_left = 0;
  for (const auto& wall : scenario.walls) {
    if (std::max(NearestWall_m(apriori, wall.start_m), NearestWall_m(apriori, wall.end_m)) < 0.7)
      continue;
    const Eigen::Vector2d middle = (wall.start_m + wall.end_m) / 2.0;
    missing_below += middle.y() < mapped.min_m.y() ? 1 : 0;
    missing_left += middle.x() < mapped.min_m.x() ? 1 : 0;
  }
  EXPECT_GE(missing_below, 2 * 3) << "two rooms at the bottom";
  EXPECT_GE(missing_left, 2 * 2) << "two small rooms on the left";
  // A priori walls whose middle is 0.25-0.65 m from the nearest true wall are shifted; none is
  // further.
  int shifted = 0;
  for (const auto& wall : apriori) {
    const double offset_m = NearestWall_m(scenario.walls, (wall.start_m + wall.end_m) / 2.0);
    EXPECT_LT(offset_m, 0.65);
    shifted += offset_m > 0.25 ? 1 : 0;
  }
  EXPECT_GE(shifted, 3);
}

TEST(BuiltinScenarios, OfficeWalkLeavesThePlanAndComesBack) {
  const Scenario scenario = LoadBuiltin("office");
  ASSERT_EQ(scenario.entities.size(), 1u);
  const Box mapped = BoundingBox(*scenario.apriori);
  const auto points = RoutePoints(scenario.entities[0]);
  EXPECT_TRUE(mapped.Contains(points.front()));
  EXPECT_TRUE(std::any_of(points.begin(), points.end(),
                          [&](const auto& p) { return p.y() < mapped.min_m.y(); }));
  EXPECT_TRUE(std::any_of(points.begin(), points.end(),
                          [&](const auto& p) { return p.x() < mapped.min_m.x(); }));
  ASSERT_FALSE(scenario.smoke.empty());
  EXPECT_TRUE(std::any_of(points.begin(), points.end(),
                          [&](const auto& p) { return scenario.smoke[0].area.Contains(p); }));
  const double planned_s =
      RouteLength_m(scenario.entities[0]) / scenario.entities[0].cruise_speed_m_s;
  EXPECT_GT(planned_s, 120.0);
  EXPECT_LT(planned_s, 600.0);
}

TEST(BuiltinScenarios, TeamStartsThreeFirefightersAndARobotAtOneEntrance) {
  const Scenario scenario = LoadBuiltin("team");
  ASSERT_EQ(scenario.entities.size(), 4u);
  int humans = 0, robots = 0;
  for (const auto& entity : scenario.entities) {
    (entity.kind == sensors::EntityKind::kHuman ? humans : robots) += 1;
  }
  EXPECT_EQ(humans, 3);
  EXPECT_EQ(robots, 1);
  const Box building = BoundingBox(scenario.walls);
  std::vector<double> start_times_s;
  for (const auto& a : scenario.entities) {
    for (const auto& b : scenario.entities)
      EXPECT_LT((RoutePoints(a)[0] - RoutePoints(b)[0]).norm(), 6.0);
    const Eigen::Vector2d start = RoutePoints(a)[0];
    EXPECT_LT(std::min({start.x() - building.min_m.x(), start.y() - building.min_m.y(),
                        building.max_m.x() - start.x(), building.max_m.y() - start.y()}),
              5.0)
        << a.id << " starts deep inside the building";
    start_times_s.push_back(a.start_time_s);
  }
  std::sort(start_times_s.begin(), start_times_s.end());
  for (std::size_t i = 1; i < start_times_s.size(); ++i) {
    EXPECT_GE(start_times_s[i] - start_times_s[i - 1], 2.0);
    EXPECT_LE(start_times_s[i] - start_times_s[i - 1], 10.0);
  }
  ASSERT_TRUE(scenario.apriori.has_value());
  EXPECT_LT(scenario.apriori->size(), scenario.walls.size());
  EXPECT_GE((building.max_m - building.min_m).prod(), 40.0 * 30.0);
}

}  // namespace
}  // namespace pena::sim
