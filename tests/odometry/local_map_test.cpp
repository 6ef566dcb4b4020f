// The reference of the laser odometry (odometry::internal::LocalMap) with the confirmation of
// far points and the tilt model's wall-only range (paper eq. 1, Fig. 2b).
#include "../../libpena/src/odometry/local_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pena::odometry::internal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

bool Contains(const scan_matching::Points2& points, const Eigen::Vector2d& point) {
  return std::any_of(points.begin(), points.end(),
                     [&](const Eigen::Vector2d& p) { return (p - point).norm() < 1e-9; });
}

TEST(TiltModel, WallOnlyRangeIsWhereTheFloorFirstAppears) {
  // The paper's example: 1.2 m up, 10 deg pitch: the floor from 6.8 m.
  EXPECT_NEAR(WallOnlyRangeM(1.2, 2.6, 10.0 * kDeg), 1.2 / std::tan(10.0 * kDeg), 1e-12);
  EXPECT_NEAR(WallOnlyRangeM(1.2, 2.6, 10.0 * kDeg), 6.81, 0.01);
  // A low ceiling is nearer than the floor: it bounds the range instead.
  EXPECT_NEAR(WallOnlyRangeM(1.2, 2.0, 10.0 * kDeg), 0.8 / std::tan(10.0 * kDeg), 1e-12);
  EXPECT_EQ(WallOnlyRangeM(1.2, 2.6, 0.0), 0.0);  // no model
}

// Two keyframes at the origin: a near point seen once, far points seen once or by both.
std::vector<Keyframe> TwoKeyframes() {
  return {{geometry::Pose2{}, {{2.0, 0.0}, {8.0, 0.0}, {9.0, 1.0}}},
          {geometry::Pose2{}, {{9.0, 1.0}, {8.5, -3.0}}}};
}

TEST(TiltModel, NearPointsNeedNoConfirmationFarOnesDo) {
  LocalMap map(8, 0.12, true, 5.0);
  for (Keyframe keyframe : TwoKeyframes()) map.Add(std::move(keyframe));
  const scan_matching::Points2 reference = map.Reference();
  EXPECT_TRUE(Contains(reference, {2.0, 0.0}));   // nearer than 5 m: a wall
  EXPECT_TRUE(Contains(reference, {9.0, 1.0}));   // far, seen by both
  EXPECT_FALSE(Contains(reference, {8.0, 0.0}));  // far, seen once: maybe the floor
  EXPECT_FALSE(Contains(reference, {8.5, -3.0}));
  EXPECT_EQ(reference.size(), 3u);
}

TEST(TiltModel, WithoutTheModelEveryPointNeedsConfirmation) {
  LocalMap map(8, 0.12, true, 0.0);
  for (Keyframe keyframe : TwoKeyframes()) map.Add(std::move(keyframe));
  const scan_matching::Points2 reference = map.Reference();
  EXPECT_FALSE(Contains(reference, {2.0, 0.0}));
  EXPECT_EQ(reference.size(), 2u);  // (9, 1) from each keyframe
}

}  // namespace
}  // namespace pena::odometry::internal
