#include "pena/localisation/plan_adaptation.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace pena::localisation {
namespace {

using geometry::Segment2;

Segment2 Wall(double x1, double y1, double x2, double y2) { return {{x1, y1}, {x2, y2}}; }

// Returns every 5 cm along the true walls (visibility does not matter here).
scan_matching::Points2 Returns(const std::vector<Segment2>& walls) {
  scan_matching::Points2 points;
  for (const Segment2& w : walls) {
    const Eigen::Vector2d d = w.end_m - w.start_m;
    const int n = static_cast<int>(d.norm() / 0.05);
    for (int i = 0; i <= n; ++i) points.push_back(w.start_m + d * (static_cast<double>(i) / n));
  }
  return points;
}

// A 6 m x 4 m room with a partition from the north wall at x = 2.
std::vector<Segment2> Room(double east_x_m, bool partition) {
  std::vector<Segment2> walls{Wall(0, 0, 6, 0), Wall(6, 4, 0, 4), Wall(0, 4, 0, 0),
                              Wall(east_x_m, 0, east_x_m, 4)};
  if (partition) walls.push_back(Wall(2, 4, 2, 2.5));
  return walls;
}

// Rounds seen from the middle of the room with a perfect pose; `walked_m` since the round
// before (far: the motion prior does not count as a reference).
PlanAdaptation Observed(const std::vector<Segment2>& truth, const std::vector<Segment2>& plan, int rounds,
                        double walked_m, PlanAdaptationOptions options = {}) {
  PlanAdaptation adaptation(options, plan);
  const RoundView view{{3.0, 2.0}, Eigen::Vector3d::Zero(), walked_m};
  for (int i = 0; i < rounds; ++i) adaptation.Observe(Returns(truth), view);
  return adaptation;
}

TEST(PlanAdaptation, AWallDrawnOffIsMovedWhereTheOtherWallsSeeIt) {
  const std::vector<Segment2> plan = Room(6.3, true);
  const PlanAdaptation adaptation = Observed(Room(6.0, true), plan, 5, 5.0);
  ASSERT_EQ(adaptation.shifts().size(), 1u);
  EXPECT_EQ(adaptation.shifts()[0].index, 3);
  EXPECT_EQ(adaptation.shifts()[0].rounds, 5);
  EXPECT_NEAR(adaptation.plan()[3].start_m.x(), 6.0, 0.02);
  EXPECT_NEAR(adaptation.plan()[3].end_m.x(), 6.0, 0.02);
  for (int i : {0, 1, 2, 4}) {
    EXPECT_EQ(adaptation.plan()[static_cast<std::size_t>(i)].start_m, plan[static_cast<std::size_t>(i)].start_m);
  }
}

TEST(PlanAdaptation, NotBeforeMinRounds) {
  EXPECT_TRUE(Observed(Room(6.0, true), Room(6.3, true), 4, 5.0).shifts().empty());
}

TEST(PlanAdaptation, ARoomDrawnTooNarrowIsLeftAloneWhenNothingElseTells) {
  // Only the west and east walls face each other: either could be the one drawn off.
  const PlanAdaptation adaptation = Observed(Room(6.0, false), Room(5.7, false), 10, 5.0);
  EXPECT_TRUE(adaptation.shifts().empty());
}

TEST(PlanAdaptation, TheMotionPriorTellsWhichOfTwoWallsIsOff) {
  // Just after a round (0.2 m walked) the odometry's prediction is a reference of its own: it
  // sides with the west wall, so the east one is moved and the west one stays.
  const PlanAdaptation adaptation = Observed(Room(6.0, false), Room(5.7, false), 5, 0.2);
  ASSERT_EQ(adaptation.shifts().size(), 1u);
  EXPECT_EQ(adaptation.shifts()[0].index, 3);
  EXPECT_NEAR(adaptation.plan()[3].start_m.x(), 6.0, 0.02);
}

TEST(PlanAdaptation, ACorridorEndWallSeenAloneIsNotMeasured) {
  const auto corridor = [](double end_x_m) {
    return std::vector<Segment2>{Wall(0, 0, 20, 0), Wall(20, 2, 0, 2), Wall(end_x_m, 0, end_x_m, 2)};
  };
  EXPECT_TRUE(Observed(corridor(20.0), corridor(20.3), 10, 5.0).shifts().empty());
}

TEST(PlanAdaptation, AWallOffByLessThanTheMinimumStays) {
  EXPECT_TRUE(Observed(Room(6.0, true), Room(6.05, true), 10, 5.0).shifts().empty());
}

TEST(PlanAdaptation, DisabledMovesNothing) {
  PlanAdaptationOptions options;
  options.enabled = false;
  EXPECT_TRUE(Observed(Room(6.0, true), Room(6.3, true), 10, 5.0, options).shifts().empty());
}

TEST(PlanAdaptationOptions, RejectsBadValuesNamingTheField) {
  const auto message = [](PlanAdaptationOptions o) {
    try {
      ValidatePlanAdaptationOptions(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  PlanAdaptationOptions o;
  EXPECT_EQ(message(o), "");
  o.association_m = 0.0;
  EXPECT_NE(message(o).find("plan_adaptation.association_m"), std::string::npos) << message(o);
  o = {};
  o.min_offset_m = 0.7;  // not below association_m
  EXPECT_NE(message(o).find("min_offset_m"), std::string::npos);
  o = {};
  o.min_rounds = 0;
  EXPECT_NE(message(o).find("min_rounds"), std::string::npos);
  o = {};
  o.prior_sigma_m = -1.0;
  EXPECT_NE(message(o).find("prior_sigma_m"), std::string::npos);
  EXPECT_THROW(PlanAdaptation(o, {}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation
