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

#include "tilted_corridor.hpp"

namespace pena::grid {
namespace {

using namespace testing::corridor;

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
