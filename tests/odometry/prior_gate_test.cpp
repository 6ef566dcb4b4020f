// The prior-consistency gate of LaserOdometry: a match far from the motion prior is output but
// not made a keyframe, until prior_gate_confirm such scans in a row show that the motion sensor
// (not the scan) is what is wrong. And the stale-scan check. On the simulated team robot (level
// laser, wheel odometry).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"
#include "team_entity.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::odometry {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

const sim::EntityRecording& Robot() { return testing::TeamEntity("robot1"); }

std::vector<OdometryEstimate> Replay(const std::vector<sensors::SensorRecord>& records,
                                     const LaserOdometryOptions& options) {
  return testing::ReplayRecords(Robot(), records, options);
}

double FinalErrorM(const std::vector<OdometryEstimate>& estimates) {
  const geometry::Pose2& truth = Robot().truth.back().world_from_body;
  const geometry::Pose2& end = estimates.back().world_from_body;
  return std::hypot(truth.x_m - end.x_m, truth.y_m - end.y_m);
}

// The scan index (into truth) where the heading changed most over the previous `back` scans.
std::size_t FastestTurn(std::size_t back) {
  const auto& truth = Robot().truth;
  std::size_t best = back;
  double best_turn = 0.0;
  for (std::size_t i = back; i < truth.size(); ++i) {
    const double turn = std::abs(geometry::NormalizeAngle(truth[i].world_from_body.theta_rad -
                                                          truth[i - back].world_from_body.theta_rad));
    if (turn > best_turn) {
      best_turn = turn;
      best = i;
    }
  }
  return best;
}

// The records with scan `target` replaced by the ranges of scan `source` (its own stamp and
// odometry kept): a stale scan re-delivered late, as the intel log does during turns on the spot.
std::vector<sensors::SensorRecord> WithStaleScan(std::size_t target, std::size_t source) {
  std::vector<sensors::SensorRecord> records = Robot().records;
  std::vector<sensors::LaserScan*> scans;
  for (auto& record : records) {
    if (auto* scan = std::get_if<sensors::LaserScan>(&record)) scans.push_back(scan);
  }
  scans.at(target)->ranges_m = scans.at(source)->ranges_m;
  return records;
}

// A scan re-delivered late during a turn (a beam-for-beam copy of a scan 8 back, with its own
// stamp and odometry): the stale-scan check flags it; it is output but not made a keyframe.
TEST(StaleScan, RepeatedScanDuringATurnIsFlaggedAndNotMadeAKeyframe) {
  constexpr std::size_t kBack = 8;
  const std::size_t target = FastestTurn(kBack);
  const auto& truth = Robot().truth;
  const double stale_turn_rad = std::abs(geometry::NormalizeAngle(
      truth[target].world_from_body.theta_rad - truth[target - kBack].world_from_body.theta_rad));
  ASSERT_GT(stale_turn_rad, 20.0 * kDeg) << "the scenario should turn fast enough to test";
  const std::vector<OdometryEstimate> estimates =
      Replay(WithStaleScan(target, target - kBack), {});
  ASSERT_EQ(estimates.size(), truth.size());
  EXPECT_TRUE(estimates[target].stale);
  EXPECT_FALSE(estimates[target].reference_changed);
  long stale = 0;
  for (const auto& estimate : estimates) stale += estimate.stale ? 1 : 0;
  EXPECT_EQ(stale, 1);
  // Without the check the copy is matched (it fails: taken 8 scans earlier) and, as a failed
  // match, restarts the local map from itself.
  LaserOdometryOptions no_check;
  no_check.stale_history_scans = 0;
  const std::vector<OdometryEstimate> unchecked = Replay(WithStaleScan(target, target - kBack), no_check);
  EXPECT_FALSE(unchecked[target].stale);
  EXPECT_TRUE(unchecked[target].reference_changed);
}

