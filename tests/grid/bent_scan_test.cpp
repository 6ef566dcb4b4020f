// Bent scans (docs/grid.md, "Bent scans"): a scan whose plane is tilted is found from the floor
// hits that end where a level walk saw through, and levelled back to horizontal ranges.
#include "pena/grid/bent_scan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "grid_test_util.hpp"

namespace pena::grid {
namespace {

constexpr double kLaserHeightM = 1.2;
constexpr double kCorridorHalfWidthM = 1.0;  // walls at y = -1 and y = +1
constexpr double kCorridorEndM = 20.0;       // end wall at x = 20
constexpr int kBeams = 361;                  // -90 .. +90 deg, 0.5 deg apart
constexpr double kIncrementRad = std::numbers::pi / 360.0;

double BeamAngle(int i) { return -std::numbers::pi / 2 + i * kIncrementRad; }

// Horizontal distance from (x, 0) along world direction `angle_rad` to the corridor's walls.
double WallDistanceM(double x_m, double angle_rad) {
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
sensors::LaserScan TiltedScan(double x_m, double tilt_rad, double normal_rad = 0.0) {
  std::vector<float> ranges(kBeams);
  for (int i = 0; i < kBeams; ++i) {
    const double a = BeamAngle(i);
    const double sin_down = std::sin(tilt_rad) * std::cos(a - normal_rad);
    const double cos_elevation = std::sqrt(1.0 - sin_down * sin_down);
    double range = WallDistanceM(x_m, a) / cos_elevation;
    if (sin_down > 1e-9) range = std::min(range, kLaserHeightM / sin_down);
    ranges[static_cast<std::size_t>(i)] = static_cast<float>(range);
  }
  return testing::MakeScan(ranges, -std::numbers::pi / 2, kIncrementRad);
}

// The grid of a level walk down the corridor from x = 0 to x = 6.
OccupancyGrid LevelWalk() {
  OccupancyGrid grid;
  for (double x = 0.0; x <= 6.0; x += 0.25) grid.Insert(TiltedScan(x, 0.0), {x, 0.0, 0.0});
  return grid;
}

TEST(BentScan, FindsTheFloorLineOfAPitchedScanAndNotOfALevelOne) {
  const OccupancyGrid walk = LevelWalk();
  const BentScanLeveller leveller;
  EXPECT_FALSE(leveller.FloorLineOf(walk, TiltedScan(3.0, 0.0), {3.0, 0.0, 0.0}));
  const double pitch = 15.0 * std::numbers::pi / 180.0;
  const auto floor = leveller.FloorLineOf(walk, TiltedScan(3.0, pitch), {3.0, 0.0, 0.0});
  ASSERT_TRUE(floor);
  EXPECT_NEAR(floor->distance_m, kLaserHeightM / std::sin(pitch), 0.05);  // 4.64 m
  EXPECT_NEAR(floor->normal.x(), 1.0, 0.01);
  // A mild lean (4 deg) meets the floor 17 m ahead: beyond max_ahead_m, not judged bent.
  EXPECT_FALSE(leveller.FloorLineOf(walk, TiltedScan(3.0, 4.0 * std::numbers::pi / 180.0),
                                    {3.0, 0.0, 0.0}));
}

TEST(BentScan, LevellingRestoresTheHorizontalRangesOfATiltWithRoll) {
  const OccupancyGrid walk = LevelWalk();
  const BentScanLeveller leveller;
  // Tilted 14 deg about an axis turned 25 deg (pitch with roll): the floor line's normal too.
  const double tilt = 14.0 * std::numbers::pi / 180.0;
  const double normal = 25.0 * std::numbers::pi / 180.0;
  const sensors::LaserScan bent = TiltedScan(3.0, tilt, normal);
  const auto floor = leveller.FloorLineOf(walk, bent, {3.0, 0.0, 0.0});
  ASSERT_TRUE(floor);
  EXPECT_NEAR(std::atan2(floor->normal.y(), floor->normal.x()), normal, 0.02);
  const sensors::LaserScan level = leveller.Level(bent, *floor);
  int walls = 0;
  int dropped = 0;
  double worst_m = 0.0;
  double worst_raw_m = 0.0;
  for (int i = 0; i < kBeams; ++i) {
    const auto index = static_cast<std::size_t>(i);
    if (std::isnan(level.ranges_m[index])) {
      ++dropped;
      continue;
    }
    const double truth_m = WallDistanceM(3.0, BeamAngle(i));
    worst_m = std::max(worst_m, std::abs(level.ranges_m[index] - truth_m));
    worst_raw_m = std::max(worst_raw_m, std::abs(bent.ranges_m[index] - truth_m));
    ++walls;
  }
  EXPECT_GT(dropped, 20);  // the floor hits ahead
  EXPECT_GT(walls, 200);
  EXPECT_GT(worst_raw_m, 0.05);   // the slant ranges put walls up to this far behind them
  EXPECT_LT(worst_m, 0.01);       // levelled: within a centimetre
}

TEST(BentScan, RefusesBadOptionsNamingTheField) {
  BentScanOptions options;
  options.laser_height_m = 0.0;
  try {
    ValidateBentScanOptions(options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("bent_scan.laser_height_m"), std::string::npos);
  }
  options = {};
  options.max_ahead_m = options.min_ahead_m;
  EXPECT_THROW(ValidateBentScanOptions(options), std::invalid_argument);
  EXPECT_NO_THROW(ValidateBentScanOptions({}));
}

TEST(BentScan, LevellerRefusesBadOptionsAtConstruction) {
  BentScanOptions options;
  options.floor_band = 1.0;
  try {
    const BentScanLeveller leveller(options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("bent_scan.floor_band"), std::string::npos);
  }
  EXPECT_NO_THROW(BentScanLeveller{});
}

}  // namespace
}  // namespace pena::grid
