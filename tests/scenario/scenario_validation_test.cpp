#include <gtest/gtest.h>

#include <string>

#include "pena/sim/scenario.hpp"

namespace pena::sim {
namespace {

// Two 5 x 4 m rooms side by side, joined by a door of `door_width_m` centred at (5, 2).
Scenario TwoRooms(double door_width_m) {
  Scenario scenario;
  scenario.name = "two_rooms";
  const double half = door_width_m / 2.0;
  scenario.walls = {{{0, 0}, {10, 0}}, {{10, 0}, {10, 4}},      {{10, 4}, {0, 4}},
                    {{0, 4}, {0, 0}},  {{5, 0}, {5, 2 - half}}, {{5, 2 + half}, {5, 4}}};
  EntitySpec ff1;
  ff1.id = "ff1";
  ff1.start = {2.0, 2.0, 0.0};
  ff1.route = {{{8.0, 2.0}, 0.0}, {{2.0, 2.0}, 0.0}};
  scenario.entities.push_back(ff1);
  return scenario;
}

TEST(ValidateScenario, AcceptsRouteThroughWideEnoughDoor) {
  EXPECT_EQ(ValidateScenario(TwoRooms(1.0)), "");
  EXPECT_EQ(ValidateScenario(TwoRooms(0.92), 0.45), "");
}

TEST(ValidateScenario, RejectsDoorNarrowerThanTwiceTheClearance) {
  const std::string error = ValidateScenario(TwoRooms(0.5));
  EXPECT_NE(error.find("entity ff1"), std::string::npos) << error;
  EXPECT_NE(error.find("leg from the start to waypoint 1 passes 0.25 m from wall"),
            std::string::npos)
      << error;
  EXPECT_NE(ValidateScenario(TwoRooms(0.8), 0.45), "");
}

TEST(ValidateScenario, NamesEntityAndWaypointOfLegCrossingWall) {
  Scenario scenario = TwoRooms(1.0);
  scenario.entities[0].route = {{{2.0, 3.0}, 0.0}, {{8.0, 3.5}, 0.0}, {{2.0, 2.0}, 0.0}};
  const std::string error = ValidateScenario(scenario);
  EXPECT_NE(error.find("entity ff1: leg from waypoint 1 to waypoint 2 crosses wall 5"),
            std::string::npos)
      << error;
}

TEST(ValidateScenario, RejectsStartNextToWall) {
  Scenario scenario = TwoRooms(1.0);
  scenario.entities[0].start.y_m = 0.1;
  EXPECT_NE(ValidateScenario(scenario).find("entity ff1: the start is 0.10 m from wall 0"),
            std::string::npos);
}

TEST(ValidateScenario, RequiresClosedRouteForSeveralLaps) {
  Scenario scenario = TwoRooms(1.0);
  scenario.entities[0].laps = 3;
  EXPECT_EQ(ValidateScenario(scenario), "");  // ends at its start
  scenario.entities[0].route.back().position_m = {3.0, 2.0};
  const std::string error = ValidateScenario(scenario);
  EXPECT_NE(
      error.find("entity ff1: laps=3 needs a closed route: waypoint 2 ends 1.00 m from the start"),
      std::string::npos)
      << error;
  scenario.entities[0].laps = 1;
  EXPECT_EQ(ValidateScenario(scenario), "");
}

TEST(ValidateScenario, RejectsNumbersOutOfRange) {
  auto error_with = [](auto&& change) {
    Scenario scenario = TwoRooms(1.0);
    change(scenario);
    return ValidateScenario(scenario);
  };
  EXPECT_NE(error_with([](Scenario& s) {
              s.entities[0].cruise_speed_m_s = 0.0;
            }).find("cruise_speed_m_s"),
            std::string::npos);
  EXPECT_NE(error_with([](Scenario& s) {
              s.entities[0].cruise_speed_m_s = 12.0;
            }).find("cruise_speed_m_s"),
            std::string::npos);
  EXPECT_NE(error_with([](Scenario& s) { s.entities[0].laps = 0; }).find("laps"),
            std::string::npos);
  EXPECT_NE(error_with([](Scenario& s) {
              s.entities[0].route.clear();
            }).find("entity ff1: has no waypoints"),
            std::string::npos);
  EXPECT_NE(
      error_with([](Scenario& s) { s.entities[0].route[1].pause_s = -1.0; }).find("waypoint 2"),
      std::string::npos);
  EXPECT_NE(error_with([](Scenario& s) {
              s.entities.push_back(s.entities[0]);
            }).find("duplicate entity id ff1"),
            std::string::npos);
  EXPECT_EQ(error_with([](Scenario& s) { s.entities.clear(); }), "the scenario has no entities");
  EXPECT_NE(error_with([](Scenario& s) { s.ceiling_height_m = 0.0; }).find("ceiling_height_m"),
            std::string::npos);
  EXPECT_NE(error_with([](Scenario& s) {
              s.smoke.push_back({{{1, 1}, {0, 2}}, 3.0});
            }).find("smoke"),
            std::string::npos);
  EXPECT_NE(error_with([](Scenario& s) {
              s.magnetic.push_back({{1, 1}, -1.0, 0.1});
            }).find("magnetic"),
            std::string::npos);
}

TEST(ValidateScenario, ValidatesParsedText) {
  const Scenario scenario = ParseScenario(
      "pena-scenario 1\nname t\nrect 0 0 10 4\nentity a human 1 2 0\nwaypoint a 9 2\nwaypoint a 9 "
      "5\n",
      "t");
  const std::string error = ValidateScenario(scenario);
  EXPECT_NE(error.find("entity a: leg from waypoint 1 to waypoint 2 crosses wall 2"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace pena::sim
