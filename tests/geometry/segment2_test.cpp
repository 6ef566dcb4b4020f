#include "pena/geometry/segment2.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace pena::geometry
