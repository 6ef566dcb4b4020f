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
  // A wall of the team's global map: how many entities saw it (their walls are in it or were
  // withheld as its copies; the plan not counted) and the estimated sd of its position error,
  // 1 cm quanta (docs/fusion.md, "The global map"). Both 0 in an entity's own map.
  std::uint32_t seen_by_entities = 0;
  double error_sd_m = 0.0;
};

}  // namespace pena::line_map
