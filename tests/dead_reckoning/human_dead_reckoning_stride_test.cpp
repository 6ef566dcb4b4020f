// The dead reckoning between stride reports: the covariance of the stride not yet reported, the
// optional extrapolation of the stride in progress (stops, turns on the spot, overdue reports) and
// resets in the middle of a stride. Split from human_dead_reckoning_test.cpp (style: small files).
#include "pena/dead_reckoning/human_dead_reckoning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "start_pose.hpp"

namespace pena::dead_reckoning {
namespace {

using testing::kDeg;
using testing::StartAt;

// Strides of 0.6 m every 0.5 s along +x (1.2 m/s); the SiLMU reports each when it ends.
void WalkStraight(HumanDeadReckoning& dead_reckoning, int strides) {
  for (int i = 1; i <= strides; ++i) {
    for (int tick = 1; tick <= 50; ++tick) dead_reckoning.Add(sensors::GyroSample{(i - 1) * 0.5 + tick * 0.01, 0.0});
    dead_reckoning.Add(sensors::StrideSample{i * 0.5, 0.6});
  }
}

// The extrapolation between stride reports switched on (off by default).
HumanDeadReckoningOptions Carried() {
  HumanDeadReckoningOptions options;
  options.stride_interpolation.enabled = false;  // extrapolation instead
  options.max_stride_period_s = 1.5;
  return options;
}

// Without the extrapolation the position waits for the report that ends the stride in progress:
// the prior's covariance holds what the walker may have walked since the last one.
TEST(HumanDeadReckoning, CovarianceHoldsTheStrideNotYetReported) {
  HumanDeadReckoning dead_reckoning(HumanDeadReckoningOptions{}, StartAt(0.0, 0.0, 0.0));
  // Before any report: up to unreported_pace_m_s (1 m/s) since the start, along the heading.
  const Eigen::Matrix2d at_start = dead_reckoning.PendingCovarianceAt(0.3);
  EXPECT_NEAR(at_start(0, 0), 0.3 * 0.3, 1e-12);
  EXPECT_NEAR(at_start(1, 1), 0.0, 1e-12);
  WalkStraight(dead_reckoning, 4);  // 0.6 m strides every 0.5 s (1.2 m/s), last at 2.0 s
  const PosePrior mid_stride = dead_reckoning.PriorAt(2.25);
  EXPECT_NEAR(mid_stride.world_from_body.x_m, 2.4, 1e-9);  // the position waits for the report
  const Eigen::Matrix2d pending = dead_reckoning.PendingCovarianceAt(2.25);
  EXPECT_NEAR(pending(0, 0), 0.3 * 0.3, 1e-9);  // 0.25 s at the last stride's pace
  EXPECT_NEAR(pending(1, 1), 0.0, 1e-12);
  EXPECT_GE(mid_stride.covariance(0, 0), pending(0, 0));  // PriorAt adds it to the walk's own
  // At most one stride, however long the next report takes; none at the report itself.
  EXPECT_NEAR(dead_reckoning.PendingCovarianceAt(9.0)(0, 0), 0.6 * 0.6, 1e-9);
  EXPECT_TRUE(dead_reckoning.PendingCovarianceAt(2.0).isZero());
  HumanDeadReckoningOptions off;
  off.unreported_pace_m_s = 0.0;
  HumanDeadReckoning left_out(off, StartAt(0.0, 0.0, 0.0));
  WalkStraight(left_out, 4);
  EXPECT_TRUE(left_out.PendingCovarianceAt(2.25).isZero());
}

TEST(HumanDeadReckoning, CarriesThePositionForwardBetweenStrideReports) {
  HumanDeadReckoning dead_reckoning(Carried(), StartAt(0.0, 0.0, 0.0));
  WalkStraight(dead_reckoning, 4);  // at 2.4 m at t = 2.0 s
  // Mid-stride the walker is half a stride on, not still at the last report (the saw tooth).
  EXPECT_NEAR(dead_reckoning.PriorAt(2.25).world_from_body.x_m, 2.7, 1e-9);
  // At most one stride ahead, however long the next report takes.
  EXPECT_NEAR(dead_reckoning.PriorAt(4.0).world_from_body.x_m, 3.0, 1e-9);
  // The next report replaces the extrapolation: no stride counted twice.
  dead_reckoning.Add(sensors::StrideSample{2.5, 0.5});
  EXPECT_NEAR(dead_reckoning.PriorAt(2.5).world_from_body.x_m, 2.9, 1e-9);
}

TEST(HumanDeadReckoning, ExtrapolationAndStrideInterpolationExcludeEachOther) {
  HumanDeadReckoningOptions both;
  both.max_stride_period_s = 1.5;  // stride_interpolation.enabled by default
  EXPECT_THROW(HumanDeadReckoning(both, StartAt(0.0, 0.0, 0.0)), std::invalid_argument);
}

TEST(HumanDeadReckoning, ExtrapolationIsOffByDefaultAndNeedsAKnownPace) {
  HumanDeadReckoningOptions options;
  EXPECT_EQ(options.max_stride_period_s, 0.0);
  HumanDeadReckoning off(options, StartAt(0.0, 0.0, 0.0));
  WalkStraight(off, 4);
  EXPECT_NEAR(off.PriorAt(2.25).world_from_body.x_m, 2.4, 1e-9);
  // The first stride after standing 5 s gives no pace: nothing is extrapolated after it.
  HumanDeadReckoning standing(Carried(), StartAt(0.0, 0.0, 0.0));
  standing.Add(sensors::StrideSample{5.0, 0.6});
  EXPECT_NEAR(standing.PriorAt(5.25).world_from_body.x_m, 0.6, 1e-9);
  options.max_stride_period_s = -1.0;
  EXPECT_THROW(HumanDeadReckoning(options, StartAt(0.0, 0.0, 0.0)), std::invalid_argument);
}

TEST(HumanDeadReckoning, ResetMidStrideDoesNotCountTheStrideTwice) {
  HumanDeadReckoning dead_reckoning(Carried(), StartAt(0.0, 0.0, 0.0));
  WalkStraight(dead_reckoning, 4);
  PosePrior corrected = dead_reckoning.PriorAt(2.25);  // 2.7 m, half a stride on
  corrected.world_from_body.x_m = 2.8;                 // scan matching says 10 cm further
  dead_reckoning.Reset(corrected);
  EXPECT_NEAR(dead_reckoning.PriorAt(2.25).world_from_body.x_m, 2.8, 1e-9);
  dead_reckoning.Add(sensors::StrideSample{2.5, 0.6});
  EXPECT_NEAR(dead_reckoning.PriorAt(2.5).world_from_body.x_m, 3.1, 1e-9);
}

// A correction that also turns the heading: the prior at the correction's stamp is the correction,
// and the stride in progress turns with it.
TEST(HumanDeadReckoning, ResetMidStrideWithAHeadingCorrectionHoldsAtItsStamp) {
  HumanDeadReckoning dead_reckoning(Carried(), StartAt(0.0, 0.0, 0.0));
  WalkStraight(dead_reckoning, 4);
  PosePrior corrected = dead_reckoning.PriorAt(2.25);
  corrected.world_from_body = {2.8, 0.1, 0.2};
  dead_reckoning.Reset(corrected);
  const PosePrior now = dead_reckoning.PriorAt(2.25);
  EXPECT_NEAR(now.world_from_body.x_m, 2.8, 1e-9);
  EXPECT_NEAR(now.world_from_body.y_m, 0.1, 1e-9);
  EXPECT_NEAR(now.world_from_body.theta_rad, 0.2, 1e-9);
  // The report ends the 0.6 m stride, half of it (0.3 m) still to go along 0.2 rad.
  dead_reckoning.Add(sensors::StrideSample{2.5, 0.6});
  const PosePrior after = dead_reckoning.PriorAt(2.5);
  EXPECT_NEAR(after.world_from_body.x_m, 2.8 + 0.3 * std::cos(0.2), 1e-9);
  EXPECT_NEAR(after.world_from_body.y_m, 0.1 + 0.3 * std::sin(0.2), 1e-9);
}

// The walker stops mid-stride and turns on the spot. The stride in progress must stay where it
// was heading when the next report became due, not swing round with the body.
TEST(HumanDeadReckoning, TurningOnTheSpotAfterStoppingDoesNotSwingTheStride) {
  HumanDeadReckoning dead_reckoning(Carried(), StartAt(0.0, 0.0, 0.0));
  WalkStraight(dead_reckoning, 4);  // at 2.4 m at t = 2.0 s, the next report due at 2.5 s
  for (int tick = 1; tick <= 200; ++tick) {
    // Still until 2.6 s, then a 180 deg turn at 180 deg/s until 3.6 s; no stride is reported.
    const bool turning = tick > 60 && tick <= 160;
    dead_reckoning.Add(sensors::GyroSample{2.0 + tick * 0.01, turning ? std::numbers::pi : 0.0});
  }
  const PosePrior turned = dead_reckoning.PriorAt(4.0);
  EXPECT_NEAR(std::abs(turned.world_from_body.theta_rad), std::numbers::pi, 1e-6);
  // One stride ahead along +x, as before the turn (the first version: 2.4 - 0.6 = 1.8 m).
  EXPECT_NEAR(turned.world_from_body.x_m, 3.0, 1e-9);
  EXPECT_NEAR(turned.world_from_body.y_m, 0.0, 1e-9);
}

// A walker who stops part of the way through a stride (office seed 3, team ff3 at 165 s: standing
// at a waypoint, the prior a whole stride ahead, then a 0.9 m jump back at the next report): once
// the next report is 1.2 periods overdue the extrapolation falls back, over one more period, to
// 30 % of the stride.
TEST(HumanDeadReckoning, AStoppedWalkerKeepsOnlyPartOfTheStrideInProgress) {
  HumanDeadReckoningOptions options = Carried();
  options.stopped_stride_fraction = 0.3;
  HumanDeadReckoning dead_reckoning(options, StartAt(0.0, 0.0, 0.0));
  WalkStraight(dead_reckoning, 4);  // at 2.4 m at t = 2.0 s, 0.6 m strides every 0.5 s
  EXPECT_NEAR(dead_reckoning.PriorAt(2.55).world_from_body.x_m, 3.0, 1e-9);
  // 0.9 s after the report: 0.3 s past 1.2 periods, so 60 % of the way to 30 % of the stride.
  EXPECT_NEAR(dead_reckoning.PriorAt(2.9).world_from_body.x_m, 2.4 + 0.6 * (0.4 + 0.6 * 0.3), 1e-9);
  EXPECT_NEAR(dead_reckoning.PriorAt(4.0).world_from_body.x_m, 2.4 + 0.3 * 0.6, 1e-9);
  // Walking on, the first report (a pace unknown after the stop) replaces the extrapolation.
  dead_reckoning.Add(sensors::StrideSample{5.0, 0.6});
  EXPECT_NEAR(dead_reckoning.PriorAt(5.0).world_from_body.x_m, 3.0, 1e-9);
  // The default keeps the whole stride through a stop.
  HumanDeadReckoning whole(Carried(), StartAt(0.0, 0.0, 0.0));
  WalkStraight(whole, 4);
  EXPECT_NEAR(whole.PriorAt(4.0).world_from_body.x_m, 3.0, 1e-9);
  HumanDeadReckoningOptions bad = Carried();
  bad.stopped_stride_fraction = 1.5;
  EXPECT_THROW(HumanDeadReckoning(bad, StartAt(0.0, 0.0, 0.0)), std::invalid_argument);
  bad = Carried();
  bad.stopped_after_periods = 0.5;
  EXPECT_THROW(HumanDeadReckoning(bad, StartAt(0.0, 0.0, 0.0)), std::invalid_argument);
}

// A turn on the spot right after a report (gyro above 1 rad/s): the stride in progress does not
// advance and keeps the heading it had before the turn (the version before this one: 0.3 m on,
// along the mean heading, 22.5 deg off).
TEST(HumanDeadReckoning, TurningOnTheSpotHoldsTheStrideInProgress) {
  HumanDeadReckoningOptions options = Carried();
  options.turning_on_the_spot_rad_s = 1.0;
  HumanDeadReckoning dead_reckoning(options, StartAt(0.0, 0.0, 0.0));
  WalkStraight(dead_reckoning, 4);
  for (int tick = 1; tick <= 25; ++tick) {
    dead_reckoning.Add(sensors::GyroSample{2.0 + tick * 0.01, std::numbers::pi});  // 45 deg
  }
  const PosePrior turned = dead_reckoning.PriorAt(2.25);
  EXPECT_NEAR(turned.world_from_body.theta_rad, 0.25 * std::numbers::pi, 1e-9);
  EXPECT_NEAR(turned.world_from_body.x_m, 2.4, 1e-9);
  EXPECT_NEAR(turned.world_from_body.y_m, 0.0, 1e-9);
  // Walking on after the turn: the stride advances again, from where the turn held it.
  for (int tick = 26; tick <= 40; ++tick) dead_reckoning.Add(sensors::GyroSample{2.0 + tick * 0.01, 0.0});
  EXPECT_NEAR(dead_reckoning.PriorAt(2.40).world_from_body.x_m, 2.4 + 0.6 * 0.3, 1e-9);
  HumanDeadReckoningOptions bad = Carried();
  bad.turning_on_the_spot_rad_s = -1.0;
  EXPECT_THROW(HumanDeadReckoning(bad, StartAt(0.0, 0.0, 0.0)), std::invalid_argument);
}

// Team3 ff3 at 35-39.5 s: the walker stops at a report, stands (the prior carried a whole stride
// on), turns 180 deg on the spot and walks back. Keyframes taken in the turn keep the invented
// stride, and the next report (a stride along the new heading) moves the prior back by both. With
// overdue_turn_rad the stride in progress is dropped once overdue and turned 45 deg: the prior is
// at the last report (its covariance widened), and the report moves it by the stride alone.
HumanDeadReckoning StopAndTurnBack(double overdue_turn_rad, double turn_rad_s) {
  HumanDeadReckoningOptions options = Carried();
  options.overdue_turn_rad = overdue_turn_rad;
  HumanDeadReckoning dead_reckoning(options, StartAt(0.0, 0.0, 0.0));
  WalkStraight(dead_reckoning, 4);  // at 2.4 m at t = 2.0 s, the next report due at 2.5 s
  for (int tick = 1; tick <= 200; ++tick) {
    // Standing until 3.0 s, then turning for 1 s (180 deg at pi rad/s) until 4.0 s.
    const bool turning = tick > 100;
    dead_reckoning.Add(sensors::GyroSample{2.0 + tick * 0.01, turning ? turn_rad_s : 0.0});
  }
  return dead_reckoning;
}

// Not turning (gyro at 0) from from_s to to_s.
void HoldHeading(HumanDeadReckoning& dead_reckoning, double from_s, double to_s) {
  for (int tick = 1; from_s + tick * 0.01 <= to_s + 1e-9; ++tick) {
    dead_reckoning.Add(sensors::GyroSample{from_s + tick * 0.01, 0.0});
  }
}

TEST(HumanDeadReckoning, AnOverdueTurnOnTheSpotDropsTheStrideInProgress) {
  HumanDeadReckoning dropped = StopAndTurnBack(45.0 * kDeg, std::numbers::pi);
  const PosePrior in_turn = dropped.PriorAt(4.0);
  EXPECT_NEAR(in_turn.world_from_body.x_m, 2.4, 1e-9);
  EXPECT_NEAR(in_turn.world_from_body.y_m, 0.0, 1e-9);
  EXPECT_GT(in_turn.covariance(1, 1), 0.3 * 0.3);  // half a stride (0.3 m), any direction
  HoldHeading(dropped, 4.0, 4.5);
  dropped.Add(sensors::StrideSample{4.5, 0.3});  // 0.3 m back along -x
  EXPECT_NEAR(dropped.PriorAt(4.5).world_from_body.x_m - in_turn.world_from_body.x_m, -0.3, 1e-6);
  // The default carries the stride on through the turn: the report moves the prior 0.9 m back.
  HumanDeadReckoning carried = StopAndTurnBack(0.0, std::numbers::pi);
  const PosePrior carried_in_turn = carried.PriorAt(4.0);
  EXPECT_NEAR(carried_in_turn.world_from_body.x_m, 3.0, 1e-9);
  HoldHeading(carried, 4.0, 4.5);
  carried.Add(sensors::StrideSample{4.5, 0.3});
  EXPECT_NEAR(carried.PriorAt(4.5).world_from_body.x_m - carried_in_turn.world_from_body.x_m, -0.9,
              1e-6);
  HumanDeadReckoningOptions bad = Carried();
  bad.overdue_turn_rad = -0.1;
  EXPECT_THROW(HumanDeadReckoning(bad, StartAt(0.0, 0.0, 0.0)), std::invalid_argument);
}

// A smaller turn than the bound (30 deg at 0.5236 rad/s) keeps the stride, and the drop lasts
// only until the next report: the stride after it is extrapolated again.
TEST(HumanDeadReckoning, TheOverdueTurnBoundKeepsSmallTurnsAndEndsAtTheNextReport) {
  HumanDeadReckoning small = StopAndTurnBack(45.0 * kDeg, 0.5236);
  EXPECT_NEAR(small.PriorAt(4.0).world_from_body.x_m, 3.0, 1e-9);
  HumanDeadReckoning dropped = StopAndTurnBack(45.0 * kDeg, std::numbers::pi);
  HoldHeading(dropped, 4.0, 4.5);
  dropped.Add(sensors::StrideSample{4.5, 0.6});  // 1.8 m, back along -x
  HoldHeading(dropped, 4.5, 5.0);
  dropped.Add(sensors::StrideSample{5.0, 0.6});  // 1.2 m; a pace known again
  EXPECT_NEAR(dropped.PriorAt(5.25).world_from_body.x_m, 1.2 - 0.3, 1e-6);
}

// The jumps the estimate makes by replacing or dropping its extrapolated stride are summed for the
// laser odometry (keyframe_absorbs_stride_jumps); steady walking and a first report (no pace yet,
// all new motion) add none.
TEST(HumanDeadReckoning, SumsTheJumpsOfReplacedAndDroppedExtrapolations) {
  HumanDeadReckoning carried = StopAndTurnBack(0.0, std::numbers::pi);
  EXPECT_NEAR(carried.extrapolation_jumps_m().norm(), 0.0, 1e-9);
  HoldHeading(carried, 4.0, 4.5);
  carried.Add(sensors::StrideSample{4.5, 0.3});  // 3.0 m carried on -> 2.1 m
  EXPECT_NEAR(carried.extrapolation_jumps_m().x(), -0.9, 1e-6);
  EXPECT_NEAR(carried.extrapolation_jumps_m().y(), 0.0, 1e-6);
  HumanDeadReckoning dropped = StopAndTurnBack(45.0 * kDeg, std::numbers::pi);
  EXPECT_NEAR(dropped.extrapolation_jumps_m().x(), -0.6, 1e-6);  // the dropped stride
  HoldHeading(dropped, 4.0, 4.5);
  dropped.Add(sensors::StrideSample{4.5, 0.3});
  EXPECT_NEAR(dropped.extrapolation_jumps_m().x(), -0.9, 1e-6);
}

// Turning while walking: the stride in progress is the chord of the arc, along the mean heading.
TEST(HumanDeadReckoning, TheStrideInProgressFollowsTheChordOfATurn) {
  HumanDeadReckoning dead_reckoning(Carried(), StartAt(0.0, 0.0, 0.0));
  WalkStraight(dead_reckoning, 4);
  for (int tick = 1; tick <= 25; ++tick) {
    dead_reckoning.Add(sensors::GyroSample{2.0 + tick * 0.01, 0.4});  // 0.1 rad by 2.25 s
  }
  const PosePrior prior = dead_reckoning.PriorAt(2.25);
  EXPECT_NEAR(prior.world_from_body.theta_rad, 0.1, 1e-9);
  EXPECT_NEAR(prior.world_from_body.x_m, 2.4 + 0.3 * std::cos(0.05), 1e-9);
  EXPECT_NEAR(prior.world_from_body.y_m, 0.3 * std::sin(0.05), 1e-9);
  // Half a stride extrapolated: its sigma is a quarter stride along the chord.
  const Eigen::Vector2d along(std::cos(0.05), std::sin(0.05));
  const Eigen::Matrix2d added = prior.covariance.topLeftCorner<2, 2>();
  EXPECT_GT(along.dot(added * along), 0.15 * 0.15);
}

}  // namespace
}  // namespace pena::dead_reckoning
