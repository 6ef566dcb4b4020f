#pragma once
// Returns that move with a walking person (issue 3, docs/odometry.md thirteenth round). A
// body-worn laser pitched down (a bend, the forward lean) hits the floor on a line across the
// corridor a few metres ahead, and one pitched up hits the ceiling: such a line keeps its distance
// from the walker. Matched, it reads as an end wall that moves with the person and pulls the match
// back against the direction of travel (loop170 seed 8 at 106-109 s: 30-44 of about 355 returns on
// a line 4.4-6 m ahead, the matches slid back 0.2-0.45 m a scan; twelfth round d5).
//
// The test compares a scan with the previous one. A return near where a previous return was in
// the body frame, but not near where the previous returns should be after the motion between the
// two scans (the previous scan moved by the motion prior), moves with the body. Static surfaces
// pass the second test whatever their shape; a floor line fails it once the walker has moved
// forward farther than the static tolerance.

#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/odometry/walker_fixed_points_options.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::odometry::internal {

// The test itself (pure: no state between calls).
class WalkerFixedPoints {
 public:
  // Throws std::invalid_argument naming the field ("walker_fixed_points.static_m must be ...").
  explicit WalkerFixedPoints(const WalkerFixedPointsOptions& options);

  // For each of `current` (laser frame now, metres): whether it moves with the body. `previous`
  // are the previous scan's returns (its laser frame, in beam order), previous_from_current the
  // motion prior between the two scans. All false when the prior moved less than min_forward_m
  // along x, turned more than max_turn_rad, or more than max_fraction of `current` would be
  // marked.
  std::vector<bool> Find(const scan_matching::Points2& previous,
                         const scan_matching::Points2& current,
                         const geometry::Pose2& previous_from_current) const;

  const WalkerFixedPointsOptions& options() const { return options_; }

 private:
  WalkerFixedPointsOptions options_;
};

// `points` without those marked in `moving` (same size).
scan_matching::Points2 WithoutMarked(const scan_matching::Points2& points,
                                     const std::vector<bool>& moving);

}  // namespace pena::odometry::internal
