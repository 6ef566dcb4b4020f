#pragma once
// Planar rigid transforms. A Pose2 named `a_from_b` maps points from frame b into frame a.

#include <Eigen/Core>

namespace pena::geometry {

// A planar pose or rigid transform: translation in metres, heading in radians (CCW from +x).
struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_rad = 0.0;
};

// Wraps an angle into [-pi, pi).
double NormalizeAngle(double angle_rad);

// a_from_c = a_from_b * b_from_c.
Pose2 Compose(const Pose2& a_from_b, const Pose2& b_from_c);

// b_from_a from a_from_b.
Pose2 Inverse(const Pose2& a_from_b);

// The motion from `a` to `b`, both in one frame: Inverse(a) * b (the Freiburg relation).
Pose2 Between(const Pose2& world_from_a, const Pose2& world_from_b);

// Maps a point given in frame b into frame a.
Eigen::Vector2d TransformPoint(const Pose2& a_from_b, const Eigen::Vector2d& point_b);

// TransformPoint for many points under one pose: the heading's cosine and sine are taken once
// (scan matching maps every point of a scan under every candidate heading). Same values.
class PointTransform {
 public:
  explicit PointTransform(const Pose2& a_from_b);
  Eigen::Vector2d operator()(const Eigen::Vector2d& point_b) const {
    return {x_m_ + c_ * point_b.x() - s_ * point_b.y(), y_m_ + s_ * point_b.x() + c_ * point_b.y()};
  }

 private:
  double c_, s_, x_m_, y_m_;
};

// Linear interpolation of translation and shortest-arc interpolation of heading; fraction in [0, 1].
Pose2 Interpolate(const Pose2& from, const Pose2& to, double fraction);

}  // namespace pena::geometry
