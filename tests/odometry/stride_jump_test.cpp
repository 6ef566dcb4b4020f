// keyframe_absorbs_stride_jumps: a stride report that replaces the extrapolated stride in progress
// corrects a guess about the past; with the option it does not move a prior anchored before it.

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"

namespace pena::odometry {
namespace {

sensors::LaserScan RingScan(double stamp_s) {
  sensors::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.geometry = {-std::numbers::pi / 2.0, std::numbers::pi / 180.0, 30.0};
  scan.ranges_m.assign(181, 5.0f);
  return scan;
}

void Gyro(std::vector<sensors::SensorRecord>& records, double from_s, double to_s, double rate) {
  for (int tick = 1; from_s + tick * 0.01 <= to_s + 1e-9; ++tick) {
    records.push_back(sensors::GyroSample{from_s + tick * 0.01, rate});
  }
}

// Team3 ff3 at 35-39.5 s: 0.6 m strides at 2 Hz along +x to 2.4 m at 2.0 s, then standing (the
// extrapolation carries the prior a stride on, to 3.0 m), the first scan (the keyframe) at 3.0 s,
// a 180 deg turn on the spot until 4.0 s (scan), and a 0.3 m report back along -x at 4.5 s (scan).
std::vector<double> PriorXAtScans(bool absorb) {
  std::vector<sensors::SensorRecord> records;
  for (int i = 1; i <= 4; ++i) {
    Gyro(records, (i - 1) * 0.5, i * 0.5, 0.0);
    records.push_back(sensors::StrideSample{i * 0.5, 0.6});
  }
  Gyro(records, 2.0, 3.0, 0.0);
  records.push_back(RingScan(3.0));
  Gyro(records, 3.0, 4.0, std::numbers::pi);
  records.push_back(RingScan(4.0));
  Gyro(records, 4.0, 4.5, 0.0);
  records.push_back(sensors::StrideSample{4.5, 0.3});
  records.push_back(RingScan(4.5));
  LaserOdometryOptions options;
  options.match_scans = false;  // the prior alone, anchored at the first scan's keyframe
  options.dead_reckoning.max_stride_period_s = 1.5;
  options.keyframe_absorbs_stride_jumps = absorb;
  LaserOdometry odometry(options, sensors::EntityKind::kHuman, {}, 0.0);
  std::vector<double> prior_x_m;
  for (const auto& record : records) {
    if (auto estimate = odometry.Add(record)) prior_x_m.push_back(estimate->world_from_prior.x_m);
  }
  return prior_x_m;
}

TEST(StrideJump, AReportReplacingTheExtrapolationDoesNotMoveAPriorAnchoredBeforeIt) {
  const std::vector<double> absorbed = PriorXAtScans(true);
  ASSERT_EQ(absorbed.size(), 3u);
  EXPECT_NEAR(absorbed[1], absorbed[0], 1e-6);  // the turn on the spot: no motion
  // The report replaces the 0.6 m carried on by 0.3 m back: the jump (-0.9 m) is absorbed.
  EXPECT_NEAR(absorbed[2], absorbed[1], 1e-6);
  // Off (the default): the prior jumps back by the report and the invented stride together.
  const std::vector<double> carried = PriorXAtScans(false);
  ASSERT_EQ(carried.size(), 3u);
  EXPECT_NEAR(carried[1], carried[0], 1e-6);
  EXPECT_NEAR(carried[2] - carried[1], -0.9, 1e-6);
}

}  // namespace
}  // namespace pena::odometry
