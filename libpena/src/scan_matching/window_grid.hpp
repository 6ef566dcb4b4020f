#pragma once
// Shared by the exhaustive and the branch-and-bound search: the window as integer indices and the
// scan discretised once per heading, so both searches score exactly the same candidates.

#include <Eigen/Core>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "pena/scan_matching/hit_grid.hpp"

namespace pena::scan_matching::internal {

// Candidate i along an axis has the centred offset i - center_*; xy offsets move step_cells cells.
struct WindowGrid {
  int num_angles = 1, num_x = 1, num_y = 1;
  int center_angle = 0, center_x = 0, center_y = 0;
  int step_cells = 1;
  double step_xy_m = 0.0;
  double step_theta_rad = 0.0;
};

// A scored candidate; the total order Better() makes every search agree on ties.
struct Candidate {
  int angle = 0, x = 0, y = 0;
  long score = -1;  // sum of hit-grid weights
  long distance_sq = 0;  // squared centred index distance to the prior
};

WindowGrid MakeWindowGrid(const SearchWindow& window, const CorrelationMatcherOptions& options);

// Higher score first; on ties the candidate nearer the prior, then the lower indices.
bool Better(const Candidate& a, const Candidate& b);

long DistanceSq(const WindowGrid& grid, int angle, int x, int y);

// A candidate with its distance to the prior.
Candidate MakeCandidate(const WindowGrid& grid, int angle, int x, int y, long score);

// Cells of the scan rotated to heading index `angle` and placed at the lowest xy offset.
std::vector<Eigen::Vector2i> DiscretizeScan(const HitGrid& hits, const Points2& scan,
                                            const geometry::Pose2& reference_from_prior,
                                            const WindowGrid& grid, int angle);

// The pose of a candidate.
geometry::Pose2 PoseOf(const WindowGrid& grid, const geometry::Pose2& reference_from_prior,
                       const Candidate& candidate);

}  // namespace pena::scan_matching::internal
