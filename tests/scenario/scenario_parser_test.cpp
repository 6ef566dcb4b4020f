#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pena/sim/scenario.hpp"

namespace pena::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

TEST(ScenarioParser, ReadsEveryKeyword) {
  const std::string text =
      "# a comment before the header\n"
      "\n"
      "pena-scenario 1   # trailing comment\n"
      "name corridor\r\n"
      "ceiling 2.8\n"
      "wall 0 0 10 0\n"
      "polyline 0 3 10 3 10 6\n"
      "rect 20 20 22 21\n"
      "apriori wall 0 0 10 0.4\n"
      "apriori polyline 0 3 5 3 5 4\n"
      "apriori rect 1 1 2 2\n"
      "smoke 1 2 3 4 2.5\n"
      "magnetic 5 1.5 2 +30\n"
      "entity ff1 human 1 1.5 90 start=2.5 speed=0.8 laps=2\n"
      "\twaypoint  ff1 9 1.5 pause=3\n"
      "waypoint ff1 1 1.5\n";
  const Scenario scenario = ParseScenario(text, "test");
  EXPECT_EQ(scenario.name, "corridor");
  EXPECT_DOUBLE_EQ(scenario.ceiling_height_m, 2.8);
  ASSERT_EQ(scenario.walls.size(), 1u + 2u + 4u);
  EXPECT_EQ(scenario.walls[0].end_m, Eigen::Vector2d(10, 0));
  EXPECT_EQ(scenario.walls[2].start_m, Eigen::Vector2d(10, 3));
  EXPECT_EQ(scenario.walls[2].end_m, Eigen::Vector2d(10, 6));
  EXPECT_EQ(scenario.walls[5].start_m, Eigen::Vector2d(22, 21));  // rect: south, east, north, west
  ASSERT_TRUE(scenario.apriori.has_value());
  EXPECT_EQ(scenario.apriori->size(), 1u + 2u + 4u);
  EXPECT_DOUBLE_EQ(scenario.apriori->front().end_m.y(), 0.4);
  ASSERT_EQ(scenario.smoke.size(), 1u);
  EXPECT_EQ(scenario.smoke[0].area.min_m, Eigen::Vector2d(1, 2));
  EXPECT_EQ(scenario.smoke[0].area.max_m, Eigen::Vector2d(3, 4));
  EXPECT_DOUBLE_EQ(scenario.smoke[0].max_range_m, 2.5);
  ASSERT_EQ(scenario.magnetic.size(), 1u);
  EXPECT_EQ(scenario.magnetic[0].center_m, Eigen::Vector2d(5, 1.5));
  EXPECT_DOUBLE_EQ(scenario.magnetic[0].radius_m, 2.0);
  EXPECT_NEAR(scenario.magnetic[0].peak_offset_rad, 30.0 * kDegToRad, 1e-12);
  ASSERT_EQ(scenario.entities.size(), 1u);
  const EntitySpec& ff1 = scenario.entities[0];
  EXPECT_EQ(ff1.id, "ff1");
  EXPECT_EQ(ff1.kind, sensors::EntityKind::kHuman);
  EXPECT_DOUBLE_EQ(ff1.start.x_m, 1.0);
  EXPECT_DOUBLE_EQ(ff1.start.y_m, 1.5);
  EXPECT_NEAR(ff1.start.theta_rad, std::numbers::pi / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(ff1.start_time_s, 2.5);
  EXPECT_DOUBLE_EQ(ff1.cruise_speed_m_s, 0.8);
  EXPECT_EQ(ff1.laps, 2);
  ASSERT_EQ(ff1.route.size(), 2u);
  EXPECT_EQ(ff1.route[0].position_m, Eigen::Vector2d(9, 1.5));
  EXPECT_DOUBLE_EQ(ff1.route[0].pause_s, 3.0);
  EXPECT_DOUBLE_EQ(ff1.route[1].pause_s, 0.0);
}

TEST(ScenarioParser, AppliesDefaultsAndWrapsHeading) {
  const Scenario scenario =
      ParseScenario("pena-scenario 1\nentity r1 robot -2 3 270\nwaypoint r1 0 3\n", "test");
  EXPECT_FALSE(scenario.apriori.has_value());
  EXPECT_TRUE(scenario.name.empty());
  EXPECT_DOUBLE_EQ(scenario.ceiling_height_m, Scenario{}.ceiling_height_m);
  const EntitySpec& robot = scenario.entities.at(0);
  EXPECT_EQ(robot.kind, sensors::EntityKind::kRobot);
  EXPECT_NEAR(robot.start.theta_rad, -std::numbers::pi / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(robot.start_time_s, 0.0);
  EXPECT_DOUBLE_EQ(robot.cruise_speed_m_s, EntitySpec{}.cruise_speed_m_s);
  EXPECT_EQ(robot.laps, 1);
}

// One malformed input: the text after the header line, the line the error must name and a
// fragment of the message.
struct BadInput {
  std::string body;
  int line;
  std::string fragment;
};

class ScenarioParserError : public ::testing::TestWithParam<BadInput> {};

TEST_P(ScenarioParserError, NamesOriginLineAndProblem) {
  const BadInput& bad = GetParam();
  const std::string text = "pena-scenario 1\n# comment\nname x\n" + bad.body;
  try {
    ParseScenario(text, "my.scn");
    FAIL() << "no error for: " << bad.body;
  } catch (const std::invalid_argument& error) {
    const std::string what = error.what();
    EXPECT_EQ(what.rfind("my.scn:" + std::to_string(bad.line) + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(bad.fragment), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Errors, ScenarioParserError,
    ::testing::Values(
        BadInput{"door 1 2 3 4\n", 4, "unknown keyword 'door'"},
        BadInput{"\n\nwall 1 2 3\n", 6, "expects 4 numbers"},
        BadInput{"rect 1 2 3 4 5\n", 4, "expects 4 numbers"},
        BadInput{"polyline 0 0 1 1 2\n", 4, "even number"},
        BadInput{"polyline 0 0\n", 4, "even number"}, BadInput{"ceiling\n", 4, "expected ceiling"},
        BadInput{"name a b\n", 4, "expected name"},
        BadInput{"smoke 0 0 1 1\n", 4, "expected smoke"},
        BadInput{"magnetic 0 0 1\n", 4, "expected magnetic"},
        BadInput{"apriori\n", 4, "apriori needs"},
        BadInput{"apriori door 0 0 1 1\n", 4, "unknown shape 'door'"},
        BadInput{"wall 0 0 x 1\n", 4, "must be a number, got 'x'"},
        BadInput{"wall 0 0 1.5m 1\n", 4, "must be a number, got '1.5m'"},
        BadInput{"wall 0 0 +-1 1\n", 4, "must be a number, got '+-1'"},
        BadInput{"wall 0 0 nan 1\n", 4, "must be finite"},
        BadInput{"ceiling inf\n", 4, "must be finite"},
        BadInput{"ceiling -2.6\n", 4, "ceiling height_m must be > 0"},
        BadInput{"rect 2 0 1 1\n", 4, "negative or zero size"},
        BadInput{"smoke 0 0 1 0 3\n", 4, "negative or zero size"},
        BadInput{"smoke 0 0 1 1 -3\n", 4, "max_range_m must be > 0"},
        BadInput{"magnetic 0 0 0 20\n", 4, "radius_m must be > 0"},
        BadInput{"entity ff1 human 0 0\n", 4, "expected entity"},
        BadInput{"entity ff1 dog 0 0 0\n", 4, "human or robot"},
        BadInput{"entity ff1 human 0 0 0 speed=0\n", 4, "speed (m/s) must be > 0"},
        BadInput{"entity ff1 human 0 0 0 start=-1\n", 4, "start (s) must be >= 0"},
        BadInput{"entity ff1 human 0 0 0 laps=1.5\n", 4, "laps must be a whole number"},
        BadInput{"entity ff1 human 0 0 0 color=red\n", 4, "unexpected argument 'color=red'"},
        BadInput{"entity ff1 human 0 0 0 speed=1 speed=2\n", 4, "duplicate option speed"},
        BadInput{"entity ff1 human 0 0 0\nentity ff1 robot 1 1 0\n", 5,
                 "duplicate entity id 'ff1'"},
        BadInput{"entity ff1 human 0 0 0\nwaypoint ff2 1 1\n", 5, "undeclared entity 'ff2'"},
        BadInput{"entity ff1 human 0 0 0\nwaypoint ff1 1\n", 5, "expected waypoint"},
        BadInput{"entity ff1 human 0 0 0\nwaypoint ff1 1 1 pause=-2\n", 5,
                 "pause (s) must be >= 0"},
        BadInput{"name y\n", 4, "duplicate name"},
        BadInput{"pena-scenario 1\n", 4, "duplicate header"}));

TEST(ScenarioParser, RequiresHeaderOnFirstNonCommentLine) {
  try {
    ParseScenario("# plan of the office\n\nname office\npena-scenario 1\n", "plan.txt");
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()).rfind("plan.txt:3: missing header", 0), 0u) << error.what();
  }
}

TEST(ScenarioParser, RejectsUnknownVersion) {
  EXPECT_THROW(
      {
        try {
          ParseScenario("pena-scenario 2\n", "v2");
        } catch (const std::invalid_argument& error) {
          EXPECT_STREQ(error.what(), "v2:1: unsupported version 2 (this reader knows 1)");
          throw;
        }
      },
      std::invalid_argument);
  EXPECT_THROW(ParseScenario("pena-scenario\n", "v"), std::invalid_argument);
  EXPECT_THROW(ParseScenario("pena-scenario one\n", "v"), std::invalid_argument);
}

TEST(ScenarioParser, RejectsEmptyText) {
  for (const char* text : {"", "\n\n# only comments\n"}) {
    try {
      ParseScenario(text, "empty.scn");
      FAIL() << "accepted '" << text << "'";
    } catch (const std::invalid_argument& error) {
      EXPECT_EQ(std::string(error.what()).rfind("empty.scn:0: empty scenario", 0), 0u)
          << error.what();
    }
  }
}

}  // namespace
}  // namespace pena::sim
