#include "pace_check.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace pena::odometry::internal {

void PaceCheck::Record(const geometry::Pose2& motion_pose, const geometry::Pose2& estimate) {
  if (!enabled()) return;
  if (!history_.empty()) {
    const geometry::Pose2& last = history_.back().motion_pose;
    path_m_ += std::hypot(motion_pose.x_m - last.x_m, motion_pose.y_m - last.y_m);
  }
  history_.push_back({motion_pose, estimate, path_m_});
  while (history_.size() > 2 && history_[1].path_m <= path_m_ - options_.window_m) {
    history_.pop_front();
  }
}

std::optional<Eigen::Vector2d> PaceCheck::FallsBehind(const geometry::Pose2& motion_pose,
                                                      const geometry::Pose2& estimate,
                                                      const geometry::Pose2& prior) const {
  if (!enabled() || history_.empty()) return std::nullopt;
  const Sample& old = history_.front();
  const Eigen::Vector2d walked(motion_pose.x_m - old.motion_pose.x_m,
                               motion_pose.y_m - old.motion_pose.y_m);
  const double walked_m = walked.norm();
  // Not enough of a straight walk yet (a start, a turn, a room): no pace to compare with.
  if (walked_m < 0.75 * options_.window_m) return std::nullopt;
  // The dead reckoning's frame is turned against the estimate's by its heading error.
  const Eigen::Vector2d along =
      Eigen::Rotation2Dd(old.estimate.theta_rad - old.motion_pose.theta_rad) * (walked / walked_m);
  auto pace = [&](const geometry::Pose2& pose) {
    return along.dot(Eigen::Vector2d(pose.x_m - old.estimate.x_m, pose.y_m - old.estimate.y_m)) /
           walked_m;
  };
  const double behind = 1.0 - pace(estimate);
  if (behind > options_.tolerance && behind > std::abs(1.0 - pace(prior))) return along;
  return std::nullopt;
}

}  // namespace pena::odometry::internal
