#include "pena/dead_reckoning/human_dead_reckoning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace pena::dead_reckoning {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

PosePrior StartAt(double x, double y, double theta) {
  PosePrior start;
  start.world_from_body = {x, y, theta};
  start.covariance = Eigen::Matrix3d::Identity() * 1e-4;
  return start;
}

// Walks a 10 m square counter-clockwise: 0.7 m strides at 2 Hz with 5% length noise, gyro at
// 100 Hz, compass at 10 Hz; 90 deg turns at 90 deg/s on the spot.
void WalkSquare(HumanDeadReckoning& dead_reckoning, std::mt19937& rng) {
  std::normal_distribution<double> stride_noise(0.0, 0.05);
  std::normal_distribution<double> compass_noise(0.0, 2.0 * kDeg);
  double t = 0.0;
  double heading = 0.0;
  for (int side = 0; side < 4; ++side) {
    for (int step = 0; step < 14; ++step) {  // 14 x 0.714 m = 10 m
      for (int tick = 0; tick < 50; ++tick) {
        t += 0.01;
        dead_reckoning.Add(sensors::GyroSample{t, 0.0});
        if (tick % 10 == 0) dead_reckoning.Add(sensors::CompassSample{t, heading + compass_noise(rng)});
      }
      dead_reckoning.Add(sensors::StrideSample{t, (10.0 / 14.0) * (1.0 + stride_noise(rng))});
    }
    for (int tick = 0; tick < 100; ++tick) {
      t += 0.01;
      heading += 0.5 * std::numbers::pi * 0.01;
      dead_reckoning.Add(sensors::GyroSample{t, 0.5 * std::numbers::pi});
    }
  }
}

TEST(HumanDeadReckoning, ClosesASquareWithinStrideError) {
  std::mt19937 rng(3);
  HumanDeadReckoning dead_reckoning({}, StartAt(0.0, 0.0, 0.0));
  WalkSquare(dead_reckoning, rng);
  const PosePrior end = dead_reckoning.PriorAt(100.0);
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

}  // namespace
}  // namespace pena::dead_reckoning
