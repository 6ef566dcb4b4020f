// An entity whose start pose is unknown: pena-entity --unknown-start runs its chain in
// its own frame (its first pose is the origin, not the robot's true start at (28.5, 4.5) facing
// north in the team building) and says so in its status; pena-fusion places it by matching its
// local map to the global map (the a priori plan and two firefighters with known starts),
// keeping several hypotheses until one wins by a margin, and sends it its frame. The entity's
// published poses then follow the truth. One pena-fusion and three pena-entity processes on
// loopback DDS.
#include <gtest/gtest.h>

#include <fcntl.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include "pena/io/line_csv.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/sim/mission_writer.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "process_support.hpp"
#include "service_test_support.hpp"

namespace pena::services {
namespace {

namespace fs = std::filesystem;

// The placement must put the entity within this of the truth (the example figure).
constexpr double kPlacedWithinM = 0.5;

fs::path TeamMission() {
  const sim::Scenario scenario =
      sim::ParseScenario(*sim::BuiltinScenarioText("team"), "builtin:team");
  const sim::SimulationResult result = sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
  const fs::path out = testing::ScratchDir("unknown-start-team");
  sim::WriteMission(scenario, result, out, "unknown_start_test");
  return out;
}

std::vector<std::string> DdsArgs(int domain) {
  const fs::path dds = fs::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  return {"--domain", std::to_string(domain), "--profiles-file",
          (dds / "pena-loopback.xml").string(), "--profiles-file", (dds / "pena-qos.xml").string()};
}

// Position error of `pose` against the truth pose nearest in time (the simulator writes truth at
// every scan, so the stamps coincide).
double ErrorM(const geometry::StampedPose2& pose, const geometry::Trajectory& truth) {
  const geometry::StampedPose2* nearest = &truth.front();
  for (const geometry::StampedPose2& t : truth) {
    if (std::abs(t.stamp_s - pose.stamp_s) < std::abs(nearest->stamp_s - pose.stamp_s)) nearest = &t;
  }
  return std::hypot(pose.pose.x_m - nearest->pose.x_m, pose.pose.y_m - nearest->pose.y_m);
}

TEST(FusionProcess, EntityWithUnknownStartIsPlacedAndEndsNearTheTruth) {
  const fs::path mission = TeamMission();
  const int domain = testing::TestDomain(61);
  const fs::path run = testing::ScratchDir("unknown-start-run");
  std::vector<std::string> fusion_args{PENA_FUSION_BIN, "--state-dir", (run / "state").string(),
                                       "--plan", (mission / "apriori.csv").string(), "--out",
                                       (run / "fusion").string(), "--correction-interval", "0.2"};
  for (const std::string& arg : DdsArgs(domain)) fusion_args.push_back(arg);
  const pid_t fusion = testing::Spawn(fusion_args, run / "fusion.log");
  ASSERT_GT(fusion, 0);
  std::vector<pid_t> entities;
  for (const char* id : {"ff1", "ff2", "robot1"}) {
    std::vector<std::string> args{PENA_ENTITY_BIN, "--input", (mission / id).string(), "--rate",
                                  "6", "--out", (run / id).string(), "--wait-for-readers", "30",
                                  "--linger", "5"};
    if (std::string(id) == "robot1") args.push_back("--unknown-start");
    for (const std::string& arg : DdsArgs(domain)) args.push_back(arg);
    entities.push_back(testing::Spawn(args, run / (std::string(id) + ".log")));
  }
  for (const pid_t pid : entities) {
    ASSERT_GT(pid, 0);
    ASSERT_EQ(testing::WaitExit(pid, 240.0), 0) << testing::ReadFile(run / "fusion.log");
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  kill(fusion, SIGTERM);
  ASSERT_EQ(testing::WaitExit(fusion, 30.0), 0) << testing::ReadFile(run / "fusion.log");

  const std::string fusion_log = testing::ReadFile(run / "fusion.log");
  const std::string robot_log = testing::ReadFile(run / "robot1.log");
  EXPECT_NE(fusion_log.find("robot1: start unknown"), std::string::npos) << fusion_log;
  EXPECT_NE(fusion_log.find("robot1: placed at"), std::string::npos) << fusion_log;
  ASSERT_NE(robot_log.find("robot1: placed by the fusion"), std::string::npos) << robot_log;

  const geometry::Trajectory truth = io::ReadTum(mission / "robot1" / "truth.tum");
  const geometry::Trajectory sent = io::ReadTum(run / "robot1" / "trajectory.tum");
  ASSERT_FALSE(truth.empty());
  ASSERT_GT(sent.size(), 100u);
  // The start really was unknown: the first pose sent (the origin) is far from the truth.
  const double first_m = ErrorM(sent.front(), truth);
  // Placed: from the first pose within reach on, and at the end.
  std::size_t placed = sent.size();
  for (std::size_t i = 0; i < sent.size() && placed == sent.size(); ++i) {
    if (ErrorM(sent[i], truth) <= kPlacedWithinM) placed = i;
  }
  const double last_m = ErrorM(sent.back(), truth);
  double sum_sq = 0.0;
  for (std::size_t i = placed; i < sent.size(); ++i) sum_sq += std::pow(ErrorM(sent[i], truth), 2);
  const double rms_after_m =
      placed < sent.size() ? std::sqrt(sum_sq / static_cast<double>(sent.size() - placed)) : 0.0;
  std::printf("[ figures  ] robot1 (start unknown): first pose %.2f m from the truth; placed "
              "(within %.1f m) at pose %zu of %zu (%.1f s mission); final error %.3f m, RMS "
              "after placement %.3f m\n",
              first_m, kPlacedWithinM, placed, sent.size(),
              placed < sent.size() ? sent[placed].stamp_s - sent.front().stamp_s : -1.0, last_m,
              rms_after_m);
  EXPECT_GT(first_m, 5.0) << "the entity's own frame should be far from the map frame";
  ASSERT_LT(placed, sent.size()) << "never within " << kPlacedWithinM << " m of the truth";
  EXPECT_LE(last_m, kPlacedWithinM);
  EXPECT_LE(rms_after_m, kPlacedWithinM);

  // Its walls are in the global map, placed (provenance robot1).
  bool robot_walls = false;
  for (const io::LineRow& row : io::ReadLineCsv(run / "fusion" / "global_map.csv")) {
    if (row.extra.find("robot1:") != std::string::npos) robot_walls = true;
  }
  EXPECT_TRUE(robot_walls);
}

// The plan is in the map frame, the chain of an entity with an unknown start in its own frame:
// the two together are refused before any DDS participant or input is opened.
TEST(FusionProcess, UnknownStartWithAPlanIsRefusedWithAClearMessage) {
  const fs::path dir = testing::ScratchDir("unknown-start-plan");
  std::ofstream(dir / "plan.csv") << "id,x1,y1,x2,y2\n1,0,0,10,0\n";
  const pid_t pid = testing::Spawn({PENA_ENTITY_BIN, "--input", (dir / "no-such.penalog").string(),
                                    "--unknown-start", "--plan", (dir / "plan.csv").string()},
                                   dir / "log");
  ASSERT_GT(pid, 0);
  EXPECT_EQ(testing::WaitExit(pid, 20.0), 1);
  const std::string log = testing::ReadFile(dir / "log");
  EXPECT_NE(log.find("--unknown-start and plan"), std::string::npos) << log;
  EXPECT_NE(log.find("plan.csv"), std::string::npos) << log;
  // Each alone is accepted as far as the options go (the input then fails to open: exit 1 too,
  // but with a message naming the input, not the combination).
  const pid_t alone = testing::Spawn(
      {PENA_ENTITY_BIN, "--input", (dir / "no-such.penalog").string(), "--unknown-start"},
      dir / "log2");
  ASSERT_GT(alone, 0);
  EXPECT_EQ(testing::WaitExit(alone, 20.0), 1);
  const std::string log2 = testing::ReadFile(dir / "log2");
  EXPECT_EQ(log2.find("--unknown-start and plan"), std::string::npos) << log2;
  EXPECT_NE(log2.find("no-such.penalog"), std::string::npos) << log2;
}

}  // namespace
}  // namespace pena::services
