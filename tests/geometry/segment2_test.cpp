#include "pena/geometry/segment2.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace pena::geometry {
namespace {

TEST(Segment2, DistanceClampsToEndpoints) {
  const Segment2 wall{{0.0, 0.0}, {2.0, 0.0}};
  EXPECT_NEAR(DistanceToSegment(wall, {1.0, 0.5}), 0.5, 1e-12);
  EXPECT_NEAR(DistanceToSegment(wall, {3.0, 0.0}), 1.0, 1e-12);
  EXPECT_NEAR(Length(wall), 2.0, 1e-12);
}

TEST(Segment2, RayHitsWallAhead) {
  const Segment2 wall{{2.0, -1.0}, {2.0, 1.0}};
  const auto range = RaySegmentIntersection({0.0, 0.0}, {1.0, 0.0}, wall);
  ASSERT_TRUE(range.has_value());
  EXPECT_NEAR(*range, 2.0, 1e-12);
}

TEST(Segment2, RayMissesWallBehindOrBeside) {
  const Segment2 wall{{2.0, -1.0}, {2.0, 1.0}};
  EXPECT_FALSE(RaySegmentIntersection({0.0, 0.0}, {-1.0, 0.0}, wall).has_value());
  EXPECT_FALSE(RaySegmentIntersection({0.0, 5.0}, {1.0, 0.0}, wall).has_value());
  EXPECT_FALSE(RaySegmentIntersection({0.0, 0.0}, {0.0, 1.0}, wall).has_value());
}

TEST(Segment2, SegmentsInBoxAreThoseWhoseBoxesOverlapIt) {
  const std::vector<Segment2> walls{{{0, 0}, {10, 0}}, {{5, 5}, {5, 9}}, {{-3, -1}, {-1, -1}}};
  EXPECT_EQ(SegmentsInBox(walls, {4, -1}, {6, 6}), (std::vector<int>{0, 1}));
  EXPECT_EQ(SegmentsInBox(walls, {-2, -2}, {-1.5, 2}), (std::vector<int>{2}));
  EXPECT_TRUE(SegmentsInBox(walls, {20, 20}, {21, 21}).empty());
}

}  // namespace
}  // namespace pena::geometry
