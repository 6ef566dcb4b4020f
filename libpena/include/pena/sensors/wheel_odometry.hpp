#pragma once
// Wheel odometry of a robot entity.

#include "pena/geometry/pose2.hpp"

namespace pena::sensors {

// Integrated odometry pose (odom frame) with the velocities the platform reported.
struct WheelOdometry {
  double stamp_s = 0.0;
  geometry::Pose2 odom_pose;
  double forward_velocity_m_s = 0.0;
  double yaw_rate_rad_s = 0.0;
};

}  // namespace pena::sensors
