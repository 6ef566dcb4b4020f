#include "pena/dead_reckoning/stride_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::dead_reckoning {

StrideCalibration::StrideCalibration(const StrideCalibrationOptions& options) : options_(options) {
  if (!(options.interval_m > 0.0)) {
    throw std::invalid_argument("stride_calibration.interval_m must be > 0 m, got " +
                                std::to_string(options.interval_m));
  }
  if (!(options.prior_weight_m2 > 0.0)) {
    throw std::invalid_argument("stride_calibration.prior_weight_m2 must be > 0 m^2, got " +
                                std::to_string(options.prior_weight_m2));
  }
  if (!(options.max_correction >= 0.0 && options.max_correction < 1.0)) {
    throw std::invalid_argument("stride_calibration.max_correction must be in [0, 1), got " +
                                std::to_string(options.max_correction));
  }
}

void StrideCalibration::AddFix(const Eigen::Vector2d& raw_walk_m,
                               const Eigen::Vector2d& world_position_m, bool continuous) {
  if (!options_.enabled) return;
  if (!raw_walk_m.allFinite() || !world_position_m.allFinite()) {
    anchor_.reset();  // a broken fix breaks the stretch; it is no sample
    return;
  }
  if (!continuous || !anchor_) {
    anchor_ = Anchor{raw_walk_m, world_position_m};
    return;
  }
  const Eigen::Vector2d walk = raw_walk_m - anchor_->raw_walk_m;
  if (walk.norm() < options_.interval_m) return;  // keep the anchor until the stretch is long
  const Eigen::Vector2d moved = world_position_m - anchor_->world_position_m;
  sum_fix_dot_walk_m2_ += moved.dot(walk);
  sum_walk_dot_walk_m2_ += walk.squaredNorm();
  ++samples_;
  anchor_ = Anchor{raw_walk_m, world_position_m};
  const double weight = options_.prior_weight_m2;
  const double scale = (sum_fix_dot_walk_m2_ + weight) / (sum_walk_dot_walk_m2_ + weight);
  scale_ = std::clamp(scale, 1.0 - options_.max_correction, 1.0 + options_.max_correction);
}

}  // namespace pena::dead_reckoning
