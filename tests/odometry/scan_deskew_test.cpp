// Scans that take time while the platform turns (LaserGeometry::sweep_s; docs/odometry.md, "Scan
// deskew"). The team robot's instantaneous scans are resampled as a slow laser would have taken
// them: beam i looks (i / (n - 1) - 1/2) * sweep further round, by the robot's true turn rate.
// Matched as if instantaneous they drag the heading in every turn; turned to mid-sweep by the
// matched turn's rate (docs/odometry.md, "Deskew by the matched turn") they do not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"
#include "team_entity.hpp"

namespace pena::odometry {
namespace {

constexpr double kSweepS = 0.1;  // a slow laser, so that the team robot's 1 rad/s turns show

// The instantaneous scan's range towards `angle_rad` (laser frame), linear between neighbouring
// returns on one surface, else the nearest beam's.
float RangeTowards(const sensors::LaserScan& scan, double angle_rad) {
  const double position = (angle_rad - scan.geometry.angle_min_rad) / scan.geometry.angle_increment_rad;
  const auto last = static_cast<double>(scan.ranges_m.size() - 1);
  if (position < 0.0 || position > last) return sensors::LaserScan::kNoReturn;
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, scan.ranges_m.size() - 1);
  const double t = position - static_cast<double>(below);
  const bool same_surface = scan.IsReturn(below) && scan.IsReturn(above) &&
                            std::abs(scan.ranges_m[below] - scan.ranges_m[above]) < 0.2f;
  if (!same_surface) return scan.ranges_m[t < 0.5 ? below : above];
  return static_cast<float>((1.0 - t) * scan.ranges_m[below] + t * scan.ranges_m[above]);
}

// The robot's records with every scan taken over kSweepS, centred on its stamp.
std::vector<sensors::SensorRecord> SweptRecords(const sim::EntityRecording& robot) {
  std::vector<sensors::SensorRecord> records = robot.records;
  std::size_t scan_index = 0;
  for (auto& record : records) {
    auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (scan == nullptr) continue;
    const std::size_t i = scan_index++;
    const auto& truth = robot.truth;
    const std::size_t a = i == 0 ? 0 : i - 1;
    const std::size_t b = i + 1 < truth.size() ? i + 1 : i;
    const double rate_rad_s =
        b == a ? 0.0
               : geometry::NormalizeAngle(truth[b].world_from_body.theta_rad -
                                          truth[a].world_from_body.theta_rad) /
                     (truth[b].stamp_s - truth[a].stamp_s);
    const sensors::LaserScan instantaneous = *scan;
    const double n = static_cast<double>(scan->ranges_m.size() - 1);
    for (std::size_t k = 0; k < scan->ranges_m.size(); ++k) {
      const double offset_s = (static_cast<double>(k) / n - 0.5) * kSweepS;
      scan->ranges_m[k] = RangeTowards(instantaneous, scan->BeamAngle(k) + rate_rad_s * offset_s);
    }
    scan->geometry.sweep_s = kSweepS;
  }
  return records;
}

double HeadingRmsDeg(const sim::EntityRecording& robot, const std::vector<OdometryEstimate>& run) {
  double sum = 0.0;
  for (std::size_t i = 0; i < run.size(); ++i) {
    const double e = geometry::NormalizeAngle(run[i].world_from_body.theta_rad -
                                              robot.truth[i].world_from_body.theta_rad);
    sum += e * e;
  }
  return std::sqrt(sum / static_cast<double>(run.size())) * 180.0 / std::numbers::pi;
}

TEST(ScanDeskew, TurnsSweptScansToMidSweepAndKeepsTheHeading) {
  const sim::EntityRecording& robot = testing::TeamEntity("robot1");
  const std::vector<sensors::SensorRecord> swept = SweptRecords(robot);
  LaserOdometryOptions off;
  off.deskew_scans = false;
  const auto deskewed = testing::ReplayRecords(robot, swept, {});
  const auto as_instantaneous = testing::ReplayRecords(robot, swept, off);
  ASSERT_EQ(deskewed.size(), robot.truth.size());
  ASSERT_EQ(as_instantaneous.size(), robot.truth.size());
  const double with_deg = HeadingRmsDeg(robot, deskewed);
  const double without_deg = HeadingRmsDeg(robot, as_instantaneous);
  std::printf("heading RMS: deskewed %.3f deg, as instantaneous %.3f deg\n", with_deg, without_deg);
  EXPECT_LT(with_deg, 0.5 * without_deg);
}

// The robot's swept records delivered in pairs, as intel's logger did: every second scan is
// stamped and recorded 1 ms before the next one, after the odometry that came in between.
std::vector<sensors::SensorRecord> DeliveredInPairs(
    const std::vector<sensors::SensorRecord>& records) {
  std::vector<sensors::SensorRecord> out;
  std::optional<sensors::LaserScan> held;
  int scans = 0;
  for (const auto& record : records) {
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (scan == nullptr) {
      out.push_back(record);
      continue;
    }
    if (held) {
      held->stamp_s = scan->stamp_s - 0.001;
      out.emplace_back(*held);
      held.reset();
    }
    if (scans++ % 2 == 1) {
      held = *scan;
    } else {
      out.push_back(record);
    }
  }
  if (held) out.emplace_back(*held);
  return out;
}

// Delivery stamps say nothing of the turn between two scans; the match does, over the mean
// interval between scans (deskew_bursty_scans, deskew_match_passes).
TEST(ScanDeskew, BurstyScansAreDeskewedByTheMatchedTurnOverTheMeanInterval) {
  const sim::EntityRecording& robot = testing::TeamEntity("robot1");
  const std::vector<sensors::SensorRecord> bursty = DeliveredInPairs(SweptRecords(robot));
  LaserOdometryOptions off;
  off.deskew_bursty_scans = false;
  LaserOdometryOptions prior_rate;
  prior_rate.deskew_match_passes = 0;
  const auto deskewed = testing::ReplayRecords(robot, bursty, {});
  const auto as_instantaneous = testing::ReplayRecords(robot, bursty, off);
  const auto by_prior = testing::ReplayRecords(robot, bursty, prior_rate);
  ASSERT_EQ(deskewed.size(), robot.truth.size());
  ASSERT_EQ(as_instantaneous.size(), robot.truth.size());
  ASSERT_EQ(by_prior.size(), robot.truth.size());
  const double with_deg = HeadingRmsDeg(robot, deskewed);
  const double without_deg = HeadingRmsDeg(robot, as_instantaneous);
  const double prior_deg = HeadingRmsDeg(robot, by_prior);
  std::printf("heading RMS, scans in pairs: deskewed %.3f deg, by the prior's turn %.3f deg, as "
              "instantaneous %.3f deg\n",
              with_deg, prior_deg, without_deg);
  EXPECT_LT(with_deg, 0.5 * without_deg);
}

// Stamps closer than deskew_min_interval_s (intel's bursts) give no turn rate: the scans are
// matched as they are.
TEST(ScanDeskew, ScansCloserThanTheMinimumIntervalAreLeftAsTheyAre) {
  const sim::EntityRecording& robot = testing::TeamEntity("robot1");
  const std::vector<sensors::SensorRecord> swept = SweptRecords(robot);
  LaserOdometryOptions off;
  off.deskew_scans = false;
  LaserOdometryOptions long_interval;
  long_interval.deskew_min_interval_s = 10.0;
  const auto a = testing::ReplayRecords(robot, swept, off);
  const auto b = testing::ReplayRecords(robot, swept, long_interval);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].world_from_body.theta_rad, b[i].world_from_body.theta_rad) << "scan " << i;
  }
}

TEST(ScanDeskew, MatchPassesOutOfRangeAreRefusedNamingThem) {
  for (const int passes : {-1, 11}) {
    LaserOdometryOptions options;
    options.deskew_match_passes = passes;
    try {
      LaserOdometry odometry(options, sensors::EntityKind::kRobot, {}, 0.0);
      FAIL() << "expected std::invalid_argument for " << passes;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("laser_odometry.deskew_match_passes"),
                std::string::npos)
          << error.what();
    }
  }
}

TEST(ScanDeskew, ANegativeMinimumIntervalIsRefusedNamingIt) {
  LaserOdometryOptions options;
  options.deskew_min_interval_s = -0.01;
  try {
    LaserOdometry odometry(options, sensors::EntityKind::kRobot, {}, 0.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("laser_odometry.deskew_min_interval_s"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace pena::odometry
