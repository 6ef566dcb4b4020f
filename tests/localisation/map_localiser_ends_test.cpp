// The plan's wall ends inside the map localiser, on the office scenario's own a priori plan: the
// building's east wall (plan segments 2 and 3, the rooms' end walls seen through the doors) is
// drawn at x 42.3 instead of 42, while the corridor walls and their door jambs are drawn right.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "office_plan.hpp"
#include "pena/localisation/map_localiser.hpp"

namespace pena::localisation {
namespace {

struct Walk {
  double worst_error_m = 0.0;
  int ends_corrected = 0;
};

// Walks the corridor east from x = 30 to 40 with a perfect odometry, a round every 0.5 m, on
// `plan`.
Walk WalkToTheEastEnd(const MapLocaliserOptions& options, const std::vector<geometry::Segment2>& plan) {
  const sim::Scenario office = testing::OfficeScenario();
  const VirtualScanner truth(office.walls);
  MapLocaliser localiser(options, plan, {});
  Walk walk;
  double stamp_s = 0.0;
  for (double x = 30.0; x <= 40.0; x += 0.5) {
    const auto round = testing::PerfectRound(localiser, truth, {x, 14.0, 0.0}, stamp_s += 0.5);
    walk.ends_corrected += round && round->ends_corrected ? 1 : 0;
    const geometry::Pose2 got = localiser.map_from_body();
    walk.worst_error_m = std::max(walk.worst_error_m, std::hypot(got.x_m - x, got.y_m - 14.0));
  }
  return walk;
}

TEST(MapLocaliserEnds, TheJambsHoldThePoseTheEastWallDrawnOffWouldPull) {
  const sim::Scenario office = testing::OfficeScenario();
  MapLocaliserOptions off;
  off.plan_adaptation.ends.enabled = false;
  // Without the ends, the rounds follow the east wall as drawn (0.3 m).
  EXPECT_GT(WalkToTheEastEnd(off, *office.apriori).worst_error_m, 0.2);
  const Walk walk = WalkToTheEastEnd({}, *office.apriori);
  EXPECT_LT(walk.worst_error_m, 0.08);
  EXPECT_GT(walk.ends_corrected, 0);
}

TEST(MapLocaliserEnds, ARightPlanIsNeverCorrectedByItsEnds) {
  const sim::Scenario office = testing::OfficeScenario();
  const Walk walk = WalkToTheEastEnd({}, office.walls);
  EXPECT_EQ(walk.ends_corrected, 0);
  EXPECT_LT(walk.worst_error_m, 0.05);
}

}  // namespace
}  // namespace pena::localisation
