// Beam geometry computed by hand: a tilted planar laser at height h between floor and ceiling.
#include "pena/sim/laser_raycaster.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim_test_util.hpp"

namespace pena::sim {
namespace {

using testing::kDeg;

constexpr double kHeight = 1.2;
constexpr double kCeiling = 2.6;

// One wall across x = 5 m from y = -10 to 10, laser at the origin facing +x.
LaserRaycaster WallAhead() { return LaserRaycaster({{{5.0, -10.0}, {5.0, 10.0}}}, kCeiling); }

LaserPose At(double pitch_rad, double roll_rad, double yaw_rad = 0.0) {
  return {{0.0, 0.0, kHeight}, yaw_rad, pitch_rad, roll_rad};
}

TEST(LaserRaycaster, LevelBeamHitsTheWallAtItsDistance) {
  const BeamHit hit = WallAhead().Cast(At(0.0, 0.0), 0.0, 30.0);
  ASSERT_EQ(hit.kind, HitKind::kWall);
  EXPECT_NEAR(hit.range_m, 5.0, 1e-9);
  EXPECT_EQ(hit.wall_index, 0u);
  EXPECT_NEAR(hit.along_m, 10.0, 1e-9);
  EXPECT_NEAR(hit.point_m.z(), kHeight, 1e-9);
  const BeamHit oblique = WallAhead().Cast(At(0.0, 0.0), 30.0 * kDeg, 30.0);
  EXPECT_NEAR(oblique.range_m, 5.0 / std::cos(30.0 * kDeg), 1e-9);
  EXPECT_NEAR(oblique.along_m, 10.0 + 5.0 * std::tan(30.0 * kDeg), 1e-9);
}

TEST(LaserRaycaster, PitchedBeamHitsTheFloorAtHeightOverTanPitch) {
  // The paper's example: 1.2 m and 10 deg put the floor hit 6.8 m ahead.
  const LaserRaycaster far_wall({{{50.0, -10.0}, {50.0, 10.0}}}, kCeiling);
  const BeamHit hit = far_wall.Cast(At(10.0 * kDeg, 0.0), 0.0, 30.0);
  ASSERT_EQ(hit.kind, HitKind::kFloor);
  EXPECT_NEAR(hit.point_m.head<2>().norm(), kHeight / std::tan(10.0 * kDeg), 1e-9);
  EXPECT_NEAR(hit.point_m.head<2>().norm(), 6.8, 0.01);
  EXPECT_NEAR(hit.range_m, kHeight / std::sin(10.0 * kDeg), 1e-9);
  EXPECT_NEAR(hit.point_m.z(), 0.0, 1e-9);
}

TEST(LaserRaycaster, PitchedBeamReachesANearWallBelowLaserHeight) {
  const BeamHit hit = WallAhead().Cast(At(10.0 * kDeg, 0.0), 0.0, 30.0);
  ASSERT_EQ(hit.kind, HitKind::kWall);
  EXPECT_NEAR(hit.range_m, 5.0 / std::cos(10.0 * kDeg), 1e-9);
  EXPECT_NEAR(hit.point_m.z(), kHeight - 5.0 * std::tan(10.0 * kDeg), 1e-9);
}

TEST(LaserRaycaster, UpwardPitchHitsTheCeiling) {
  const LaserRaycaster far_wall({{{50.0, -10.0}, {50.0, 10.0}}}, kCeiling);
  const BeamHit hit = far_wall.Cast(At(-10.0 * kDeg, 0.0), 0.0, 30.0);
  ASSERT_EQ(hit.kind, HitKind::kCeiling);
  EXPECT_NEAR(hit.range_m, (kCeiling - kHeight) / std::sin(10.0 * kDeg), 1e-9);
  EXPECT_NEAR(hit.point_m.x(), (kCeiling - kHeight) / std::tan(10.0 * kDeg), 1e-9);
}

TEST(LaserRaycaster, PitchLeavesTheSideBeamsLevel) {
  // Pitch turns about the laser's y axis: the +-90 deg beams lie on that axis.
  const LaserRaycaster side_walls({{{-10.0, 3.0}, {10.0, 3.0}}, {{-10.0, -3.0}, {10.0, -3.0}}},
                                  kCeiling);
  for (const double angle : {90.0 * kDeg, -90.0 * kDeg}) {
    const BeamHit hit = side_walls.Cast(At(15.0 * kDeg, 0.0), angle, 30.0);
    ASSERT_EQ(hit.kind, HitKind::kWall);
    EXPECT_NEAR(hit.range_m, 3.0, 1e-9);
  }
}

TEST(LaserRaycaster, PositiveRollLiftsTheLeftBeamsToTheCeiling) {
  const LaserRaycaster far_walls({{{-40.0, 40.0}, {40.0, 40.0}}, {{-40.0, -40.0}, {40.0, -40.0}}},
                                 kCeiling);
  const double roll = 8.0 * kDeg;
  const BeamHit left = far_walls.Cast(At(0.0, roll), 90.0 * kDeg, 30.0);
  ASSERT_EQ(left.kind, HitKind::kCeiling);
  EXPECT_NEAR(left.range_m, (kCeiling - kHeight) / std::sin(roll), 1e-9);
  EXPECT_NEAR(left.point_m.y(), (kCeiling - kHeight) / std::tan(roll), 1e-9);
  const BeamHit right = far_walls.Cast(At(0.0, roll), -90.0 * kDeg, 30.0);
  ASSERT_EQ(right.kind, HitKind::kFloor);
  EXPECT_NEAR(right.range_m, kHeight / std::sin(roll), 1e-9);
  // The forward beam lies on the roll axis and stays level.
  EXPECT_NEAR(WallAhead().Cast(At(0.0, roll), 0.0, 30.0).range_m, 5.0, 1e-9);
}

TEST(LaserRaycaster, YawTurnsTheBeamPlane) {
  const LaserRaycaster wall_north({{{-10.0, 4.0}, {10.0, 4.0}}}, kCeiling);
  const BeamHit hit = wall_north.Cast(At(0.0, 0.0, 90.0 * kDeg), 0.0, 30.0);
  ASSERT_EQ(hit.kind, HitKind::kWall);
  EXPECT_NEAR(hit.range_m, 4.0, 1e-9);
  EXPECT_NEAR(hit.point_m.x(), 0.0, 1e-9);
}

TEST(LaserRaycaster, NothingWithinMaxRangeIsANoHit) {
  const BeamHit hit = WallAhead().Cast(At(0.0, 0.0), 0.0, 4.0);
  EXPECT_EQ(hit.kind, HitKind::kNothing);
  EXPECT_TRUE(std::isinf(hit.range_m));
}

TEST(LaserRaycaster, NearestOfSeveralWallsWins) {
  const LaserRaycaster walls({{{8.0, -1.0}, {8.0, 1.0}}, {{3.0, -1.0}, {3.0, 1.0}}}, kCeiling);
  const BeamHit hit = walls.Cast(At(0.0, 0.0), 0.0, 30.0);
  EXPECT_EQ(hit.wall_index, 1u);
  EXPECT_NEAR(hit.range_m, 3.0, 1e-9);
}

TEST(LaserRaycaster, CulledCandidatesGiveTheSameHitsAsAllWalls) {
  const Scenario scenario = testing::CorridorLoop();
  const LaserRaycaster raycaster(scenario.walls, scenario.ceiling_height_m);
  Random random(3);
  for (int trial = 0; trial < 200; ++trial) {
    const LaserPose pose{{random.Uniform(0.5, 19.5), random.Uniform(0.5, 1.5), kHeight},
                         random.Uniform(-3.0, 3.0),
                         random.Normal(0.0, 0.1),
                         random.Normal(0.0, 0.1)};
    const double max_range = random.Uniform(2.0, 30.0);
    const auto candidates = raycaster.WallsNear(pose.position_m.head<2>(), max_range);
    const double angle = random.Uniform(-1.5, 1.5);
    const BeamHit all = raycaster.Cast(pose, angle, max_range);
    const BeamHit culled = raycaster.Cast(pose, angle, max_range, candidates);
    EXPECT_EQ(all.kind, culled.kind);
    EXPECT_EQ(all.range_m, culled.range_m);
  }
}

}  // namespace
}  // namespace pena::sim
