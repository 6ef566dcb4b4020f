#pragma once
// Offline smoothing of a localised walk (beyond the paper): the causal chain corrects the scan at
// a plan round but leaves the scans before it with the drift they had, and `map_from_odom`
// corrections come as steps. Over a whole log the trajectory can be optimised at once, as
// Cartographer's and slam_toolbox's offline modes do: one pose graph node per anchored scan,
// odometry edges between consecutive scans, and every accepted plan round an edge from the plan's
// origin (node 0, anchored) carrying the corrected pose, weak along a corridor when the round was
// degenerate.

#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/localisation/localised_pose.hpp"

namespace pena::localisation {

// Standard deviations of the edges; validated by SmoothTrajectory (docs/localisation.md,
// "Offline smoothing").
struct TrajectorySmootherOptions {
  // An accepted plan round, per constrained direction (body frame) and in heading; loose, so many
  // rounds are averaged.
  double round_sigma_m = 0.2;
  double round_sigma_rad = 0.0174532925199433;  // 1 deg
  // A degenerate round along its weak direction (the odometry was kept there causally).
  double degenerate_along_sigma_m = 2.0;
  // The odometry between consecutive scans: a floor plus a part growing with the step.
  double odometry_sigma_m = 0.01;
  double odometry_sigma_per_m = 0.03;  // metres per metre walked
  double odometry_sigma_rad = 0.001;
  double odometry_sigma_rad_per_rad = 0.01;  // per radian turned
  double odometry_sigma_rad_per_m = 0.001;   // per metre walked
  // The known start (or the global anchor): the first anchored scan's pose.
  double start_sigma_m = 0.05;
  double start_sigma_rad = 0.0174532925199433;
  int max_iterations = 10;
};

// What the smoother did; failure is data (the causal poses are returned then).
struct SmoothedTrajectory {
  bool solved = false;
  int rounds_used = 0;                         // accepted plan rounds in the graph
  std::vector<geometry::Pose2> map_from_body;  // one per anchored pose of the input, in order
};

// Smooths the anchored poses of `poses` (the entity pipeline's plan stage, in time order). A round that
// relocalised the entity breaks the odometry chain there. Throws std::invalid_argument for a
// non-positive sigma or iteration count, naming the field.
SmoothedTrajectory SmoothTrajectory(const std::vector<LocalisedPose>& poses,
                                    const TrajectorySmootherOptions& options);

}  // namespace pena::localisation
