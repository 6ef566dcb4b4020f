#pragma once
// Small helpers of the grid tests: scans built beam by beam.

#include <utility>
#include <vector>

#include "pena/sensors/laser_scan.hpp"

namespace pena::grid::testing {

// A scan with the given ranges, beams `increment_rad` apart starting at `angle_min_rad`.
inline sensors::LaserScan MakeScan(std::vector<float> ranges_m, double angle_min_rad = 0.0,
                                   double increment_rad = 0.0, double sensor_max_m = 30.0) {
  sensors::LaserScan scan;
  scan.geometry = {angle_min_rad, increment_rad, sensor_max_m};
  scan.ranges_m = std::move(ranges_m);
  return scan;
}

// The centre of world cell (i, j) at `resolution_m`, as a laser pose heading `theta_rad`.
inline geometry::Pose2 CellCentre(int i, int j, double theta_rad = 0.0,
                                  double resolution_m = 0.05) {
  return {(i + 0.5) * resolution_m, (j + 0.5) * resolution_m, theta_rad};
}

}  // namespace pena::grid::testing
