#include "frozen_odometry.hpp"

#include <cmath>

namespace pena::odometry::internal {

FrozenOdometry::FrozenOdometry(double min_turn_rad, double min_move_m)
    : min_turn_rad_(min_turn_rad), min_move_m_(min_move_m) {}

std::optional<geometry::Pose2> FrozenOdometry::Predict(
    const std::optional<geometry::Pose2>& sensor_pose, const geometry::Pose2& previous_estimate,
    const geometry::Pose2& velocity, bool burst) {
  const bool enabled = (min_turn_rad_ > 0.0 || min_move_m_ > 0.0) && !burst;
  // Exactly the same pose: a logger repeating its last odometry message, not a slow robot.
  const bool repeated = sensor_pose && last_sensor_pose_ &&
                        sensor_pose->x_m == last_sensor_pose_->x_m &&
                        sensor_pose->y_m == last_sensor_pose_->y_m &&
                        sensor_pose->theta_rad == last_sensor_pose_->theta_rad;
  last_sensor_pose_ = sensor_pose;
  if (!enabled || !repeated) {
    frozen_ = false;
  } else if (!frozen_) {
    // A robot that stops reports zero motion too: only a repeat while the scans moved counts.
    const double moved_m = std::hypot(velocity.x_m, velocity.y_m);
    const bool moving = (min_turn_rad_ > 0.0 && std::abs(velocity.theta_rad) >= min_turn_rad_) ||
                        (min_move_m_ > 0.0 && moved_m >= min_move_m_);
    frozen_ = moving && fresh_estimate_.has_value();
  }
  if (frozen_) {
    scans_since_frozen_ = 0;
  } else if (scans_since_frozen_) {
    ++*scans_since_frozen_;
  }
  if (!frozen_) return std::nullopt;
  return geometry::Compose(previous_estimate, velocity);
}

std::optional<geometry::Pose2> FrozenOdometry::PairedPose(
    const std::optional<geometry::Pose2>& sensor_pose,
    const geometry::Pose2& world_from_body) const {
  if (!frozen_ || !sensor_pose || !fresh_estimate_) return sensor_pose;
  return geometry::Compose(*sensor_pose, geometry::Between(*fresh_estimate_, world_from_body));
}

void FrozenOdometry::Estimated(const geometry::Pose2& world_from_body) {
  if (!frozen_) fresh_estimate_ = world_from_body;
}

}  // namespace pena::odometry::internal
