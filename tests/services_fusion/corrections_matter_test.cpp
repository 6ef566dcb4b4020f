// Corrections matter: a firefighter whose heading sensors are disturbed drifts; with
// pena-fusion's virtual-scan corrections (against the global map, here the a priori plan) its RMS
// position error is at most half of its own laser odometry's. One pena-fusion and one pena-entity
// on loopback DDS. Both figures come from the same run: the entity's published world_from_body
// (corrections applied) and its odom_from_body (the odometry, which corrections never touch).
#include <gtest/gtest.h>

#include <fcntl.h>

#include <chrono>
#include <sstream>
#include <thread>

#include "pena/eval/trajectory_error.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/sim/mission_writer.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "process_support.hpp"
#include "service_test_support.hpp"

namespace pena::services {
namespace {

namespace fs = std::filesystem;

// The team building and plan with ff1 alone, walking through three strong magnetic disturbances
// (steel structures along its corridors: the compass is off by up to 40 deg there). Over the
// whole team route its laser odometry drifts 0.94 m RMS instead of 0.58 m (seed 1).
std::string DisturbedScenario() {
  std::istringstream team{std::string(*sim::BuiltinScenarioText("team"))};
  std::ostringstream out;
  for (std::string line; std::getline(team, line);) {
    const bool other = (line.rfind("entity ", 0) == 0 || line.rfind("waypoint ", 0) == 0) &&
                       line.find(" ff1 ") == std::string::npos;
    // ff1's last leg, back into the lobby, ends with a laser-odometry failure that has nothing
    // to do with the compass (1.5-2.8 m with or without corrections, and no reference scans
    // reach the fusion after it: docs/demo.md); the route ends at the corridor instead.
    if (!other && line != "waypoint ff1 23 3") out << line << '\n';
  }
  out << "magnetic 16 9 5 40\nmagnetic 7 15 5 -40\nmagnetic 14 26 5 40\n";
  return out.str();
}

fs::path DisturbedMission() {
  const sim::Scenario scenario = sim::ParseScenario(DisturbedScenario(), "test:disturbed");
  const sim::SimulationResult result = sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
  const fs::path out = testing::ScratchDir("disturbed");
  sim::WriteMission(scenario, result, out, "corrections_matter_test");
  return out;
}

std::vector<std::string> DdsArgs(int domain) {
  const fs::path dds = fs::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  return {"--domain", std::to_string(domain), "--profiles-file",
          (dds / "pena-loopback.xml").string(), "--profiles-file", (dds / "pena-qos.xml").string()};
}

double Rmse(const fs::path& estimate, const fs::path& truth) {
  return eval::EvaluateAgainstTruth(io::ReadTum(estimate), io::ReadTum(truth)).translation_rmse_m;
}

TEST(FusionProcess, CorrectionsHalveTheErrorOfAnEntityWhoseHeadingIsDisturbed) {
  const fs::path mission = DisturbedMission();
  const int domain = testing::TestDomain(50);
  const fs::path run = testing::ScratchDir("disturbed-run");
  std::vector<std::string> fusion_args{PENA_FUSION_BIN, "--state-dir", (run / "state").string(),
                                       "--plan", (mission / "apriori.csv").string(), "--out",
                                       (run / "fusion").string(), "--correction-interval", "0.2"};
  std::vector<std::string> entity_args{PENA_ENTITY_BIN, "--input", (mission / "ff1").string(),
                                       "--rate", "6", "--out", (run / "ff1").string(),
                                       "--wait-for-readers", "30", "--linger", "5"};
  for (const std::string& arg : DdsArgs(domain)) {
    fusion_args.push_back(arg);
    entity_args.push_back(arg);
  }
  const pid_t fusion = testing::Spawn(fusion_args, run / "fusion.log");
  ASSERT_GT(fusion, 0);
  const pid_t entity = testing::Spawn(entity_args, run / "ff1.log");
  ASSERT_EQ(testing::WaitExit(entity, 240.0), 0) << testing::ReadFile(run / "ff1.log");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  kill(fusion, SIGTERM);
  ASSERT_EQ(testing::WaitExit(fusion, 30.0), 0) << testing::ReadFile(run / "fusion.log");
  const fs::path truth = mission / "ff1" / "truth.tum";
  const double with_m = Rmse(run / "ff1" / "trajectory.tum", truth);
  const double without_m = Rmse(run / "fusion" / "poses" / "ff1_odom.tum", truth);
  std::printf("[ figures  ] ff1 (disturbed heading): RMS position error %.3f m with corrections, "
              "%.3f m without\n", with_m, without_m);
  // The disturbance must make the odometry drift for halving to mean anything: the odometry alone
  // drifts 0.40 m here, and corrections bring it to 0.15 m.
  EXPECT_GT(without_m, 0.3) << "the disturbance should make the odometry drift";
  EXPECT_LE(with_m, 0.5 * without_m);
}

}  // namespace
}  // namespace pena::services
