#pragma once
// Operator-assisted localisation (paper section 4.1): the operator fixes a trajectory by hand on
// the map. A heading error is fixed by three points (rotation origin, a point in the wrong
// direction, the same point in the correct direction); a position error by a point and its correct
// position. Each correction applies from a chosen time onward. pena-console draws them and
// pena-fusion applies them; both keep the list (ordered, undone from its end) with its ids.

#include <Eigen/Core>
#include <variant>

#include "pena/geometry/pose2.hpp"

namespace pena::localisation {

// Rotate the trajectory about `origin_m` so that the direction origin -> wrong_m becomes
// origin -> correct_m (map frame, metres), for poses stamped at or after from_stamp_s.
struct RotationCorrection {
  double from_stamp_s = 0.0;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d wrong_m = Eigen::Vector2d::UnitX();
  Eigen::Vector2d correct_m = Eigen::Vector2d::UnitX();
};

// Translate the trajectory so that `point_m` moves to `correct_m` (map frame, metres), for poses
// stamped at or after from_stamp_s.
struct TranslationCorrection {
  double from_stamp_s = 0.0;
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d correct_m = Eigen::Vector2d::Zero();
};

// One operator correction.
using OperatorCorrection = std::variant<RotationCorrection, TranslationCorrection>;

// The rigid transform corrected_from_wrong (map frame) a correction applies. Throws
// std::invalid_argument if a rotation's wrong or correct point coincides with its origin.
geometry::Pose2 CorrectionTransform(const OperatorCorrection& correction);

// Stamp from which the correction applies, seconds.
double FromStamp(const OperatorCorrection& correction);

}  // namespace pena::localisation
