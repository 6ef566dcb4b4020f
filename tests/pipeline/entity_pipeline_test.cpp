// The per-entity facade on a small simulated building: poses, line-map deltas that rebuild the
// map, corrections and the global map.
#include "pena/pipeline/entity_pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

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

// The same floor walked by a firefighter (gyro, compass and stride reports).
const sim::EntityRecording& Walker() {
  static const sim::SimulationResult result = [] {
    std::string text = kScenario;
    text = text.substr(0, text.find("entity robot1")) +
           "entity ff1 human 2 2 0 speed=0.9\nwaypoint ff1 20 2\nwaypoint ff1 20 1.5\n";
    return sim::Simulator{sim::SimulationOptions{}}.Run(sim::ParseScenario(text, "test:walker"));
  }();
  return result.entities.front();
}

struct Replayed {
  std::vector<ScanStep> steps;
  std::vector<line_map::MapDelta> deltas;
};

Replayed Replay(EntityPipeline& pipeline, const sim::EntityRecording& entity) {
  Replayed run;
  const auto take = [&](ScanStep& step) {
    if (step.map_delta) run.deltas.push_back(*step.map_delta);
    run.steps.push_back(std::move(step));
  };
  for (const sensors::SensorRecord& record : entity.records) {
    for (ScanStep& step : pipeline.Add(record)) take(step);
  }
  pipeline.EndOfInput();
  while (std::optional<ScanStep> step = pipeline.Next()) take(*step);
  line_map::MapDelta last = pipeline.Flush();
  if (!last.empty()) run.deltas.push_back(std::move(last));
  return run;
}

// The step of one of a robot's records: nothing is held for a robot, so at most one.
std::optional<ScanStep> AddRecord(EntityPipeline& pipeline, const sensors::SensorRecord& record) {
  std::vector<ScanStep> steps = pipeline.Add(record);
  EXPECT_LE(steps.size(), 1u);
  if (steps.empty()) return std::nullopt;
  return std::move(steps.front());
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

// Where the pipeline's time goes: every scan's odometry and grid insertion, the extractions; the
// stages sum to no more than the total, whose odometry stage holds the odometry's own total.
TEST(EntityPipeline, StageTimesFillTheMapStagesAndSumToNoMoreThanTheTotal) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline pipeline = MakePipeline(robot);
  const Replayed run = Replay(pipeline, robot);
  const PipelineStageTimes& t = pipeline.stage_times();
  const odometry::OdometryStageTimes& odometry = pipeline.odometry().stage_times();
  EXPECT_EQ(t[PipelineStage::kOdometry].calls, static_cast<long>(robot.records.size()));
  EXPECT_EQ(t[PipelineStage::kGridInsertion].calls, static_cast<long>(robot.scans));
  EXPECT_GE(t[PipelineStage::kLineExtraction].calls, 1);
  EXPECT_EQ(t[PipelineStage::kSlam].calls, 0);
  for (PipelineStage stage : {PipelineStage::kOdometry, PipelineStage::kGridInsertion,
                              PipelineStage::kLineExtraction}) {
    EXPECT_GT(t[stage].seconds, 0.0) << ToString(stage);
  }
  for (const StageTime& stage : t.stages) EXPECT_GE(stage.seconds, 0.0);
  EXPECT_LE(t.StagesSeconds(), t.total.seconds + 1e-9);
  EXPECT_GE(t[PipelineStage::kOdometry].seconds, odometry.total.seconds);
  EXPECT_EQ(odometry.total.calls, static_cast<long>(robot.records.size()));
  EXPECT_FALSE(run.steps.empty());
}

