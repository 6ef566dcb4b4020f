// The pieces of the laser odometry's pose covariance (odometry::internal, pose_covariance.hpp):
// exact values on small cases.
#include "pena/odometry/internal/pose_covariance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pena::odometry::internal {
namespace {

constexpr double kTight = 1e-12;

TEST(PoseCovariance, HeadingUncertaintyMovesAPoseAcrossTheLeverArm) {
  const double sd_rad = 0.01;
  const Eigen::Matrix3d heading_only = Eigen::Vector3d(0.0, 0.0, sd_rad * sd_rad).asDiagonal();
  // 2 m ahead along x: a heading error swings the pose along y by 2 m per radian.
  const Eigen::Matrix3d carried = CarryCovariance(heading_only, {0.0, 0.0, 0.0}, {2.0, 0.0, 0.3});
  EXPECT_NEAR(carried(0, 0), 0.0, kTight);
  EXPECT_NEAR(carried(1, 1), 4.0 * sd_rad * sd_rad, kTight);
  EXPECT_NEAR(carried(1, 2), 2.0 * sd_rad * sd_rad, kTight);
  EXPECT_NEAR(carried(2, 2), sd_rad * sd_rad, kTight);
  EXPECT_NEAR(carried(0, 1), 0.0, kTight);
}

TEST(PoseCovariance, PositionUncertaintyCarriesUnchanged) {
  Eigen::Matrix3d position_only = Eigen::Matrix3d::Zero();
  position_only(0, 0) = 0.04;
  position_only(1, 1) = 0.09;
  position_only(0, 1) = position_only(1, 0) = 0.01;
  EXPECT_TRUE(CarryCovariance(position_only, {1.0, 2.0, 0.5}, {-3.0, 7.0, -1.0})
                  .isApprox(position_only, kTight));
}

TEST(PoseCovariance, MotionDriftGrowsWithDistanceAndTurn) {
  PoseCovarianceOptions options;
  options.motion_m_per_sqrt_m = 0.05;
  options.motion_rad_per_sqrt_m = 0.01;
  options.motion_rad_per_sqrt_rad = 0.03;
  const Eigen::Matrix3d walked = MotionCovariance({3.0, 4.0, 0.0}, options);  // 5 m
  EXPECT_NEAR(walked(0, 0), 0.05 * 0.05 * 5.0, kTight);
  EXPECT_NEAR(walked(1, 1), 0.05 * 0.05 * 5.0, kTight);
  EXPECT_NEAR(walked(2, 2), 0.01 * 0.01 * 5.0, kTight);
  const Eigen::Matrix3d turned = MotionCovariance({0.0, 0.0, -std::numbers::pi / 2}, options);
  EXPECT_NEAR(turned(0, 0), 0.0, kTight);
  EXPECT_NEAR(turned(2, 2), 0.03 * 0.03 * std::numbers::pi / 2, kTight);
}

TEST(PoseCovariance, MatchWithoutInformationIsBoundedByItsWindow) {
  PoseCovarianceOptions options;
  options.match_min_sd_m = 0.01;
  options.match_min_sd_rad = 0.002;
  const Eigen::Matrix3d covariance = MatchCovariance(Eigen::Matrix3d::Zero(), 0.3, 0.05, options);
  EXPECT_NEAR(covariance(0, 0), 0.3 * 0.3 + 0.01 * 0.01, kTight);
  EXPECT_NEAR(covariance(1, 1), 0.3 * 0.3 + 0.01 * 0.01, kTight);
  EXPECT_NEAR(covariance(2, 2), 0.05 * 0.05 + 0.002 * 0.002, kTight);
  EXPECT_NEAR(covariance(0, 1), 0.0, kTight);
}

TEST(PoseCovariance, WellConstrainedMatchFollowsItsResiduals) {
  PoseCovarianceOptions options;
  options.match_residual_sd_m = 0.03;
  options.match_min_sd_m = 0.0;
  options.match_min_sd_rad = 0.0;
  // 400 point-to-line pairs half facing x, half facing y: J^T J = diag(200, 200, 400 * 4 m^2).
  const Eigen::Matrix3d information = Eigen::Vector3d(200.0, 200.0, 1600.0).asDiagonal();
  const Eigen::Matrix3d covariance = MatchCovariance(information, 1e6, 1e6, options);
  EXPECT_NEAR(covariance(0, 0), 0.03 * 0.03 / 200.0, 1e-10);
  EXPECT_NEAR(covariance(2, 2), 0.03 * 0.03 / 1600.0, 1e-10);
}

TEST(PoseCovariance, DegenerateDirectionTakesThePriorsVariance) {
  Eigen::Matrix3d covariance;
  covariance << 0.01, 0.002, 0.001,  //
      0.002, 0.02, 0.0005,           //
      0.001, 0.0005, 0.0004;
  const Eigen::Vector2d weak = Eigen::Vector2d(1.0, 1.0).normalized();
  const Eigen::Vector2d across(-weak.y(), weak.x());
  const Eigen::Matrix3d out = WithVarianceAlong(covariance, weak, 0.25);
  const Eigen::Matrix2d block = out.topLeftCorner<2, 2>();
  EXPECT_NEAR(weak.dot(block * weak), 0.25, kTight);
  EXPECT_NEAR(weak.dot(block * across), 0.0, kTight);
  EXPECT_NEAR(across.dot(block * across), across.dot(covariance.topLeftCorner<2, 2>() * across),
              kTight);
  // Heading stays; its correlation with the weak direction goes, that across it stays.
  EXPECT_NEAR(out(2, 2), covariance(2, 2), kTight);
  const Eigen::Vector2d heading_cross = out.block<2, 1>(0, 2);
  EXPECT_NEAR(weak.dot(heading_cross), 0.0, kTight);
  EXPECT_NEAR(across.dot(heading_cross), across.dot(covariance.block<2, 1>(0, 2)), kTight);
  EXPECT_TRUE(out.isApprox(out.transpose(), kTight));
}

TEST(PoseCovariance, WeakDirectionTakesTheDisagreementAlongIt) {
  PoseCovarianceOptions options;
  options.weak_ratio = 0.2;
  options.weak_disagreement_share = 1.0;
  // A corridor along x: the scan constrains y a hundred times better than x.
  const Eigen::Matrix3d corridor = Eigen::Vector3d(1.0, 100.0, 10.0).asDiagonal();
  const Eigen::Matrix3d along =
      WeakDisagreementCovariance(corridor, {0.3, 0.1, 0.0}, {0.0, 0.0, 0.0}, options);
  EXPECT_NEAR(along(0, 0), 0.09, kTight);  // 0.3 m along the corridor, squared
  EXPECT_NEAR(along(1, 1), 0.0, kTight);   // across it the match is trusted
  EXPECT_NEAR(along(2, 2), 0.0, kTight);
  options.weak_disagreement_share = 0.5;
  EXPECT_NEAR(WeakDisagreementCovariance(corridor, {0.3, 0.1, 0.0}, {}, options)(0, 0), 0.045,
              kTight);
  // A room constrains both directions alike: nothing is added.
  const Eigen::Matrix3d room = Eigen::Vector3d(50.0, 100.0, 10.0).asDiagonal();
  EXPECT_TRUE(WeakDisagreementCovariance(room, {0.3, 0.1, 0.0}, {}, options).isZero());
  options.weak_disagreement_share = 0.0;
  EXPECT_TRUE(WeakDisagreementCovariance(corridor, {0.3, 0.1, 0.0}, {}, options).isZero());
}

TEST(PoseCovariance, DisagreementWrapsTheHeading) {
  const double near_pi = std::numbers::pi - 0.01;
  const Eigen::Matrix3d d = DisagreementCovariance({1.0, 0.0, near_pi}, {0.0, 0.5, -near_pi});
  EXPECT_NEAR(d(0, 0), 1.0, kTight);
  EXPECT_NEAR(d(1, 1), 0.25, kTight);
  EXPECT_NEAR(d(0, 1), -0.5, kTight);
  EXPECT_NEAR(d(2, 2), 0.02 * 0.02, 1e-12);  // -0.02 rad, not 2 pi - 0.02
}

}  // namespace
}  // namespace pena::odometry::internal
