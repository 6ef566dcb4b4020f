#pragma once
// A planar laser scan as the sensor gives it, in the laser's own frame.

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "pena/geometry/pose2.hpp"

namespace pena::sensors {

// Beam geometry of a planar laser: beam i points at angle_min_rad + i * angle_increment_rad
// (CCW, 0 = straight ahead along the laser's +x).
struct LaserGeometry {
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  double max_range_m = 0.0;  // ranges at or beyond this are no-returns
  // Time from the first beam to the last, beams in index order evenly in time; 0: all at once. s.
  double sweep_s = 0.0;
  // Sweeps interleaved into one scan, one mirror turn (sweep_s * 2 pi / field) apart: beam i
  // belongs to sweep i mod interlace (docs/odometry.md, "Interlaced scans").
  int interlace = 1;
  static constexpr int kMaxInterlace = 16;  // SICK lasers interleave at most 4 turns (0.25 deg)
};

// One sweep. A beam that saw nothing holds kNoReturn (+infinity); readers map a format's own
// no-return codes (max range, 0) onto it so algorithms test one thing.
struct LaserScan {
  static constexpr float kNoReturn = std::numeric_limits<float>::infinity();

  double stamp_s = 0.0;  // acquisition time; for CARMEN logs the ipc_timestamp
  LaserGeometry geometry;
  std::vector<float> ranges_m;
  // Wheel odometry pose of the platform at stamp_s, where the source logs it (CARMEN FLASER).
  std::optional<geometry::Pose2> odometry_pose;
  // The pose the source logged for the laser (corrected poses in the radish logs), if any.
  std::optional<geometry::Pose2> logged_pose;

  // Angle of beam `index` in the laser frame, radians.
  double BeamAngle(std::size_t index) const {
    return geometry.angle_min_rad + static_cast<double>(index) * geometry.angle_increment_rad;
  }
  // True when beam `index` holds a usable range (finite, > 0, below max range).
  bool IsReturn(std::size_t index) const {
    const float r = ranges_m[index];
    return r > 0.0f && r < static_cast<float>(geometry.max_range_m);
  }
  // Number of beams holding a usable range.
  std::size_t CountReturns() const;
};

}  // namespace pena::sensors
