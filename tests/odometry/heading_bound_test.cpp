// The heading bound for people (heading_bound_rad): the prior is anchored at the keyframes, so a
// heading error in the keyframes stays for good unless something absolute pulls it back. Here
// the chain starts 8 deg off the true heading (as a keyframe taken badly in a turn leaves it);
// the gyro + compass filter converges to the compass, and with the bound the chain follows it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pena/odometry/laser_odometry.hpp"
#include "team_entity.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::odometry {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

const sim::EntityRecording& Firefighter() { return testing::TeamEntity("ff2"); }

struct BoundRun {
  double mean_heading_error_rad = 0.0;  // over the scans after the first 30 s
  OdometryCounts counts;
};

// The first 90 s of ff2, started `start_error_rad` off the true heading.
BoundRun Replay(const LaserOdometryOptions& options, double start_error_rad) {
  const sim::EntityRecording& person = Firefighter();
  geometry::Pose2 start = person.truth.front().world_from_body;
  start.theta_rad += start_error_rad;
  LaserOdometry odometry(options, person.kind, start, person.start_s);
  BoundRun run;
  std::size_t truth_index = 0;
  int counted = 0;
  for (const auto& record : person.records) {
    const auto estimate = odometry.Add(record);
    if (!estimate) continue;
    if (estimate->stamp_s > person.start_s + 90.0) break;
    while (truth_index + 1 < person.truth.size() && person.truth[truth_index].stamp_s < estimate->stamp_s) {
      ++truth_index;
    }
    if (estimate->stamp_s < person.start_s + 30.0) continue;
    run.mean_heading_error_rad += std::abs(geometry::NormalizeAngle(
        estimate->world_from_body.theta_rad - person.truth[truth_index].world_from_body.theta_rad));
    ++counted;
  }
  if (counted > 0) run.mean_heading_error_rad /= counted;
  run.counts = odometry.counts();
  return run;
}

TEST(HeadingBound, AKeyframeHeadingErrorStaysWithoutTheBoundAndIsRemovedWithIt) {
  const BoundRun plain = Replay(LaserOdometryOptions{}, 8.0 * kDeg);
  EXPECT_GT(plain.mean_heading_error_rad, 5.0 * kDeg) << plain.mean_heading_error_rad / kDeg;  // nothing pulls it back
  EXPECT_EQ(plain.counts.heading_resets, 0);
  LaserOdometryOptions bounded;
  bounded.heading_bound_rad = 4.0 * kDeg;
  const BoundRun fixed = Replay(bounded, 8.0 * kDeg);
  EXPECT_GE(fixed.counts.heading_resets, 1);
  EXPECT_LT(fixed.mean_heading_error_rad, 2.0 * kDeg) << fixed.mean_heading_error_rad / kDeg;
}

TEST(HeadingBound, OptionsAreChecked) {
  LaserOdometryOptions options;
  options.heading_bound_rad = -0.1;
  EXPECT_THROW(LaserOdometry(options, sensors::EntityKind::kHuman, {}, 0.0), std::invalid_argument);
  options = {};
  options.heading_bound_scans = 0;
  EXPECT_THROW(LaserOdometry(options, sensors::EntityKind::kHuman, {}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace pena::odometry
