#pragma once
// Finding the pose a trajectory holds at a given stamp, and checking a trajectory can be searched.

#include <cstddef>
#include <optional>
#include <string_view>

#include "pena/geometry/trajectory.hpp"

namespace pena::eval {

// Stamps closer than this are the same instant: 1 ms, well below a laser's 25-200 ms scan period
// and above the 1 us rounding of 6-decimal text stamps.
inline constexpr double kDefaultStampTolerance_s = 1e-3;

// Throws std::invalid_argument naming `what` (e.g. "estimated trajectory") if the trajectory is
// empty, holds a non-finite value or its stamps are not strictly increasing.
void ValidateTrajectory(const geometry::Trajectory& trajectory, std::string_view what);

// Index of the pose whose stamp is closest to stamp_s if within tolerance_s, else nullopt.
// The trajectory must be sorted (see ValidateTrajectory).
std::optional<std::size_t> FindStamp(const geometry::Trajectory& trajectory, double stamp_s,
                                     double tolerance_s = kDefaultStampTolerance_s);

}  // namespace pena::eval
