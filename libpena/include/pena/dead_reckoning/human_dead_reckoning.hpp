#pragma once
// Human dead reckoning (paper section 2.1): heading from the gyro/compass Kalman filter, distance
// from the stride-length sensor; gives the pose prior with covariance for every laser scan.

#include <Eigen/Core>
#include <cstddef>

#include "pena/dead_reckoning/heading_filter.hpp"
#include "pena/geometry/pose2.hpp"
#include "pena/sensors/record.hpp"

namespace pena::dead_reckoning {

// Options of the walking model. Validated by HumanDeadReckoning's constructor.
struct HumanDeadReckoningOptions {
  HeadingFilterOptions heading;
  double stride_sigma_fraction = 0.05;  // stride length error, fraction of the stride (SiLMU ~5%)
  double max_stride_m = 2.0;            // longer strides are sensor faults and are rejected
};

// A pose estimate with its covariance (x_m, y_m, theta_rad), mission frame.
struct PosePrior {
  double stamp_s = 0.0;
  geometry::Pose2 world_from_body;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

// What happened to the last sample (kNone: used as is).
enum class DeadReckoningEvent {
  kNone,
  kIgnored,           // a record this model does not use (scans, wheel odometry, truth)
  kCompassRejected,   // magnetic disturbance: innovation outside the gate
  kGyroGap,           // gyro silent for too long: heading uncertainty inflated
  kStrideRejected,    // non-finite, negative or longer than max_stride_m
  kOutOfOrder,        // stamp before the previous sample of that sensor
};

// Counts of everything not used as is, for logs and reports.
struct DeadReckoningCounts {
  std::size_t compass_rejected = 0;
  std::size_t gyro_gaps = 0;
  std::size_t strides_rejected = 0;
  std::size_t out_of_order = 0;
};

// Integrates gyro, compass and stride samples in time order.
class HumanDeadReckoning {
 public:
  // Throws std::invalid_argument naming the field if an option is out of range.
  HumanDeadReckoning(const HumanDeadReckoningOptions& options, const PosePrior& start);

  // Feeds one sensor record; returns what was done with it.
  DeadReckoningEvent Add(const sensors::SensorRecord& record);

  // The current estimate, heading extrapolated to stamp_s (a scan time).
  PosePrior PriorAt(double stamp_s) const;

  // Replaces the estimate after a correction (scan matching, map localisation, operator).
  void Reset(const PosePrior& corrected);

  const DeadReckoningCounts& counts() const { return counts_; }

 private:
  DeadReckoningEvent AddStride(const sensors::StrideSample& stride);
  DeadReckoningEvent Count(DeadReckoningEvent event);

  HumanDeadReckoningOptions options_;
  HeadingFilter heading_;
  Eigen::Vector2d position_m_;
  Eigen::Matrix2d position_covariance_;
  double last_stride_stamp_s_;
  DeadReckoningCounts counts_;
};

}  // namespace pena::dead_reckoning
