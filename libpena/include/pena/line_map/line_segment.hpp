#pragma once
// A wall of a line map (paper section 3): a segment with what supports it.

#include <cstdint>
#include <string>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::line_map {

// One map segment, world frame, metres.
struct LineSegment {
  std::int64_t id = 0;            // stable within a LineMap
  geometry::Segment2 segment;
  double support_cells = 0.0;     // occupied grid cells behind it
  double observations = 0.0;      // laser hits behind it (sum over merged segments)
  double rms_error_m = 0.0;       // fit quality: RMS distance of the supporting cells to the line
  std::vector<std::string> provenance;  // where it came from (entity ids, merged segment ids)
};

}  // namespace pena::line_map
