// The per-entity facade on a small simulated building: poses, line-map deltas that rebuild the
// map, corrections and the global map.
#include "pena/pipeline/entity_pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "pena/pipeline/start_pose.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::pipeline {
namespace {

// A 24 x 8 m floor: a corridor with two rooms to the north; a robot drives along it and back.
constexpr const char* kScenario = R"scn(pena-scenario 1
name pipeline_test
ceiling 2.7
rect 0 0 24 8
wall 0 4 5 4
wall 6 4 13 4
wall 14 4 24 4
wall 12 4 12 8
entity robot1 robot 2 2 0 speed=0.8
waypoint robot1 22 2
waypoint robot1 22 1.5
waypoint robot1 13.5 1.5
waypoint robot1 13.5 6
waypoint robot1 16 6
)scn";

const sim::EntityRecording& Robot() {
  static const sim::SimulationResult result = [] {
    const sim::Scenario scenario = sim::ParseScenario(kScenario, "test:pipeline");
    return sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
  }();
  return result.entities.front();
}

struct Replayed {
  std::vector<ScanStep> steps;
  std::vector<line_map::MapDelta> deltas;
};

Replayed Replay(EntityPipeline& pipeline, const sim::EntityRecording& entity) {
  Replayed run;
  for (const sensors::SensorRecord& record : entity.records) {
    if (auto step = pipeline.Add(record)) {
      if (step->map_delta) run.deltas.push_back(*step->map_delta);
      run.steps.push_back(std::move(*step));
    }
  }
  line_map::MapDelta last = pipeline.Flush();
  if (!last.empty()) run.deltas.push_back(std::move(last));
  return run;
}

EntityPipeline MakePipeline(const sim::EntityRecording& entity,
                            const EntityPipelineOptions& options = {}) {
  return EntityPipeline(options, entity.kind, entity.id, entity.truth.front().world_from_body,
                        entity.start_s);
}

TEST(EntityPipeline, PublishesAPosePerScanAndFollowsTheTruth) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  const Replayed run = Replay(pipeline, robot);
  ASSERT_EQ(run.steps.size(), robot.scans);
  const geometry::Pose2& truth = robot.truth.back().world_from_body;
  const geometry::Pose2& estimate = run.steps.back().world_from_body;
  EXPECT_LT(std::hypot(truth.x_m - estimate.x_m, truth.y_m - estimate.y_m), 0.3);
}

TEST(EntityPipeline, DeltasInOrderRebuildTheLocalMap) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  const Replayed run = Replay(pipeline, robot);
  ASSERT_GE(run.deltas.size(), 2u);
  line_map::LineMap receiver;
  for (const line_map::MapDelta& delta : run.deltas) {
    ASSERT_TRUE(receiver.Apply(delta).ok()) << receiver.Apply(delta).message;
  }
  EXPECT_TRUE(line_map::SameMap(receiver.Snapshot(), pipeline.local_map().Snapshot()));
  // The corridor's long walls are in the map: some segment at least 8 m long.
  double longest_m = 0.0;
  for (const auto& segment : pipeline.local_map().segments()) {
    longest_m = std::max(longest_m, geometry::Length(segment.segment));
  }
  EXPECT_GT(longest_m, 8.0);
}

TEST(EntityPipeline, MapFromOdomCorrectionMovesThePose) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  std::optional<ScanStep> first;
  for (std::size_t i = 0; i < robot.records.size() && !first; ++i) first = pipeline.Add(robot.records[i]);
  ASSERT_TRUE(first.has_value());
  Correction correction;
  correction.map_from_odom = {1.0, -0.5, 0.0};
  correction.confidence = 0.9;
  EXPECT_EQ(pipeline.ApplyCorrection(correction).status, CorrectionStatus::kApplied);
  std::optional<ScanStep> next;
  for (std::size_t i = 0; i < robot.records.size() && !next; ++i) {
    if (std::holds_alternative<sensors::LaserScan>(robot.records[i]) &&
        sensors::StampOf(robot.records[i]) > first->odometry.stamp_s) {
      next = pipeline.Add(robot.records[i]);
    } else if (sensors::StampOf(robot.records[i]) > first->odometry.stamp_s) {
      pipeline.Add(robot.records[i]);
    }
  }
  ASSERT_TRUE(next.has_value());
  EXPECT_NEAR(next->world_from_body.x_m - next->odometry.world_from_body.x_m, 1.0, 1e-9);
  EXPECT_NEAR(next->world_from_body.y_m - next->odometry.world_from_body.y_m, -0.5, 1e-9);
}

// What EntityPose publishes: the laser odometry's covariance, turned with the map frame.
TEST(EntityPipeline, PublishedCovarianceIsTheOdometrysInTheMapFrame) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  std::size_t i = 0;
  std::optional<ScanStep> first;
  for (; i < robot.records.size() && !first; ++i) first = pipeline.Add(robot.records[i]);
  ASSERT_TRUE(first.has_value());
  EXPECT_TRUE(first->covariance.isZero());  // the start defines the frame
  Correction correction;
  correction.map_from_odom = {1.0, -0.5, std::numbers::pi / 2};  // a quarter turn
  correction.confidence = 0.9;
  ASSERT_EQ(pipeline.ApplyCorrection(correction).status, CorrectionStatus::kApplied);
  std::optional<ScanStep> last;
  for (; i < robot.records.size(); ++i) {
    if (auto step = pipeline.Add(robot.records[i])) last = std::move(step);
  }
  ASSERT_TRUE(last.has_value());
  const Eigen::Matrix3d& odom = last->odometry.covariance;
  const Eigen::Matrix3d& map = last->covariance;
  ASSERT_GT(odom(0, 0) + odom(1, 1), 0.0);
  // R P R^T with R the quarter turn: x and y swap, their cross terms change sign where x flips.
  EXPECT_NEAR(map(0, 0), odom(1, 1), 1e-12);
  EXPECT_NEAR(map(1, 1), odom(0, 0), 1e-12);
  EXPECT_NEAR(map(0, 1), -odom(1, 0), 1e-12);
  EXPECT_NEAR(map(0, 2), -odom(1, 2), 1e-12);
  EXPECT_NEAR(map(1, 2), odom(0, 2), 1e-12);
  EXPECT_NEAR(map(2, 2), odom(2, 2), 1e-15);
}

