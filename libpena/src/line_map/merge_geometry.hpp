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
// `span_only` parts (bounded drift) do not move the line: they only widen its span and enter the
// fit error; their counts are not added, since they do not support the line where it lies.
LineSegment Refit(const std::vector<const LineSegment*>& parts,
                  const std::vector<const LineSegment*>& span_only = {});

// How much a part pulls a refit: hits if the extractor counted them, else cells, else length.
double Weight(const LineSegment& part);

// `line` with its ends swapped if it points against `reference`.
LineSegment OrientLike(LineSegment line, const geometry::Segment2& reference);

// True if both endpoints of `piece` lie within `band_m` of the infinite line through `line`.
bool WithinBand(const geometry::Segment2& piece, const geometry::Segment2& line, double band_m);

}  // namespace pena::line_map::detail
