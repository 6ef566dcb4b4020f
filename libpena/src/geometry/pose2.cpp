#include "pena/geometry/pose2.hpp"

#include <cmath>
#include <numbers>

namespace pena::geometry {

double NormalizeAngle(double angle_rad) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  double wrapped = std::fmod(angle_rad + std::numbers::pi, kTwoPi);
  if (wrapped < 0.0) wrapped += kTwoPi;
  return wrapped - std::numbers::pi;
}

Pose2 Compose(const Pose2& a_from_b, const Pose2& b_from_c) {
  const double c = std::cos(a_from_b.theta_rad);
  const double s = std::sin(a_from_b.theta_rad);
  return {a_from_b.x_m + c * b_from_c.x_m - s * b_from_c.y_m,
          a_from_b.y_m + s * b_from_c.x_m + c * b_from_c.y_m,
          NormalizeAngle(a_from_b.theta_rad + b_from_c.theta_rad)};
}

Pose2 Inverse(const Pose2& a_from_b) {
  const double c = std::cos(a_from_b.theta_rad);
  const double s = std::sin(a_from_b.theta_rad);
  return {-c * a_from_b.x_m - s * a_from_b.y_m, s * a_from_b.x_m - c * a_from_b.y_m,
          NormalizeAngle(-a_from_b.theta_rad)};
}

Pose2 Between(const Pose2& world_from_a, const Pose2& world_from_b) {
  return Compose(Inverse(world_from_a), world_from_b);
}

Eigen::Vector2d TransformPoint(const Pose2& a_from_b, const Eigen::Vector2d& point_b) {
  return PointTransform(a_from_b)(point_b);
}

PointTransform::PointTransform(const Pose2& a_from_b)
    : c_(std::cos(a_from_b.theta_rad)),
      s_(std::sin(a_from_b.theta_rad)),
      x_m_(a_from_b.x_m),
      y_m_(a_from_b.y_m) {}

Pose2 Interpolate(const Pose2& from, const Pose2& to, double fraction) {
  const double dtheta = NormalizeAngle(to.theta_rad - from.theta_rad);
  return {from.x_m + fraction * (to.x_m - from.x_m), from.y_m + fraction * (to.y_m - from.y_m),
          NormalizeAngle(from.theta_rad + fraction * dtheta)};
}

}  // namespace pena::geometry
