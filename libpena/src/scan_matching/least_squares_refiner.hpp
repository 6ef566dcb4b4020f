#pragma once
// Step 5 of the paper's algorithm: least squares on the nearest-neighbour pairs of the best pose.

#include "nearest_neighbours.hpp"
#include "pena/scan_matching/hit_grid.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "window_grid.hpp"

namespace pena::scan_matching::internal {

// A refined pose and the information matrix J^T J of its point-to-line residuals (x, y, theta).
struct Refinement {
  geometry::Pose2 reference_from_scan;
  Eigen::Matrix3d information;
};

// Gauss-Newton on point-to-line distances to the reference (normals from its neighbourhood),
// re-pairing within the threshold each round. Keeps the start pose with too few pairs.
Refinement RefineLeastSquares(const NearestNeighbours& neighbours,
                                   const CorrelationMatcherOptions& options, const Points2& scan,
                                   const geometry::Pose2& reference_from_scan);

// Scan points on a hit cell (eq. 2's count) at a pose.
int CountHits(const HitGrid& hits, const Points2& scan, const geometry::Pose2& reference_from_scan);

// The searched score (sum of cell weights) at a pose.
long WeightAt(const HitGrid& hits, const Points2& scan, const geometry::Pose2& reference_from_scan);

// Builds the MatchResult of a search's best candidate; refined unless polish says grid pose only.
MatchResult Finish(const NearestNeighbours& neighbours, const HitGrid& hits,
                   const CorrelationMatcherOptions& options, const Points2& scan, const WindowGrid& grid,
                   const geometry::Pose2& reference_from_prior, const Candidate& best, long scored,
                   scan_matching::Polish polish);

// The least-squares polish of a result at its grid pose (reference_from_scan, information).
void RefineResult(const NearestNeighbours& neighbours, const HitGrid& hits,
                  const CorrelationMatcherOptions& options, const Points2& scan, MatchResult& result);

}  // namespace pena::scan_matching::internal
