// The pipeline's bent-scan stage (docs/grid.md, "Bent scans"): given a first pass's grid of the
// same walk, a scan whose plane was tilted reaches the map levelled, or not at all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "tilted_corridor.hpp"

namespace pena::pipeline {
namespace {

using namespace testing::corridor;

constexpr double kPitchRad = 15.0 * std::numbers::pi / 180.0;  // floor met 4.64 m ahead

EntityPipeline SecondPass(BentScanMode mode) {
  EntityPipelineOptions options;
  options.bent_scans.mode = mode;
  EntityPipeline pipeline(options, sensors::EntityKind::kHuman, "ff1", {}, 0.0);
  pipeline.SetBentScanReference(LevelWalk());
  return pipeline;
}

TEST(BentScanStage, LevelsAScanWithFloorHitsBeforeTheMap) {
  EntityPipeline pipeline = SecondPass(BentScanMode::kLevel);
  const geometry::Pose2 pose{3.0, 0.0, 0.0};
  const sensors::LaserScan bent = TiltedScan(3.0, kPitchRad);
  const Placement placed = pipeline.Place(bent, pose);
  EXPECT_TRUE(placed.bent);
  ASSERT_TRUE(placed.scan);
  ASSERT_EQ(placed.scan->ranges_m.size(), bent.ranges_m.size());
  int floor = 0;
  int walls = 0;
  double worst_m = 0.0;
  double worst_raw_m = 0.0;
  for (int i = 0; i < kBeams; ++i) {
    const auto index = static_cast<std::size_t>(i);
    if (std::isnan(placed.scan->ranges_m[index])) {
      ++floor;
      continue;
    }
    const double truth_m = WallDistanceM(3.0, BeamAngle(i));
    worst_m = std::max(worst_m, std::abs(placed.scan->ranges_m[index] - truth_m));
    worst_raw_m = std::max(worst_raw_m, std::abs(bent.ranges_m[index] - truth_m));
    ++walls;
  }
  EXPECT_GT(floor, 20);          // the floor hits ahead are not drawn as a wall
  EXPECT_GT(walls, 200);
  EXPECT_GT(worst_raw_m, 0.05);  // measured: walls drawn up to this far behind them
  EXPECT_LT(worst_m, 0.01);      // as the map got them: within a centimetre
  EXPECT_EQ(pipeline.counts().bent_scans, 1);

  // A level scan of the same walk reaches the map as measured.
  const sensors::LaserScan level = TiltedScan(3.5, 0.0);
  const Placement kept = pipeline.Place(level, {3.5, 0.0, 0.0});
  EXPECT_FALSE(kept.bent);
  ASSERT_TRUE(kept.scan);
  EXPECT_EQ(kept.scan->ranges_m, level.ranges_m);
  EXPECT_EQ(pipeline.counts().bent_scans, 1);
}

TEST(BentScanStage, DropLeavesABentScanOutAndWithoutAFirstPassNothingIsBent) {
  EntityPipeline dropping = SecondPass(BentScanMode::kDrop);
  const Placement dropped = dropping.Place(TiltedScan(3.0, kPitchRad), {3.0, 0.0, 0.0});
  EXPECT_TRUE(dropped.bent);
  EXPECT_FALSE(dropped.scan);
  EXPECT_EQ(dropping.counts().bent_scans, 1);

  // The first pass itself: the stage has no grid to judge against yet.
  EntityPipelineOptions options;
  options.bent_scans.mode = BentScanMode::kLevel;
  EntityPipeline first(options, sensors::EntityKind::kHuman, "ff1", {}, 0.0);
  const sensors::LaserScan bent = TiltedScan(3.0, kPitchRad);
  const Placement placed = first.Place(bent, {3.0, 0.0, 0.0});
  EXPECT_FALSE(placed.bent);
  ASSERT_TRUE(placed.scan);
  EXPECT_EQ(placed.scan->ranges_m, bent.ranges_m);
  EXPECT_FALSE(first.has_bent_scan_reference());
}

// A firefighter bending over now and then walks a corridor and back.
const sim::EntityRecording& Walker() {
  static const sim::SimulationResult result = [] {
    constexpr const char* kScenario = R"scn(pena-scenario 1
name bent_scan_stage_test
ceiling 2.7
rect 0 0 24 8
wall 0 4 5 4
wall 6 4 13 4
wall 14 4 24 4
wall 12 4 12 8
entity ff1 human 2 2 0 speed=0.9
waypoint ff1 20 2
waypoint ff1 20 1.5
waypoint ff1 2 1.5
)scn";
    return sim::Simulator{sim::SimulationOptions{}}.Run(sim::ParseScenario(kScenario, "test:bent"));
  }();
  return result.entities.front();
}

std::vector<ScanStep> Replay(EntityPipeline& pipeline, const sim::EntityRecording& entity) {
  std::vector<ScanStep> steps;
  for (const sensors::SensorRecord& record : entity.records) {
    for (ScanStep& step : pipeline.Add(record)) steps.push_back(std::move(step));
  }
  pipeline.EndOfInput();
  while (std::optional<ScanStep> step = pipeline.Next()) steps.push_back(std::move(*step));
  return steps;
}

// The two passes through Push/Next: the second judges each scan against the first pass's grid
// before its map stages and leaves the odometry's poses as they were.
TEST(BentScanStage, TheSecondPassOfAWalkLevelsItsBendsAndKeepsItsPoses) {
  const sim::EntityRecording& walker = Walker();
  EntityPipelineOptions options;
  options.bent_scans.mode = BentScanMode::kLevel;
  const geometry::Pose2 start = walker.truth.front().world_from_body;
  EntityPipeline first(options, walker.kind, walker.id, start, walker.start_s);
  const std::vector<ScanStep> first_steps = Replay(first, walker);
  grid::OccupancyGrid first_grid;
  for (const ScanStep& step : first_steps) first_grid.Insert(step.scan, step.world_from_body);
  EXPECT_EQ(first.counts().bent_scans, 0);

  EntityPipeline second(options, walker.kind, walker.id, start, walker.start_s);
  second.SetBentScanReference(std::move(first_grid));
  const std::vector<ScanStep> second_steps = Replay(second, walker);
  ASSERT_EQ(second_steps.size(), first_steps.size());
  long bent = 0;
  for (std::size_t i = 0; i < first_steps.size(); ++i) {
    const geometry::Pose2& a = first_steps[i].world_from_body;
    const geometry::Pose2& b = second_steps[i].world_from_body;
    ASSERT_EQ(a.x_m, b.x_m) << "scan " << i;
    ASSERT_EQ(a.theta_rad, b.theta_rad) << "scan " << i;
    if (second_steps[i].bent) ++bent;
  }
  EXPECT_GT(bent, 0);
  EXPECT_LT(bent, static_cast<long>(first_steps.size()) / 3);
  EXPECT_EQ(second.counts().bent_scans, bent);
}

TEST(BentScanStage, RefusesBadOptionsAtConstructionAndAFirstPassWhenOff) {
  EntityPipelineOptions options;
  options.bent_scans.judge.laser_height_m = 0.0;
  try {
    const EntityPipeline pipeline(options, sensors::EntityKind::kHuman, "ff1", {}, 0.0);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("bent_scan.laser_height_m"), std::string::npos);
  }
  options = {};
  options.bent_scans.mode = static_cast<BentScanMode>(7);
  try {
    ValidateEntityPipelineOptions(options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("pipeline.bent_scans.mode"), std::string::npos);
  }
  EntityPipeline off(EntityPipelineOptions{}, sensors::EntityKind::kHuman, "ff1", {}, 0.0);
  EXPECT_THROW(off.SetBentScanReference(LevelWalk()), std::logic_error);

  for (const BentScanMode mode : {BentScanMode::kOff, BentScanMode::kLevel, BentScanMode::kDrop}) {
    EXPECT_EQ(BentScanModeOf(ToString(mode)), mode);
  }
  EXPECT_FALSE(BentScanModeOf("bent"));
}

}  // namespace
}  // namespace pena::pipeline
