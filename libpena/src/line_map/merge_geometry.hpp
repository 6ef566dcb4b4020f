#pragma once
// The geometry of merging (docs/line-map.md): when two segments are one wall, and the weighted
// refit of several. Internal to the line_map module.

#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena/line_map/line_segment.hpp"

namespace pena::line_map::detail {

// True if `a` and `b` lie on one wall: nearly parallel, the shorter's endpoints close to the
// longer's line, and overlapping or separated by at most options.max_gap_m along it.
bool SameWall(const geometry::Segment2& a, const geometry::Segment2& b,
              const LineMapOptions& options);

// One segment fitted to all `parts` (non-empty), each weighted by its observations (else support
// cells, else length), spanning the extremes of all of them and oriented like parts[0]. Counts are
// summed, the fit error combines each part's own error with its distance to the new line.
// Id and provenance are left empty; the result is not quantised.
LineSegment Refit(const std::vector<const LineSegment*>& parts);

}  // namespace pena::line_map::detail
