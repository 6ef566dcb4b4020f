// Wheel odometry that freezes in a turn and catches up (frozen_odometry_*): mit-csail's logged
// pose repeats for three to four scans while the robot turns 10 deg a scan, then jumps by
// 50-85 deg. On the simulated team robot (level laser, odometry logged with each scan), whose
// logged odometry is frozen here by hand over four scans of its fastest turn.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"
#include "team_entity.hpp"

namespace pena::odometry {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr std::size_t kFrozenScans = 4;

const sim::EntityRecording& Robot() { return testing::TeamEntity("robot1"); }

std::vector<OdometryEstimate> Replay(const std::vector<sensors::SensorRecord>& records,
                                     const LaserOdometryOptions& options) {
  return testing::ReplayRecords(Robot(), records, options);
}

double HeadingRad(std::size_t scan) { return Robot().truth.at(scan).world_from_body.theta_rad; }

// The first scan of the kFrozenScans-scan stretch that turns most.
std::size_t FastestTurnStart() {
  std::size_t best = 1;
  double best_turn = 0.0;
  for (std::size_t i = 1; i + kFrozenScans < Robot().truth.size(); ++i) {
    const double turn =
        std::abs(geometry::NormalizeAngle(HeadingRad(i + kFrozenScans - 1) - HeadingRad(i - 1)));
    if (turn > best_turn) {
      best_turn = turn;
      best = i;
    }
  }
  return best;
}

// The odometry logged with scans first .. first + kFrozenScans - 1 repeats the pose logged with
// scan first - 1; the next scan's is its own again (the catch-up).
std::vector<sensors::SensorRecord> WithFrozenOdometry(std::size_t first) {
  std::vector<sensors::SensorRecord> records = Robot().records;
  std::vector<sensors::LaserScan*> scans;
  for (auto& record : records) {
    if (auto* scan = std::get_if<sensors::LaserScan>(&record)) scans.push_back(scan);
  }
  const std::optional<geometry::Pose2> frozen = scans.at(first - 1)->odometry_pose;
  if (!frozen) throw std::runtime_error("the simulated robot should log odometry with scans");
  for (std::size_t i = first; i < first + kFrozenScans; ++i) scans.at(i)->odometry_pose = frozen;
  return records;
}

// The largest heading error of the prior over the frozen scans but the first (predicted from
// the motion before it: the robot accelerates into the turn there) and the three after them.
double WorstPriorHeadingErrorRad(const std::vector<OdometryEstimate>& estimates,
                                 std::size_t first) {
  double worst = 0.0;
  for (std::size_t i = first + 1; i < first + kFrozenScans + 3; ++i) {
    worst = std::max(worst, std::abs(geometry::NormalizeAngle(
                                estimates.at(i).world_from_prior.theta_rad - HeadingRad(i))));
  }
  return worst;
}

TEST(FrozenOdometry, FrozenScansArePredictedAtConstantVelocityAndTheCatchUpIsNotAddedTwice) {
  const std::size_t first = FastestTurnStart();
  const double frozen_turn_rad = std::abs(
      geometry::NormalizeAngle(HeadingRad(first + kFrozenScans - 1) - HeadingRad(first - 1)));
  ASSERT_GT(frozen_turn_rad, 20.0 * kDeg) << "the robot should turn enough while frozen";
  const std::vector<sensors::SensorRecord> records = WithFrozenOdometry(first);

  // Without the option the frozen scans are predicted where the odometry stopped, and a keyframe
  // taken meanwhile is paired with the frozen pose: the catch-up overshoots.
  LaserOdometryOptions off;
  off.frozen_odometry_min_turn_rad = 0.0;
  off.frozen_odometry_min_move_m = 0.0;
  const std::vector<OdometryEstimate> plain = Replay(records, off);
  ASSERT_EQ(plain.size(), Robot().truth.size());
  EXPECT_GT(WorstPriorHeadingErrorRad(plain, first), 0.5 * frozen_turn_rad);

  LaserOdometryOptions options;
  options.frozen_odometry_min_turn_rad = 1.0 * kDeg;
  options.frozen_odometry_min_move_m = 0.05;
  const std::vector<OdometryEstimate> estimates = Replay(records, options);
  ASSERT_EQ(estimates.size(), Robot().truth.size());
  EXPECT_LT(WorstPriorHeadingErrorRad(estimates, first), 3.0 * kDeg);
  for (std::size_t i = first; i < first + kFrozenScans + 3; ++i) {
    EXPECT_FALSE(estimates[i].gated) << "scan " << i;
  }
  const double end_error_rad =
      geometry::NormalizeAngle(estimates.back().world_from_body.theta_rad -
                               Robot().truth.back().world_from_body.theta_rad);
  EXPECT_LT(std::abs(end_error_rad), 2.0 * kDeg);
}

// A robot's defaults (1 deg, 0.15 m) handle the freeze too.
TEST(FrozenOdometry, TheRobotDefaultsHandleAFreeze) {
  const std::size_t first = FastestTurnStart();
  const std::vector<OdometryEstimate> estimates = Replay(WithFrozenOdometry(first), {});
  ASSERT_EQ(estimates.size(), Robot().truth.size());
  EXPECT_LT(WorstPriorHeadingErrorRad(estimates, first), 3.0 * kDeg);
}

// local_map_place_fill_frozen_scans: while frozen and a few scans after, the place choice's
// free slots go to the latest keyframes. The runs agree up to the freeze, differ
// in it (the rule acted), and the priors and the end stay as good as with the defaults.
TEST(FrozenOdometry, TheReferenceIsFilledWhileFrozen) {
  const std::size_t first = FastestTurnStart();
  const std::vector<sensors::SensorRecord> records = WithFrozenOdometry(first);
  LaserOdometryOptions place_only;
  place_only.local_map_place_fill_frozen_scans = 0;
  LaserOdometryOptions filled;
  filled.local_map_place_fill_frozen_scans = 5;
  const std::vector<OdometryEstimate> plain = Replay(records, place_only);
  const std::vector<OdometryEstimate> estimates = Replay(records, filled);
  ASSERT_EQ(estimates.size(), plain.size());
  const auto same = [&](std::size_t i) {
    return plain[i].score == estimates[i].score &&
           plain[i].world_from_body.theta_rad == estimates[i].world_from_body.theta_rad;
  };
  for (std::size_t i = 0; i < first; ++i) ASSERT_TRUE(same(i)) << "scan " << i;
  bool acted = false;
  for (std::size_t i = first; i < first + kFrozenScans + 5; ++i) acted = acted || !same(i);
  EXPECT_TRUE(acted);
  // A robot's default (chosen on the Freiburg start frames, docs/odometry.md).
  const std::vector<OdometryEstimate> defaults = Replay(records, {});
  ASSERT_EQ(defaults.size(), estimates.size());
  for (std::size_t i = 0; i < defaults.size(); ++i) {
    ASSERT_EQ(defaults[i].world_from_body.theta_rad, estimates[i].world_from_body.theta_rad) << i;
  }
  EXPECT_LT(WorstPriorHeadingErrorRad(estimates, first), 3.0 * kDeg);
  const double end_error_rad =
      geometry::NormalizeAngle(estimates.back().world_from_body.theta_rad -
                               Robot().truth.back().world_from_body.theta_rad);
  EXPECT_LT(std::abs(end_error_rad), 2.0 * kDeg);
}

TEST(FrozenOdometry, OptionsAreChecked) {
  LaserOdometryOptions options;
  options.frozen_odometry_min_turn_rad = -0.1;
  EXPECT_THROW(LaserOdometry(options, sensors::EntityKind::kRobot, {}, 0.0), std::invalid_argument);
  options.frozen_odometry_min_turn_rad = 0.0;
  options.frozen_odometry_min_move_m = -0.1;
  EXPECT_THROW(LaserOdometry(options, sensors::EntityKind::kRobot, {}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace pena::odometry
