#pragma once
// The paper's correlation-based scan matcher (section 2): poses on an even grid around the prior
// are scored by the fraction of scan points whose nearest reference point is within a threshold
// (eq. 2); the best is refined by least squares on its nearest-neighbour pairs. Besides the
// exhaustive search of the paper, a branch-and-bound search (Olson 2009; Cartographer's fast
// correlative matcher) returns the same best grid pose for wide windows at a fraction of the cost.

#include <Eigen/Core>
#include <memory>

#include "pena/geometry/pose2.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::scan_matching {

// Options of the matcher. Validated by the constructor.
struct CorrelationMatcherOptions {
  double threshold_m = 0.06;        // eq. 2's t_h: a scan point is a hit within this distance
  double grid_resolution_m = 0.02;  // lookup grid cell; window steps are multiples of it
  int refine_iterations = 8;        // least-squares rounds on nearest-neighbour pairs
  int min_refine_pairs = 10;        // fewer pairs: keep the grid pose
  // Beyond the paper: rank poses by how close their hits are (weight 1 - (d/t_h)^2) rather than
  // by the count alone. In clutter, eq. 2 saturates over a wide range of poses and the search
  // then follows the prior; the graded score keeps a single peak. MatchResult::score stays eq. 2.
  bool graded = true;
};

// The searched poses: the prior in the middle, full extents (the paper: 60 cm x 36 cm x 3 deg at
// 6 cm and 0.6 deg). x and y are along the reference frame's axes.
struct SearchWindow {
  double size_x_m = 0.60;
  double size_y_m = 0.36;
  double size_theta_rad = 0.05235987755982988;  // 3 deg
  double step_xy_m = 0.06;
  double step_theta_rad = 0.010471975511965976;  // 0.6 deg
};

// True if `grid_pose` (MatchResult::grid_pose) is among the outermost candidates of `window`
// around `prior` in x, y or heading: the optimum may lie outside, so the match is not evidence.
bool OnWindowEdge(const geometry::Pose2& grid_pose, const geometry::Pose2& prior,
                  const SearchWindow& window);

// What a match found; failure is data (converged = false), not an exception.
struct MatchResult {
  bool converged = false;                 // at least one scan point hit
  geometry::Pose2 reference_from_scan;    // refined pose
  geometry::Pose2 grid_pose;              // best pose of the search grid, before refinement
  double score = 0.0;                     // eq. 2 at grid_pose: hits / points, in [0, 1]
  int hits = 0;                           // scan points within the threshold at grid_pose
  long weight = 0;                        // the searched (graded) score at grid_pose
  int points = 0;
  long candidates_scored = 0;             // poses (or B&B nodes) scored: the work done
  double max_grids_s = 0.0;  // wall time building branch and bound's max-grids (first use; profiling)
  // J^T J of the point-to-line residuals at the refined pose, (x_m, y_m, theta_rad): a small
  // eigenvalue marks a direction the scan does not constrain (a featureless corridor).
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
};

// Whether a search ends with the least-squares refinement of its best grid pose, or leaves
// reference_from_scan at the grid pose and information zero for a later Refine: a caller that
// compares several searches (grown windows, other priors) refines only the one it keeps.
enum class Polish { kRefine, kGridPoseOnly };

// Matches scans against one reference point set (a reference scan or a small local map).
// One instance per thread.
class CorrelationScanMatcher {
 public:
  // Builds the hit lookup and the nearest-neighbour index of the reference (its own frame).
  // Throws std::invalid_argument naming the option if one is out of range.
  CorrelationScanMatcher(const CorrelationMatcherOptions& options, const Points2& reference);
  ~CorrelationScanMatcher();
  CorrelationScanMatcher(CorrelationScanMatcher&&) noexcept;
  CorrelationScanMatcher& operator=(CorrelationScanMatcher&&) noexcept;

  // The paper's algorithm: every pose of the window is scored.
  MatchResult MatchExhaustive(const Points2& scan, const geometry::Pose2& reference_from_prior,
                              const SearchWindow& window, Polish polish = Polish::kRefine) const;

  // Same best grid pose as MatchExhaustive (same score, same tie-break), found by branch and
  // bound over max-grids built on first use per step and cached (so not thread-safe).
  MatchResult MatchBranchAndBound(const Points2& scan, const geometry::Pose2& reference_from_prior,
                                  const SearchWindow& window, Polish polish = Polish::kRefine) const;

  // The refinement of a result of this matcher found with Polish::kGridPoseOnly: the same
  // reference_from_scan and information as a search with Polish::kRefine would have given.
  void Refine(const Points2& scan, MatchResult& result) const;

  // Eq. 2 for one pose: fraction of scan points within the threshold of a reference point.
  double Score(const Points2& scan, const geometry::Pose2& reference_from_scan) const;

  const CorrelationMatcherOptions& options() const { return options_; }

 private:
  struct Impl;
  CorrelationMatcherOptions options_;
  std::unique_ptr<Impl> impl_;
};

// Throws std::invalid_argument naming the field if an option is out of range (the constructor
// calls it; so does ValidateWindow, so that option checks of the matcher's users catch it early).
void ValidateOptions(const CorrelationMatcherOptions& options);

// Throws std::invalid_argument naming the field if the window is unusable for these options
// (non-positive sizes or steps, xy step not a whole number of grid cells) or an option is.
void ValidateWindow(const SearchWindow& window, const CorrelationMatcherOptions& options);

}  // namespace pena::scan_matching
