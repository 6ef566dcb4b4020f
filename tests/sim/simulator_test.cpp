// The simulator end to end, without files: geometry of every beam against the ground truth,
// floor and ceiling hits, sensor streams and determinism.
#include "pena/sim/simulator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>

#include "sim_test_util.hpp"

namespace pena::sim {
namespace {

using testing::kDeg;

// The first surface along a beam, computed independently of LaserRaycaster: rotation matrices
// from Eigen and a brute-force search over the walls' vertical slabs.
double ExpectedRange(const Scenario& scenario, const sensors::GroundTruth& truth, double angle) {
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(truth.world_from_body.theta_rad, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(truth.pitch_rad, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(truth.roll_rad, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  const Eigen::Vector3d d = rotation * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
  const Eigen::Vector3d p(truth.world_from_body.x_m, truth.world_from_body.y_m,
                          truth.laser_height_m);
  double best = std::numeric_limits<double>::infinity();
  if (d.z() < 0) best = -p.z() / d.z();
  if (d.z() > 0) best = (scenario.ceiling_height_m - p.z()) / d.z();
  for (const auto& wall : scenario.walls) {
    // p.xy + t d.xy = a + s (b - a)
    Eigen::Matrix2d m;
    m << d.x(), -(wall.end_m - wall.start_m).x(), d.y(), -(wall.end_m - wall.start_m).y();
    if (std::abs(m.determinant()) < 1e-12) continue;
    const Eigen::Vector2d ts = m.inverse() * (wall.start_m - p.head<2>());
    if (ts[0] <= 0 || ts[1] < 0 || ts[1] > 1) continue;
    const double z = p.z() + ts[0] * d.z();
    if (z >= 0 && z <= scenario.ceiling_height_m) best = std::min(best, ts[0]);
  }
  return best;
}

SimulationResult Simulate(const Scenario& scenario, const SimulationOptions& options) {
  return Simulator(options).Run(scenario);
}

TEST(Simulator, NoiseFreeRangesMatchTheTiltedBeamGeometryOfTheTruth) {
  const Scenario scenario = testing::CorridorLoop();
  const SimulationResult result = Simulate(scenario, testing::NoiseFreeLaser());
  const EntityRecording& ff1 = result.entities.at(0);
  std::map<double, sensors::GroundTruth> truth_at;
  for (const auto& truth : ff1.truth) truth_at[truth.stamp_s] = truth;
  std::size_t checked = 0, floor_or_ceiling = 0;
  for (const auto& record : ff1.records) {
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (!scan) continue;
    const sensors::GroundTruth& truth = truth_at.at(scan->stamp_s);
    EXPECT_EQ(truth.laser_height_m, 1.2);
    for (std::size_t b = 0; b < scan->ranges_m.size(); ++b) {
      const double expected = ExpectedRange(scenario, truth, scan->BeamAngle(b));
      if (std::abs(expected - scan->geometry.max_range_m) < 0.01) continue;  // rounding at the edge
      if (expected >= scan->geometry.max_range_m) {
        ASSERT_TRUE(std::isinf(scan->ranges_m[b])) << "t " << scan->stamp_s << " beam " << b;
      } else {
        ASSERT_NEAR(scan->ranges_m[b], expected, 6e-4) << "t " << scan->stamp_s << " beam " << b;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 50000u);
  floor_or_ceiling = ff1.beams.floor + ff1.beams.ceiling;
  EXPECT_GT(floor_or_ceiling, 0u);
}

TEST(Simulator, AtLeastFivePercentOfHumanScansHitFloorOrCeiling) {
  const SimulationResult result = Simulate(testing::CorridorLoop(), {});
  const EntityRecording& ff1 = result.entities.at(0);
  ASSERT_GT(ff1.scans, 100u);
  const double fraction =
      static_cast<double>(ff1.scans_with_floor_or_ceiling) / static_cast<double>(ff1.scans);
  EXPECT_GE(fraction, 0.05);
  EXPECT_GT(ff1.beams.floor, 0u);
  EXPECT_GT(ff1.beams.ceiling, 0u);
}

TEST(Simulator, RobotLaserIsLevelAndNeverSeesFloorOrCeiling) {
  const SimulationResult result = Simulate(testing::CorridorLoop(sensors::EntityKind::kRobot), {});
  const EntityRecording& robot = result.entities.at(0);
  EXPECT_EQ(robot.laser_height_m, 0.4);
  EXPECT_EQ(robot.beams.floor + robot.beams.ceiling, 0u);
  std::size_t odometry = 0, scans_with_odometry = 0;
  for (const auto& record : robot.records) {
    odometry += std::holds_alternative<sensors::WheelOdometry>(record);
    EXPECT_FALSE(std::holds_alternative<sensors::GyroSample>(record));
    if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
      scans_with_odometry += scan->odometry_pose.has_value();
    }
  }
  EXPECT_EQ(scans_with_odometry, robot.scans);
  EXPECT_NEAR(static_cast<double>(odometry), 5.0 * static_cast<double>(robot.scans),
              6.0);  // 20 Hz vs 4 Hz
}

TEST(Simulator, RecordsAreInTimeOrderWithTruthAtEveryScan) {
  const SimulationResult result = Simulate(testing::CorridorLoop(), {});
  const EntityRecording& ff1 = result.entities.at(0);
  double last = -1.0;
  std::size_t scans = 0;
  std::map<int, std::size_t> kinds;
  for (std::size_t i = 0; i < ff1.records.size(); ++i) {
    const double stamp = sensors::StampOf(ff1.records[i]);
    ASSERT_GE(stamp, last);
    last = stamp;
    ++kinds[static_cast<int>(ff1.records[i].index())];
    if (const auto* scan = std::get_if<sensors::LaserScan>(&ff1.records[i])) {
      ASSERT_GT(i, 0u);
      const auto* truth = std::get_if<sensors::GroundTruth>(&ff1.records[i - 1]);
      ASSERT_NE(truth, nullptr);
      EXPECT_EQ(truth->stamp_s, scan->stamp_s);
      EXPECT_EQ(scan->ranges_m.size(), 361u);
      EXPECT_NEAR(scan->stamp_s - ff1.start_s, 0.25 * static_cast<double>(scans), 1e-9);
      ++scans;
    }
  }
  EXPECT_EQ(scans, ff1.truth.size());
  const double duration = ff1.end_s - ff1.start_s;
  EXPECT_NEAR(static_cast<double>(kinds[1]), 100.0 * duration, 2.0);  // gyro at 100 Hz
  EXPECT_NEAR(static_cast<double>(kinds[2]), 10.0 * duration, 2.0);   // compass at 10 Hz
  EXPECT_NEAR(static_cast<double>(kinds[3]) / duration, 1.7, 0.4);    // ~1.8 steps/s walking
}

TEST(Simulator, NoiseFreeGyroIntegratesToTheTrueHeading) {
  SimulationOptions options;
  options.gyro = {0.0, 0.0, 0.0};
  const SimulationResult result = Simulate(testing::CorridorLoop(), options);
  const EntityRecording& ff1 = result.entities.at(0);
  double heading = ff1.truth.front().world_from_body.theta_rad;
  double max_error = 0.0;
  for (const auto& record : ff1.records) {
    if (const auto* gyro = std::get_if<sensors::GyroSample>(&record))
      heading += gyro->yaw_rate_rad_s * 0.01;
    if (const auto* truth = std::get_if<sensors::GroundTruth>(&record)) {
      max_error =
          std::max(max_error,
                   std::abs(geometry::NormalizeAngle(heading - truth->world_from_body.theta_rad)));
    }
  }
  EXPECT_LT(max_error, 1e-6);
}

// A walker who stops mid-stride lands the trailing foot, and the stride sensor reports that step:
// while the walker stands, the strides add up to the distance walked. Before the landing step the
// last 0-0.7 m before every stop went unreported until the walk went on.
TEST(Simulator, WhileTheWalkerStandsTheStridesAddUpToTheDistanceWalked) {
  SimulationOptions options;
  options.stride = {0.0, 0.0, 0.0};
  options.human.side_step_rate_per_s = 0.0;  // a dodge reports its net displacement as a step
  options.human.back_step_rate_per_s = 0.0;
  options.human.stop_rate_per_s = 1.0 / 5.0;  // many stops at random points of the gait
  options.seed = 3;
  const EntityRecording ff1 = Simulate(testing::CorridorLoop(), options).entities.at(0);
  double strides_m = 0.0, walked_m = 0.0, worst_m = 0.0;
  int standing = 0;
  const sensors::GroundTruth* previous = nullptr;
  for (const auto& record : ff1.records) {
    if (const auto* stride = std::get_if<sensors::StrideSample>(&record)) strides_m += stride->length_m;
    const auto* truth = std::get_if<sensors::GroundTruth>(&record);
    if (truth == nullptr) continue;
    if (previous != nullptr) {
      const double step_m = std::hypot(truth->world_from_body.x_m - previous->world_from_body.x_m,
                                       truth->world_from_body.y_m - previous->world_from_body.y_m);
      walked_m += step_m;
      if (step_m == 0.0 && walked_m > 1.0) {  // standing after a walk: compare, then start over
        ++standing;
        // Strides are chords of whole steps, walked_m chords of scan intervals: they differ a
        // little on curves.
        worst_m = std::max(worst_m, std::abs(walked_m - strides_m) - 0.003 * walked_m);
        walked_m = strides_m = 0.0;
      }
    }
    previous = truth;
  }
  EXPECT_GE(standing, 5);
  EXPECT_LT(worst_m, 0.05) << "strides and the distance walked since the last stand differ";
}

TEST(Simulator, ObservedSegmentsLieOnTheirWalls) {
  const Scenario scenario = testing::CorridorLoop();
  const SimulationResult result = Simulate(scenario, {});
  ASSERT_FALSE(result.observed.empty());
  double observed_m = 0.0;
  for (const ObservedSegment& part : result.observed) {
    const geometry::Segment2& wall = scenario.walls.at(part.wall_index);
    EXPECT_LT(geometry::DistanceToSegment(wall, part.segment.start_m), 1e-9);
    EXPECT_LT(geometry::DistanceToSegment(wall, part.segment.end_m), 1e-9);
    observed_m += geometry::Length(part.segment);
  }
  // The corridor loop is walked all round: most of its 128 m of walls are seen.
  EXPECT_GT(observed_m, 100.0);
  EXPECT_LE(observed_m, 128.0 + 1e-9);
}

// Walls 0.2 m thick around the corridor loop's lines: from the corridor the laser meets the
// rectangles 0.1 m inside the outer walls and 0.1 m outside the block (built here by hand, not
// with ThickWallFaces), and every observed part lies 0.1 m from its wall.
TEST(Simulator, ThickWallsMoveTheFacesTheLaserMeetsAndTheObservedParts) {
  const Scenario scenario = testing::CorridorLoop();
  SimulationOptions options = testing::NoiseFreeLaser();
  options.wall_thickness_m = 0.2;
  const SimulationResult result = Simulate(scenario, options);
  Scenario faces = scenario;
  faces.walls = testing::Rectangle(0.1, 0.1, 19.9, 11.9);
  for (const auto& wall : testing::Rectangle(1.9, 1.9, 18.1, 10.1)) faces.walls.push_back(wall);
  const EntityRecording& ff1 = result.entities.at(0);
  std::map<double, sensors::GroundTruth> truth_at;
  for (const auto& truth : ff1.truth) truth_at[truth.stamp_s] = truth;
  std::size_t checked = 0;
  for (const auto& record : ff1.records) {
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (!scan) continue;
    const sensors::GroundTruth& truth = truth_at.at(scan->stamp_s);
    for (std::size_t b = 0; b < scan->ranges_m.size(); ++b) {
      const double expected = ExpectedRange(faces, truth, scan->BeamAngle(b));
      if (expected >= scan->geometry.max_range_m - 0.01) continue;
      ASSERT_NEAR(scan->ranges_m[b], expected, 6e-4) << "t " << scan->stamp_s << " beam " << b;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50000u);
  // Each observed part lies on the faces, and on its own wall's box: within 0.1 m of the wall's
  // line, or on a cap beyond its end (a corner's cap lies in the other wall's face).
  const auto on_faces = [&faces](const Eigen::Vector2d& p) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& face : faces.walls) {
      nearest = std::min(nearest, geometry::DistanceToSegment(face, p));
    }
    return nearest;
  };
  ASSERT_FALSE(result.observed.empty());
  for (const ObservedSegment& part : result.observed) {
    const geometry::Segment2& wall = scenario.walls.at(part.wall_index);
    for (const Eigen::Vector2d& end : {part.segment.start_m, part.segment.end_m}) {
      EXPECT_LT(on_faces(end), 1e-9);
      EXPECT_LE(geometry::DistanceToSegment(wall, end), 0.1 * std::sqrt(2.0) + 1e-9);
      EXPECT_GE(geometry::DistanceToSegment(wall, end), 0.1 - 1e-9);
    }
  }
  // The walker keeps the lines: the same walk as without thickness.
  const EntityRecording thin = Simulate(scenario, testing::NoiseFreeLaser()).entities.at(0);
  ASSERT_EQ(ff1.truth.size(), thin.truth.size());
  for (std::size_t i = 0; i < thin.truth.size(); ++i) {
    ASSERT_EQ(ff1.truth[i].world_from_body.x_m, thin.truth[i].world_from_body.x_m) << i;
    ASSERT_EQ(ff1.truth[i].world_from_body.y_m, thin.truth[i].world_from_body.y_m) << i;
  }
}

TEST(Simulator, SmokeLimitsEveryRange) {
  Scenario scenario = testing::CorridorLoop();
  scenario.smoke.push_back({{{-1.0, -1.0}, {21.0, 13.0}}, 2.5});
  const SimulationResult result = Simulate(scenario, {});
  std::size_t returns = 0;
  for (const auto& record : result.entities.at(0).records) {
    if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
      for (const float range : scan->ranges_m) {
        if (std::isinf(range)) continue;
        ASSERT_LE(range, 2.5f);
        ++returns;
      }
    }
  }
  EXPECT_GT(returns, 0u);
}

// A digest of everything a record holds, for comparing runs.
std::string Digest(const SimulationResult& result) {
  std::string bytes;
  const auto put = [&bytes](double value) {
    char raw[sizeof value];
    std::memcpy(raw, &value, sizeof value);
    bytes.append(raw, sizeof raw);
  };
  for (const auto& entity : result.entities) {
    for (const auto& record : entity.records) {
      put(static_cast<double>(record.index()));
      put(sensors::StampOf(record));
      if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
        for (const float r : scan->ranges_m) put(r);
      } else if (const auto* gyro = std::get_if<sensors::GyroSample>(&record)) {
        put(gyro->yaw_rate_rad_s);
      } else if (const auto* compass = std::get_if<sensors::CompassSample>(&record)) {
        put(compass->heading_rad);
      } else if (const auto* stride = std::get_if<sensors::StrideSample>(&record)) {
        put(stride->length_m);
      } else if (const auto* truth = std::get_if<sensors::GroundTruth>(&record)) {
        put(truth->world_from_body.x_m), put(truth->world_from_body.y_m);
        put(truth->world_from_body.theta_rad), put(truth->pitch_rad), put(truth->roll_rad);
      } else if (const auto* odometry = std::get_if<sensors::WheelOdometry>(&record)) {
        put(odometry->odom_pose.x_m), put(odometry->odom_pose.y_m),
            put(odometry->odom_pose.theta_rad);
      }
    }
  }
  return bytes;
}

TEST(Simulator, SameSeedGivesIdenticalDataAndAnotherSeedDoesNot) {
  Scenario scenario = testing::CorridorLoop();
  scenario.entities.push_back(testing::CorridorLoop(sensors::EntityKind::kRobot).entities[0]);
  SimulationOptions options;
  options.seed = 11;
  const std::string first = Digest(Simulate(scenario, options));
  EXPECT_EQ(first, Digest(Simulate(scenario, options)));
  options.seed = 12;
  EXPECT_NE(first, Digest(Simulate(scenario, options)));
}

TEST(Simulator, LapsOverrideRepeatsTheRoute) {
  SimulationOptions options;
  const double one = Simulate(testing::CorridorLoop(), options).entities[0].end_s;
  options.laps_override = 2;
  const double two = Simulate(testing::CorridorLoop(), options).entities[0].end_s;
  EXPECT_NEAR(two / one, 2.0, 0.25);
}

TEST(Simulator, RejectsRatesThatDoNotDivideTheMotionRate) {
  SimulationOptions options;
  options.laser_rate_hz = 3.0;
  EXPECT_THROW(Simulator{options}, std::invalid_argument);
  options = {};
  options.laser_max_range_m = -1.0;
  EXPECT_THROW(Simulator{options}, std::invalid_argument);
  options = {};
  options.wall_thickness_m = -0.1;
  try {
    Simulator{options};
    ADD_FAILURE() << "a negative wall thickness was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("simulation.wall_thickness_m"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace pena::sim
