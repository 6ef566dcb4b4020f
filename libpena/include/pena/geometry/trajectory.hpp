#pragma once
// Timestamped poses and relative-motion measurements between them.

#include <vector>

#include "pena/geometry/pose2.hpp"

namespace pena::geometry {

// A pose of the body in the trajectory's frame at one instant.
struct StampedPose2 {
  double stamp_s = 0.0;
  Pose2 pose;
};

// Poses in increasing stamp order.
using Trajectory = std::vector<StampedPose2>;

// A Freiburg relation: the motion Between(pose(t1), pose(t2)) (Kuemmerle et al. 2009).
struct Relation {
  double t1_s = 0.0;
  double t2_s = 0.0;
  Pose2 motion;
};

}  // namespace pena::geometry