// The SLAM stage is KeyframeSlam fed with every step's odometry pose, inside the pipeline (as
// `pena map` runs it): the same corrected trajectory as feeding it by hand.
TEST(EntityPipeline, TheSlamStageIsKeyframeSlamOverTheOdometryPoses) {
  const sim::EntityRecording& robot = Robot();
  EntityPipelineOptions with_slam;
  with_slam.slam.enabled = true;
  EntityPipeline staged = MakePipeline(robot, with_slam);
  ASSERT_NE(staged.slam(), nullptr);
  Replay(staged, robot);
  staged.slam()->Finish();
  const geometry::Trajectory corrected = staged.slam()->Trajectory();

  EntityPipeline plain = MakePipeline(robot);
  EXPECT_EQ(plain.slam(), nullptr);
  slam::KeyframeSlam by_hand(with_slam.slam.graph, robot.kind);
  for (const ScanStep& step : Replay(plain, robot).steps) {
    by_hand.Add(step.scan, step.odometry.world_from_body);
  }
  by_hand.Finish();
  const geometry::Trajectory expected = by_hand.Trajectory();
  ASSERT_EQ(corrected.size(), robot.scans);
  ASSERT_EQ(corrected.size(), expected.size());
  for (std::size_t i = 0; i < corrected.size(); ++i) {
    EXPECT_EQ(corrected[i].stamp_s, expected[i].stamp_s);
    EXPECT_EQ(corrected[i].pose.x_m, expected[i].pose.x_m);
    EXPECT_EQ(corrected[i].pose.theta_rad, expected[i].pose.theta_rad);
  }
  EXPECT_GT(staged.slam()->counts().keyframes, 10);
  EXPECT_EQ(staged.slam()->counts().loop_closures, by_hand.counts().loop_closures);

  EntityPipelineOptions bad = with_slam;
  bad.slam.graph.keyframe_distance_m = -1.0;
  try {
    MakePipeline(robot, bad);
    ADD_FAILURE() << "a bad SLAM option was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("slam.keyframe_distance_m"), std::string::npos)
        << error.what();
  }
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
  for (std::size_t i = 0; i < robot.records.size() && !first; ++i) first = AddRecord(pipeline, robot.records[i]);
  ASSERT_TRUE(first.has_value());
  Correction correction;
  correction.map_from_odom = {1.0, -0.5, 0.0};
  correction.confidence = 0.9;
  EXPECT_EQ(pipeline.ApplyCorrection(correction).status, CorrectionStatus::kApplied);
  std::optional<ScanStep> next;
  for (std::size_t i = 0; i < robot.records.size() && !next; ++i) {
    if (std::holds_alternative<sensors::LaserScan>(robot.records[i]) &&
        sensors::StampOf(robot.records[i]) > first->odometry.stamp_s) {
      next = AddRecord(pipeline, robot.records[i]);
    } else if (sensors::StampOf(robot.records[i]) > first->odometry.stamp_s) {
      AddRecord(pipeline, robot.records[i]);
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
  for (; i < robot.records.size() && !first; ++i) first = AddRecord(pipeline, robot.records[i]);
  ASSERT_TRUE(first.has_value());
  EXPECT_TRUE(first->covariance.isZero());  // the start defines the frame
  Correction correction;
  correction.map_from_odom = {1.0, -0.5, std::numbers::pi / 2};  // a quarter turn
  correction.confidence = 0.9;
  ASSERT_EQ(pipeline.ApplyCorrection(correction).status, CorrectionStatus::kApplied);
  std::optional<ScanStep> last;
  for (; i < robot.records.size(); ++i) {
    if (auto step = AddRecord(pipeline, robot.records[i])) last = std::move(step);
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
    if (auto step = AddRecord(pipeline, record)) steps.push_back(*step);
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
    if (AddRecord(pipeline, record) && ++scans == 12) break;
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

// The poses do not depend on the line map: an odometry-only run (`pena odometry`) gives the
// poses pena-entity publishes.
TEST(EntityPipeline, WithoutTheLineMapGivesTheSamePosesAndNoDeltas) {
  const sim::EntityRecording& robot = Robot();
  EntityPipeline full = MakePipeline(robot);
  const Replayed with_map = Replay(full, robot);
  EntityPipelineOptions poses_only;
  poses_only.build_line_map = false;
  EntityPipeline bare = MakePipeline(robot, poses_only);
  const Replayed without_map = Replay(bare, robot);
  ASSERT_EQ(without_map.steps.size(), with_map.steps.size());
  for (std::size_t i = 0; i < with_map.steps.size(); ++i) {
    const geometry::Pose2& a = with_map.steps[i].world_from_body;
    const geometry::Pose2& b = without_map.steps[i].world_from_body;
    ASSERT_EQ(a.x_m, b.x_m) << "scan " << i;
    ASSERT_EQ(a.y_m, b.y_m) << "scan " << i;
    ASSERT_EQ(a.theta_rad, b.theta_rad) << "scan " << i;
  }
  EXPECT_FALSE(with_map.deltas.empty());
  EXPECT_TRUE(without_map.deltas.empty());
  EXPECT_EQ(bare.local_map().size(), 0u);
}

// A person's strides are spread over the scans inside them by the pipeline itself, on by
// default: a library user gets what `pena odometry` and pena-entity run. Every scan comes out
// once the input ends; a robot's records are not held.
TEST(EntityPipeline, SpreadsAPersonsStridesOverTheirScansByDefault) {
  const sim::EntityRecording& walker = Walker();
  EntityPipeline spreading = MakePipeline(walker);
  const Replayed spread = Replay(spreading, walker);
  ASSERT_TRUE(spreading.stride_spreading().has_value());
  EXPECT_GT(spreading.stride_spreading()->strides_spread, 10u);
  EXPECT_GT(spreading.stride_spreading()->pieces, spreading.stride_spreading()->strides_spread);
  EXPECT_EQ(spread.steps.size(), walker.scans);

  EntityPipelineOptions off;
  off.odometry.dead_reckoning.stride_interpolation.enabled = false;
  EntityPipeline whole_strides = MakePipeline(walker, off);
  const Replayed whole = Replay(whole_strides, walker);
  EXPECT_FALSE(whole_strides.stride_spreading().has_value());
  ASSERT_EQ(whole.steps.size(), walker.scans);
  // Between reports the spread prediction moves: the odometry's priors differ.
  double largest_m = 0.0;
  for (std::size_t i = 0; i < whole.steps.size(); ++i) {
    const geometry::Pose2& a = spread.steps[i].odometry.world_from_prior;
    const geometry::Pose2& b = whole.steps[i].odometry.world_from_prior;
    largest_m = std::max(largest_m, std::hypot(a.x_m - b.x_m, a.y_m - b.y_m));
  }
  EXPECT_GT(largest_m, 0.05);

  EXPECT_FALSE(MakePipeline(Robot()).stride_spreading().has_value());
}

}  // namespace
}  // namespace pena::pipeline
