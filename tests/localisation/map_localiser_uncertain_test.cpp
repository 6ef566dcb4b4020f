// Plan rounds between keyframes where the odometry is uncertain (MapLocaliserOptions::
// uncertain_scans), taken only through the innovation gate.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "office_plan.hpp"
#include "pena/localisation/map_localiser.hpp"

namespace pena::localisation {
namespace {

// A 6 m x 4 m room with a pillar and a door stub: every direction pinned.
const std::vector<geometry::Segment2>& Room() {
  static const std::vector<geometry::Segment2> room{
      {{0, 0}, {6, 0}}, {{6, 0}, {6, 4}},     {{6, 4}, {0, 4}},     {{0, 4}, {0, 0}},
      {{4, 1}, {4.5, 1}}, {{4.5, 1}, {4.5, 1.5}}, {{4.5, 1.5}, {4, 1.5}}, {{4, 1.5}, {4, 1}}, {{1, 4}, {1, 3}}};
  return room;
}

MapLocaliserOptions Uncertain() {
  MapLocaliserOptions options;
  options.uncertain_scans = true;
  options.uncertain_every_scans = 1;
  options.plan_adaptation.enabled = false;
  return options;
}

// A keyframe round at the truth, then one non-keyframe scan whose odometry pose is `drift` off
// the truth with position sigma `sigma_m` since that round, flagged `gated`.
std::optional<MapCorrection> DriftedScan(const MapLocaliserOptions& options, const geometry::Pose2& drift,
                                         double sigma_m, bool gated, geometry::Pose2* pose_after = nullptr) {
  MapLocaliser localiser(options, Room(), {});
  const VirtualScanner walls(Room());
  const geometry::Pose2 truth{2.0, 2.0, 0.3};
  const auto first = testing::PerfectRound(localiser, walls, truth, 1.0);
  EXPECT_TRUE(first && first->accepted);
  odometry::OdometryEstimate estimate;
  estimate.stamp_s = 1.1;
  estimate.world_from_body = geometry::Compose(truth, drift);
  estimate.status = odometry::MatchStatus::kMatched;
  estimate.gated = gated;
  estimate.covariance.diagonal() << sigma_m * sigma_m, sigma_m * sigma_m, 0.05 * 0.05;
  const auto round = localiser.Update(walls.Scan(truth, testing::OfficeLaser(), 361, 1.1), estimate);
  if (pose_after) *pose_after = geometry::Between(truth, localiser.map_from_body());
  return round;
}

TEST(MapLocaliserUncertain, AGatedScanIsPulledBackOntoThePlan) {
  geometry::Pose2 error;
  const auto round = DriftedScan(Uncertain(), {0.3, -0.2, 0.0}, 0.3, true, &error);
  ASSERT_TRUE(round.has_value());
  EXPECT_TRUE(round->uncertain);
  EXPECT_TRUE(round->accepted);
  EXPECT_LT(round->innovation_nees, 11.34);
  EXPECT_LT(std::hypot(error.x_m, error.y_m), 0.05);
}

TEST(MapLocaliserUncertain, ACorrectionBeyondTheInnovationGateIsRefused) {
  geometry::Pose2 error;
  // 0.18 m off (inside the window) while the odometry claims 1 cm and the match 2 cm: ~8 sigma.
  MapLocaliserOptions options = Uncertain();
  options.match_sigma_m = 0.02;
  const auto round = DriftedScan(options, {0.15, -0.1, 0.0}, 0.01, true, &error);
  ASSERT_TRUE(round.has_value());
  EXPECT_TRUE(round->uncertain);
  EXPECT_FALSE(round->accepted);
  EXPECT_GT(round->innovation_nees, 11.34);
  EXPECT_EQ(round->status, MapStatus::kInMap);  // a refused round between keyframes changes nothing
  EXPECT_NEAR(std::hypot(error.x_m, error.y_m), std::hypot(0.15, 0.1), 1e-6);
}

TEST(MapLocaliserUncertain, ASureScanBetweenKeyframesRunsNoRound) {
  EXPECT_FALSE(DriftedScan(Uncertain(), {0.0, 0.0, 0.0}, 0.05, false).has_value());
  MapLocaliserOptions off = Uncertain();
  off.uncertain_scans = false;
  EXPECT_FALSE(DriftedScan(off, {0.3, -0.2, 0.0}, 0.3, true).has_value());
}

}  // namespace
}  // namespace pena::localisation
