#pragma once
// The pieces of the laser odometry's pose covariance (PoseCovarianceOptions): pure functions of
// poses, J^T J and options. Covariances are of (x_m, y_m, theta_rad) in the world frame.

#include <Eigen/Core>

#include "pena/geometry/pose2.hpp"
#include "pena/odometry/pose_covariance_options.hpp"

namespace pena::odometry::internal {

// The covariance of a pose `from` (covariance `from_covariance`) carried rigidly to `to`: its
// heading uncertainty moves `to` across the lever arm between them.
Eigen::Matrix3d CarryCovariance(const Eigen::Matrix3d& from_covariance, const geometry::Pose2& from,
                                const geometry::Pose2& to);

// The motion prior's drift over `step` (the keyframe to the scan).
Eigen::Matrix3d MotionCovariance(const geometry::Pose2& step, const PoseCovarianceOptions& options);

// A match's covariance from its J^T J (world frame) and the window it was searched in (half
// extents, metres and radians: the match cannot be farther off), floored.
Eigen::Matrix3d MatchCovariance(const Eigen::Matrix3d& information, double window_half_m,
                                double window_half_rad, const PoseCovarianceOptions& options);

// `covariance` with its variance along the unit direction `weak` (x-y block) replaced by
// `variance_m2` and its cross terms with it dropped: a degenerate match takes that component from
// the prior.
Eigen::Matrix3d WithVarianceAlong(const Eigen::Matrix3d& covariance, const Eigen::Vector2d& weak,
                                  double variance_m2);

// Along the weakest x-y direction of `information`, when its eigenvalue is below weak_ratio times
// the strongest: weak_disagreement_share of the squared disagreement (match minus prior) along it.
// Zero otherwise.
Eigen::Matrix3d WeakDisagreementCovariance(const Eigen::Matrix3d& information,
                                           const geometry::Pose2& match,
                                           const geometry::Pose2& prior,
                                           const PoseCovarianceOptions& options);

// The outer product of the difference between two poses: where the match and the motion prior
// disagree, either may be wrong by that much.
Eigen::Matrix3d DisagreementCovariance(const geometry::Pose2& a, const geometry::Pose2& b);

}  // namespace pena::odometry::internal
