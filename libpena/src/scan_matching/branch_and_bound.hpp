#pragma once
// Branch and bound over the search window (Olson 2009, "Real-time correlative scan matching";
// Hess et al. 2016). Per heading, the xy candidates form a tree: a node covering h x h candidates is
// bounded by summing, per scan point, the maximum of the hit grid over the h x h cells it could
// land on (precomputed max-grids, one per h), times the prior penalty at the node's candidate
// closest to the prior (the penalty's maximum over the node; 1 when the penalty is off). Bounds
// never underestimate, so pruning keeps the exact optimum of the exhaustive search; ties are
// broken by the same order (window_grid.hpp).

#include "max_grids.hpp"
#include "pena/scan_matching/hit_grid.hpp"
#include "window_grid.hpp"

namespace pena::scan_matching::internal {

// The quadtree depth the window needs: 2^TopLevel covers the larger xy candidate count.
int TopLevel(const WindowGrid& grid);

// The best candidate of the window; `scored` counts the nodes whose bound or score was computed.
// `max_grids` must have been built for grid.step_cells with at least TopLevel(grid) + 1 levels.
Candidate BranchAndBound(const HitGrid& hits, const MaxGrids& max_grids, const Points2& scan,
                         const geometry::Pose2& reference_from_prior, const WindowGrid& grid,
                         long& scored);

}  // namespace pena::scan_matching::internal
