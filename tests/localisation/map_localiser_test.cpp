#include "pena/localisation/map_localiser.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "office_plan.hpp"

namespace pena::localisation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

class MapLocaliserTest : public ::testing::Test {
 protected:
  MapLocaliserTest()
      : office_(testing::OfficeScenario()), truth_scanner_(office_.walls) {}

  // A perfect scan of the true building at `truth` and an odometry estimate `error` (body frame)
  // off it.
  std::pair<sensors::LaserScan, odometry::OdometryEstimate> At(const geometry::Pose2& truth,
                                                               const geometry::Pose2& error = {},
                                                               bool reference_changed = true) {
    stamp_s_ += 1.0;
    sensors::LaserScan scan = truth_scanner_.Scan(truth, testing::OfficeLaser(), 361, stamp_s_);
    odometry::OdometryEstimate estimate;
    estimate.stamp_s = stamp_s_;
    estimate.world_from_body = geometry::Compose(truth, error);  // error in the body frame
    estimate.reference_changed = reference_changed;
    return {scan, estimate};
  }

  sim::Scenario office_;
  VirtualScanner truth_scanner_;
  double stamp_s_ = 0.0;
};

void ExpectNear(const geometry::Pose2& got, const geometry::Pose2& expected, double tol_m,
                double tol_rad) {
  EXPECT_NEAR(got.x_m, expected.x_m, tol_m);
  EXPECT_NEAR(got.y_m, expected.y_m, tol_m);
  EXPECT_NEAR(geometry::NormalizeAngle(got.theta_rad - expected.theta_rad), 0.0, tol_rad);
}

TEST_F(MapLocaliserTest, CorrectsAnOffsetPoseInAMappedRoom) {
  MapLocaliser localiser({}, *office_.apriori, {});
  const geometry::Pose2 truth{7.0, 18.5, -90.0 * kDeg};
  const auto [scan, estimate] = At(truth, {0.15, -0.12, 2.5 * kDeg});
  const auto round = localiser.Update(scan, estimate);
  ASSERT_TRUE(round.has_value());
  EXPECT_TRUE(round->accepted);
  EXPECT_EQ(round->status, MapStatus::kInMap);
  EXPECT_GT(round->confidence, 0.5);
  ExpectNear(localiser.MapFromBody(estimate.world_from_body), truth, 0.03, 0.5 * kDeg);
  ExpectNear(round->map_from_body_after, truth, 0.03, 0.5 * kDeg);
}

TEST_F(MapLocaliserTest, RunsOnlyWhenTheReferenceChanges) {
  MapLocaliser localiser({}, *office_.apriori, {});
  const auto [scan, estimate] = At({7.0, 18.5, -90.0 * kDeg}, {0.15, 0.0, 0.0}, false);
  EXPECT_FALSE(localiser.Update(scan, estimate).has_value());
  EXPECT_EQ(localiser.status(), MapStatus::kUnknown);
  EXPECT_NEAR(localiser.MapFromBody(estimate.world_from_body).y_m, estimate.world_from_body.y_m, 1e-12);
  EXPECT_TRUE(localiser.Update(scan, estimate, /*force=*/true).has_value());
}

TEST_F(MapLocaliserTest, RobustToAShiftedWall) {
  std::vector<geometry::Segment2> plan = *office_.apriori;
  for (auto& s : plan) {  // the room's east wall x = 10 drawn 0.3 m too far east
    if (s.start_m.x() == 10.0 && s.end_m.x() == 10.0) s.start_m.x() = s.end_m.x() = 10.3;
  }
  MapLocaliser localiser({}, plan, {});
  // Facing north: the shifted east wall is about a quarter of the returns.
  const geometry::Pose2 truth{7.0, 18.5, 90.0 * kDeg};
  const auto [scan, estimate] = At(truth, {-0.12, 0.1, -2.0 * kDeg});
  const auto round = localiser.Update(scan, estimate);
  ASSERT_TRUE(round && round->accepted);
  ExpectNear(round->map_from_body_after, truth, 0.05, 0.5 * kDeg);
}

TEST_F(MapLocaliserTest, GoesOutsideTheMapAndIsReacquired) {
  MapLocaliser localiser({}, *office_.apriori, {});
  auto [scan, estimate] = At({8.0, 14.0, 180.0 * kDeg});
  EXPECT_EQ(localiser.Update(scan, estimate)->status, MapStatus::kInMap);
  // The west wing is not on the plan: rounds there fail and the entity is judged outside.
  std::tie(scan, estimate) = At({2.0, 14.0, 180.0 * kDeg});
  EXPECT_FALSE(localiser.Update(scan, estimate)->accepted);
  std::tie(scan, estimate) = At({2.0, 11.0, -90.0 * kDeg});
  const auto outside = localiser.Update(scan, estimate);
  EXPECT_FALSE(outside->accepted);
  EXPECT_EQ(outside->status, MapStatus::kOutsideMap);
  EXPECT_GT(outside->window_xy_m, MapLocaliserOptions{}.window.size_x_m);
  // Back in the corridor with 0.3 m of lateral drift and 1.5 deg: the grown window finds the
  // plan again (along the corridor the odometry is kept, so no along-corridor error is made).
  const geometry::Pose2 truth{7.0, 14.0, 0.0};
  std::tie(scan, estimate) = At(truth, {0.0, 0.3, 1.5 * kDeg});
  const auto back = localiser.Update(scan, estimate);
  ASSERT_TRUE(back->accepted);
  EXPECT_EQ(back->status, MapStatus::kReacquired);
  ExpectNear(back->map_from_body_after, truth, 0.05, 0.5 * kDeg);
}

TEST(MapLocaliserOptions, RejectsBadValues) {
  MapLocaliserOptions options;
  options.min_score = 0.0;
  EXPECT_THROW(MapLocaliser(options, {}, {}), std::invalid_argument);
  options = {};
  options.window.step_xy_m = 0.03;  // not a multiple of the 0.02 m grid
  EXPECT_THROW(MapLocaliser(options, {}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation
