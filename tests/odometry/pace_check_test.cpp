// The pace check (odometry::internal::PaceCheck): a position that falls behind the dead
// reckoning's progress over the last few metres walked, by more than the tolerance and more
// than the prior, is flagged with the direction walked; ahead, or too short or bent a walk, is not.
#include "pena/odometry/internal/pace_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pena::odometry::internal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Walks 6 m along x in 0.25 m steps: dead reckoning and estimate agree (the estimate's frame
// turned by `frame_rad` against the dead reckoning's, as a heading error would).
PaceCheck WalkedStraight(double frame_rad = 0.0, double tolerance = 0.1) {
  PaceCheck check({tolerance, 4.0});
  for (int i = 0; i <= 24; ++i) {
    const double x = 0.25 * i;
    check.Record({x, 0.0, 0.0},
                 {x * std::cos(frame_rad), x * std::sin(frame_rad), frame_rad});
  }
  return check;
}

TEST(PaceCheck, AMatchBehindTheWalkIsFlaggedWithTheDirectionWalked) {
  const PaceCheck check = WalkedStraight();
  const geometry::Pose2 motion{6.25, 0.0, 0.0};
  const geometry::Pose2 prior{6.25, 0.0, 0.0};
  // 4.25 m walked since the window's start (x 2.0): 0.6 m behind is 14 %.
  const auto along = check.FallsBehind(motion, {5.65, 0.02, 0.0}, prior);
  ASSERT_TRUE(along.has_value());
  EXPECT_NEAR(along->x(), 1.0, 1e-9);
  EXPECT_NEAR(along->y(), 0.0, 1e-9);
  // 0.3 m behind (7 %) is within the tolerance.
  EXPECT_FALSE(check.FallsBehind(motion, {5.95, 0.0, 0.0}, prior).has_value());
}

TEST(PaceCheck, AMatchAheadOfTheWalkIsACorrectionNotASlide) {
  const PaceCheck check = WalkedStraight();
  EXPECT_FALSE(check.FallsBehind({6.25, 0.0, 0.0}, {6.85, 0.0, 0.0}, {6.25, 0.0, 0.0}).has_value());
}

TEST(PaceCheck, NotWhenThePriorIsAsFarBehind) {
  const PaceCheck check = WalkedStraight();
  // The prior itself is 0.8 m behind (a stall of the dead reckoning's chain): the match is not
  // the one that fell behind.
  EXPECT_FALSE(check.FallsBehind({6.25, 0.0, 0.0}, {5.65, 0.0, 0.0}, {5.45, 0.0, 0.0}).has_value());
}

TEST(PaceCheck, TheDirectionIsTurnedIntoTheEstimatesFrame) {
  const PaceCheck check = WalkedStraight(10.0 * kDeg);
  const double c = std::cos(10.0 * kDeg), s = std::sin(10.0 * kDeg);
  const auto along = check.FallsBehind({6.25, 0.0, 0.0}, {5.65 * c, 5.65 * s, 10.0 * kDeg},
                                       {6.25 * c, 6.25 * s, 10.0 * kDeg});
  ASSERT_TRUE(along.has_value());
  EXPECT_NEAR(along->x(), c, 1e-9);
  EXPECT_NEAR(along->y(), s, 1e-9);
}

TEST(PaceCheck, NothingBeforeAWindowsWorthOfStraightWalkOrWhenOff) {
  PaceCheck start({0.1, 4.0});
  for (int i = 0; i <= 8; ++i) start.Record({0.25 * i, 0.0, 0.0}, {0.25 * i, 0.0, 0.0});
  EXPECT_FALSE(start.FallsBehind({2.25, 0.0, 0.0}, {1.0, 0.0, 0.0}, {2.25, 0.0, 0.0}).has_value());
  // Out 3 m and back 3 m: 6 m walked, 0 m from where the window starts.
  PaceCheck back({0.1, 4.0});
  for (int i = 0; i <= 24; ++i) {
    const double x = i <= 12 ? 0.25 * i : 6.0 - 0.25 * i;
    back.Record({x, 0.0, 0.0}, {x, 0.0, 0.0});
  }
  EXPECT_FALSE(back.FallsBehind({-0.25, 0.0, 0.0}, {2.0, 0.0, 0.0}, {-0.25, 0.0, 0.0}).has_value());
  const PaceCheck off = WalkedStraight(0.0, 0.0);
  EXPECT_FALSE(off.enabled());
  EXPECT_FALSE(off.FallsBehind({6.25, 0.0, 0.0}, {4.0, 0.0, 0.0}, {6.25, 0.0, 0.0}).has_value());
}

}  // namespace
}  // namespace pena::odometry::internal
