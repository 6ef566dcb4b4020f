#include "pena/dead_reckoning/human_dead_reckoning.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::dead_reckoning {

StrideInterpolationOptions SpreadOptionsOf(const HumanDeadReckoningOptions& options) {
  StrideInterpolationOptions spread = options.stride_interpolation;
  spread.max_stride_m = options.max_stride_m;
  return spread;
}

HumanDeadReckoning::HumanDeadReckoning(const HumanDeadReckoningOptions& options,
                                       const PosePrior& start)
    : options_(options),
      heading_(options.heading, start.world_from_body.theta_rad, start.stamp_s),
      position_m_(start.world_from_body.x_m, start.world_from_body.y_m),
      position_covariance_(start.covariance.topLeftCorner<2, 2>()),
      last_stride_stamp_s_(start.stamp_s),
      calibration_(options.stride_calibration) {
  if (!(options.stride_sigma_fraction >= 0.0 && options.stride_sigma_fraction < 1.0)) {
    throw std::invalid_argument(
        "human_dead_reckoning.stride_sigma_fraction must be in [0, 1), got " +
        std::to_string(options.stride_sigma_fraction));
  }
  if (!(options.max_stride_period_s >= 0.0)) {
    throw std::invalid_argument("human_dead_reckoning.max_stride_period_s must be >= 0 s, got " +
                                std::to_string(options.max_stride_period_s));
  }
  if (!(options.stopped_after_periods >= 1.0)) {
    throw std::invalid_argument("human_dead_reckoning.stopped_after_periods must be >= 1, got " +
                                std::to_string(options.stopped_after_periods));
  }
  if (!(options.stopped_stride_fraction >= 0.0 && options.stopped_stride_fraction <= 1.0)) {
    throw std::invalid_argument(
        "human_dead_reckoning.stopped_stride_fraction must be in [0, 1], got " +
        std::to_string(options.stopped_stride_fraction));
  }
  if (!(options.turning_on_the_spot_rad_s >= 0.0)) {
    throw std::invalid_argument(
        "human_dead_reckoning.turning_on_the_spot_rad_s must be >= 0 rad/s, got " +
        std::to_string(options.turning_on_the_spot_rad_s));
  }
  if (!(options.overdue_turn_rad >= 0.0)) {
    throw std::invalid_argument("human_dead_reckoning.overdue_turn_rad must be >= 0 rad, got " +
                                std::to_string(options.overdue_turn_rad));
  }
  StrideInterpolator::Validate(options.stride_interpolation);
  if (options.stride_interpolation.enabled && options.max_stride_period_s > 0.0) {
    throw std::invalid_argument(
        "human_dead_reckoning.max_stride_period_s (the stride extrapolation) and "
        "dead_reckoning.stride_interpolation.enabled exclude each other: set "
        "dead_reckoning.stride_interpolation.enabled=0 to extrapolate");
  }
  if (!(options.max_stride_m > 0.0)) {
    throw std::invalid_argument("human_dead_reckoning.max_stride_m must be > 0 m, got " +
                                std::to_string(options.max_stride_m));
  }
  if (!(options.unreported_pace_m_s >= 0.0)) {
    throw std::invalid_argument("human_dead_reckoning.unreported_pace_m_s must be >= 0 m/s, got " +
                                std::to_string(options.unreported_pace_m_s));
  }
}

DeadReckoningEvent HumanDeadReckoning::Add(const sensors::SensorRecord& record) {
  if (const auto* gyro = std::get_if<sensors::GyroSample>(&record)) {
    const double from_s = heading_.stamp_s();
    const double from_heading_rad = heading_.HeadingAt(from_s);
    const HeadingEvent event = heading_.Predict(*gyro);
    if (event == HeadingEvent::kNone) NoteTurning(from_s, from_heading_rad, *gyro);
    NoteStrideDue(gyro->stamp_s);
    NoteOverdueTurn(gyro->stamp_s);
    if (event == HeadingEvent::kGyroGap) return Count(DeadReckoningEvent::kGyroGap);
    if (event == HeadingEvent::kOutOfOrder) return Count(DeadReckoningEvent::kOutOfOrder);
    return DeadReckoningEvent::kNone;
  }
  if (const auto* compass = std::get_if<sensors::CompassSample>(&record)) {
    const HeadingEvent event = heading_.Update(*compass);
    NoteStrideDue(compass->stamp_s);
    NoteOverdueTurn(compass->stamp_s);
    return event == HeadingEvent::kNone ? DeadReckoningEvent::kNone
                                        : Count(DeadReckoningEvent::kCompassRejected);
  }
  if (const auto* stride = std::get_if<sensors::StrideSample>(&record)) return AddStride(*stride);
  return DeadReckoningEvent::kIgnored;
}

