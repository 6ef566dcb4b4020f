#include "pose_covariance.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace pena::odometry::internal {

Eigen::Matrix3d CarryCovariance(const Eigen::Matrix3d& from_covariance, const geometry::Pose2& from,
                                const geometry::Pose2& to) {
  // to = from (+) step with the step fixed: d to / d from.
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Identity();
  jacobian(0, 2) = -(to.y_m - from.y_m);
  jacobian(1, 2) = to.x_m - from.x_m;
  return jacobian * from_covariance * jacobian.transpose();
}

Eigen::Matrix3d MotionCovariance(const geometry::Pose2& step, const PoseCovarianceOptions& o) {
  const double moved_m = std::hypot(step.x_m, step.y_m);
  const double turned_rad = std::abs(geometry::NormalizeAngle(step.theta_rad));
  const double xy_m2 = o.motion_m_per_sqrt_m * o.motion_m_per_sqrt_m * moved_m;
  const double theta_rad2 = o.motion_rad_per_sqrt_m * o.motion_rad_per_sqrt_m * moved_m +
                            o.motion_rad_per_sqrt_rad * o.motion_rad_per_sqrt_rad * turned_rad;
  return Eigen::Vector3d(xy_m2, xy_m2, theta_rad2).asDiagonal();
}

Eigen::Matrix3d MatchCovariance(const Eigen::Matrix3d& information, double window_half_m,
                                double window_half_rad, const PoseCovarianceOptions& o) {
  const Eigen::Matrix3d floor =
      Eigen::Vector3d(o.match_min_sd_m * o.match_min_sd_m, o.match_min_sd_m * o.match_min_sd_m,
                      o.match_min_sd_rad * o.match_min_sd_rad)
          .asDiagonal();
  // The search window bounds the match where J^T J says little (a corridor's axis, a scan with
  // few points): its half extents enter as prior information, so the inverse always exists.
  const Eigen::Matrix3d window_information =
      Eigen::Vector3d(1.0 / (window_half_m * window_half_m), 1.0 / (window_half_m * window_half_m),
                      1.0 / (window_half_rad * window_half_rad))
          .asDiagonal();
  const double residual_m2 = o.match_residual_sd_m * o.match_residual_sd_m;
  const Eigen::Matrix3d total = information / residual_m2 + window_information;
  return total.ldlt().solve(Eigen::Matrix3d::Identity()) + floor;
}

Eigen::Matrix3d WithVarianceAlong(const Eigen::Matrix3d& covariance, const Eigen::Vector2d& weak,
                                  double variance_m2) {
  Eigen::Matrix3d out = covariance;
  const Eigen::Matrix2d block = covariance.topLeftCorner<2, 2>();
  const Eigen::Vector2d across(-weak.y(), weak.x());
  // Re-express the block in (weak, across) coordinates, set the weak variance, drop its cross
  // terms (the prior's component is independent of the match), and rotate back.
  Eigen::Matrix2d basis;
  basis.col(0) = weak;
  basis.col(1) = across;
  Eigen::Matrix2d local = basis.transpose() * block * basis;
  local(0, 0) = variance_m2;
  local(0, 1) = local(1, 0) = 0.0;
  out.topLeftCorner<2, 2>() = basis * local * basis.transpose();
  const Eigen::Vector2d heading_cross = basis.transpose() * covariance.block<2, 1>(0, 2);
  const Eigen::Vector2d kept = basis * Eigen::Vector2d(0.0, heading_cross.y());
  out.block<2, 1>(0, 2) = kept;
  out.block<1, 2>(2, 0) = kept.transpose();
  return out;
}

Eigen::Matrix3d WeakDisagreementCovariance(const Eigen::Matrix3d& information,
                                           const geometry::Pose2& match,
                                           const geometry::Pose2& prior,
                                           const PoseCovarianceOptions& o) {
  Eigen::Matrix3d out = Eigen::Matrix3d::Zero();
  if (o.weak_disagreement_share <= 0.0) return out;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information.topLeftCorner<2, 2>());
  const double weak = solver.eigenvalues()(0);
  const double strong = solver.eigenvalues()(1);
  if (!(strong > 0.0) || weak >= o.weak_ratio * strong) return out;
  const Eigen::Vector2d direction = solver.eigenvectors().col(0);
  const double along_m =
      direction.dot(Eigen::Vector2d(match.x_m - prior.x_m, match.y_m - prior.y_m));
  out.topLeftCorner<2, 2>() =
      o.weak_disagreement_share * along_m * along_m * direction * direction.transpose();
  return out;
}

Eigen::Matrix3d DisagreementCovariance(const geometry::Pose2& a, const geometry::Pose2& b) {
  const Eigen::Vector3d d(a.x_m - b.x_m, a.y_m - b.y_m,
                          geometry::NormalizeAngle(a.theta_rad - b.theta_rad));
  return d * d.transpose();
}

}  // namespace pena::odometry::internal
