#include "motion_tracker.hpp"

#include <algorithm>
#include <cmath>

namespace pena::odometry::internal {
namespace {

dead_reckoning::PosePrior StartPrior(const geometry::Pose2& pose, double stamp_s) {
  dead_reckoning::PosePrior prior;
  prior.stamp_s = stamp_s;
  prior.world_from_body = pose;
  return prior;
}

}  // namespace

MotionTracker::MotionTracker(MotionPrior mode,
                             const dead_reckoning::HumanDeadReckoningOptions& options,
                             const geometry::Pose2& world_from_start, double start_stamp_s)
    : mode_(mode),
      dead_reckoning_(options, StartPrior(world_from_start, start_stamp_s)),
      world_from_start_(world_from_start),
      start_stamp_s_(start_stamp_s) {}

bool MotionTracker::Add(const sensors::SensorRecord& record) {
  switch (mode_) {
    case MotionPrior::kDeadReckoning: {
      const dead_reckoning::DeadReckoningEvent event = dead_reckoning_.Add(record);
      const auto* compass = std::get_if<sensors::CompassSample>(&record);
      if (compass && event == dead_reckoning::DeadReckoningEvent::kCompassRejected) {
        last_compass_rejected_s_ = compass->stamp_s;
      }
      return event != dead_reckoning::DeadReckoningEvent::kIgnored;
    }
    case MotionPrior::kStrideOnly:
      if (const auto* stride = std::get_if<sensors::StrideSample>(&record)) {
        // The same sanity limits as full dead reckoning, without a heading source.
        if (stride->length_m >= 0.0 && stride->length_m <= 2.0) stride_sum_m_ += stride->length_m;
        return true;
      }
      return false;
    case MotionPrior::kOdometry:
      if (const auto* wheel = std::get_if<sensors::WheelOdometry>(&record)) {
        if (latest_wheel_ && wheel->stamp_s <= latest_wheel_->stamp_s) return false;
        previous_wheel_ = latest_wheel_;
        latest_wheel_ = *wheel;
        return true;
      }
      return false;
    default:
      return false;
  }
}

std::optional<geometry::Pose2> MotionTracker::OdometryPoseAt(const sensors::LaserScan& scan) const {
  if (scan.odometry_pose) return scan.odometry_pose;  // CARMEN FLASER: interpolated at the scan
  if (!latest_wheel_) return std::nullopt;
  if (!previous_wheel_ || scan.stamp_s >= latest_wheel_->stamp_s) return latest_wheel_->odom_pose;
  const double span = latest_wheel_->stamp_s - previous_wheel_->stamp_s;
  const double fraction = span > 0.0 ? (scan.stamp_s - previous_wheel_->stamp_s) / span : 1.0;
  return geometry::Interpolate(previous_wheel_->odom_pose, latest_wheel_->odom_pose,
                               std::clamp(fraction, 0.0, 1.0));
}

geometry::Pose2 MotionTracker::TakeIncrement(const sensors::LaserScan& scan) {
  std::optional<geometry::Pose2> now;
  switch (mode_) {
    case MotionPrior::kDeadReckoning: {
      const dead_reckoning::PosePrior prior = dead_reckoning_.PriorAt(scan.stamp_s);
      now = prior.world_from_body;
      pending_position_covariance_ = dead_reckoning_.PendingCovarianceAt(scan.stamp_s);
      break;
    }
    case MotionPrior::kOdometry:
      now = OdometryPoseAt(scan);
      break;
    case MotionPrior::kStrideOnly: {
      // No heading source: the strides are taken straight ahead; the wide window finds the turn.
      const geometry::Pose2 forward{stride_sum_m_, 0.0, 0.0};
      stride_sum_m_ = 0.0;
      return forward;
    }
    default:
      return {};
  }
  if (!now) return {};
  // The dead reckoning started at the start pose: a first scan taken after the start is moved by
  // what it measured since. Taken as zero, a turn between the two was lost for good, since the
  // odometry takes only increments from here on: an unknown start waits for the first compass
  // reading, the first scan can come 0.2 s later, 30 deg into a fast turn (office seed 1 at
  // 97.8 s), and the odometry stayed 31 deg off the compass-held dead reckoning to the end. A scan
  // at the start stamp is at the start pose. Wheel odometry has a frame of its own: its first
  // reading is the reference.
  if (!last_odometry_pose_ && mode_ == MotionPrior::kDeadReckoning && scan.stamp_s > start_stamp_s_) {
    last_odometry_pose_ = world_from_start_;
  }
  const geometry::Pose2 increment =
      last_odometry_pose_ ? geometry::Between(*last_odometry_pose_, *now) : geometry::Pose2{};
  last_odometry_pose_ = now;
  return increment;
}

bool MotionTracker::CompassRejectedWithin(double stamp_s, double window_s) const {
  return last_compass_rejected_s_ && stamp_s - *last_compass_rejected_s_ <= window_s;
}

void MotionTracker::AddPositionFix(double stamp_s, const geometry::Pose2& world_from_body,
                                   bool fixed) {
  if (mode_ != MotionPrior::kDeadReckoning) return;
  if (!fixed) {
    fix_broken_ = true;
    return;
  }
  dead_reckoning_.AddPositionFix(stamp_s, {world_from_body.x_m, world_from_body.y_m}, !fix_broken_);
  fix_broken_ = false;
}

const dead_reckoning::DeadReckoningCounts& MotionTracker::dead_reckoning_counts() const {
  return dead_reckoning_.counts();
}

}  // namespace pena::odometry::internal
