#pragma once
// A start pose for the dead-reckoning tests: a pose with a small, round covariance.

#include <numbers>

#include "pena/dead_reckoning/human_dead_reckoning.hpp"

namespace pena::dead_reckoning::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;

inline PosePrior StartAt(double x, double y, double theta) {
  PosePrior start;
  start.world_from_body = {x, y, theta};
  start.covariance = Eigen::Matrix3d::Identity() * 1e-4;
  return start;
}

}  // namespace pena::dead_reckoning::testing
