#include "pena/localisation/global_localiser.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "office_plan.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(SampleSegments, SpacesPointsAlongEverySegment) {
  const auto points = SampleSegments({{{0.0, 0.0}, {1.0, 0.0}}, {{2.0, 0.0}, {2.0, 0.0}}}, 0.25);
  ASSERT_EQ(points.size(), 5u + 2u);  // 0, .25, .5, .75, 1 and a point segment's two ends
  EXPECT_NEAR(points[1].x(), 0.25, 1e-12);
}

TEST(GlobalLocaliser, FindsUnknownPosesOnThePartialOfficePlan) {
  const sim::Scenario office = testing::OfficeScenario();
  const VirtualScanner truth_scanner(office.walls);
  const GlobalLocaliser localiser(*office.apriori);
  // Poses a single scan identifies. Elsewhere in the corridor the doors repeat every ~6 m and
  // one 180-deg scan is ambiguous; bench_global_localisation measures the rate there.
  const std::vector<geometry::Pose2> poses = {{7.0, 18.5, -90.0 * kDeg}, {40.0, 14.0, 170.0 * kDeg},
                                              {41.0, 14.0, 180.0 * kDeg}};
  for (const geometry::Pose2& truth : poses) {
    const auto scan = truth_scanner.Scan(truth, testing::OfficeLaser(), 361);
    const GlobalResult result = localiser.Localise(scan);
    ASSERT_FALSE(result.hypotheses.empty());
    const geometry::Pose2& best = result.hypotheses.front().map_from_body;
    EXPECT_NEAR(best.x_m, truth.x_m, 0.1) << truth.x_m << "," << truth.y_m;
    EXPECT_NEAR(best.y_m, truth.y_m, 0.1) << truth.x_m << "," << truth.y_m;
    EXPECT_NEAR(geometry::NormalizeAngle(best.theta_rad - truth.theta_rad), 0.0, 1.0 * kDeg);
    for (std::size_t i = 1; i < result.hypotheses.size(); ++i) {
      EXPECT_LE(result.hypotheses[i].agreement, result.hypotheses[i - 1].agreement);
    }
    EXPECT_GE(result.margin, 0.0);
  }
}

// Three scans of the plan itself along the corridor, merged into the latest body frame: the door
// frames over 1 m of walk pin the pose along the corridor, from a guess 0.4 m off along it.
TEST(GlobalLocaliser, FitMergedPinsAPoseAlongTheCorridor) {
  const sim::Scenario office = testing::OfficeScenario();
  const VirtualScanner plan_scanner(*office.apriori);
  const GlobalLocaliser localiser(*office.apriori);
  const geometry::Pose2 latest{25.0, 14.0, 0.0};
  scan_matching::Points2 merged;
  for (const double back_m : {1.0, 0.5, 0.0}) {
    const geometry::Pose2 pose{latest.x_m - back_m, latest.y_m, latest.theta_rad};
    const auto scan = plan_scanner.Scan(pose, testing::OfficeLaser(), 361);
    const geometry::Pose2 latest_from_pose = geometry::Compose(geometry::Inverse(latest), pose);
    for (const Eigen::Vector2d& p : scan_matching::ScanToPoints(scan, 0.1)) {
      merged.push_back(geometry::TransformPoint(latest_from_pose, p));
    }
  }
  const PoseHypothesis fitted = localiser.FitMerged(merged, {latest.x_m + 0.4, latest.y_m + 0.05, 1.0 * kDeg});
  EXPECT_NEAR(fitted.map_from_body.x_m, latest.x_m, 0.03);
  EXPECT_NEAR(fitted.map_from_body.y_m, latest.y_m, 0.03);
  EXPECT_NEAR(geometry::NormalizeAngle(fitted.map_from_body.theta_rad - latest.theta_rad), 0.0, 0.3 * kDeg);
  EXPECT_GT(fitted.score, 0.9);
  EXPECT_EQ(localiser.FitMerged({}, latest).score, 0.0);  // nothing to fit: the guess, score 0
}

