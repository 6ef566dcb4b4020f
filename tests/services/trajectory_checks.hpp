#pragma once
// Two runs of the chain compared pose by pose (service tests: a live run against a file run, the
// service against `pena odometry`).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/trajectory.hpp"

namespace pena::services::testing {

// Both trajectories hold the same stamps (more than 40 of them), and no pose of `other` lies
// further than tolerance_m / tolerance_rad from `reference`'s. Prints the largest differences,
// with `what` naming the two runs.
inline void ExpectSameTrajectory(const std::string& id, const geometry::Trajectory& reference,
                                 const geometry::Trajectory& other, const std::string& what,
                                 double tolerance_m, double tolerance_rad) {
  ASSERT_EQ(other.size(), reference.size()) << id;
  ASSERT_GT(reference.size(), 40u) << id;
  double max_position_m = 0.0;
  double max_heading_rad = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    ASSERT_EQ(other[i].stamp_s, reference[i].stamp_s) << id << " pose " << i;
    const geometry::Pose2& a = reference[i].pose;
    const geometry::Pose2& b = other[i].pose;
    max_position_m = std::max(max_position_m, std::hypot(a.x_m - b.x_m, a.y_m - b.y_m));
    max_heading_rad =
        std::max(max_heading_rad, std::abs(geometry::NormalizeAngle(a.theta_rad - b.theta_rad)));
  }
  std::cout << id << ": " << reference.size() << " poses, largest difference " << what << " "
            << max_position_m << " m, " << max_heading_rad << " rad\n";
  EXPECT_LE(max_position_m, tolerance_m) << id;
  EXPECT_LE(max_heading_rad, tolerance_rad) << id;
}

}  // namespace pena::services::testing
