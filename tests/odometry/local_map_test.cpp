// The reference of the laser odometry (odometry::internal::LocalMap) with the confirmation of
// points: floor and ceiling hits of a tilting body-worn laser move with the person (paper Fig. 2b),
// so a point enters the reference only where another keyframe saw something too.
#include "pena/odometry/internal/local_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace pena::odometry::internal {
namespace {

bool Contains(const scan_matching::Points2& points, const Eigen::Vector2d& point) {
  return std::any_of(points.begin(), points.end(),
                     [&](const Eigen::Vector2d& p) { return (p - point).norm() < 1e-9; });
}

// Two keyframes at the origin: points seen once or by both.
std::vector<Keyframe> TwoKeyframes() {
  return {{geometry::Pose2{}, {{2.0, 0.0}, {8.0, 0.0}, {9.0, 1.0}}},
          {geometry::Pose2{}, {{9.0, 1.0}, {8.5, -3.0}}}};
}

TEST(ReferenceConfirmation, OnlyPointsAnotherKeyframeSawEnterTheReference) {
  LocalMap map(8, 0.12, true);
  for (Keyframe keyframe : TwoKeyframes()) map.Add(std::move(keyframe));
  const scan_matching::Points2 reference = map.Reference();
  EXPECT_FALSE(Contains(reference, {2.0, 0.0}));
  EXPECT_FALSE(Contains(reference, {8.0, 0.0}));
  EXPECT_TRUE(Contains(reference, {9.0, 1.0}));
  EXPECT_EQ(reference.size(), 2u);  // (9, 1) from each keyframe
}

TEST(ReferenceConfirmation, WithoutConfirmationEveryPointIsKept) {
  LocalMap map(8, 0.12, false);
  for (Keyframe keyframe : TwoKeyframes()) map.Add(std::move(keyframe));
  EXPECT_EQ(map.Reference().size(), 5u);
}

}  // namespace
}  // namespace pena::odometry::internal
