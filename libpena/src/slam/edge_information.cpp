#include "edge_information.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace pena::slam::internal {

Eigen::Matrix3d IsotropicInformation(double sigma_m, double sigma_rad) {
  return Eigen::Vector3d(1.0 / (sigma_m * sigma_m), 1.0 / (sigma_m * sigma_m),
                         1.0 / (sigma_rad * sigma_rad))
      .asDiagonal();
}

Eigen::Matrix3d ClosureInformation(const LoopMatch& match, const SlamOptions& options) {
  Eigen::Matrix3d information = IsotropicInformation(options.loop_sigma_m, options.loop_sigma_rad);
  if (options.loop_weak_sigma_max_m <= 0.0) return information;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(match.information.block<2, 2>(0, 0));
  const Eigen::Vector2d lambda = solver.eigenvalues();  // ascending
  if (!(lambda.y() > 0.0)) return information;          // nothing measured: the plain closure
  const double weak_sigma_m =
      lambda.x() > 0.0 ? std::min(options.loop_weak_sigma_max_m,
                                  options.loop_sigma_m * std::sqrt(lambda.y() / lambda.x()))
                       : options.loop_weak_sigma_max_m;
  const Eigen::Matrix2d& axes = solver.eigenvectors();
  const Eigen::Vector2d inverse_variances(1.0 / (weak_sigma_m * weak_sigma_m),
                                          1.0 / (options.loop_sigma_m * options.loop_sigma_m));
  const Eigen::Matrix2d centre_frame = axes * inverse_variances.asDiagonal() * axes.transpose();
  // EdgeError's position error is R(measured theta)^T times the centre-frame one.
  const double c = std::cos(match.centre_from_scan.theta_rad);
  const double s = std::sin(match.centre_from_scan.theta_rad);
  const Eigen::Matrix2d rotation = (Eigen::Matrix2d() << c, -s, s, c).finished();
  information.block<2, 2>(0, 0) = rotation.transpose() * centre_frame * rotation;
  return information;
}

}  // namespace pena::slam::internal
