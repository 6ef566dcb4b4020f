#pragma once
// A 2 m wide corridor ending at x = 20 m scanned by a 361-beam laser 1.2 m above the floor, level
// or tilted: the bent-scan tests of the grid module and of the pipeline's stage share it.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "pena/grid/occupancy_grid.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::testing::corridor {

inline constexpr double kLaserHeightM = 1.2;
inline constexpr double kCorridorHalfWidthM = 1.0;  // walls at y = -1 and y = +1
inline constexpr double kCorridorEndM = 20.0;       // end wall at x = 20
inline constexpr int kBeams = 361;                  // -90 .. +90 deg, 0.5 deg apart
inline constexpr double kIncrementRad = std::numbers::pi / 360.0;

inline double BeamAngle(int i) { return -std::numbers::pi / 2 + i * kIncrementRad; }

// Horizontal distance from (x, 0) along world direction `angle_rad` to the corridor's walls.
inline double WallDistanceM(double x_m, double angle_rad) {
  const double c = std::cos(angle_rad);
  const double s = std::sin(angle_rad);
  double d = std::numeric_limits<double>::infinity();
  if (std::abs(s) > 1e-9) d = std::min(d, kCorridorHalfWidthM / std::abs(s));
  if (c > 1e-9) d = std::min(d, (kCorridorEndM - x_m) / c);
  return d;
}

// A scan at (x, 0) heading +x from a laser tilted by `tilt_rad` about the axis perpendicular to
// `normal_rad` (0: pitched straight ahead): beam a falls by sin(tilt) cos(a - normal). Returns the
// slant range to the nearer of the floor and the (vertical) walls, as a laser reports it.
inline sensors::LaserScan TiltedScan(double x_m, double tilt_rad, double normal_rad = 0.0) {
  sensors::LaserScan scan;
  scan.stamp_s = x_m;
  scan.geometry = {-std::numbers::pi / 2, kIncrementRad, 30.0};
  for (int i = 0; i < kBeams; ++i) {
    const double a = BeamAngle(i);
    const double sin_down = std::sin(tilt_rad) * std::cos(a - normal_rad);
    double range = WallDistanceM(x_m, a) / std::sqrt(1.0 - sin_down * sin_down);
    if (sin_down > 1e-9) range = std::min(range, kLaserHeightM / sin_down);
    scan.ranges_m.push_back(static_cast<float>(range));
  }
  return scan;
}

// The grid of a level walk down the corridor from x = 0 to x = 6.
inline grid::OccupancyGrid LevelWalk() {
  grid::OccupancyGrid grid;
  for (double x = 0.0; x <= 6.0; x += 0.25) grid.Insert(TiltedScan(x, 0.0), {x, 0.0, 0.0});
  return grid;
}

}  // namespace pena::testing::corridor
