// A scan that takes time while the laser turns (LaserGeometry::sweep_s, docs/odometry.md "Scan
// deskew"): ScanToPointsAtMidSweep puts every return where the laser saw it at mid-sweep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "pena/scan_matching/point_set.hpp"
#include "synthetic_room.hpp"

namespace pena::scan_matching {
namespace {

constexpr int kBeams = 361;
constexpr double kSweepS = 0.05;
constexpr double kRateRadS = 1.5;  // a robot spinning on the spot

// The synthetic room scanned beam by beam while the laser turns at rate_rad_s: beam i is taken
// i / 360 * sweep_s plus (i mod interlace) mirror turns (2 sweep_s: the field is half a turn)
// after the first beam, when the laser points that much further round than at the mean time.
sensors::LaserScan SweptScan(const geometry::Pose2& world_from_laser_at_mid, double sweep_s,
                             double rate_rad_s, int interlace = 1) {
  const std::vector<geometry::Segment2> walls = testing::SyntheticRoom();
  sensors::LaserScan scan;
  scan.geometry = {-std::numbers::pi / 2, std::numbers::pi / (kBeams - 1), 30.0, sweep_s,
                   interlace};
  const auto taken_s = [&](int i) {
    return static_cast<double>(i) / (kBeams - 1) * sweep_s + (i % interlace) * 2.0 * sweep_s;
  };
  double mean_s = 0.0;
  for (int i = 0; i < kBeams; ++i) mean_s += taken_s(i) / kBeams;
  const Eigen::Vector2d origin(world_from_laser_at_mid.x_m, world_from_laser_at_mid.y_m);
  for (int i = 0; i < kBeams; ++i) {
    const double offset_s = taken_s(i) - mean_s;
    const double world_angle =
        world_from_laser_at_mid.theta_rad + rate_rad_s * offset_s + scan.BeamAngle(i);
    const Eigen::Vector2d direction(std::cos(world_angle), std::sin(world_angle));
    double range = std::numeric_limits<double>::infinity();
    for (const auto& wall : walls) {
      if (const auto hit = geometry::RaySegmentIntersection(origin, direction, wall)) {
        range = std::min(range, *hit);
      }
    }
    scan.ranges_m.push_back(static_cast<float>(range));
  }
  return scan;
}

// Largest distance from each point to the nearest wall of the room, both in the world frame.
double WorstWallDistanceM(const Points2& points_laser, const geometry::Pose2& world_from_laser) {
  double worst = 0.0;
  for (const Eigen::Vector2d& p : TransformPoints(world_from_laser, points_laser)) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& wall : testing::SyntheticRoom()) {
      nearest = std::min(nearest, geometry::DistanceToSegment(wall, p));
    }
    worst = std::max(worst, nearest);
  }
  return worst;
}

const geometry::Pose2 kMid{3.0, 2.0, 0.4};

TEST(MidSweepPoints, ReturnsLieOnTheWallsSeenFromTheMidSweepPose) {
  const sensors::LaserScan scan = SweptScan(kMid, kSweepS, kRateRadS);
  const Points2 deskewed = ScanToPointsAtMidSweep(scan, 0.05, kRateRadS);
  ASSERT_EQ(deskewed.size(), ScanToPoints(scan, 0.05).size());
  // Float ranges: sub-millimetre.
  EXPECT_LT(WorstWallDistanceM(deskewed, kMid), 1e-3);
  // Taken as instantaneous, the edges of the field are turned by 1.5 rad/s * 25 ms = 2.1 deg:
  // centimetres off the walls at a few metres.
  EXPECT_GT(WorstWallDistanceM(ScanToPoints(scan, 0.05), kMid), 0.05);
}

TEST(MidSweepPoints, TheTurnsDirectionMatters) {
  const sensors::LaserScan scan = SweptScan(kMid, kSweepS, -kRateRadS);
  EXPECT_LT(WorstWallDistanceM(ScanToPointsAtMidSweep(scan, 0.05, -kRateRadS), kMid), 1e-3);
  EXPECT_GT(WorstWallDistanceM(ScanToPointsAtMidSweep(scan, 0.05, kRateRadS), kMid), 0.1);
}

// A SICK LMS 2xx at 0.5 deg takes its even beams in one mirror turn and its odd beams in the
// next: neighbouring returns are a turn apart, and only the interlaced timing puts both on the
// walls.
TEST(MidSweepPoints, InterlacedSweepsAreEachTurnedByTheirOwnTime) {
  const sensors::LaserScan scan = SweptScan(kMid, kSweepS, kRateRadS, 2);
  EXPECT_LT(WorstWallDistanceM(ScanToPointsAtMidSweep(scan, 0.05, kRateRadS), kMid), 1e-3);
  sensors::LaserScan as_one_sweep = scan;
  as_one_sweep.geometry.interlace = 1;
  // The odd beams are 2 * 50 ms * 1.5 rad/s = 8.6 deg round from the even ones.
  EXPECT_GT(WorstWallDistanceM(ScanToPointsAtMidSweep(as_one_sweep, 0.05, kRateRadS), kMid), 0.1);
}

TEST(MidSweepPoints, AnInstantaneousScanOrNoTurnIsLeftAsItIs) {
  const sensors::LaserScan instantaneous = SweptScan(kMid, 0.0, 0.0);
  EXPECT_EQ(ScanToPointsAtMidSweep(instantaneous, 0.05, kRateRadS), ScanToPoints(instantaneous, 0.05));
  const sensors::LaserScan swept = SweptScan(kMid, kSweepS, kRateRadS);
  EXPECT_EQ(ScanToPointsAtMidSweep(swept, 0.05, 0.0), ScanToPoints(swept, 0.05));
  const sensors::LaserScan interlaced = SweptScan(kMid, kSweepS, kRateRadS, 2);
  EXPECT_EQ(ScanToPointsAtMidSweep(interlaced, 0.05, 0.0), ScanToPoints(interlaced, 0.05));
}

}  // namespace
}  // namespace pena::scan_matching
