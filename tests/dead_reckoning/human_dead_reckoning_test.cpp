#include "pena/dead_reckoning/human_dead_reckoning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "start_pose.hpp"

namespace pena::dead_reckoning {
namespace {

using testing::kDeg;
using testing::StartAt;

// Walks a 10 m square counter-clockwise: 0.7 m strides at 2 Hz with 5% length noise, gyro at
// 100 Hz, compass at 10 Hz; 90 deg turns at 90 deg/s on the spot. Returns the last stride's stamp.
double WalkSquare(HumanDeadReckoning& dead_reckoning, std::mt19937& rng) {
  std::normal_distribution<double> stride_noise(0.0, 0.05);
  std::normal_distribution<double> compass_noise(0.0, 2.0 * kDeg);
  double t = 0.0;
  double last_stride_s = 0.0;
  double heading = 0.0;
  for (int side = 0; side < 4; ++side) {
    for (int step = 0; step < 14; ++step) {  // 14 x 0.714 m = 10 m
      for (int tick = 0; tick < 50; ++tick) {
        t += 0.01;
        dead_reckoning.Add(sensors::GyroSample{t, 0.0});
        if (tick % 10 == 0) dead_reckoning.Add(sensors::CompassSample{t, heading + compass_noise(rng)});
      }
      dead_reckoning.Add(sensors::StrideSample{t, (10.0 / 14.0) * (1.0 + stride_noise(rng))});
      last_stride_s = t;
    }
    for (int tick = 0; tick < 100; ++tick) {
      t += 0.01;
      heading += 0.5 * std::numbers::pi * 0.01;
      dead_reckoning.Add(sensors::GyroSample{t, 0.5 * std::numbers::pi});
    }
  }
  return last_stride_s;
}

TEST(HumanDeadReckoning, ClosesASquareWithinStrideError) {
  std::mt19937 rng(3);
  HumanDeadReckoning dead_reckoning({}, StartAt(0.0, 0.0, 0.0));
  // At the last stride report: during the turn on the spot that follows, the position is carried
  // a stride forward at the last pace (the SiLMU cannot tell a stop from a slow stride).
  const double last_stride_s = WalkSquare(dead_reckoning, rng);
  const PosePrior end = dead_reckoning.PriorAt(last_stride_s);
  // 40 m walked with 5% per-stride noise: a few tens of centimetres at most.
  EXPECT_LT(std::hypot(end.world_from_body.x_m, end.world_from_body.y_m), 0.6);
  EXPECT_GT(end.covariance(0, 0), 1e-3);  // uncertainty grew with the walk
}

TEST(HumanDeadReckoning, RejectsFortyMetreStrideAndCarriesOn) {
  HumanDeadReckoning dead_reckoning({}, StartAt(1.0, 2.0, 0.0));
  EXPECT_EQ(dead_reckoning.Add(sensors::StrideSample{0.5, 40.0}),
            DeadReckoningEvent::kStrideRejected);
  EXPECT_EQ(dead_reckoning.Add(sensors::StrideSample{0.6, std::nan("")}),
            DeadReckoningEvent::kStrideRejected);
  EXPECT_EQ(dead_reckoning.Add(sensors::StrideSample{1.0, 0.7}), DeadReckoningEvent::kNone);
  const PosePrior prior = dead_reckoning.PriorAt(1.0);
  EXPECT_NEAR(prior.world_from_body.x_m, 1.7, 1e-9);
  EXPECT_NEAR(prior.world_from_body.y_m, 2.0, 1e-9);
  EXPECT_EQ(dead_reckoning.counts().strides_rejected, 2u);
}

TEST(HumanDeadReckoning, GyroGapOfFiveSecondsIsCountedNotIntegrated) {
  HumanDeadReckoning dead_reckoning({}, StartAt(0.0, 0.0, 0.0));
  dead_reckoning.Add(sensors::GyroSample{0.01, 1.0});
  EXPECT_EQ(dead_reckoning.Add(sensors::GyroSample{5.01, 1.0}), DeadReckoningEvent::kGyroGap);
  EXPECT_EQ(dead_reckoning.counts().gyro_gaps, 1u);
  // 5 s at 1 rad/s would be 5 rad; the gap is not integrated, its uncertainty is.
  const PosePrior prior = dead_reckoning.PriorAt(5.01);
  EXPECT_LT(std::abs(prior.world_from_body.theta_rad), 0.05);
  EXPECT_GT(std::sqrt(prior.covariance(2, 2)), 1.0);
}

TEST(HumanDeadReckoning, ResetMovesTheEstimate) {
  HumanDeadReckoning dead_reckoning({}, StartAt(0.0, 0.0, 0.0));
  dead_reckoning.Reset(StartAt(5.0, -1.0, 90.0 * kDeg));
  dead_reckoning.Add(sensors::StrideSample{0.5, 1.0});
  const PosePrior prior = dead_reckoning.PriorAt(0.5);
  EXPECT_NEAR(prior.world_from_body.x_m, 5.0, 1e-9);
  EXPECT_NEAR(prior.world_from_body.y_m, 0.0, 1e-9);
}

TEST(HumanDeadReckoning, LearnsTheStrideScaleFromPositionFixes) {
  HumanDeadReckoningOptions options;
  options.stride_calibration.enabled = true;
  HumanDeadReckoning dead_reckoning(options, StartAt(0.0, 0.0, 0.0));
  // The sensor reads 0.6 m for strides of 0.63 m (5 % short); fixes every stride, all matched.
  for (int i = 1; i <= 40; ++i) {
    for (int tick = 1; tick <= 50; ++tick) dead_reckoning.Add(sensors::GyroSample{(i - 1) * 0.5 + tick * 0.01, 0.0});
    dead_reckoning.Add(sensors::StrideSample{i * 0.5, 0.6});
    dead_reckoning.AddPositionFix(i * 0.5, {0.63 * i, 0.0}, true);
  }
  // Nine samples of four strides (2.4 m raw, the first fix only anchors) against the prior 1 of
  // weight 8 m^2: (1.05 * 9 * 2.4^2 + 8) / (9 * 2.4^2 + 8), most of the way to 1.05.
  const double walk_m2 = 9 * 2.4 * 2.4;
  EXPECT_NEAR(dead_reckoning.stride_scale(), (1.05 * walk_m2 + 8.0) / (walk_m2 + 8.0), 1e-9);
  EXPECT_GT(dead_reckoning.stride_scale(), 1.04);
  const double before = dead_reckoning.PriorAt(20.0).world_from_body.x_m;
  dead_reckoning.Add(sensors::StrideSample{20.5, 0.6});
  EXPECT_NEAR(dead_reckoning.PriorAt(20.5).world_from_body.x_m - before,
              0.6 * dead_reckoning.stride_scale(), 1e-9);
}

TEST(HumanDeadReckoning, BrokenFixesAndTheDefaultLeaveTheScaleAlone) {
  HumanDeadReckoningOptions options;
  options.stride_calibration.enabled = true;
  HumanDeadReckoning broken(options, StartAt(0.0, 0.0, 0.0));
  HumanDeadReckoning by_default({}, StartAt(0.0, 0.0, 0.0));
  for (int i = 1; i <= 40; ++i) {
    broken.Add(sensors::StrideSample{i * 0.5, 0.6});
    by_default.Add(sensors::StrideSample{i * 0.5, 0.6});
    // Every fix follows an unfixed stretch (a corridor): no 2 m stretch is fixed throughout.
    broken.AddPositionFix(i * 0.5, {0.8 * i, 0.0}, false);
    by_default.AddPositionFix(i * 0.5, {0.8 * i, 0.0}, true);
  }
  EXPECT_DOUBLE_EQ(broken.stride_scale(), 1.0);
  EXPECT_DOUBLE_EQ(by_default.stride_scale(), 1.0);
  StrideCalibrationOptions bad;
  bad.max_correction = 1.0;
  EXPECT_THROW(StrideCalibration{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace pena::dead_reckoning