DeadReckoningEvent HumanDeadReckoning::AddStride(const sensors::StrideSample& stride) {
  if (!(stride.stamp_s >= last_stride_stamp_s_)) return Count(DeadReckoningEvent::kOutOfOrder);
  if (!(stride.length_m >= 0.0 && stride.length_m <= options_.max_stride_m)) {
    return Count(DeadReckoningEvent::kStrideRejected);
  }
  // What the estimate had extrapolated by now (nothing without a known pace: then the report is
  // all new motion, and no jump is counted).
  const bool extrapolating = PaceKnown();
  const Eigen::Vector2d ahead_m = calibration_.scale() * AheadRawM(stride.stamp_s);
  last_stride_period_s_ = stride.stamp_s - last_stride_stamp_s_;
  last_stride_stamp_s_ = stride.stamp_s;
  last_stride_m_ = stride.length_m;
  // The SiLMU measures length, not direction: the step is taken along the current heading. The
  // position covariance grows by J Sigma J^T with the stride and heading uncertainties.
  const double heading = heading_.HeadingAt(stride.stamp_s);
  last_stride_heading_rad_ = heading;
  due_heading_rad_.reset();
  turning_s_ = 0.0;
  turn_start_heading_rad_.reset();
  stride_dropped_ = false;
  const Eigen::Vector2d direction(std::cos(heading), std::sin(heading));
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  const double length_m = calibration_.scale() * stride.length_m;
  position_m_ += length_m * direction;
  if (extrapolating) extrapolation_jumps_m_ += length_m * direction - ahead_m;
  raw_walk_m_ += stride.length_m * direction;
  const double length_sigma_m = options_.stride_sigma_fraction * length_m;
  const double lateral_sigma_m = length_m * heading_.heading_sigma_rad();
  position_covariance_ += length_sigma_m * length_sigma_m * direction * direction.transpose() +
                          lateral_sigma_m * lateral_sigma_m * normal * normal.transpose();
  return DeadReckoningEvent::kNone;
}

DeadReckoningEvent HumanDeadReckoning::Count(DeadReckoningEvent event) {
  switch (event) {
    case DeadReckoningEvent::kCompassRejected: ++counts_.compass_rejected; break;
    case DeadReckoningEvent::kGyroGap: ++counts_.gyro_gaps; break;
    case DeadReckoningEvent::kStrideRejected: ++counts_.strides_rejected; break;
    case DeadReckoningEvent::kOutOfOrder: ++counts_.out_of_order; break;
    default: break;
  }
  return event;
}

bool HumanDeadReckoning::PaceKnown() const {
  return last_stride_period_s_ > 0.0 && last_stride_period_s_ <= options_.max_stride_period_s;
}

void HumanDeadReckoning::NoteStrideDue(double stamp_s) {
  if (PaceKnown() && !due_heading_rad_ &&
      stamp_s >= last_stride_stamp_s_ + last_stride_period_s_) {
    due_heading_rad_ = heading_.HeadingAt(stamp_s);
  }
}

void HumanDeadReckoning::NoteOverdueTurn(double stamp_s) {
  if (options_.overdue_turn_rad <= 0.0 || stride_dropped_ || !PaceKnown()) return;
  if (stamp_s < last_stride_stamp_s_ + last_stride_period_s_) return;  // not overdue yet
  const double turned_rad =
      geometry::NormalizeAngle(heading_.HeadingAt(stamp_s) - last_stride_heading_rad_);
  if (std::abs(turned_rad) <= options_.overdue_turn_rad) return;
  // The prior steps back.
  extrapolation_jumps_m_ -= calibration_.scale() * AheadRawM(stamp_s);
  stride_dropped_ = true;
}

void HumanDeadReckoning::NoteTurning(double from_s, double from_heading_rad,
                                     const sensors::GyroSample& gyro) {
  if (options_.turning_on_the_spot_rad_s <= 0.0 || !PaceKnown()) return;
  if (std::abs(gyro.yaw_rate_rad_s) <= options_.turning_on_the_spot_rad_s) return;
  const double start_s = std::max(from_s, last_stride_stamp_s_);
  if (!(gyro.stamp_s > start_s)) return;
  // The heading before this gyro interval (a report inside it: the report's heading).
  if (!turn_start_heading_rad_) {
    turn_start_heading_rad_ = from_s >= last_stride_stamp_s_ ? from_heading_rad : last_stride_heading_rad_;
  }
  turning_s_ += gyro.stamp_s - start_s;
}

double HumanDeadReckoning::AheadFraction(double stamp_s) const {
  const double since_s = stamp_s - last_stride_stamp_s_;
  const double period_s = last_stride_period_s_;
  const double walked = std::clamp((since_s - turning_s_) / period_s, 0.0, 1.0);
  // Overdue by stopped_after_periods: the walker stopped; blend to the stopped fraction over a period.
  const double stopped_s = since_s - options_.stopped_after_periods * period_s;
  if (stopped_s <= 0.0) return walked;
  const double weight = std::min(stopped_s / period_s, 1.0);
  return (1.0 - weight) * walked + weight * std::min(walked, options_.stopped_stride_fraction);
}

