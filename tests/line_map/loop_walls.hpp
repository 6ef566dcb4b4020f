#pragma once
// Synthetic line-map input: the walls of a loop corridor and the jittered, overlapping pieces an
// extractor would report batch by batch while an entity walks the loop.

#include <cstdint>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/line_map/line_segment.hpp"

namespace pena::line_map::testing {

// The true walls: a 2 m wide corridor around a 16 m x 8 m block, with doorways, metres.
std::vector<geometry::Segment2> LoopWalls();

// A segment from (x0, y0) to (x1, y1) with `observations` hits and matching support.
LineSegment Piece(double x0, double y0, double x1, double y1, double observations = 50.0);

// What the extractor reports per batch while walking the loop `passes` times: for each stop
// (every 4 m), the parts of the walls within 5 m, endpoints jittered by `jitter_m`
// (1 sigma) across and along the wall.
std::vector<std::vector<LineSegment>> WalkLoop(int passes, double jitter_m, std::uint64_t seed);

// Sum of segment lengths in metres.
double TotalLength(const std::vector<LineSegment>& segments);

}  // namespace pena::line_map::testing
