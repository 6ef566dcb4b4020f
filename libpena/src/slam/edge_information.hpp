#pragma once
// How much a pose-graph edge is trusted (internal to pena::slam): information matrices (inverse
// covariances) in the graph's edge frame.

#include <Eigen/Core>

#include "pena/slam/slam_options.hpp"
#include "submap_matcher.hpp"

namespace pena::slam::internal {

// sigma_m on x and y, sigma_rad on theta, no correlation.
Eigen::Matrix3d IsotropicInformation(double sigma_m, double sigma_rad);

// A loop closure's information in the edge's frame (the new keyframe as the match placed it;
// PoseGraph's EdgeError). loop_sigma_m both ways when loop_weak_sigma_max_m is 0. Otherwise the
// position part follows the match's J^T J (centre frame): loop_sigma_m along its best-pinned
// direction, loop_sigma_m * sqrt(lambda_max / lambda_min) along the weakest, at most
// loop_weak_sigma_max_m (also for a J^T J with no information at all across it).
Eigen::Matrix3d ClosureInformation(const LoopMatch& match, const SlamOptions& options);

}  // namespace pena::slam::internal
