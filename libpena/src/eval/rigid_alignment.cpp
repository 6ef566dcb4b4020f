#include "pena/eval/rigid_alignment.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::eval {

geometry::Pose2 AlignRigid2D(const std::vector<Eigen::Vector2d>& source_points_m,
                             const std::vector<Eigen::Vector2d>& target_points_m) {
  if (source_points_m.size() != target_points_m.size()) {
    throw std::invalid_argument("rigid alignment needs matched point sets, got " +
                                std::to_string(source_points_m.size()) + " and " +
                                std::to_string(target_points_m.size()) + " points");
  }
  if (source_points_m.size() < 2) {
    throw std::invalid_argument("rigid alignment needs at least 2 matched points, got " +
                                std::to_string(source_points_m.size()));
  }
  const double n = static_cast<double>(source_points_m.size());
  Eigen::Vector2d source_mean = Eigen::Vector2d::Zero();
  Eigen::Vector2d target_mean = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < source_points_m.size(); ++i) {
    source_mean += source_points_m[i] / n;
    target_mean += target_points_m[i] / n;
  }
  // In 2D the SVD of the cross-covariance reduces to one angle: the rotation maximising
  // sum target_i . R source_i is atan2(sum cross, sum dot) of the centred points.
  double sum_dot = 0.0;
  double sum_cross = 0.0;
  for (std::size_t i = 0; i < source_points_m.size(); ++i) {
    const Eigen::Vector2d a = source_points_m[i] - source_mean;
    const Eigen::Vector2d b = target_points_m[i] - target_mean;
    sum_dot += a.dot(b);
    sum_cross += a.x() * b.y() - a.y() * b.x();
  }
  const double theta_rad = std::atan2(sum_cross, sum_dot);
  const double c = std::cos(theta_rad);
  const double s = std::sin(theta_rad);
  const Eigen::Vector2d rotated_mean(c * source_mean.x() - s * source_mean.y(),
                                     s * source_mean.x() + c * source_mean.y());
  const Eigen::Vector2d translation = target_mean - rotated_mean;
  return {translation.x(), translation.y(), geometry::NormalizeAngle(theta_rad)};
}

}  // namespace pena::eval
