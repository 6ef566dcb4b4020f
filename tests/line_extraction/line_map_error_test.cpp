#include "pena/eval/line_map_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pena::eval {
namespace {

constexpr double kTol = 1e-9;
constexpr double kDegToRad = std::numbers::pi / 180.0;

geometry::Segment2 Seg(double x1, double y1, double x2, double y2) { return {{x1, y1}, {x2, y2}}; }

TEST(LineMapError, CoverageIsWallLengthNearAMapSegment) {
  // Wall 10 m; the map has 6 m of it, 5 cm off. Covered: the 6 m, plus the wall within 10 cm of
  // the map segment's end beyond x = 6 (sqrt(0.1^2 - 0.05^2) m). All of the map is precise.
  const LineMapErrorSummary s = EvaluateLineMap({Seg(0, 0.05, 6, 0.05)}, {Seg(0, 0, 10, 0)});
  const double covered_m = 6.0 + std::sqrt(0.1 * 0.1 - 0.05 * 0.05);
  EXPECT_NEAR(s.wall_length_m, 10.0, kTol);
  EXPECT_NEAR(s.covered_length_m, covered_m, 0.011);
  EXPECT_NEAR(s.coverage, covered_m / 10.0, 0.0011);
  EXPECT_NEAR(s.map_length_m, 6.0, kTol);
  EXPECT_NEAR(s.precision, 1.0, kTol);
  EXPECT_NEAR(s.fragmentation, 1.0, kTol);
  EXPECT_EQ(s.walls_matched, 1u);
}

TEST(LineMapError, SegmentBeyondDistanceNeitherCoversNorIsPrecise) {
  const LineMapErrorSummary s = EvaluateLineMap({Seg(0, 0.2, 2, 0.2)}, {Seg(0, 0, 10, 0)});
  EXPECT_NEAR(s.coverage, 0.0, kTol);
  EXPECT_NEAR(s.precision, 0.0, kTol);
  EXPECT_EQ(s.walls_matched, 0u);
  EXPECT_NEAR(s.fragmentation, 0.0, kTol);
}

TEST(LineMapError, CrossingSegmentIsPartlyPreciseButCoversNothing) {
  // 2 m long through (5, 0) at 20 deg: within 10 cm of the wall for |t| <= 0.1 / sin(20 deg).
  const double a = 20.0 * kDegToRad;
  const LineMapErrorSummary s = EvaluateLineMap(
      {Seg(5 - std::cos(a), -std::sin(a), 5 + std::cos(a), std::sin(a))}, {Seg(0, 0, 10, 0)});
  EXPECT_NEAR(s.coverage, 0.0, kTol);
  EXPECT_NEAR(s.precision, 0.1 / std::sin(a), 0.01);
  // Within the 10 deg direction tolerance it covers the wall under it, |x - 5| <= cos(5 deg), and
  // beyond each end what lies within 10 cm of that end (which is sin(5 deg) off the wall).
  const double b = 5.0 * kDegToRad;
  const LineMapErrorSummary t = EvaluateLineMap(
      {Seg(5 - std::cos(b), -std::sin(b), 5 + std::cos(b), std::sin(b))}, {Seg(0, 0, 10, 0)});
  const double beyond_m = std::sqrt(0.1 * 0.1 - std::sin(b) * std::sin(b));
  EXPECT_NEAR(t.covered_length_m, 2.0 * (std::cos(b) + beyond_m), 0.015);
}

TEST(LineMapError, FragmentationCountsSegmentsPerWall) {
  // Wall A in three pieces, wall B in one: (3 + 1) / 2.
  const LineMapErrorSummary s = EvaluateLineMap(
      {Seg(0, 0.02, 3, 0.02), Seg(3, 0.02, 7, 0.02), Seg(7, 0.02, 10, 0.02), Seg(0, 5, 4, 5)},
      {Seg(0, 0, 10, 0), Seg(0, 5, 4, 5)});
  EXPECT_NEAR(s.coverage, 1.0, kTol);
  EXPECT_NEAR(s.precision, 1.0, kTol);
  EXPECT_NEAR(s.fragmentation, 2.0, kTol);
  EXPECT_EQ(s.walls, 2u);
  EXPECT_EQ(s.map_segments, 4u);
}

TEST(LineMapError, GrazingEndIsNoFragment) {
  // The first map segment runs 5 cm into the collinear next wall, so it covers 15 cm of it (its
  // end reaches 10 cm further): under min_fragment_m (25 cm), not a fragment of it.
  const LineMapErrorSummary s = EvaluateLineMap({Seg(0, 0, 5.05, 0), Seg(5.05, 0, 10, 0)},
                                                {Seg(0, 0, 5, 0), Seg(5, 0, 10, 0)});
  EXPECT_NEAR(s.fragmentation, 1.0, kTol);
  EXPECT_NEAR(s.coverage, 1.0, kTol);
}

TEST(LineMapError, EmptyInputsGiveZeroRatios) {
  const LineMapErrorSummary s = EvaluateLineMap({}, {});
  EXPECT_EQ(s.coverage, 0.0);
  EXPECT_EQ(s.precision, 0.0);
  EXPECT_EQ(s.fragmentation, 0.0);
}

TEST(LineMapError, RejectsBadTolerances) {
  EXPECT_THROW(EvaluateLineMap({}, {}, {.distance_m = 0.0}), std::invalid_argument);
  EXPECT_THROW(EvaluateLineMap({}, {}, {.angle_rad = -0.1}), std::invalid_argument);
  EXPECT_THROW(EvaluateLineMap({}, {}, {.sample_step_m = 0.0}), std::invalid_argument);
  EXPECT_THROW(EvaluateLineMap({}, {}, {.min_fragment_m = -1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::eval
