#include "pena/localisation/global_tracker.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "office_plan.hpp"

namespace pena::localisation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A walk west from the entrance with perfect scans of the true walls; the odometry frame is an
// arbitrary placement of the plan frame. The tracker must settle on the true pose.
TEST(GlobalTracker, SettlesOnTheTruePoseOverAWalk) {
  const sim::Scenario office = testing::OfficeScenario();
  const VirtualScanner truth_scanner(office.walls);
  const GlobalLocaliser localiser(*office.apriori);
  GlobalTracker tracker(localiser);
  const geometry::Pose2 odom_from_map{3.0, -7.0, 40.0 * kDeg};
  std::optional<PoseHypothesis> decided;
  geometry::Pose2 truth;
  for (int step = 0; step < 16 && !decided; ++step) {
    truth = {40.5 - 0.5 * step, 14.0, 180.0 * kDeg};
    const auto scan = truth_scanner.Scan(truth, testing::OfficeLaser(), 361);
    decided = tracker.Update(scan, geometry::Compose(odom_from_map, truth)).decided;
  }
  ASSERT_TRUE(decided.has_value());
  EXPECT_NEAR(decided->map_from_body.x_m, truth.x_m, 0.1);
  EXPECT_NEAR(decided->map_from_body.y_m, truth.y_m, 0.1);
  EXPECT_NEAR(geometry::NormalizeAngle(decided->map_from_body.theta_rad - truth.theta_rad), 0.0, 1.0 * kDeg);
  EXPECT_GE(tracker.searches(), 1);
}

TEST(GlobalTracker, DecidesNothingBeforeEnoughKeyframes) {
  const sim::Scenario office = testing::OfficeScenario();
  const VirtualScanner truth_scanner(office.walls);
  const GlobalLocaliser localiser(*office.apriori);
  GlobalTracker tracker(localiser);
  const geometry::Pose2 truth{40.0, 14.0, 180.0 * kDeg};
  const TrackerUpdate update = tracker.Update(truth_scanner.Scan(truth, testing::OfficeLaser(), 361), truth);
  EXPECT_TRUE(update.searched);
  EXPECT_FALSE(update.decided.has_value());
  EXPECT_FALSE(update.ranked.hypotheses.empty());
}

TEST(GlobalTrackerOptions, RejectsBadValues) {
  const GlobalLocaliser localiser({{{0.0, 0.0}, {5.0, 0.0}}});
  GlobalTrackerOptions options;
  options.min_keyframes = options.max_keyframes + 1;
  EXPECT_THROW(GlobalTracker(localiser, options), std::invalid_argument);
  options = {};
  options.drop_margin_beams = options.decide_margin_beams;
  EXPECT_THROW(GlobalTracker(localiser, options), std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation
