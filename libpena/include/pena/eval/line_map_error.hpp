#pragma once
// A line map judged against the true walls the laser saw (the simulator's observed.csv): coverage,
// precision and fragmentation (definitions in docs/line-extraction.md).

#include <cstddef>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::eval {

// Tolerances of the comparison.
struct LineMapErrorOptions {
  double distance_m = 0.10;     // a point matches a segment within this distance
  double angle_rad = 0.17453292519943295;  // coverage also needs directions within this (10 deg)
  double sample_step_m = 0.01;  // segments are judged at points at most this far apart
  // A map segment counts as a fragment of a wall when it covers at least this much of it (or half
  // of a wall shorter than twice this), so a neighbour's end grazing a wall is not a fragment (an
  // end covers distance_m beyond itself, plus any overshoot).
  double min_fragment_m = 0.25;
};

// Lengths in metres; ratios in [0, 1] (0 when the denominator is empty).
struct LineMapErrorSummary {
  std::size_t map_segments = 0;
  std::size_t walls = 0;
  double wall_length_m = 0.0;     // total observed wall length
  double covered_length_m = 0.0;  // wall length within distance_m and angle_rad of a map segment
  double map_length_m = 0.0;      // total map segment length
  double precise_length_m = 0.0;  // map length within distance_m of a wall
  double coverage = 0.0;          // covered_length_m / wall_length_m
  double precision = 0.0;         // precise_length_m / map_length_m
  // Mean number of map segments covering a wall, over the walls with at least one (1 = ideal).
  double fragmentation = 0.0;
  std::size_t walls_matched = 0;  // walls with at least one fragment
};

// Compares `map` with `walls` (same frame, metres). Throws std::invalid_argument for tolerances
// that are not > 0 (distance_m, sample_step_m), in [0, pi/2] (angle_rad) or >= 0 (min_fragment_m).
LineMapErrorSummary EvaluateLineMap(const std::vector<geometry::Segment2>& map,
                                    const std::vector<geometry::Segment2>& walls,
                                    const LineMapErrorOptions& options = {});

}  // namespace pena::eval
