// The laser's interlace decided from its own scans (interlace_evidence.hpp; docs/odometry.md,
// "Sensor timing"): scans of a room taken while turning, by a laser that interleaves two sweeps
// or takes one, labelled as interleaving two; the evidence keeps the truth in both cases.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "pena/odometry/internal/interlace_evidence.hpp"

namespace pena::odometry::internal {
namespace {

constexpr double kTurnRadS = 1.0;        // a robot turning on the spot
constexpr double kSweepS = 1.0 / 150.0;  // SICK LMS: 180 deg of a 75 Hz mirror turn

// Range from the origin along `angle_rad` to the walls of the room [-4, 6] x [-3, 5] m.
double RoomRange(double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  double best = std::numeric_limits<double>::infinity();
  for (const double x : {-4.0, 6.0}) {
    if (c != 0.0 && x / c > 0.0) best = std::min(best, x / c);
  }
  for (const double y : {-3.0, 5.0}) {
    if (s != 0.0 && y / s > 0.0) best = std::min(best, y / s);
  }
  return best;
}

// A 361-beam, 0.5 deg scan taken while turning, by a laser interleaving `true_interlace` sweeps,
// labelled with interlace 2; ranges carry a +-2 mm deterministic ripple.
sensors::LaserScan TurningScan(int true_interlace) {
  sensors::LaserScan scan;
  scan.geometry.angle_min_rad = -std::numbers::pi / 2.0;
  scan.geometry.angle_increment_rad = std::numbers::pi / 360.0;
  scan.geometry.max_range_m = 80.0;
  scan.geometry.sweep_s = kSweepS;
  scan.geometry.interlace = true_interlace;
  const int beams = 361;
  // The times ScanToPointsAtMidSweep assumes: along the sweep, plus a mirror turn per interleaved
  // sweep; the beam looks that much further round (the deskew turns it back).
  const double mirror_turn_s = kSweepS * 2.0;
  double mean_sweep = 0.0;
  for (int i = 0; i < beams; ++i) mean_sweep += i % true_interlace;
  mean_sweep /= beams;
  for (int i = 0; i < beams; ++i) {
    const double t_s = (i - 0.5 * (beams - 1)) / (beams - 1) * kSweepS +
                       (i % true_interlace - mean_sweep) * mirror_turn_s;
    const double ripple_m = 0.002 * std::sin(1.7 * i);
    scan.ranges_m.push_back(
        static_cast<float>(RoomRange(scan.BeamAngle(static_cast<std::size_t>(i)) + kTurnRadS * t_s) +
                           ripple_m));
  }
  scan.geometry.interlace = 2;  // what a reader assumes of 0.5 deg SICK scans
  return scan;
}

TEST(InterlaceEvidence, ContourIsSmoothOnlyUnderTheTrueInterlace) {
  const sensors::LaserScan interleaved = TurningScan(2);
  sensors::LaserGeometry one_sweep = interleaved.geometry;
  one_sweep.interlace = 1;
  const std::optional<double> right = ContourRoughness(interleaved, interleaved.geometry, kTurnRadS, 0.1);
  const std::optional<double> wrong = ContourRoughness(interleaved, one_sweep, kTurnRadS, 0.1);
  ASSERT_TRUE(right && wrong);
  EXPECT_LT(*right, 0.005);
  EXPECT_GT(*wrong, 3.0 * *right);
}

TEST(InterlaceEvidence, KeepsTheConfiguredInterlaceOfAnInterleavingLaser) {
  InterlaceEvidence evidence;
  const sensors::LaserScan scan = TurningScan(2);
  for (int i = 0; i < 10 && !evidence.decided(); ++i) evidence.Add(scan, kTurnRadS, 0.1);
  ASSERT_TRUE(evidence.decided());
  EXPECT_EQ(*evidence.decided(), 2);
  EXPECT_EQ(evidence.Interlace(2), 2);
}

TEST(InterlaceEvidence, FindsThatALaserLabelledInterleavingTakesOneSweep) {
  InterlaceEvidence evidence;
  const sensors::LaserScan scan = TurningScan(1);
  EXPECT_EQ(evidence.Interlace(2), 2);  // the configured one until decided
  for (int i = 0; i < 10 && !evidence.decided(); ++i) evidence.Add(scan, kTurnRadS, 0.1);
  ASSERT_TRUE(evidence.decided());
  EXPECT_EQ(*evidence.decided(), 1);
  EXPECT_EQ(evidence.Interlace(2), 1);
}

TEST(InterlaceEvidence, WithoutATurnNothingIsDecided) {
  InterlaceEvidence evidence;
  for (int i = 0; i < 100; ++i) evidence.Add(TurningScan(1), 0.0, 0.1);
  EXPECT_FALSE(evidence.decided());
  EXPECT_EQ(evidence.Interlace(2), 2);
}

TEST(InterlaceEvidence, NotInQuestionForAOneSweepLaser) {
  InterlaceEvidence evidence;
  sensors::LaserScan scan = TurningScan(1);
  scan.geometry.interlace = 1;
  for (int i = 0; i < 100; ++i) evidence.Add(scan, kTurnRadS, 0.1);
  EXPECT_FALSE(evidence.decided());
  EXPECT_EQ(evidence.Interlace(1), 1);
}

}  // namespace
}  // namespace pena::odometry::internal
