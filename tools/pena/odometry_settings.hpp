#pragma once
// `--set NAME=VALUE` for the laser odometry's options (names as in LaserOdometryOptions), shared
// by `pena odometry` and `pena localise` (there prefixed "odometry."): one list of names.

#include <string>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"

namespace pena::cli {

// Applies the settings in order; integer options are rounded. Throws std::runtime_error naming
// an unknown option. The options are validated where they are used, as usual.
void ApplyOdometrySettings(const std::vector<std::string>& settings,
                           odometry::LaserOdometryOptions& o);

}  // namespace pena::cli
