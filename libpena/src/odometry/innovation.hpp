#pragma once
// A wheel-odometry match seen as an observation of the pose the odometry predicts: its
// innovation (prior -> match, in the prior's frame) against the odometry's noise model since the
// keyframe the prior is anchored at (PoseCovarianceOptions::motion_*) plus the match's own
// covariance. The squared Mahalanobis distance (NEES) is chi-square with 3 degrees of freedom
// when both covariances are honest (mean 3, median 2.37): its distribution over a log measures
// how far they are from that.

#include <Eigen/Core>

#include "pena/geometry/pose2.hpp"
#include "pena/odometry/pose_covariance_options.hpp"

namespace pena::odometry::internal {

// One match seen from its prior.
struct Innovation {
  Eigen::Vector3d deviation_m_rad = Eigen::Vector3d::Zero();  // prior^-1 * match (x, y, theta)
  Eigen::Matrix3d prior_covariance = Eigen::Matrix3d::Zero();  // the odometry's since the keyframe
  Eigen::Matrix3d match_covariance = Eigen::Matrix3d::Zero();  // the match's, in the prior's frame
  double nees = 0.0;  // deviation^T (prior + match covariance)^-1 deviation
};

// The innovation of `match` against `prior`; `motion_since_keyframe` is the odometry's motion
// since the keyframe the prior is anchored at, `match_covariance_world` the match's covariance
// (world frame).
Innovation ComputeInnovation(const geometry::Pose2& prior, const geometry::Pose2& match,
                             const geometry::Pose2& motion_since_keyframe,
                             const Eigen::Matrix3d& match_covariance_world,
                             const PoseCovarianceOptions& noise);

}  // namespace pena::odometry::internal