// The odometry logged with one scan is 30 deg off (a glitch of the motion sensor): the match
// finds the true pose, outside the gate; it is output, not made a keyframe, and the next scan,
// whose odometry is right again, is inside the gate.
TEST(PriorGate, OneScanOdometryGlitchIsOutputButNotMadeAKeyframe) {
  const sim::EntityRecording& robot = Robot();
  const std::size_t glitch = robot.truth.size() / 3;
  std::vector<sensors::SensorRecord> records = robot.records;
  std::size_t scan_index = 0;
  for (auto& record : records) {
    auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (scan == nullptr) continue;
    if (scan_index++ != glitch) continue;
    ASSERT_TRUE(scan->odometry_pose.has_value()) << "the simulated robot logs odometry with scans";
    scan->odometry_pose =
        geometry::Compose(*scan->odometry_pose, geometry::Pose2{0.0, 0.0, 30.0 * kDeg});
  }
  const std::vector<OdometryEstimate> estimates = Replay(records, {});
  ASSERT_EQ(estimates.size(), robot.truth.size());
  const OdometryEstimate& glitched = estimates[glitch];
  EXPECT_TRUE(glitched.gated);
  EXPECT_FALSE(glitched.reference_changed);
  EXPECT_NEAR(geometry::NormalizeAngle(glitched.world_from_body.theta_rad -
                                       robot.truth[glitch].world_from_body.theta_rad),
              0.0, 1.0 * kDeg);  // the output is the match's pose
  EXPECT_FALSE(estimates[glitch + 1].gated);
  EXPECT_LT(FinalErrorM(estimates), 0.4);

  LaserOdometryOptions no_gate;
  no_gate.prior_gate_rad = 0.0;
  EXPECT_FALSE(Replay(records, no_gate)[glitch].gated);
}

// The wheel odometry slips once by 30 deg (a wheel spins on the spot): every later scan is
// 30 deg from its prior. The first prior_gate_confirm - 1 are gated, then the scans win.
TEST(PriorGate, ConsistentDeviationIsTrustedAfterConfirmScans) {
  const sim::EntityRecording& robot = Robot();
  const std::size_t slip_scan = robot.truth.size() / 2;
  const double slip_stamp_s = robot.truth[slip_scan].stamp_s - 1e-3;
  std::vector<sensors::SensorRecord> records = robot.records;
  std::optional<geometry::Pose2> odom_at_slip;
  const geometry::Pose2 slip{0.0, 0.0, 30.0 * kDeg};
  // From the slip on, every odometry pose (wheel records and the pose logged with each scan)
  // is turned by 30 deg about the pose at the slip.
  const auto slipped = [&](double stamp_s, geometry::Pose2& odom_pose) {
    if (stamp_s < slip_stamp_s) return;
    if (!odom_at_slip) odom_at_slip = odom_pose;
    odom_pose = geometry::Compose(geometry::Compose(*odom_at_slip, slip),
                                  geometry::Between(*odom_at_slip, odom_pose));
  };
  for (auto& record : records) {
    if (auto* wheel = std::get_if<sensors::WheelOdometry>(&record)) {
      slipped(wheel->stamp_s, wheel->odom_pose);
    } else if (auto* scan = std::get_if<sensors::LaserScan>(&record); scan && scan->odometry_pose) {
      slipped(scan->stamp_s, *scan->odometry_pose);
    }
  }
  ASSERT_TRUE(odom_at_slip.has_value());

  LaserOdometryOptions options;
  const std::vector<OdometryEstimate> estimates = Replay(records, options);
  ASSERT_EQ(estimates.size(), robot.truth.size());
  std::size_t first_gated = estimates.size();
  for (std::size_t i = slip_scan; i < estimates.size(); ++i) {
    if (estimates[i].gated) {
      first_gated = i;
      break;
    }
  }
  ASSERT_LT(first_gated, slip_scan + 3) << "the slip must be seen at once";
  const auto confirm = static_cast<std::size_t>(options.prior_gate_confirm);
  for (std::size_t i = first_gated; i < first_gated + confirm - 1; ++i) {
    EXPECT_TRUE(estimates[i].gated) << "scan " << i;
    EXPECT_FALSE(estimates[i].reference_changed) << "scan " << i;
  }
  const OdometryEstimate& trusted = estimates[first_gated + confirm - 1];
  EXPECT_FALSE(trusted.gated);
  EXPECT_TRUE(trusted.reference_changed);
  // Anchored at the trusted keyframe, the priors agree with the scans again: the next scan is
  // inside the gate, and the slip does not end up in the heading.
  EXPECT_FALSE(estimates[first_gated + confirm].gated);
  const double heading_error_rad = geometry::NormalizeAngle(
      estimates.back().world_from_body.theta_rad - robot.truth.back().world_from_body.theta_rad);
  EXPECT_LT(std::abs(heading_error_rad), 2.0 * kDeg);
  EXPECT_LT(FinalErrorM(estimates), 0.4);
}

}  // namespace
}  // namespace pena::odometry
