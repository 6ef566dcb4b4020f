#include "pena/sim/sensor_models.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim_test_util.hpp"

namespace pena::sim {
namespace {

using testing::kDeg;

TEST(StrideModel, StepLengthErrorIsAboutFivePercent) {
  double sum_sq = 0.0;
  int count = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    StrideModel stride({}, Random(seed));
    EXPECT_LE(std::abs(stride.scale_error()), StrideOptions{}.max_scale_error);
    for (int step = 0; step < 500; ++step) {
      const double error = stride.Measure(step, 0.55).length_m / 0.55 - 1.0;
      sum_sq += error * error;
      ++count;
    }
  }
  const double rms = std::sqrt(sum_sq / count);
  EXPECT_GT(rms, 0.04);
  EXPECT_LT(rms, 0.08);
}

TEST(GyroModel, NoiseMatchesAndTheBiasDrifts) {
  GyroOptions options;
  options.bias_walk_rad_s_per_sqrt_s = 0.002;
  GyroModel gyro(options, Random(4));
  const double bias_at_start = gyro.bias_rad_s();
  TrueState still;
  double sum = 0.0, sum_sq = 0.0;
  const int n = 60000;  // 10 minutes at 100 Hz
  for (int i = 0; i < n; ++i) {
    still.stamp_s = i * 0.01;
    const double reading = gyro.Measure(still, 0.01).yaw_rate_rad_s - gyro.bias_rad_s();
    sum += reading;
    sum_sq += reading * reading;
  }
  EXPECT_NEAR(std::sqrt(sum_sq / n - std::pow(sum / n, 2)), options.noise_sd_rad_s, 2e-4);
  // A random walk of 0.002 rad/s/sqrt(s) over 600 s has sd 0.049 rad/s; it does not stay put.
  EXPECT_GT(std::abs(gyro.bias_rad_s() - bias_at_start), 0.002);
}

TEST(CompassModel, DisturbanceIsPeakAtTheCentreAndFadesToZero) {
  const MagneticDisturbance steel{{10.0, 5.0}, 2.0, 0.5};
  CompassModel compass({}, {steel}, Random(1));
  EXPECT_NEAR(compass.DisturbanceAt({10.0, 5.0}), 0.5, 1e-12);
  EXPECT_NEAR(compass.DisturbanceAt({11.0, 5.0}), 0.25, 1e-12);
  EXPECT_EQ(compass.DisturbanceAt({12.5, 5.0}), 0.0);
  CompassOptions exact;
  exact.noise_sd_rad = 0.0;
  CompassModel noiseless(exact, {steel}, Random(1));
  TrueState state;
  state.world_from_body = {10.0, 5.0, 1.0};
  EXPECT_NEAR(noiseless.Measure(state).heading_rad, 1.5, 1e-12);
}

TEST(LaserNoiseModel, DropsAboutOnePercentWithCentimetreNoise) {
  LaserNoiseModel laser({}, Random(2));
  BeamHit hit;
  hit.kind = HitKind::kWall;
  hit.range_m = 5.0;
  int dropped = 0;
  double sum_sq = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const float range = laser.Measure(hit, 30.0);
    if (std::isinf(range)) {
      ++dropped;
    } else {
      sum_sq += (range - 5.0) * (range - 5.0);
    }
  }
  EXPECT_NEAR(static_cast<double>(dropped) / n, 0.01, 0.002);
  EXPECT_NEAR(std::sqrt(sum_sq / (n - dropped)), 0.01, 0.001);
}

TEST(LaserNoiseModel, SmokeCutsTheRangeToAFewMetres) {
  const std::vector<SmokeZone> smoke = {{{{0.0, 0.0}, {10.0, 10.0}}, 3.0}};
  EXPECT_EQ(SmokeMaxRange(smoke, {5.0, 5.0}, 30.0), 3.0);
  EXPECT_EQ(SmokeMaxRange(smoke, {15.0, 5.0}, 30.0), 30.0);
  LaserNoiseModel laser({0.0, 0.0}, Random(1));
  BeamHit hit;
  hit.kind = HitKind::kWall;
  hit.range_m = 5.0;
  EXPECT_TRUE(std::isinf(laser.Measure(hit, 3.0)));
  hit.range_m = 2.5;
  EXPECT_FLOAT_EQ(laser.Measure(hit, 3.0), 2.5f);
}

TEST(WheelOdometryModel, ScaleErrorShowsInTheDrivenDistance) {
  WheelOdometryOptions options;
  options.slip_rate_per_s = 0.0;
  WheelOdometryModel odometry(options, Random(9));
  TrueState state;
  state.forward_velocity_m_s = 0.5;
  state.speed_m_s = 0.5;
  for (int i = 1; i <= 2000; ++i) {  // 20 s straight at 0.5 m/s: 10 m
    state.stamp_s = i * 0.01;
    odometry.Advance(state, 0.01);
  }
  const geometry::Pose2 pose = odometry.Current().odom_pose;
  const double distance = std::hypot(pose.x_m, pose.y_m);
  EXPECT_NEAR(distance, 10.0, 1.0);
  EXPECT_GT(std::abs(distance - 10.0), 1e-3);
  EXPECT_EQ(odometry.Current().stamp_s, state.stamp_s);
}

TEST(SensorModels, RejectNegativeNoise) {
  GyroOptions gyro;
  gyro.noise_sd_rad_s = -1.0;
  EXPECT_THROW(GyroModel(gyro, Random(1)), std::invalid_argument);
  LaserNoiseOptions laser;
  laser.dropout_probability = 2.0;
  EXPECT_THROW(LaserNoiseModel(laser, Random(1)), std::invalid_argument);
}

}  // namespace
}  // namespace pena::sim
