// One pipeline: `pena localise` is an adapter over pipeline::EntityPipeline with its plan stage,
// `pena map --bent-scans` over its bent-scan stage. The same simulated firefighter localised by
// the binary and by the pipeline in-process (the options `pena localise` documents: no line map,
// lost and found on) gives the same trajectory; mapped, the same grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "pena/geometry/trajectory.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "pena/io/ros_map.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/plan_reader.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/pipeline/start_pose.hpp"
#include "run_pena.hpp"

namespace pena::testing {
namespace {

// The anchored poses of the pipeline over `log` on `plan_path`, started as `pena localise` starts
// a simulated log (the ground truth before the first scan), or unknown with `global_start`.
geometry::Trajectory LocaliseInProcess(const std::filesystem::path& log, const std::filesystem::path& plan_path,
                                       bool global_start) {
  const std::unique_ptr<io::LogSource> source = io::OpenLog(log, io::ReadOptions{});
  std::vector<sensors::SensorRecord> records;
  while (auto record = source->Next()) records.push_back(std::move(*record));
  pipeline::EntityPipelineOptions options;
  options.build_line_map = false;
  options.plan_localisation.lost.enabled = true;
  options.plan_localisation.global_start = global_start;
  const pipeline::StartPose start = pipeline::StartPoseOf(records, true);
  pipeline::EntityPipeline chain(options, source->description().kind.value_or(sensors::EntityKind::kRobot), source->description().entity_id,
                                 start.world_from_body, sensors::StampOf(records.front()));
  chain.SetPlan(io::ReadPlan(plan_path, io::PlanOptions{}));
  geometry::Trajectory out;
  const auto take = [&](const pipeline::ScanStep& step) {
    if (step.plan && step.plan->anchored) out.push_back({step.odometry.stamp_s, step.world_from_body});
  };
  for (const sensors::SensorRecord& record : records) {
    for (const pipeline::ScanStep& step : chain.Add(record)) take(step);
  }
  chain.EndOfInput();
  while (const auto step = chain.Next()) take(*step);
  return out;
}

void ExpectSameTrajectory(const geometry::Trajectory& cli, const geometry::Trajectory& library) {
  ASSERT_EQ(cli.size(), library.size());
  ASSERT_GT(cli.size(), 100u);
  double worst_m = 0.0, worst_rad = 0.0;
  for (std::size_t i = 0; i < cli.size(); ++i) {
    ASSERT_NEAR(cli[i].stamp_s, library[i].stamp_s, 1e-6) << "pose " << i;
    worst_m = std::max(worst_m, std::hypot(cli[i].pose.x_m - library[i].pose.x_m, cli[i].pose.y_m - library[i].pose.y_m));
    worst_rad = std::max(worst_rad, std::abs(geometry::NormalizeAngle(cli[i].pose.theta_rad - library[i].pose.theta_rad)));
  }
  EXPECT_LT(worst_m, 1e-3);
  EXPECT_LT(worst_rad, 1e-3);
}

// One pass of `log` through the pipeline's stages at the true poses (the scan's stamp within 1 ms)
// into a whole-walk grid, as `pena map --trajectory` places them; the second pass judges bent
// scans against `first_pass`. Returns the grid; `bent` counts the scans the stage found bent.
grid::OccupancyGrid MapPassInProcess(const std::filesystem::path& log, const geometry::Trajectory& truth,
                                     std::optional<grid::OccupancyGrid> first_pass, long& bent) {
  pipeline::EntityPipelineOptions options;
  options.build_line_map = false;
  options.bent_scans.mode = pipeline::BentScanMode::kLevel;
  const std::unique_ptr<io::LogSource> source = io::OpenLog(log, io::ReadOptions{});
  std::optional<pipeline::EntityPipeline> stages;
  grid::OccupancyGrid grid;
  while (const auto record = source->Next()) {
    const auto* scan = std::get_if<sensors::LaserScan>(&*record);
    if (scan == nullptr) continue;
    const auto pose = std::find_if(truth.begin(), truth.end(), [&](const geometry::StampedPose2& p) {
      return std::abs(p.stamp_s - scan->stamp_s) <= 1e-3;
    });
    if (pose == truth.end()) continue;
    if (!stages) {
      stages.emplace(options, sensors::EntityKind::kHuman, "ff1", pose->pose, scan->stamp_s);
      if (first_pass) stages->SetBentScanReference(std::move(*first_pass));
    }
    const pipeline::Placement placed = stages->Place(*scan, pose->pose);
    if (placed.scan) grid.Insert(*placed.scan, pose->pose);
  }
  bent = stages ? stages->counts().bent_scans : 0;
  return grid;
}

TEST(CliOnePipeline, PenaMapBentScansIsThePipelinesBentScanStage) {
  const auto mission = FreshDir("one_pipeline_bent");
  ASSERT_EQ(RunPena("simulate --scenario office --seed 1 --out " + mission.string()).exit_code, 0);
  const std::filesystem::path log = mission / "ff1" / "sensors.penalog";
  const std::filesystem::path truth_path = mission / "ff1" / "truth.tum";
  const auto out = FreshDir("one_pipeline_bent_map");
  const PenaRun run = RunPena("map --quiet --log " + log.string() + " --trajectory " + truth_path.string() +
                              " --out " + out.string() + " --bent-scans level");
  ASSERT_EQ(run.exit_code, 0) << run.err;

  const geometry::Trajectory truth = io::ReadTum(truth_path);
  long bent = 0;
  grid::OccupancyGrid first = MapPassInProcess(log, truth, std::nullopt, bent);
  EXPECT_EQ(bent, 0);
  const grid::OccupancyGrid second = MapPassInProcess(log, truth, std::move(first), bent);
  EXPECT_GT(bent, 20);
  EXPECT_NE(run.out.find("second pass: " + std::to_string(bent) + " bent"), std::string::npos) << run.out;
  const auto library = FreshDir("one_pipeline_bent_library");
  io::WriteRosMap(library / "grid", second.ToImage());
  EXPECT_EQ(ReadBytes(out / "grid.pgm"), ReadBytes(library / "grid.pgm"));
  EXPECT_EQ(ReadBytes(out / "grid.yaml"), ReadBytes(library / "grid.yaml"));
}

TEST(CliOnePipeline, PenaLocaliseAndThePipelineGiveTheSameTrajectory) {
  const auto mission = FreshDir("one_pipeline_sim");
  ASSERT_EQ(RunPena("simulate --scenario office --seed 2 --out " + mission.string()).exit_code, 0);
  const std::filesystem::path log = mission / "ff1" / "sensors.penalog";
  const std::filesystem::path plan = mission / "apriori.csv";
  for (const bool global : {false, true}) {
    const auto out = FreshDir(global ? "one_pipeline_global" : "one_pipeline_start");
    const PenaRun run = RunPena("localise --quiet --log " + log.string() + " --map " + plan.string() + " --out " +
                                out.string() + (global ? " --global" : ""));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    SCOPED_TRACE(global ? "--global" : "known start");
    ExpectSameTrajectory(io::ReadTum(out / "trajectory.tum"), LocaliseInProcess(log, plan, global));
  }
}

}  // namespace
}  // namespace pena::testing
