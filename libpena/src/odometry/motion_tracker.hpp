#pragma once
// The motion prior between scans, from whichever motion sensor the entity has.

#include <optional>
#include <vector>

#include "pena/dead_reckoning/human_dead_reckoning.hpp"
#include "pena/odometry/laser_odometry.hpp"

namespace pena::odometry::internal {

// Feeds on the non-scan records and gives the body-frame motion since the previous scan.
class MotionTracker {
 public:
  MotionTracker(MotionPrior mode, const dead_reckoning::HumanDeadReckoningOptions& options,
                const geometry::Pose2& world_from_start, double start_stamp_s);

  // Gyro, compass, stride, wheel odometry; returns false for records it does not use.
  bool Add(const sensors::SensorRecord& record);

  // Motion of the body from the previous scan to this one (body frame of the previous scan).
  geometry::Pose2 TakeIncrement(const sensors::LaserScan& scan);

  // The pose in the motion sensor's own frame at the last scan given to TakeIncrement, where
  // the sensor has one (dead reckoning, wheel odometry); nullopt for stride-only and none.
  const std::optional<geometry::Pose2>& last_pose() const { return last_odometry_pose_; }

  // Dead reckoning: the scan's pose, and whether scan matching fixed it in every direction; the
  // stride scale is calibrated over stretches fixed throughout (HumanDeadReckoning::AddPositionFix).
  void AddPositionFix(double stamp_s, const geometry::Pose2& world_from_body, bool fixed);

  MotionPrior mode() const { return mode_; }
  // The dead reckoning's covariance of the motion its pose did not hold yet at the last scan given
  // to TakeIncrement (x-y, m^2; HumanDeadReckoning::PendingCovarianceAt); zero for other priors.
  const Eigen::Matrix2d& pending_position_covariance() const {
    return pending_position_covariance_;
  }
  // Whether the heading filter rejected a compass reading (innovation-gated: a magnetic
  // disturbance) in the window_s before stamp_s. Dead reckoning only; false otherwise.
  bool CompassRejectedWithin(double stamp_s, double window_s) const;
  const dead_reckoning::DeadReckoningCounts& dead_reckoning_counts() const;

 private:
  std::optional<geometry::Pose2> OdometryPoseAt(const sensors::LaserScan& scan) const;

  MotionPrior mode_;
  dead_reckoning::HumanDeadReckoning dead_reckoning_;
  std::optional<geometry::Pose2> last_odometry_pose_;     // at the previous scan
  geometry::Pose2 world_from_start_;                      // the dead reckoning's start
  double start_stamp_s_ = 0.0;
  Eigen::Matrix2d pending_position_covariance_ = Eigen::Matrix2d::Zero();  // at the previous scan
  std::optional<sensors::WheelOdometry> previous_wheel_, latest_wheel_;
  double stride_sum_m_ = 0.0;                             // since the previous scan
  std::optional<double> last_compass_rejected_s_;
  bool fix_broken_ = true;                                // an unfixed scan since the last fix
};

}  // namespace pena::odometry::internal
