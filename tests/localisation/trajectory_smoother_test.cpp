#include "pena/localisation/trajectory_smoother.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace pena::localisation {
namespace {

using geometry::Pose2;

constexpr double kStep_m = 0.25;
constexpr int kScans = 81;               // a 20 m corridor along x
constexpr double kOdometryScale = 1.03;  // the odometry walks 3 % too far
constexpr int kEndRounds = 8;            // the last 2 m
constexpr int kMiddleRounds = 9;         // 2 m around the middle

// A causal walk along a corridor: the odometry overestimates every step, nothing corrects it until
// full plan rounds at the far end (door frames, the corridor's end wall: one round at each of the
// last kEndRounds scans) put the scans there where they are. Optionally degenerate rounds at the
// kMiddleRounds scans around the middle whose poses are `middle_along_error_m` off along the
// corridor (weak axis x: a plan wall drawn across an opening).
std::vector<LocalisedPose> CorridorWalk(double middle_along_error_m = 0.0,
                                        bool middle_round = false) {
  std::vector<LocalisedPose> poses;
  Pose2 map_from_odom;  // as MapLocaliser keeps it: moved by every accepted round
  for (int i = 0; i < kScans; ++i) {
    LocalisedPose pose;
    pose.stamp_s = 0.25 * i;
    pose.anchored = true;
    pose.status = MapStatus::kInMap;
    const Pose2 odom_from_body{kOdometryScale * kStep_m * i, 0.0, 0.0};
    pose.map_from_body = geometry::Compose(map_from_odom, odom_from_body);
    const bool end = i >= kScans - kEndRounds;
    if (end || (middle_round && std::abs(i - kScans / 2) <= kMiddleRounds / 2)) {
      MapCorrection round;
      round.accepted = true;
      round.map_from_body_before = pose.map_from_body;
      round.map_from_body_after = end ? Pose2{kStep_m * i, 0.0, 0.0}
                                      : Pose2{odom_from_body.x_m + middle_along_error_m, 0.0, 0.0};
      round.degenerate = !end;
      round.weak_axis_rad = 0.0;  // along x
      pose.correction = round;
      pose.map_from_body = round.map_from_body_after;
      map_from_odom = geometry::Compose(pose.map_from_body, geometry::Inverse(odom_from_body));
    }
    poses.push_back(pose);
  }
  return poses;
}

double MiddleError(const std::vector<Pose2>& map_from_body) {
  const Pose2& middle = map_from_body[kScans / 2];
  return std::hypot(middle.x_m - kStep_m * (kScans / 2), middle.y_m);
}

double RmsError(const std::vector<Pose2>& map_from_body) {
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < map_from_body.size(); ++i) {
    const double dx = map_from_body[i].x_m - kStep_m * static_cast<double>(i);
    sum_sq += dx * dx + map_from_body[i].y_m * map_from_body[i].y_m;
  }
  return std::sqrt(sum_sq / static_cast<double>(map_from_body.size()));
}

std::vector<Pose2> Causal(const std::vector<LocalisedPose>& poses) {
  std::vector<Pose2> out;
  for (const LocalisedPose& pose : poses) out.push_back(pose.map_from_body);
  return out;
}

TEST(TrajectorySmoother, AnAlongTrackDriftPinnedAtBothEndsIsSmallerInTheMiddle) {
  const std::vector<LocalisedPose> walk = CorridorWalk();
  const SmoothedTrajectory smoothed = SmoothTrajectory(walk, {});
  ASSERT_TRUE(smoothed.solved);
  ASSERT_EQ(smoothed.map_from_body.size(), walk.size());
  EXPECT_EQ(smoothed.rounds_used, kEndRounds);
  const double causal_m = MiddleError(Causal(walk));  // 0.3 m: 3 % of 10 m
  EXPECT_NEAR(causal_m, 0.30, 1e-9);
  EXPECT_LT(MiddleError(smoothed.map_from_body), 0.5 * causal_m);
  // Over the whole walk too; the ends stay near where the start and the rounds put them (the
  // rounds are loose by default, 0.2 m: the end is a compromise with the odometry).
  EXPECT_LT(RmsError(smoothed.map_from_body), 0.6 * RmsError(Causal(walk)));
  EXPECT_NEAR(smoothed.map_from_body.front().x_m, 0.0, 0.05);
  EXPECT_NEAR(smoothed.map_from_body.back().x_m, kStep_m * (kScans - 1), 0.15);
}

TEST(TrajectorySmoother, ADegenerateRoundDoesNotPullAlongItsWeakAxis) {
  // The middle rounds are 0.5 m off along the corridor but say so only along their weak axis:
  // they may not drag the middle there.
  const std::vector<LocalisedPose> walk = CorridorWalk(0.5, true);
  const SmoothedTrajectory smoothed = SmoothTrajectory(walk, {});
  ASSERT_TRUE(smoothed.solved);
  EXPECT_EQ(smoothed.rounds_used, kEndRounds + kMiddleRounds);
  EXPECT_NEAR(MiddleError(Causal(walk)), 0.8, 0.01);  // the causal chain took them
  EXPECT_LT(MiddleError(smoothed.map_from_body), 0.2);
}

TEST(TrajectorySmoother, SkipsPosesBeforeTheAnchor) {
  std::vector<LocalisedPose> walk = CorridorWalk();
  walk[0].anchored = false;
  walk[1].anchored = false;
  const SmoothedTrajectory smoothed = SmoothTrajectory(walk, {});
  EXPECT_EQ(smoothed.map_from_body.size(), walk.size() - 2);
}

TEST(TrajectorySmoother, RejectsBadOptionsNamingTheField) {
  TrajectorySmootherOptions options;
  options.round_sigma_m = 0.0;
  try {
    SmoothTrajectory(CorridorWalk(), options);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("round_sigma_m"), std::string::npos);
  }
  options = {};
  options.odometry_sigma_per_m = -1.0;
  EXPECT_THROW(SmoothTrajectory(CorridorWalk(), options), std::invalid_argument);
  options = {};
  options.max_iterations = 0;
  EXPECT_THROW(SmoothTrajectory(CorridorWalk(), options), std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation
