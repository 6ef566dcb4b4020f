#pragma once
// Closed-form least-squares rigid alignment of matched 2D point sets (Horn/Umeyama, no scale).

#include <Eigen/Core>
#include <vector>

#include "pena/geometry/pose2.hpp"

namespace pena::eval {

// The rigid transform target_from_source minimising sum |target_i - T * source_i|^2 over matched
// pairs (metres). Throws std::invalid_argument if the sizes differ or there are fewer than 2 pairs.
geometry::Pose2 AlignRigid2D(const std::vector<Eigen::Vector2d>& source_points_m,
                             const std::vector<Eigen::Vector2d>& target_points_m);

}  // namespace pena::eval
