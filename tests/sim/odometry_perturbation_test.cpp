#include "pena/sim/odometry_perturbation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pena::sim {
namespace {

// A straight drive along x, one pose every 5 cm, then a quarter turn on the spot.
std::vector<geometry::Pose2> StraightThenTurn(double length_m) {
  std::vector<geometry::Pose2> poses;
  for (double x = 0.0; x <= length_m + 1e-9; x += 0.05) poses.push_back({x, 0.0, 0.0});
  for (int k = 1; k <= 45; ++k) poses.push_back({length_m, 0.0, k * std::numbers::pi / 90.0});
  return poses;
}

TEST(OdometryPerturbation, WithoutNoiseTheOdometryIsUnchanged) {
  OdometryNoiseModel quiet;
  quiet.distance_scale_sd = quiet.turn_scale_sd = quiet.heading_walk_rad_per_sqrt_m = 0.0;
  quiet.slips_per_m = 0.0;
  OdometryPerturber perturber(quiet, 7);
  for (const geometry::Pose2& pose : StraightThenTurn(20.0)) {
    const geometry::Pose2 out = perturber.Perturb(pose);
    EXPECT_NEAR(out.x_m, pose.x_m, 1e-9);
    EXPECT_NEAR(out.y_m, pose.y_m, 1e-9);
    EXPECT_NEAR(geometry::NormalizeAngle(out.theta_rad - pose.theta_rad), 0.0, 1e-9);
  }
}

TEST(OdometryPerturbation, ScaleErrorsStretchDistanceAndTurns) {
  OdometryNoiseModel scale_only;
  scale_only.heading_walk_rad_per_sqrt_m = 0.0;
  scale_only.slips_per_m = 0.0;
  OdometryPerturber perturber(scale_only, 3);
  geometry::Pose2 last;
  for (const geometry::Pose2& pose : StraightThenTurn(20.0)) last = perturber.Perturb(pose);
  EXPECT_NEAR(last.x_m, 20.0 * perturber.distance_scale(), 1e-6);
  EXPECT_NEAR(last.theta_rad, 0.5 * std::numbers::pi * perturber.turn_scale(), 1e-6);
  EXPECT_NE(perturber.distance_scale(), 1.0);
}

TEST(OdometryPerturbation, SlipsTurnTheHeadingAtOnceWithinTheModelsRange) {
  OdometryNoiseModel slips_only;
  slips_only.distance_scale_sd = slips_only.turn_scale_sd = 0.0;
  slips_only.heading_walk_rad_per_sqrt_m = 0.0;
  slips_only.slips_per_m = 0.05;  // about ten over 200 m
  OdometryPerturber perturber(slips_only, 11);
  geometry::Pose2 previous = perturber.Perturb({0.0, 0.0, 0.0});
  int jumps = 0;
  for (int k = 1; k <= 4000; ++k) {
    const geometry::Pose2 out = perturber.Perturb({0.05 * k, 0.0, 0.0});
    const double turn_rad = std::abs(geometry::NormalizeAngle(out.theta_rad - previous.theta_rad));
    if (turn_rad > 1e-9) {
      ++jumps;
      EXPECT_GE(turn_rad, slips_only.slip_min_rad - 1e-9);
      EXPECT_LE(turn_rad, slips_only.slip_max_rad + 1e-9);
    }
    previous = out;
  }
  EXPECT_EQ(jumps, perturber.slips());
  EXPECT_GE(jumps, 3);
  EXPECT_LE(jumps, 25);
}

TEST(OdometryPerturbation, TheSameSeedGivesTheSameOdometry) {
  OdometryPerturber a(OdometryNoiseModel{}, 42), b(OdometryNoiseModel{}, 42), c(OdometryNoiseModel{}, 43);
  bool differs = false;
  for (const geometry::Pose2& pose : StraightThenTurn(50.0)) {
    const geometry::Pose2 pa = a.Perturb(pose), pb = b.Perturb(pose), pc = c.Perturb(pose);
    EXPECT_EQ(pa.x_m, pb.x_m);
    EXPECT_EQ(pa.theta_rad, pb.theta_rad);
    differs = differs || pa.x_m != pc.x_m;
  }
  EXPECT_TRUE(differs);
}

TEST(OdometryPerturbation, AnUnusableModelIsRefusedNamingTheField) {
  OdometryNoiseModel bad;
  bad.slips_per_m = -1.0;
  try {
    OdometryPerturber perturber(bad, 1);
    FAIL() << "a negative slip rate was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("odometry_noise.slips_per_m"), std::string::npos);
  }
  bad = {};
  bad.slip_max_rad = std::nan("");
  EXPECT_THROW(OdometryPerturber(bad, 1), std::invalid_argument);
}

}  // namespace
}  // namespace pena::sim
