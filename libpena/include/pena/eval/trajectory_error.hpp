#pragma once
// Absolute error of an estimated trajectory against a ground-truth one (simulated missions, or a
// reference trajectory of a real log).

#include <cstddef>

#include "pena/eval/stamp_matching.hpp"
#include "pena/geometry/trajectory.hpp"

namespace pena::eval {

// How estimate and truth are paired and compared.
struct TrajectoryErrorOptions {
  // An estimated pose is compared with the truth pose within this many seconds, else skipped.
  double stamp_tolerance_s = kDefaultStampTolerance_s;
  // false: compare in the shared frame (simulated missions start in the truth frame).
  // true: first move the estimate by the least-squares rigid transform onto the truth positions.
  bool align = false;
};

// Absolute errors over the matched poses (after alignment if requested).
struct TrajectoryErrorSummary {
  std::size_t poses_matched = 0;
  std::size_t poses_skipped = 0;             // estimated poses with no truth stamp in tolerance
  double translation_rmse_m = 0.0;           // sqrt(mean |p_est - p_true|^2)
  double heading_rmse_deg = 0.0;             // sqrt(mean wrapped heading difference^2)
  double max_translation_error_m = 0.0;      // largest |p_est - p_true|
  double final_position_error_m = 0.0;       // |p_est - p_true| at the last matched stamp
  double max_heading_error_deg = 0.0;        // largest |wrapped heading difference|
  double final_heading_error_deg = 0.0;      // |wrapped heading difference| at the last stamp
  double truth_path_length_m = 0.0;          // truth path from first to last matched stamp
  double final_error_percent_of_path = 0.0;  // 100 * final error / path length (0 if no path)
  geometry::Pose2 truth_from_estimate;       // applied alignment; identity when align is false
};

// Compares `estimate` with `truth`. Throws std::invalid_argument if either trajectory is invalid
// (see ValidateTrajectory), no stamps match, or alignment is asked with fewer than 2 matches.
TrajectoryErrorSummary EvaluateAgainstTruth(const geometry::Trajectory& estimate,
                                            const geometry::Trajectory& truth,
                                            const TrajectoryErrorOptions& options = {});

}  // namespace pena::eval
