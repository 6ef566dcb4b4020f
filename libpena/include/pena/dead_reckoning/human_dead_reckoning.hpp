#pragma once
// Human dead reckoning (paper section 2.1): heading from the gyro/compass Kalman filter, distance
// from the stride-length sensor; gives the pose prior with covariance for every laser scan.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "pena/dead_reckoning/heading_filter.hpp"
#include "pena/dead_reckoning/stride_calibration.hpp"
#include "pena/dead_reckoning/stride_interpolator.hpp"
#include "pena/geometry/pose2.hpp"
#include "pena/sensors/record.hpp"

namespace pena::dead_reckoning {

// Options of the walking model. Validated by HumanDeadReckoning's constructor.
struct HumanDeadReckoningOptions {
  HeadingFilterOptions heading;
  double stride_sigma_fraction = 0.05;  // stride length error, fraction of the stride (SiLMU ~5%)
  double max_stride_m = 2.0;            // longer strides are sensor faults and are rejected
  // Extrapolate the stride in progress at the last stride's pace if it took at most this (0 = off).
  double max_stride_period_s = 0.0;
  // Pace the walker may be ahead of the last report, for the covariance of the stride in progress
  // (PendingCovarianceAt; 0 leaves it out).
  double unreported_pace_m_s = 1.0;
  double stopped_after_periods = 1.2;    // with extrapolation: a report this overdue means stopped ...
  double stopped_stride_fraction = 1.0;  // ... and the extrapolation falls back to this share of a stride
  double turning_on_the_spot_rad_s = 0.0;  // with extrapolation: no advance while turning faster (0 = off)
  double overdue_turn_rad = 0.0;  // with extrapolation: drop an overdue stride after this turn (0 = off)
  StrideCalibrationOptions stride_calibration;  // stride scale learnt from position fixes
  // Each stride spread over its scans in front of this model (StrideInterpolator); excludes the
  // extrapolation above.
  StrideInterpolationOptions stride_interpolation;
};

// The stride spreading options with this model's fault limit (max_stride_m).
StrideInterpolationOptions SpreadOptionsOf(const HumanDeadReckoningOptions& options);

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
  // The part of PriorAt's x-y covariance (m^2) for the motion the position does not hold yet: the
  // extrapolated stride's share, a dropped stride, or the stride in progress when not extrapolated.
  Eigen::Matrix2d PendingCovarianceAt(double stamp_s) const;

  // Replaces the estimate after a correction (scan matching, map localisation, operator).
  void Reset(const PosePrior& corrected);

  // Scan matching fixed the position at stamp_s in every direction. continuous = false when the
  // position was not fixed all the way since the previous call (a corridor, a failed match).
  // Calibrates the stride scale (StrideCalibration); the estimate itself is not changed.
  void AddPositionFix(double stamp_s, const Eigen::Vector2d& world_position_m, bool continuous);

  // Sum of the jumps made when a report replaced or dropped the extrapolated stride (world frame,
  // m): corrections of a guess about the past, not motion.
  const Eigen::Vector2d& extrapolation_jumps_m() const { return extrapolation_jumps_m_; }

  // The scale applied to the stride sensor's lengths (1 until calibrated).
  double stride_scale() const { return calibration_.scale(); }

  const DeadReckoningCounts& counts() const { return counts_; }

 private:
  DeadReckoningEvent AddStride(const sensors::StrideSample& stride);
  // Whether the last stride gave a pace to extrapolate at (max_stride_period_s).
  bool PaceKnown() const;
  // Remembers the heading when the next stride report became due (called with every gyro and
  // compass sample).
  void NoteStrideDue(double stamp_s);
  // Drops the stride in progress once overdue and turned by more than overdue_turn_rad.
  void NoteOverdueTurn(double stamp_s);
  // Adds the part of a gyro interval (from from_s, heading then from_heading_rad) after the last
  // report to turning_s_ if it turned on the spot.
  void NoteTurning(double from_s, double from_heading_rad, const sensors::GyroSample& gyro);
  // The part of the last stride walked by stamp_s at its pace (turns on the spot and stops held).
  double AheadFraction(double stamp_s) const;
  // World-frame displacement walked since the last stride report, extrapolated at the last
  // stride's pace, at most one stride (raw: before the stride scale).
  Eigen::Vector2d AheadRawM(double stamp_s) const;
  DeadReckoningEvent Count(DeadReckoningEvent event);

  HumanDeadReckoningOptions options_;
  HeadingFilter heading_;
  Eigen::Vector2d position_m_;
  Eigen::Matrix2d position_covariance_;
  double last_stride_stamp_s_;
  double last_stride_m_ = 0.0;         // raw length of the last accepted stride
  double last_stride_period_s_ = 0.0;  // time from the stride before it (0: none yet)
  double last_stride_heading_rad_ = 0.0;        // heading at the last stride report
  std::optional<double> due_heading_rad_;       // heading when the next report became due
  double turning_s_ = 0.0;  // time since the last report spent turning on the spot
  std::optional<double> turn_start_heading_rad_;  // heading when that turning started
  bool stride_dropped_ = false;  // overdue and turned on the spot: no extrapolation until a report
  DeadReckoningCounts counts_;
  StrideCalibration calibration_;
  Eigen::Vector2d raw_walk_m_ = Eigen::Vector2d::Zero();  // unscaled strides along the heading
  Eigen::Vector2d extrapolation_jumps_m_ = Eigen::Vector2d::Zero();  // see extrapolation_jumps_m()
};

}  // namespace pena::dead_reckoning
