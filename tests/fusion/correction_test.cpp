// Corrections by virtual-scan matching against the global map (paper section 4.2).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pena/fusion/correction.hpp"
#include "pena/localisation/virtual_scanner.hpp"

namespace pena::fusion {
namespace {

// An L-shaped corridor with a side room: enough structure to fix x, y and heading.
std::vector<geometry::Segment2> Building() {
  const auto s = [](double x1, double y1, double x2, double y2) {
    return geometry::Segment2{{x1, y1}, {x2, y2}};
  };
  return {s(0, 0, 20, 0), s(0, 2, 8, 2), s(10, 2, 18, 2), s(18, 2, 18, 12), s(20, 0, 20, 12),
          s(8, 2, 8, 6),  s(10, 2, 10, 6), s(8, 6, 10, 6), s(0, 0, 0, 2)};
}

sensors::LaserScan RealScan(const geometry::Pose2& map_from_body) {
  const localisation::VirtualScanner truth(Building());
  sensors::LaserGeometry laser{-std::numbers::pi / 2.0, std::numbers::pi / 360.0, 30.0};
  return truth.Scan(map_from_body, laser, 361, 12.0);
}

TEST(Correction, RecoversAnAlignmentErrorFromTheVirtualScan) {
  const geometry::Pose2 true_map_from_entity{3.0, -1.0, 0.2};
  const geometry::Pose2 map_from_body{12.0, 1.0, 0.3};
  const geometry::Pose2 entity_from_body =
      geometry::Compose(geometry::Inverse(true_map_from_entity), map_from_body);
  // The fusion's alignment is 0.25 m and 3 deg off.
  const geometry::Pose2 wrong{3.2, -0.85, 0.2 + 3.0 * std::numbers::pi / 180.0};
  const FusionCorrection correction =
      ComputeCorrection("ff1", RealScan(map_from_body), entity_from_body, wrong, Building());
  ASSERT_TRUE(correction.accepted) << correction.reason;
  const geometry::Pose2 corrected_body =
      geometry::Compose(correction.map_from_entity, entity_from_body);
  EXPECT_NEAR(corrected_body.x_m, map_from_body.x_m, 0.03);
  EXPECT_NEAR(corrected_body.y_m, map_from_body.y_m, 0.03);
  EXPECT_NEAR(geometry::NormalizeAngle(corrected_body.theta_rad - map_from_body.theta_rad), 0.0,
              0.01);
  EXPECT_GT(correction.confidence, 0.5);
}

TEST(Correction, LeavesTheAlignmentAloneWhenTheMapDoesNotFit) {
  const geometry::Pose2 map_from_body{12.0, 1.0, 0.3};
  // The global map holds only a far-away wall: the scan cannot be matched.
  const std::vector<geometry::Segment2> other = {{{100, 100}, {110, 100}}};
  const FusionCorrection correction =
      ComputeCorrection("ff1", RealScan(map_from_body), map_from_body, geometry::Pose2{}, other);
  EXPECT_FALSE(correction.accepted);
  EXPECT_FALSE(correction.reason.empty());
  EXPECT_EQ(correction.map_from_entity.x_m, 0.0);
}

}  // namespace
}  // namespace pena::fusion
