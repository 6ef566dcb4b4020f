#pragma once
// Branch and bound over the search window (Olson 2009, "Real-time correlative scan matching";
// Hess et al. 2016). Per heading, the xy candidates form a tree: a node covering h x h candidates is
// bounded by summing, per scan point, the maximum of the hit grid over the h x h cells it could
// land on (precomputed max-grids, one per h). Bounds never underestimate, so pruning keeps the
// exact optimum of the exhaustive search; ties are broken by the same order (window_grid.hpp).

#include "pena/scan_matching/hit_grid.hpp"
#include "window_grid.hpp"

namespace pena::scan_matching::internal {

// The best candidate of the window; `scored` counts the nodes whose bound or score was computed.
Candidate BranchAndBound(const HitGrid& hits, const Points2& scan,
                         const geometry::Pose2& reference_from_prior, const WindowGrid& grid,
                         long& scored);

}  // namespace pena::scan_matching::internal
