#include "innovation.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "pose_covariance.hpp"

namespace pena::odometry::internal {

Innovation ComputeInnovation(const geometry::Pose2& prior, const geometry::Pose2& match,
                             const geometry::Pose2& motion_since_keyframe,
                             const Eigen::Matrix3d& match_covariance_world,
                             const PoseCovarianceOptions& noise) {
  Innovation out;
  const geometry::Pose2 deviation = geometry::Between(prior, match);
  out.deviation_m_rad = {deviation.x_m, deviation.y_m, geometry::NormalizeAngle(deviation.theta_rad)};
  // The noise model is isotropic in x and y, so it reads the same in the prior's frame.
  out.prior_covariance = MotionCovariance(motion_since_keyframe, noise);
  Eigen::Matrix3d world_to_prior = Eigen::Matrix3d::Identity();
  const double c = std::cos(prior.theta_rad), s = std::sin(prior.theta_rad);
  world_to_prior.topLeftCorner<2, 2>() << c, s, -s, c;
  out.match_covariance = world_to_prior * match_covariance_world * world_to_prior.transpose();
  const Eigen::Matrix3d total = out.prior_covariance + out.match_covariance;
  out.nees = out.deviation_m_rad.dot(total.ldlt().solve(out.deviation_m_rad));
  return out;
}

}  // namespace pena::odometry::internal
