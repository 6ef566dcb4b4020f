#pragma once
// The pace check of the people's laser odometry (internal): evidence over several metres, not
// one match, that a corridor match is sliding back (docs/odometry.md, "Estimator").
//
// In a corridor the only returns across it are often floor lines a few metres ahead. They move
// with the walker, so a match against the reference keyframes reads them as an end wall that
// keeps its distance and pulls the pose back. One such match is within a stride of the prior
// and no single-match rule tells it from a correction. Over several metres the stride sensor's
// pace, spread over the scans, is good to a few per cent (0.04-0.05 m RMS per 0.25 s,
// docs/dead-reckoning.md), so a position that falls behind it by more than that is the slide.

#include <Eigen/Core>
#include <deque>
#include <optional>

#include "pena/geometry/pose2.hpp"

namespace pena::odometry::internal {

struct PaceCheckOptions {
  double tolerance = 0.0;  // fraction of the distance walked; 0: off
  double window_m = 4.0;   // distance walked the pace is measured over
};

class PaceCheck {
 public:
  explicit PaceCheck(const PaceCheckOptions& options) : options_(options) {}

  // After each scan: the dead reckoning's pose and the scan's final estimate.
  void Record(const geometry::Pose2& motion_pose, const geometry::Pose2& estimate);

  // The direction walked (unit, estimate's frame) when `estimate` lies further behind the
  // dead reckoning's progress over the window than the tolerance and than `prior` does; nullopt
  // otherwise, and until a window's worth was walked in a roughly straight line. Only behind:
  // returns that move with the walker never pull a match ahead, and a match ahead of the prior is
  // a correction after a slide (loop170 seed 8 at 108-131 s).
  std::optional<Eigen::Vector2d> FallsBehind(const geometry::Pose2& motion_pose,
                                             const geometry::Pose2& estimate,
                                             const geometry::Pose2& prior) const;

  bool enabled() const { return options_.tolerance > 0.0; }

 private:
  struct Sample {
    geometry::Pose2 motion_pose;
    geometry::Pose2 estimate;
    double path_m = 0.0;  // dead reckoning's distance walked up to it
  };
  PaceCheckOptions options_;
  std::deque<Sample> history_;  // the oldest is the newest at least window_m back
  double path_m_ = 0.0;
};

}  // namespace pena::odometry::internal
