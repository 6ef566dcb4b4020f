#include "pena/dead_reckoning/human_dead_reckoning.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::dead_reckoning {

HumanDeadReckoning::HumanDeadReckoning(const HumanDeadReckoningOptions& options,
                                       const PosePrior& start)
    : options_(options),
      heading_(options.heading, start.world_from_body.theta_rad, start.stamp_s),
      position_m_(start.world_from_body.x_m, start.world_from_body.y_m),
      position_covariance_(start.covariance.topLeftCorner<2, 2>()),
      last_stride_stamp_s_(start.stamp_s) {
  if (!(options.stride_sigma_fraction >= 0.0 && options.stride_sigma_fraction < 1.0)) {
    throw std::invalid_argument(
        "human_dead_reckoning.stride_sigma_fraction must be in [0, 1), got " +
        std::to_string(options.stride_sigma_fraction));
  }
  if (!(options.max_stride_m > 0.0)) {
    throw std::invalid_argument("human_dead_reckoning.max_stride_m must be > 0 m, got " +
                                std::to_string(options.max_stride_m));
  }
}

DeadReckoningEvent HumanDeadReckoning::Add(const sensors::SensorRecord& record) {
  if (const auto* gyro = std::get_if<sensors::GyroSample>(&record)) {
    const HeadingEvent event = heading_.Predict(*gyro);
    if (event == HeadingEvent::kGyroGap) return Count(DeadReckoningEvent::kGyroGap);
    if (event == HeadingEvent::kOutOfOrder) return Count(DeadReckoningEvent::kOutOfOrder);
    return DeadReckoningEvent::kNone;
  }
  if (const auto* compass = std::get_if<sensors::CompassSample>(&record)) {
    return heading_.Update(*compass) == HeadingEvent::kNone
               ? DeadReckoningEvent::kNone
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
  last_stride_stamp_s_ = stride.stamp_s;
  // The SiLMU measures length, not direction: the step is taken along the current heading. The
  // position covariance grows by J Sigma J^T with the stride and heading uncertainties.
  const double heading = heading_.HeadingAt(stride.stamp_s);
  const Eigen::Vector2d direction(std::cos(heading), std::sin(heading));
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  position_m_ += stride.length_m * direction;
  const double length_sigma_m = options_.stride_sigma_fraction * stride.length_m;
  const double lateral_sigma_m = stride.length_m * heading_.heading_sigma_rad();
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

PosePrior HumanDeadReckoning::PriorAt(double stamp_s) const {
  PosePrior prior;
  prior.stamp_s = stamp_s;
  prior.world_from_body = {position_m_.x(), position_m_.y(), heading_.HeadingAt(stamp_s)};
  prior.covariance.topLeftCorner<2, 2>() = position_covariance_;
  prior.covariance(2, 2) = std::pow(heading_.heading_sigma_rad(), 2);
  return prior;
}

void HumanDeadReckoning::Reset(const PosePrior& corrected) {
  position_m_ = {corrected.world_from_body.x_m, corrected.world_from_body.y_m};
  position_covariance_ = corrected.covariance.topLeftCorner<2, 2>();
  heading_.Reset(corrected.world_from_body.theta_rad, std::sqrt(corrected.covariance(2, 2)));
}

}  // namespace pena::dead_reckoning
