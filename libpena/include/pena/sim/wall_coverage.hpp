#pragma once
// Which parts of the true walls a laser actually hit: each wall is cut into short bins, beams mark
// bins, and runs of marked bins become the observed segments (DIR/observed.csv).

#include <cstddef>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::sim {

// Bin size and how small a gap between hit runs is bridged.
struct WallCoverageOptions {
  double bin_m = 0.05;     // target bin length; each wall gets round(length / bin_m) >= 1 bins
  double max_gap_m = 0.1;  // runs separated by at most this many metres of unhit bins are merged
};

// A hit part of one wall.
struct ObservedSegment {
  std::size_t wall_index = 0;  // index into the scenario's walls
  geometry::Segment2 segment;  // mission frame, metres; lies on the wall
};

// Hit bins over all walls of one building.
class WallCoverage {
 public:
  // Throws std::invalid_argument unless bin_m > 0 and max_gap_m >= 0.
  explicit WallCoverage(const std::vector<geometry::Segment2>& walls,
                        const WallCoverageOptions& options = {});

  // Marks the bin at `along_m` metres from the start of wall `wall_index`; out-of-range is clamped.
  void Mark(std::size_t wall_index, double along_m);
  // The hit parts of all walls, in wall order then along each wall.
  std::vector<ObservedSegment> Segments() const;

 private:
  std::vector<geometry::Segment2> walls_;
  WallCoverageOptions options_;
  std::vector<std::vector<bool>> hit_;  // per wall, per bin
};

}  // namespace pena::sim
