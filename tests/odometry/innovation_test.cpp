// A wheel-odometry match as an observation of the odometry's prediction (odometry::internal
// innovation.hpp): its NEES under the odometry's noise model plus the match's covariance.
#include "pena/odometry/internal/innovation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"
#include "team_entity.hpp"

namespace pena::odometry::internal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Matrix3d MatchCovariance(double sd_m, double sd_rad) {
  return Eigen::Vector3d(sd_m * sd_m, sd_m * sd_m, sd_rad * sd_rad).asDiagonal();
}

TEST(Innovation, NeesIsTheSquaredMahalanobisDistanceUnderTheNoiseModel) {
  PoseCovarianceOptions noise;
  const geometry::Pose2 moved{4.0, 0.0, 90.0 * kDeg};  // since the keyframe
  const geometry::Pose2 prior{1.0, 2.0, 30.0 * kDeg};
  const geometry::Pose2 match = geometry::Compose(prior, geometry::Pose2{0.1, 0.0, 2.0 * kDeg});
  const Innovation innovation =
      ComputeInnovation(prior, match, moved, MatchCovariance(0.02, 0.005), noise);
  EXPECT_NEAR(innovation.deviation_m_rad.x(), 0.1, 1e-12);
  EXPECT_NEAR(innovation.deviation_m_rad.z(), 2.0 * kDeg, 1e-12);
  const double var_xy = noise.motion_m_per_sqrt_m * noise.motion_m_per_sqrt_m * 4.0 + 0.02 * 0.02;
  const double var_theta = noise.motion_rad_per_sqrt_m * noise.motion_rad_per_sqrt_m * 4.0 +
                           noise.motion_rad_per_sqrt_rad * noise.motion_rad_per_sqrt_rad * 0.5 *
                               std::numbers::pi +
                           0.005 * 0.005;
  EXPECT_NEAR(innovation.nees, 0.01 / var_xy + std::pow(2.0 * kDeg, 2) / var_theta, 1e-9);
}

TEST(Innovation, TheMatchCovarianceIsTurnedIntoThePriorsFrame) {
  PoseCovarianceOptions noise;
  // A match uncertain along the world's x axis only; the prior faces along world y.
  Eigen::Matrix3d covariance = MatchCovariance(0.001, 0.001);
  covariance(0, 0) = 0.25;
  const geometry::Pose2 prior{0.0, 0.0, 90.0 * kDeg};
  const Innovation innovation = ComputeInnovation(prior, prior, {}, covariance, noise);
  EXPECT_NEAR(innovation.match_covariance(1, 1), 0.25, 1e-12);  // the prior's y is the world's -x
  EXPECT_NEAR(innovation.match_covariance(0, 0), 1e-6, 1e-12);
}

// The whole chain on the simulated team robot (wheel odometry with scale errors and slips): every
// match gets its NEES, people's scans none.
TEST(Innovation, TheChainReportsTheNeesOfEveryRobotMatch) {
  const sim::EntityRecording& robot = testing::TeamEntity("robot1");
  std::vector<double> nees;
  for (const OdometryEstimate& e : testing::ReplayRecords(robot, robot.records, {})) {
    if (e.status == MatchStatus::kMatched) nees.push_back(e.innovation_nees);
  }
  ASSERT_GT(nees.size(), 100u);
  const auto computed = std::count_if(nees.begin(), nees.end(), [](double n) { return n > 0.0; });
  EXPECT_GT(static_cast<double>(computed), 0.9 * static_cast<double>(nees.size()));
  const sim::EntityRecording& person = testing::TeamEntity("ff1");
  for (const OdometryEstimate& e : testing::ReplayRecords(person, person.records, {})) {
    EXPECT_EQ(e.innovation_nees, 0.0);
  }
}

}  // namespace
}  // namespace pena::odometry::internal
