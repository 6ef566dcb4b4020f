// The weak-direction rules of the laser odometry (odometry::internal::WeakDirection): a degenerate
// match keeps the prior along its weak direction; a weakly constrained one only when it slid back
// against the walk, away from a prior that agrees with it across the weak direction and that the
// latest constraining match confirmed.
#include "pena/odometry/internal/weak_direction.hpp"

#include <gtest/gtest.h>

namespace pena::odometry::internal {
namespace {

// A corridor along x: the position along it is weakly constrained (ratio 0.1), across it well.
const Eigen::Matrix3d kCorridor = Eigen::Vector3d(10.0, 100.0, 50.0).asDiagonal();
const Eigen::Matrix3d kFeaturelessCorridor = Eigen::Vector3d(1.0, 100.0, 50.0).asDiagonal();
const Eigen::Matrix3d kRoom = Eigen::Vector3d(80.0, 100.0, 50.0).asDiagonal();
const Eigen::Vector2d kWalkingEast(0.2, 0.0);

WeakDirectionOptions People() {
  WeakDirectionOptions o;
  o.slide_ratio = 0.2;
  return o;
}

TEST(WeakDirection, AMatchThatSlidBackAlongTheCorridorKeepsThePrior) {
  WeakDirection check(People());
  geometry::Pose2 match{9.7, 0.02, 0.0};
  const auto weak = check.Apply(kCorridor, {10.0, 0.0, 0.0}, kWalkingEast, match);
  ASSERT_TRUE(weak.has_value());
  EXPECT_NEAR(std::abs(weak->x()), 1.0, 1e-9);
  EXPECT_NEAR(match.x_m, 10.0, 1e-9);  // along: the prior's
  EXPECT_NEAR(match.y_m, 0.02, 1e-9);  // across: the match's
}

TEST(WeakDirection, AMatchAheadOfThePriorIsACorrection) {
  WeakDirection check(People());
  geometry::Pose2 match{10.3, 0.0, 0.0};
  EXPECT_FALSE(check.Apply(kCorridor, {10.0, 0.0, 0.0}, kWalkingEast, match).has_value());
  EXPECT_NEAR(match.x_m, 10.3, 1e-9);
  WeakDirectionOptions both_ways = People();
  both_ways.backward_only = false;
  WeakDirection either(both_ways);
  EXPECT_TRUE(either.Apply(kCorridor, {10.0, 0.0, 0.0}, kWalkingEast, match).has_value());
  EXPECT_NEAR(match.x_m, 10.0, 1e-9);
}

TEST(WeakDirection, APriorOffAcrossTheCorridorIsNotKeptAlongIt) {
  // A side step that the stride model read as a step forward: the prior is 0.3 m off across.
  WeakDirection check(People());
  geometry::Pose2 match{9.7, 0.0, 0.0};
  EXPECT_FALSE(check.Apply(kCorridor, {10.0, 0.3, 0.0}, kWalkingEast, match).has_value());
  EXPECT_NEAR(match.x_m, 9.7, 1e-9);
  WeakDirectionOptions any_across = People();
  any_across.max_across_m = 0.0;
  WeakDirection unchecked(any_across);
  EXPECT_TRUE(unchecked.Apply(kCorridor, {10.0, 0.3, 0.0}, kWalkingEast, match).has_value());
}

TEST(WeakDirection, AConstrainingMatchFarFromItsPriorStopsTheSlideCheckUntilOneAgrees) {
  WeakDirection check(People());
  // A step back, read as a step forward: in a room the match puts the walker 0.3 m behind.
  geometry::Pose2 in_room{4.7, 0.0, 0.0};
  EXPECT_FALSE(check.Apply(kRoom, {5.0, 0.0, 0.0}, kWalkingEast, in_room).has_value());
  EXPECT_FALSE(check.prior_held_lately());
  geometry::Pose2 slid{9.7, 0.0, 0.0};
  EXPECT_FALSE(check.Apply(kCorridor, {10.0, 0.0, 0.0}, kWalkingEast, slid).has_value());
  EXPECT_NEAR(slid.x_m, 9.7, 1e-9);
  // A constraining match within 0.15 m of its prior: the prior holds again.
  geometry::Pose2 agreeing{5.1, 0.0, 0.0};
  check.Apply(kRoom, {5.0, 0.0, 0.0}, kWalkingEast, agreeing);
  EXPECT_TRUE(check.prior_held_lately());
  EXPECT_TRUE(check.Apply(kCorridor, {10.0, 0.0, 0.0}, kWalkingEast, slid).has_value());
  EXPECT_NEAR(slid.x_m, 10.0, 1e-9);
}

TEST(WeakDirection, ShortSlidesAndConstrainedMatchesAreLeftAlone) {
  WeakDirection check(People());
  geometry::Pose2 short_slide{9.9, 0.0, 0.0};
  EXPECT_FALSE(check.Apply(kCorridor, {10.0, 0.0, 0.0}, kWalkingEast, short_slide).has_value());
  geometry::Pose2 in_room{9.7, 0.0, 0.0};  // 0.3 m back, but the room pins it down
  EXPECT_FALSE(check.Apply(kRoom, {10.0, 0.0, 0.0}, kWalkingEast, in_room).has_value());
  EXPECT_NEAR(in_room.x_m, 9.7, 1e-9);
  WeakDirection off(WeakDirectionOptions{});  // slide_ratio 0: robots
  geometry::Pose2 slid{9.7, 0.0, 0.0};
  EXPECT_FALSE(off.Apply(kCorridor, {10.0, 0.0, 0.0}, kWalkingEast, slid).has_value());
}

TEST(WeakDirection, ADegenerateMatchAlwaysKeepsThePriorAlongTheCorridor) {
  WeakDirection check(People());
  geometry::Pose2 ahead{10.3, 0.0, 0.0};  // ahead, and the prior off across: degenerate all the same
  ASSERT_TRUE(check.Apply(kFeaturelessCorridor, {10.0, 0.3, 0.0}, kWalkingEast, ahead).has_value());
  EXPECT_NEAR(ahead.x_m, 10.0, 1e-9);
  EXPECT_NEAR(ahead.y_m, 0.0, 1e-9);
}

}  // namespace
}  // namespace pena::odometry::internal