TEST(EntityPipeline, PoseCorrectionAtAPastStampSolvesMapFromOdom) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  std::vector<ScanStep> steps;
  for (const auto& record : robot.records) {
    if (auto step = pipeline.Add(record)) steps.push_back(*step);
    if (steps.size() == 20) break;
  }
  ASSERT_EQ(steps.size(), 20u);
  const ScanStep& past = steps[10];
  Correction correction;
  correction.kind = Correction::Kind::kPose;
  correction.stamp_s = past.odometry.stamp_s;
  correction.world_from_body = {past.odometry.world_from_body.x_m + 0.4,
                                past.odometry.world_from_body.y_m,
                                past.odometry.world_from_body.theta_rad};
  ASSERT_EQ(pipeline.ApplyCorrection(correction).status, CorrectionStatus::kApplied);
  EXPECT_NEAR(pipeline.map_from_odom().x_m, 0.4, 1e-9);
  EXPECT_NEAR(pipeline.map_from_odom().theta_rad, 0.0, 1e-12);
  correction.stamp_s = -100.0;
  EXPECT_EQ(pipeline.ApplyCorrection(correction).status, CorrectionStatus::kUnknownStamp);
}

TEST(EntityPipeline, IgnoresLowConfidenceAndInvalidCorrections) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  Correction weak;
  weak.map_from_odom = {5.0, 0.0, 0.0};
  weak.confidence = 0.1;
  EXPECT_EQ(pipeline.ApplyCorrection(weak).status, CorrectionStatus::kLowConfidence);
  Correction broken;
  broken.map_from_odom = {std::nan(""), 0.0, 0.0};
  EXPECT_EQ(pipeline.ApplyCorrection(broken).status, CorrectionStatus::kInvalid);
  EXPECT_DOUBLE_EQ(pipeline.map_from_odom().x_m, 0.0);
  EXPECT_EQ(pipeline.counts().corrections_ignored, 2);
}

TEST(EntityPipeline, LargeCorrectionKeepsTheOldGridsLinesAndStartsAFreshGrid) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  int scans = 0;
  for (const auto& record : robot.records) {
    if (pipeline.Add(record) && ++scans == 12) break;
  }
  Correction correction;
  correction.map_from_odom = {0.0, 0.5, 0.0};
  const CorrectionResult result = pipeline.ApplyCorrection(correction);
  EXPECT_EQ(result.status, CorrectionStatus::kApplied);
  EXPECT_EQ(pipeline.counts().grid_resets, 1);
  ASSERT_TRUE(result.map_delta.has_value());
  EXPECT_FALSE(result.map_delta->added.empty());
}

TEST(EntityPipeline, AppliesGlobalDeltasInOrderAndReportsGaps) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  line_map::LineMap fusion;
  line_map::LineSegment wall;
  wall.segment = {{0.0, 0.0}, {5.0, 0.0}};
  wall.support_cells = 10;
  wall.observations = 10;
  const line_map::MapDelta first = fusion.Integrate({wall}, "apriori");
  wall.segment = {{0.0, 3.0}, {5.0, 3.0}};
  const line_map::MapDelta second = fusion.Integrate({wall}, "apriori");
  EXPECT_EQ(pipeline.ApplyGlobalDelta(second).status, line_map::ApplyStatus::kVersionGap);
  EXPECT_TRUE(pipeline.ApplyGlobalDelta(first).ok());
  EXPECT_TRUE(pipeline.ApplyGlobalDelta(second).ok());
  EXPECT_EQ(pipeline.global_map().size(), 2u);
  pipeline.ResetGlobalMap(fusion.Snapshot());
  EXPECT_TRUE(line_map::SameMap(pipeline.global_map().Snapshot(), fusion.Snapshot()));
}

TEST(EntityPipeline, RejectsBadOptionsNamingTheField) {
  EntityPipelineOptions options;
  options.map_update_distance_m = -1.0;
  try {
    ValidateEntityPipelineOptions(options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("pipeline.map_update_distance_m"), std::string::npos);
  }
  EXPECT_THROW(EntityPipeline(EntityPipelineOptions{}, sensors::EntityKind::kRobot, "", {}, 0.0),
               std::invalid_argument);
}

TEST(StartPose, NativeLogsStartAtTheirGroundTruth) {
  const sim::EntityRecording& robot = Robot();
  std::vector<sensors::SensorRecord> ahead;
  for (const auto& record : robot.records) {
    ahead.push_back(record);
    if (std::holds_alternative<sensors::LaserScan>(record)) break;
  }
  EXPECT_EQ(StartPoseOf(ahead, true).source, "ground truth");
  EXPECT_NE(StartPoseOf(ahead, false).source, "ground truth");
}

}  // namespace
}  // namespace pena::pipeline
