#include "gate_confirmation.hpp"

#include <cmath>

namespace pena::odometry::internal {

GateConfirmation::GateConfirmation(double agree_m, double agree_rad)
    : agree_m_(agree_m), agree_rad_(agree_rad) {}

bool GateConfirmation::Agrees(const geometry::Pose2& deviation, bool agree) const {
  if (!agree || agree_m_ <= 0.0 || in_row_ == 0) return true;
  const double apart_m = std::hypot(deviation.x_m - previous_.x_m, deviation.y_m - previous_.y_m);
  const double apart_rad = std::abs(geometry::NormalizeAngle(deviation.theta_rad - previous_.theta_rad));
  return apart_m <= agree_m_ && apart_rad <= agree_rad_;
}

bool GateConfirmation::Outside(const geometry::Pose2& deviation, int confirm, bool agree) {
  in_row_ = Agrees(deviation, agree) ? in_row_ + 1 : 1;
  previous_ = deviation;
  if (in_row_ < confirm) return false;
  in_row_ = 0;
  return true;
}

}  // namespace pena::odometry::internal
