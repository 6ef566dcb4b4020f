// One pipeline: `pena odometry` and pena-entity replaying the same log give the same trajectory.
// Both run pipeline::EntityPipeline with their defaults (the entity also builds its line map, on
// which the poses do not depend). A firefighter exercises the stride spreading, which the
// pipeline does itself; a robot the wheel odometry.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "pena/geometry/pose2.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/sim/mission_writer.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "process_support.hpp"
#include "service_test_support.hpp"
#include "trajectory_checks.hpp"

namespace pena::services {
namespace {

// The corridor of the entity process tests, walked by a firefighter and driven by a robot.
constexpr const char* kScenario = R"scn(pena-scenario 1
name one_pipeline_test
ceiling 2.7
rect 0 0 24 8
wall 0 4 5 4
wall 6 4 13 4
wall 14 4 24 4
wall 12 4 12 8
entity ff1 human 2 2 0 speed=0.9
waypoint ff1 20 2
waypoint ff1 20 1.5
waypoint ff1 13.5 1.5
entity robot1 robot 2 1.5 0 speed=0.8
waypoint robot1 14 1.5
)scn";

std::filesystem::path WriteMission() {
  const sim::Scenario scenario = sim::ParseScenario(kScenario, "test:one_pipeline");
  const sim::SimulationResult result = sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
  const std::filesystem::path dir = testing::ScratchDir("one-pipeline-mission");
  sim::WriteMission(scenario, result, dir, "one_pipeline_test");
  return dir;
}

// Runs `args` to completion; its output goes to `log`. Fails the test naming the log otherwise.
void RunToEnd(const std::vector<std::string>& args, const std::filesystem::path& log) {
  std::filesystem::create_directories(log.parent_path());
  const pid_t pid = testing::Spawn(args, log);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(testing::WaitExit(pid, 300.0), 0) << testing::ReadFile(log);
}

TEST(OnePipeline, PenaOdometryAndPenaEntityGiveTheSameTrajectory) {
  testing::UseLoopbackByDefault();
  const int domain = testing::TestDomain(70);
  const std::filesystem::path mission = WriteMission();
  const std::filesystem::path root = testing::ScratchDir("one-pipeline");
  const std::filesystem::path dds = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  for (const std::string id : {"ff1", "robot1"}) {
    const std::filesystem::path odometry = root / ("odometry-" + id);
    const std::filesystem::path entity = root / ("entity-" + id);
    RunToEnd({PENA_CLI_BIN, "odometry", "--log", (mission / id / "sensors.penalog").string(),
              "--out", odometry.string(), "--quiet"},
             odometry / "pena.log");
    RunToEnd({PENA_ENTITY_BIN, "--input", (mission / id).string(), "--rate", "0", "--out",
              entity.string(), "--linger", "0", "--domain", std::to_string(domain),
              "--profiles-file", (dds / "pena-loopback.xml").string(), "--profiles-file",
              (dds / "pena-qos.xml").string()},
             entity / "entity.log");
    testing::ExpectSameTrajectory(id, io::ReadTum(odometry / "trajectory.tum"),
                                  io::ReadTum(entity / "trajectory.tum"),
                                  "pena-entity vs pena odometry", 1e-3, 1e-3);
  }
}

}  // namespace
}  // namespace pena::services