Eigen::Vector2d HumanDeadReckoning::AheadRawM(double stamp_s) const {
  if (!PaceKnown() || stride_dropped_) return Eigen::Vector2d::Zero();
  const double since_s = stamp_s - last_stride_stamp_s_;
  if (!(since_s > 0.0)) return Eigen::Vector2d::Zero();
  const double fraction = AheadFraction(stamp_s);
  // The stride in progress runs from the last report's heading to the heading now, or, once the
  // next report is overdue (the walker stopped, or slowed), to the heading when it was due: a
  // turn on the spot after stopping must not swing the stride round with the body (an earlier
  // version took the heading now, which moved the prior by up to two strides during such turns).
  // Likewise a turn on the spot (turning_on_the_spot_rad_s) keeps the heading it started from.
  const double now_heading = heading_.HeadingAt(stamp_s);
  const double end_heading =
      turn_start_heading_rad_ ? *turn_start_heading_rad_
      : since_s < last_stride_period_s_ ? now_heading
                                        : due_heading_rad_.value_or(now_heading);
  // Chord of a steady turn: along the mean of the start and end headings.
  const double heading =
      last_stride_heading_rad_ + 0.5 * geometry::NormalizeAngle(end_heading - last_stride_heading_rad_);
  return last_stride_m_ * fraction * Eigen::Vector2d(std::cos(heading), std::sin(heading));
}

PosePrior HumanDeadReckoning::PriorAt(double stamp_s) const {
  PosePrior prior;
  prior.stamp_s = stamp_s;
  const double heading = heading_.HeadingAt(stamp_s);
  const Eigen::Vector2d ahead_m = calibration_.scale() * AheadRawM(stamp_s);
  const Eigen::Vector2d position = position_m_ + ahead_m;
  prior.world_from_body = {position.x(), position.y(), heading};
  prior.covariance.topLeftCorner<2, 2>() = position_covariance_ + PendingCovarianceAt(stamp_s);
  prior.covariance(2, 2) = std::pow(heading_.heading_sigma_rad(), 2);
  return prior;
}

Eigen::Matrix2d HumanDeadReckoning::PendingCovarianceAt(double stamp_s) const {
  if (stride_dropped_) {
    // The dropped stride: anything from none to a whole stride, in any direction.
    const double half_stride_m = 0.5 * calibration_.scale() * last_stride_m_;
    return half_stride_m * half_stride_m * Eigen::Matrix2d::Identity();
  }
  if (PaceKnown()) {
    // The pace may have changed (or the walker stopped): half the extrapolated distance, 1 sigma.
    const Eigen::Vector2d ahead_m = calibration_.scale() * AheadRawM(stamp_s);
    return 0.25 * ahead_m * ahead_m.transpose();
  }
  // Not extrapolated: the walker may be as far ahead as it walks between reports (the stride
  // reported at its end); along the heading, since the sensor measures length, not direction.
  const double since_s = stamp_s - last_stride_stamp_s_;
  if (!(since_s > 0.0) || options_.unreported_pace_m_s <= 0.0) return Eigen::Matrix2d::Zero();
  const bool stride_known = last_stride_period_s_ > 0.0 && last_stride_m_ > 0.0;
  const double pace_m_s =
      stride_known ? std::max(last_stride_m_ / last_stride_period_s_, options_.unreported_pace_m_s)
                   : options_.unreported_pace_m_s;
  constexpr double kFirstStride_s = 1.0;  // before any report: a stride of one second's walk
  const double stride_m =
      stride_known ? last_stride_m_ : options_.unreported_pace_m_s * kFirstStride_s;
  const double unreported_m = calibration_.scale() * std::min(pace_m_s * since_s, stride_m);
  const double heading = heading_.HeadingAt(stamp_s);
  const Eigen::Vector2d along(std::cos(heading), std::sin(heading));
  return unreported_m * unreported_m * along * along.transpose();
}

void HumanDeadReckoning::Reset(const PosePrior& corrected) {
  // The stride in progress keeps its direction relative to the corrected heading.
  const double turn_rad = geometry::NormalizeAngle(corrected.world_from_body.theta_rad -
                                                   heading_.HeadingAt(corrected.stamp_s));
  last_stride_heading_rad_ += turn_rad;
  if (due_heading_rad_) *due_heading_rad_ += turn_rad;
  if (turn_start_heading_rad_) *turn_start_heading_rad_ += turn_rad;
  heading_.Reset(corrected.world_from_body.theta_rad, std::sqrt(corrected.covariance(2, 2)));
  // The correction holds at its stamp, extrapolation included: the next stride report replaces
  // the extrapolated part, so keep the position of the last report that the correction implies.
  const Eigen::Vector2d ahead_m = calibration_.scale() * AheadRawM(corrected.stamp_s);
  position_m_ = Eigen::Vector2d(corrected.world_from_body.x_m, corrected.world_from_body.y_m) - ahead_m;
  position_covariance_ = corrected.covariance.topLeftCorner<2, 2>();
}

void HumanDeadReckoning::AddPositionFix(double stamp_s, const Eigen::Vector2d& world_position_m,
                                        bool continuous) {
  calibration_.AddFix(raw_walk_m_ + AheadRawM(stamp_s), world_position_m, continuous);
}

}  // namespace pena::dead_reckoning
