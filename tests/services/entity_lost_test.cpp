// An entity that goes silent is marked lost and its data kept (fault test): pena-fusion
// and pena-entity as real processes on loopback DDS; the entity is killed with SIGKILL (no
// "finished" status, no goodbye) after fusion merged some of its walls. Fusion must log it
// active -> lost within silent_after_s plus a tick, and its global map must still hold the
// entity's walls at the end.
#include <gtest/gtest.h>

#include <chrono>
#include <regex>
#include <thread>

#include "dds_endpoints.hpp"
#include "from_dds.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/sim/mission_writer.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "pena_dds/global_mapPubSubTypes.h"
#include "corridor_scenario.hpp"
#include "process_support.hpp"
#include "service_test_support.hpp"
#include "work_queue.hpp"

namespace pena::services {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kScenario = pena::testing::kCorridorScenario;

std::filesystem::path LostMission() {
  static const std::filesystem::path dir = [] {
    const sim::Scenario scenario = sim::ParseScenario(kScenario, "test:lost");
    const sim::SimulationResult result = sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
    const std::filesystem::path out = testing::ScratchDir("lost-mission");
    sim::WriteMission(scenario, result, out, "entity_lost_test");
    return out;
  }();
  return dir;
}

std::vector<std::string> Profiles(int domain) {
  const std::filesystem::path dds = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  return {"--profiles-file", (dds / "pena-loopback.xml").string(), "--profiles-file",
          (dds / "pena-qos.xml").string(), "--domain", std::to_string(domain)};
}

pid_t SpawnFusion(int domain, const std::filesystem::path& run) {
  std::ofstream(run / "fusion.conf") << "state_dir: \"state\"\noutput_dir: \"out\"\n"
                                     << "silent_after_s: 2\ntick_period_s: 0.25\n";
  std::vector<std::string> args = {PENA_FUSION_BIN, "--config", (run / "fusion.conf").string()};
  for (const std::string& arg : Profiles(domain)) args.push_back(arg);
  return testing::Spawn(args, run / "fusion.log");
}

pid_t SpawnEntity(int domain, const std::filesystem::path& run) {
  std::vector<std::string> args = {PENA_ENTITY_BIN, "--input", (LostMission() / "robot1").string(),
                                   "--rate", "2", "--wait-for-readers", "20",
                                   // killed with SIGKILL: no shared memory (LoopbackUdpDds)
                                   "--profile", "pena_loopback_udp"};
  for (const std::string& arg : Profiles(domain)) args.push_back(arg);
  return testing::Spawn(args, run / "entity.log");
}

// Fusion has no plan here: every wall in a global delta came from robot1.
bool AddsWalls(const pena_dds::GlobalMapDelta& delta) {
  return !delta.added().empty() || !delta.changed().empty();
}

TEST(EntityLost, SilentEntityIsMarkedLostAndItsWallsStayInTheGlobalMap) {
  const int domain = testing::TestDomain(50);
  const std::filesystem::path run = testing::ScratchDir("lost-run");
  Participant participant(testing::LoopbackUdpDds(domain), "test-lost");
  WorkQueue<pena_dds::GlobalMapDelta> deltas;
  Reader<pena_dds::GlobalMapDeltaPubSubType> reader(
      participant, topics::kGlobalMapDelta,
      [&](pena_dds::GlobalMapDelta&& d, const SampleMeta&) { deltas.Push(std::move(d)); });
  const pid_t fusion = SpawnFusion(domain, run);
  ASSERT_GT(fusion, 0);
  const pid_t entity = SpawnEntity(domain, run);
  ASSERT_GT(entity, 0);
  // Wait until the fusion merged some of robot1's walls, then kill robot1 without a goodbye.
  bool merged = false;
  for (const auto until = Clock::now() + std::chrono::seconds(60); !merged && Clock::now() < until;) {
    if (auto delta = deltas.PopFor(std::chrono::milliseconds(100))) merged = AddsWalls(*delta);
  }
  ASSERT_TRUE(merged) << testing::ReadFile(run / "fusion.log") << testing::ReadFile(run / "entity.log");
  kill(entity, SIGKILL);
  const auto killed = Clock::now();
  EXPECT_EQ(testing::WaitExit(entity, 10.0), 128 + SIGKILL);
  const std::regex lost("robot1: (joined|active) -> lost");
  bool marked = false;
  while (!marked && Clock::now() - killed < std::chrono::seconds(15)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    marked = std::regex_search(testing::ReadFile(run / "fusion.log"), lost);
  }
  const double after_s = std::chrono::duration<double>(Clock::now() - killed).count();
  kill(fusion, SIGTERM);
  const std::string log = testing::ReadFile(run / "fusion.log");
  ASSERT_EQ(testing::WaitExit(fusion, 30.0), 0) << log;
  ASSERT_TRUE(marked) << log;
  // silent_after_s 2 + tick 0.25 + the 100 ms poll; generous for a loaded machine.
  EXPECT_LT(after_s, 6.0) << log;
  EXPECT_EQ(log.find("robot1: lost -> left"), std::string::npos) << log;
  // Its walls are kept: the final global map still names robot1 as a source.
  long kept = 0;
  for (const io::LineRow& row : io::ReadLineCsv(run / "out" / "global_map.csv")) {
    if (row.extra.find("robot1") != std::string::npos) ++kept;
  }
  EXPECT_GE(kept, 1) << log;
}

}  // namespace
}  // namespace pena::services
