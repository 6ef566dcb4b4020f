#pragma once
// The relative-pose error metric of Kuemmerle et al. 2009 ("On measuring the accuracy of SLAM
// algorithms"): compare the estimated motion between two stamps with a ground-truth relation.

#include <cstddef>
#include <vector>

#include "pena/eval/mean_std.hpp"
#include "pena/eval/stamp_matching.hpp"
#include "pena/geometry/trajectory.hpp"

namespace pena::eval {

// How relation stamps are looked up in the estimated trajectory.
struct RelationErrorOptions {
  // A relation stamp matches a trajectory pose within this many seconds; otherwise it is skipped.
  double stamp_tolerance_s = kDefaultStampTolerance_s;
};

// The error of one relation: e = relation.motion^-1 * Between(est(t1), est(t2)).
struct RelationError {
  double t1_s = 0.0;
  double t2_s = 0.0;
  double translation_error_m = 0.0;  // |translation of e|
  double rotation_error_rad = 0.0;   // |yaw of e|, in [0, pi]
};

// The metric over all relations whose two stamps are both in the trajectory.
struct RelationErrorSummary {
  std::size_t relations_used = 0;
  std::size_t relations_skipped = 0;  // a stamp had no pose within the tolerance
  MeanStd translation_m;              // |translational error|, metres
  MeanStd translation_sq_m2;          // squared translational error, m^2
  MeanStd rotation_deg;               // |rotational error|, degrees
  MeanStd rotation_sq_deg2;           // squared rotational error, deg^2
  Spread translation_spread_m;        // median, 95th percentile and max of |translational error|
  Spread rotation_spread_deg;         // the same of |rotational error|, degrees
  std::vector<RelationError> errors;  // one per used relation, in input order
};

// Error of one relation given the two estimated poses (trajectory frame).
RelationError ComputeRelationError(const geometry::Relation& relation,
                                   const geometry::Pose2& world_from_t1,
                                   const geometry::Pose2& world_from_t2);

// Evaluates `estimate` against `relations`. Throws std::invalid_argument if the trajectory is
// invalid (see ValidateTrajectory), there are no relations, or none of them can be used.
RelationErrorSummary EvaluateRelations(const geometry::Trajectory& estimate,
                                       const std::vector<geometry::Relation>& relations,
                                       const RelationErrorOptions& options = {});

}  // namespace pena::eval
