// Returns where an earlier scan saw through (odometry::internal::SeenThroughPoints): a bend's
// floor line across a corridor that the scans before the bend saw go on is dropped; the walls are
// kept, also seen again from farther along; a scan that returned nothing says nothing.
#include "../../libpena/src/odometry/seen_through_points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

namespace pena::odometry::internal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A 2 m wide corridor along +x (walls at y = +-1 m) ending at x = 30 m; a scan from (x_m, 0)
// heading +x, 0.5 deg beams over 180 deg. With floor_line_m, the laser is pitched down and hits
// the floor on the line floor_line_m ahead wherever the beam gets there before a wall.
sensors::LaserScan CorridorScan(double x_m, std::optional<double> floor_line_m) {
  sensors::LaserScan scan;
  scan.geometry = {-90.0 * kDeg, 0.5 * kDeg, 30.0};
  for (int beam = 0; beam <= 360; ++beam) {
    const double angle = (-90.0 + 0.5 * beam) * kDeg;
    const double c = std::cos(angle), s = std::sin(angle);
    double range = std::numeric_limits<double>::infinity();
    if (std::abs(s) > 1e-9) range = 1.0 / std::abs(s);          // a side wall
    if (c > 1e-9) range = std::min(range, (30.0 - x_m) / c);     // the end wall
    if (floor_line_m && c > 1e-9) range = std::min(range, *floor_line_m / c);
    scan.ranges_m.push_back(range < 30.0 ? static_cast<float>(range) : sensors::LaserScan::kNoReturn);
  }
  return scan;
}

struct Split {
  int floor = 0, floor_marked = 0, walls = 0, walls_marked = 0;
};

// Marks the returns of a scan at x_m against earlier scans, and counts them by kind.
Split MarkAt(const SeenThroughPoints& seen, double x_m, double floor_line_m) {
  const sensors::LaserScan scan = CorridorScan(x_m, floor_line_m);
  const scan_matching::Points2 points = scan_matching::ScanToPoints(scan, 0.1);
  const std::vector<bool> marked = seen.Find(points, {x_m, 0.0, 0.0});
  Split split;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool on_floor = std::abs(points[i].x() - floor_line_m) < 1e-3 && std::abs(points[i].y()) < 1.0 - 1e-3;
    (on_floor ? split.floor : split.walls) += 1;
    (on_floor ? split.floor_marked : split.walls_marked) += marked[i] ? 1 : 0;
  }
  return split;
}

TEST(SeenThroughPoints, DropsABendsFloorLineWhereEarlierScansSawTheCorridorGoOn) {
  SeenThroughPoints seen;
  for (int k = 0; k < 4; ++k) {
    const double x = 8.0 + 0.3 * k;
    seen.Remember(CorridorScan(x, std::nullopt), {x, 0.0, 0.0});
  }
  const Split split = MarkAt(seen, 9.5, 4.0);  // bent over: the floor 4 m ahead
  ASSERT_GT(split.floor, 20);
  // Near a side wall the earlier beams ended on that wall, within the margin of the line: those
  // few returns cannot be told from the wall and are kept (43 of 51 here are marked).
  EXPECT_GE(split.floor_marked, split.floor * 3 / 4);
  EXPECT_EQ(split.walls_marked, 0);
}

TEST(SeenThroughPoints, KeepsTheWallsAndAFloorLineNoEarlierScanSawPast) {
  SeenThroughPoints seen;
  EXPECT_EQ(MarkAt(seen, 9.5, 4.0).floor_marked, 0);  // nothing remembered yet
  // An earlier scan bent over too: it saw the floor line 4 m ahead of itself, so it never saw
  // past the line 4 m ahead of the later scan, 0.3 m farther on.
  seen.Remember(CorridorScan(9.2, 4.0), {9.2, 0.0, 0.0});
  const Split split = MarkAt(seen, 9.5, 4.0);
  EXPECT_EQ(split.floor_marked, 0);
  EXPECT_EQ(split.walls_marked, 0);
}

TEST(SeenThroughPoints, AScanThatReturnedNothingSaysNothing) {
  // In smoke a beam ends without a return as it does in open space: no evidence of free space.
  sensors::LaserScan blind = CorridorScan(8.0, std::nullopt);
  for (float& r : blind.ranges_m) r = sensors::LaserScan::kNoReturn;
  SeenThroughPoints seen;
  seen.Remember(blind, {8.0, 0.0, 0.0});
  EXPECT_EQ(MarkAt(seen, 9.5, 4.0).floor_marked, 0);
}

TEST(SeenThroughPoints, ForgetsScansOlderThanTheHistory) {
  SeenThroughOptions options;
  options.history_scans = 2;
  SeenThroughPoints seen(options);
  seen.Remember(CorridorScan(8.0, std::nullopt), {8.0, 0.0, 0.0});
  for (int k = 0; k < 2; ++k) seen.Remember(CorridorScan(9.2, 4.0), {9.2, 0.0, 0.0});
  EXPECT_EQ(MarkAt(seen, 9.5, 4.0).floor_marked, 0);
}

}  // namespace
}  // namespace pena::odometry::internal
