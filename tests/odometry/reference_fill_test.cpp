// Densifying a keyframe along its walls (odometry::internal::FillReference).
#include "pena/odometry/internal/reference_fill.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace pena::odometry::internal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Returns of a wall at x = 10 m seen from the origin at 1 deg beams around straight ahead.
scan_matching::Points2 WallAtTenMetres() {
  scan_matching::Points2 points;
  for (int i = -3; i <= 3; ++i) points.emplace_back(10.0, 10.0 * std::tan(i * kDeg));
  return points;
}

TEST(FillReference, FillsAlongAWallBetweenNeighbouringBeams) {
  const scan_matching::Points2 wall = WallAtTenMetres();
  const scan_matching::Points2 filled = FillReference(wall, {}, 0.03, 0.5);
  EXPECT_GT(filled.size(), 5 * wall.size());  // 17.5 cm gaps at 3 cm: 5 points added per gap
  for (std::size_t i = 1; i < filled.size(); ++i) {
    EXPECT_NEAR(filled[i].x(), 10.0, 1e-9);                          // on the wall
    EXPECT_LT((filled[i] - filled[i - 1]).norm(), 0.03 + 1e-9);      // no gap left
  }
}

TEST(FillReference, DoesNotJoinAnEdgeToTheWallBehindIt) {
  // A box edge at 3 m in front of a wall at 10 m: the two returns are neighbours in beam order.
  const scan_matching::Points2 jump = {{3.0, 0.0}, {10.0, 10.0 * std::tan(1.0 * kDeg)}};
  EXPECT_EQ(FillReference(jump, {}, 0.03, 0.5).size(), 2u);
  // Across a 0.9 m doorway (its beams saw nothing): farther apart than the 0.5 m maximum.
  const scan_matching::Points2 doorway = {{10.0, 0.0}, {10.0, 0.9}};
  EXPECT_EQ(FillReference(doorway, {}, 0.03, 0.5).size(), 2u);
}

TEST(FillReference, ZeroSpacingLeavesThePointsAlone) {
  EXPECT_EQ(FillReference(WallAtTenMetres(), {}, 0.0, 0.5).size(), 7u);
}

TEST(FillReference, GrazingBandBeyondTheBeamLimitIsNotFilled) {
  // A wall 1 m to the side seen by the beams at 18 and 19 deg: about 72 deg incidence, the two
  // returns 17 cm apart, 3.2 beam spacings (beyond the limit of 3, within the along-beam cut).
  const scan_matching::Points2 grazing = {{1.0 / std::tan(18.0 * kDeg), 1.0},
                                          {1.0 / std::tan(19.0 * kDeg), 1.0}};
  EXPECT_EQ(FillReference(grazing, {}, 0.03, 0.5, 3.0).size(), 2u);  // the band is not filled
  EXPECT_EQ(FillReference(grazing, {}, 0.03, 0.5, 0.0).size(), 7u);  // no limit: every 3 cm
}

}  // namespace
}  // namespace pena::odometry::internal
