#pragma once
// Operator-assisted localisation (paper section 4.1): the operator fixes a trajectory by hand on
// the map. A heading error is fixed by three points (rotation origin, a point in the wrong
// direction, the same point in the correct direction); a position error by a point and its correct
// position. Each correction applies from a chosen time onward. Corrections form a list: applied in
// order (each one is given on the trajectory as already corrected by those before it, as the
// operator sees it) and undone from the end.

#include <Eigen/Core>
#include <cstddef>
#include <variant>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/trajectory.hpp"

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

// `trajectory` with one correction applied: poses at or after the correction's stamp are mapped
// by its transform (position and heading); earlier poses are unchanged.
geometry::Trajectory ApplyCorrection(const geometry::Trajectory& trajectory,
                                     const OperatorCorrection& correction);

// An ordered, undoable list of corrections over one raw trajectory.
class OperatorCorrections {
 public:
  // Appends a correction (validated: throws std::invalid_argument like CorrectionTransform).
  void Add(const OperatorCorrection& correction);
  // Removes the last correction; false if there was none.
  bool Undo();
  // Removes every correction.
  void Clear() { corrections_.clear(); }

  // The raw trajectory with every correction applied in order.
  geometry::Trajectory Apply(const geometry::Trajectory& raw) const;
  // The correction for one pose stamped stamp_s: corrected = Compose(transform, raw).
  geometry::Pose2 CorrectedFromRaw(double stamp_s) const;

  const std::vector<OperatorCorrection>& corrections() const { return corrections_; }
  std::size_t size() const { return corrections_.size(); }

 private:
  std::vector<OperatorCorrection> corrections_;
};

}  // namespace pena::localisation