// In the corridor one scan fits the corridor seen the other way round too. With a heading bound
// (the compass) no hypothesis lies outside it, and the true pose is still one of them.
TEST(GlobalLocaliser, HeadingBoundKeepsTheCorridorTheRightWayRound) {
  const sim::Scenario office = testing::OfficeScenario();
  const VirtualScanner truth_scanner(office.walls);
  const GlobalLocaliser localiser(*office.apriori);
  const geometry::Pose2 truth{12.0, 14.0, 0.0};
  const auto scan = truth_scanner.Scan(truth, testing::OfficeLaser(), 361);
  const auto reversed = [&](const PoseHypothesis& h) {
    return std::abs(geometry::NormalizeAngle(h.map_from_body.theta_rad - truth.theta_rad)) > 90.0 * kDeg;
  };
  const GlobalResult all = localiser.Localise(scan, 30);
  EXPECT_TRUE(std::any_of(all.hypotheses.begin(), all.hypotheses.end(), reversed));
  const GlobalResult bounded = localiser.Localise(scan, 30, HeadingBound{5.0 * kDeg, 30.0 * kDeg});
  ASSERT_FALSE(bounded.hypotheses.empty());
  for (const PoseHypothesis& h : bounded.hypotheses) {
    EXPECT_LE(std::abs(geometry::NormalizeAngle(h.map_from_body.theta_rad - 5.0 * kDeg)), 30.0 * kDeg);
  }
  // One scan there is ambiguous along the corridor (doors every ~6 m): the true place is among
  // the hypotheses, not necessarily the best.
  EXPECT_TRUE(std::any_of(bounded.hypotheses.begin(), bounded.hypotheses.end(),
                          [&](const PoseHypothesis& h) { return SamePlace(h.map_from_body, truth); }));
  // A bound across the +/-180 deg seam: the same corridor seen walking west.
  const geometry::Pose2 west{12.0, 14.0, 180.0 * kDeg};
  const GlobalResult seam =
      localiser.Localise(truth_scanner.Scan(west, testing::OfficeLaser(), 361), 30, HeadingBound{-175.0 * kDeg, 30.0 * kDeg});
  ASSERT_FALSE(seam.hypotheses.empty());
  for (const PoseHypothesis& h : seam.hypotheses) {
    EXPECT_LE(std::abs(geometry::NormalizeAngle(h.map_from_body.theta_rad + 175.0 * kDeg)), 30.0 * kDeg);
  }
}

// A room whose north wall the plan draws 0.4 m off (a rough plan's shifted wall, as in front of
// office's archive): the beams near the wall's normal agree with the default 0.5 m tolerance,
// whichever side the plan draws it, and none of that wall's beams do with 0.3 m.
TEST(GlobalLocaliser, BeamAgreementTakesInAWallThePlanDrawsOff) {
  const auto room = [](double north_y_m) {
    return std::vector<geometry::Segment2>{{{0.0, 0.0}, {6.0, 0.0}}, {{6.0, 0.0}, {6.0, north_y_m}},
                                           {{6.0, north_y_m}, {0.0, north_y_m}}, {{0.0, north_y_m}, {0.0, 0.0}}};
  };
  const geometry::Pose2 pose{3.0, 2.0, 90.0 * kDeg};  // facing the north wall, 2 m away
  const auto scan = VirtualScanner(room(4.0)).Scan(pose, testing::OfficeLaser(), 361);
  GlobalLocaliserOptions strict;
  strict.agreement_tolerance_m = 0.3;
  for (const double north_y_m : {4.4, 3.6}) {
    const BeamAgreement narrow = GlobalLocaliser(room(north_y_m), strict).Agreement(scan, pose);
    const BeamAgreement wide = GlobalLocaliser(room(north_y_m)).Agreement(scan, pose);
    EXPECT_EQ(wide.returns, 361);
    // The north wall's 225 beams (within 56 deg of its normal) end 0.4 m or more from the plan's
    // wall but near its corners; with 0.5 m those within 37 deg of its normal agree too.
    EXPECT_LT(narrow.agree, 150) << north_y_m;
    EXPECT_GT(wide.agree, narrow.agree + 140) << north_y_m;
    // Drawn too far south, the others pass the plan's wall.
    if (north_y_m < 4.0) EXPECT_GT(wide.through, 50);
    else EXPECT_EQ(wide.through, 0);
  }
}

TEST(GlobalLocaliser, EmptyScanGivesNoHypothesis) {
  const GlobalLocaliser localiser({{{0.0, 0.0}, {5.0, 0.0}}});
  EXPECT_TRUE(localiser.Localise(scan_matching::Points2{}).hypotheses.empty());
  EXPECT_TRUE(localiser.Localise(sensors::LaserScan{}).hypotheses.empty());
}

TEST(GlobalLocaliserOptions, RejectsBadValues) {
  GlobalLocaliserOptions options;
  options.tile_size_m = 0.0;
  EXPECT_THROW(GlobalLocaliser({}, options), std::invalid_argument);
  options = {};
  options.coarse_step_xy_m = 0.07;  // not a multiple of the coarse 0.05 m grid
  EXPECT_THROW(GlobalLocaliser({}, options), std::invalid_argument);
  options = {};
  options.agreement_tolerance_m = std::nan("");
  EXPECT_THROW(GlobalLocaliser({}, options), std::invalid_argument);
  options = {};
  options.agreement_tolerance_m = 0.0;
  EXPECT_THROW(GlobalLocaliser({}, options), std::invalid_argument);
  options = {};
  options.min_range_m = options.max_range_m;
  EXPECT_THROW(GlobalLocaliser({}, options), std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation
