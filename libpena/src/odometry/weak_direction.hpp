#pragma once
// Degenerate and weakly constrained matches (docs/odometry.md, step 3 of the chain): along the
// weak direction of the refinement's information matrix the prior's component is kept instead of
// the match's. A degenerate match (a featureless corridor) always; a weakly constrained one only
// when it slid away from a prior that is worth keeping (the slide check).

#include <Eigen/Core>
#include <optional>

#include "pena/geometry/pose2.hpp"

namespace pena::odometry::internal {

struct WeakDirectionOptions {
  double degenerate_ratio = 0.05;  // smaller / larger translation eigenvalue below this: degenerate
  double slide_ratio = 0.0;        // below this: weakly constrained, the slide check applies (0: off)
  double max_slide_m = 0.15;       // a slide along the weak direction longer than this
  bool backward_only = true;       // ... back against the direction of travel only
  double max_across_m = 0.1;       // ... with the prior within this of the match across it (0: any)
  double prior_agreed_m = 0.15;    // ... and the latest constraining match this near its prior (0: any)
};

// Keeps the prior's component along the weak direction where the options say so.
class WeakDirection {
 public:
  explicit WeakDirection(const WeakDirectionOptions& options) : options_(options) {}

  // The match `pose` (moved in place when the prior's component is kept) against `prior`, with the
  // refinement's `information` (x, y, heading) and `travel_m`, the motion predicted over the last
  // scan interval. Returns the weak direction (world frame, unit) when the prior's component was
  // kept. A match that pins the position down (not weak) checks the prior for the scans after it.
  std::optional<Eigen::Vector2d> Apply(const Eigen::Matrix3d& information, const geometry::Pose2& prior,
                                       const Eigen::Vector2d& travel_m, geometry::Pose2& pose);

  // The latest constraining match lay within prior_agreed_m of its prior.
  bool prior_held_lately() const { return prior_held_lately_; }

 private:
  WeakDirectionOptions options_;
  bool prior_held_lately_ = true;
};

}  // namespace pena::odometry::internal
