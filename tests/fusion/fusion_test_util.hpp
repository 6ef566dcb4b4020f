#pragma once
// Small builders shared by the fusion tests.

#include <cmath>
#include <string>
#include <vector>

#include "pena/fusion/fusion_state.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::fusion::test {

// A wall from (x1, y1) to (x2, y2) with `observations` hits behind it, solid on a 5 cm grid.
inline line_map::LineSegment Wall(double x1, double y1, double x2, double y2,
                                  double observations = 100.0) {
  line_map::LineSegment wall;
  wall.segment.start_m = {x1, y1};
  wall.segment.end_m = {x2, y2};
  wall.support_cells = std::round(20.0 * geometry::Length(wall.segment));
  wall.observations = observations;
  return wall;
}

// Walls as a sender's LineMap would publish them: integrated into `map` as `source`.
inline line_map::MapDelta Observe(line_map::LineMap& map, const std::vector<line_map::LineSegment>& walls,
                                  const std::string& source) {
  return map.Integrate(walls, source);
}

// The same walls moved by a_from_b (walls given in frame b).
inline std::vector<line_map::LineSegment> Moved(const geometry::Pose2& a_from_b,
                                                std::vector<line_map::LineSegment> walls) {
  for (line_map::LineSegment& wall : walls) {
    wall.segment.start_m = geometry::TransformPoint(a_from_b, wall.segment.start_m);
    wall.segment.end_m = geometry::TransformPoint(a_from_b, wall.segment.end_m);
  }
  return walls;
}

// True if the two global snapshots hold the same version and bit-identical segments.
inline bool SameGlobal(const line_map::MapSnapshot& a, const line_map::MapSnapshot& b) {
  return line_map::SameMap(a, b);
}

}  // namespace pena::fusion::test
