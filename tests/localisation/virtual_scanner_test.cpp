#include "pena/localisation/virtual_scanner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "building_plan.hpp"

namespace pena::localisation {
namespace {

using geometry::Segment2;

// The nearest hit by testing every segment: what the index must reproduce.
double BruteForce(const std::vector<Segment2>& plan, const Eigen::Vector2d& origin,
                  const Eigen::Vector2d& direction, double max_range_m) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment2& s : plan) {
    const auto range = geometry::RaySegmentIntersection(origin, direction, s);
    if (range && *range < best) best = *range;
  }
  return best < max_range_m ? best : std::numeric_limits<double>::infinity();
}

TEST(VirtualScanner, MatchesBruteForceOnRandomSegments) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-10.0, 30.0), angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> length(0.2, 8.0);
  std::vector<Segment2> plan;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector2d a(coord(rng), coord(rng));
    const double t = angle(rng), l = length(rng);
    plan.push_back({a, a + l * Eigen::Vector2d(std::cos(t), std::sin(t))});
  }
  for (double cell : {0.3, 1.0, 4.0}) {
    const VirtualScanner scanner(plan, {cell});
    for (int i = 0; i < 3000; ++i) {
      // Origins also outside the plan's box, so rays enter the grid from outside.
      const Eigen::Vector2d origin(coord(rng) * 1.5 - 5.0, coord(rng) * 1.5 - 5.0);
      const double t = angle(rng);
      const Eigen::Vector2d direction(std::cos(t), std::sin(t));
      const double expected = BruteForce(plan, origin, direction, 25.0);
      const double got = scanner.CastRay(origin, direction, 25.0);
      if (std::isinf(expected)) {
        EXPECT_TRUE(std::isinf(got)) << "cell " << cell << " ray " << i;
      } else {
        EXPECT_NEAR(got, expected, 1e-9) << "cell " << cell << " ray " << i;
      }
    }
  }
}

TEST(VirtualScanner, AxisAlignedRaysInARoomGrid) {
  const VirtualScanner scanner(testing::RoomGrid(3, 3, 4.0));
  // From (5, 5) in room (1, 1): walls at x = 4 and 8, y = 4 and 8 (doors at the middles 6 +- 0.5).
  EXPECT_NEAR(scanner.CastRay({5.0, 5.0}, {1.0, 0.0}, 30.0), 3.0, 1e-12);
  EXPECT_NEAR(scanner.CastRay({5.0, 5.0}, {-1.0, 0.0}, 30.0), 1.0, 1e-12);
  EXPECT_NEAR(scanner.CastRay({5.0, 5.0}, {0.0, -1.0}, 30.0), 1.0, 1e-12);
  // Through the door at y = 6 on the east wall x = 8, on to the next wall at x = 12 ... door again
  // at (12, 6) and the outer wall at x = 12 is the last: it has a door too, so nothing.
  EXPECT_TRUE(std::isinf(scanner.CastRay({5.0, 6.0}, {1.0, 0.0}, 30.0)));
  EXPECT_TRUE(std::isinf(scanner.CastRay({5.0, 5.0}, {1.0, 0.0}, 2.5)));  // beyond max range
}

TEST(VirtualScanner, BeamsThatHitNothingAreNoReturns) {
  const VirtualScanner scanner({{{0.0, -1.0}, {0.0, 1.0}}});
  const sensors::LaserGeometry laser{-std::numbers::pi / 2, std::numbers::pi / 2, 10.0};
  // Facing the wall at 2 m: beams at -90, 0, +90 deg; only the middle one hits.
  const sensors::LaserScan scan = scanner.Scan({-2.0, 0.0, 0.0}, laser, 3, 5.0);
  ASSERT_EQ(scan.ranges_m.size(), 3u);
  EXPECT_EQ(scan.ranges_m[0], sensors::LaserScan::kNoReturn);
  EXPECT_NEAR(scan.ranges_m[1], 2.0f, 1e-6f);
  EXPECT_EQ(scan.ranges_m[2], sensors::LaserScan::kNoReturn);
  EXPECT_EQ(scan.stamp_s, 5.0);
  EXPECT_EQ(scan.CountReturns(), 1u);
}

TEST(VirtualScanner, EmptyPlanSeesNothing) {
  const VirtualScanner scanner({});
  EXPECT_TRUE(std::isinf(scanner.CastRay({0.0, 0.0}, {1.0, 0.0}, 10.0)));
}

TEST(VirtualScanner, RejectsBadCellSize) {
  EXPECT_THROW(VirtualScanner({}, {0.0}), std::invalid_argument);
  EXPECT_THROW(VirtualScanner({{{0.0, 0.0}, {1e6, 1e6}}}, {0.01}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation
