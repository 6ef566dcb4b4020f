#pragma once
// Validation of LaserOdometryOptions with messages that name the field and its unit.

#include "pena/odometry/laser_odometry.hpp"

namespace pena::odometry::internal {

// Returns the options if usable; throws std::invalid_argument naming the first bad field.
const LaserOdometryOptions& CheckedOptions(const LaserOdometryOptions& options);

}  // namespace pena::odometry::internal
