// pena-entity as a real process on loopback DDS, with this test playing the fusion and an
// intruder (docs/security.md, "Defence at the entity"): a small correction answering one of its
// reference scans is applied, the same correction again is dropped out of sequence, one that moves
// it 20 m is held, an operator's 3 m correction is applied, and a global map snapshot of another
// map id is refused.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <set>

#include "corridor_scenario.hpp"
#include "dds_endpoints.hpp"
#include "pena/sim/mission_writer.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/scanPubSubTypes.h"
#include "process_support.hpp"
#include "service_test_support.hpp"
#include "to_dds.hpp"
#include "work_queue.hpp"

namespace pena::services {
namespace {

using std::chrono::milliseconds;

std::filesystem::path MissionEntity() {
  static const std::filesystem::path entity = [] {
    const sim::Scenario scenario = sim::ParseScenario(pena::testing::kCorridorScenario, "test:gate");
    const sim::SimulationResult result = sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
    const std::filesystem::path dir = testing::ScratchDir("gate-mission");
    sim::WriteMission(scenario, result, dir, "entity_gate_test");
    return dir / "robot1";
  }();
  return entity;
}

// The fusion's side of the topics, and an intruder's global map writer.
struct FakeFusion {
  explicit FakeFusion(const DdsOptions& dds)
      : participant(dds, "test-fusion"),
        scans(participant, topics::kReferenceScan,
              [this](pena_dds::ReferenceScan&& s, const SampleMeta&) { scan_queue.Push(std::move(s)); }),
        poses(participant, topics::kPose,
              [this](pena_dds::EntityPose&& s, const SampleMeta&) { pose_queue.Push(std::move(s)); }),
        deltas(participant, topics::kLineMapDelta, [](pena_dds::LineMapDelta&&, const SampleMeta&) {}),
        corrections(participant, topics::kCorrection),
        snapshots(participant, topics::kGlobalMapSnapshot) {}

  WorkQueue<pena_dds::ReferenceScan> scan_queue;
  WorkQueue<pena_dds::EntityPose> pose_queue;
  Participant participant;
  Reader<pena_dds::ReferenceScanPubSubType> scans;
  Reader<pena_dds::EntityPosePubSubType> poses;
  Reader<pena_dds::LineMapDeltaPubSubType> deltas;
  Writer<pena_dds::CorrectionPubSubType> corrections;
  Writer<pena_dds::GlobalMapSnapshotPubSubType> snapshots;
};

// A pose correction answering `scan`, moving its pose by dx_m.
pena_dds::Correction Answer(const pena_dds::ReferenceScan& scan, double dx_m, std::uint64_t seq,
                            const std::string& operator_id = "") {
  pipeline::Correction correction;
  correction.kind = pipeline::Correction::Kind::kPose;
  correction.stamp_s = scan.stamp_s();
  correction.world_from_body = {scan.world_from_body().x_m() + dx_m, scan.world_from_body().y_m(),
                                scan.world_from_body().theta_rad()};
  correction.confidence = 1.0;
  pena_dds::Correction sample = ToDdsCorrection(correction, scan.entity_id().to_string(), seq, 0,
                                                operator_id.empty() ? scan.seq() : 0);
  SetBounded(sample.operator_id(), operator_id, "operator_id");
  return sample;
}

TEST(EntityGate, AppliesInSequenceWithinItsUncertaintyHoldsTheRestAndRefusesOtherMaps) {
  const int domain = testing::TestDomain(14);
  FakeFusion fusion(testing::LoopbackDds(domain));
  const std::filesystem::path out = testing::ScratchDir("gate-run");
  const std::filesystem::path dds = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  const pid_t pid = testing::Spawn(
      {PENA_ENTITY_BIN, "--input", MissionEntity().string(), "--rate", "2", "--domain",
       std::to_string(domain), "--out", out.string(), "--profiles-file",
       (dds / "pena-loopback.xml").string(), "--profiles-file", (dds / "pena-qos.xml").string(),
       "--wait-for-readers", "20", "--linger", "1"},
      out / "entity.log");
  ASSERT_GT(pid, 0);
  // Reference scans to answer, and the corrections applied as the poses report them.
  std::vector<pena_dds::ReferenceScan> scans;
  std::set<std::uint64_t> applied;
  // Polls both topics until `done` or `timeout_s` passed.
  auto wait_for = [&](const auto& done, double timeout_s) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(
                                                             static_cast<long>(timeout_s * 1000.0));
    while (!done() && std::chrono::steady_clock::now() < until) {
      while (auto scan = fusion.scan_queue.TryPop()) scans.push_back(std::move(*scan));
      if (auto pose = fusion.pose_queue.PopFor(milliseconds(20))) applied.insert(pose->correction_seq());
    }
    return done();
  };
  ASSERT_TRUE(wait_for([&] { return !scans.empty(); }, 60.0)) << testing::ReadFile(out / "entity.log");
  // The fusion's answer to the first scan, 1 cm off: applied. The same again: a replay.
  pena_dds::Correction small = Answer(scans[0], 0.01, 1000);
  ASSERT_TRUE(fusion.corrections.Write(small));
  ASSERT_TRUE(wait_for([&] { return applied.count(1000) > 0; }, 20.0)) << testing::ReadFile(out / "entity.log");
  ASSERT_TRUE(fusion.corrections.Write(small));
  // An answer to a later scan that moves the entity 20 m: held. An operator's 3 m: applied.
  ASSERT_TRUE(wait_for([&] { return scans.size() >= 2; }, 60.0)) << testing::ReadFile(out / "entity.log");
  pena_dds::Correction far = Answer(scans.back(), 20.0, 1001);
  ASSERT_TRUE(fusion.corrections.Write(far));
  pena_dds::Correction by_operator = Answer(scans.back(), 3.0, 1002, "op1");
  ASSERT_TRUE(fusion.corrections.Write(by_operator));
  pena_dds::GlobalMapSnapshot rogue;
  SetBounded(rogue.map_id(), std::string("rogue"), "map_id");
  rogue.schema_version(pena_dds::SCHEMA_VERSION);
  rogue.version(5);
  ASSERT_TRUE(fusion.snapshots.Write(rogue));
  wait_for([&] { return applied.count(1002) > 0; }, 20.0);
  kill(pid, SIGTERM);
  ASSERT_EQ(testing::WaitExit(pid, 30.0), 0);
  const std::string log = testing::ReadFile(out / "entity.log");
  EXPECT_EQ(applied.count(1000), 1U) << log;
  EXPECT_EQ(applied.count(1001), 0U) << log;
  EXPECT_EQ(applied.count(1002), 1U) << log;
  EXPECT_NE(log.find("correction 1000 dropped: seq 1000 is not above the last one seen, 1000"),
            std::string::npos) << log;
  EXPECT_NE(log.find("correction 1001 held, not applied: moves reference scan " +
                     std::to_string(scans.back().seq()) + " by (20.000 m"),
            std::string::npos) << log;
  EXPECT_NE(log.find("global map snapshot for map id 'rogue' refused"), std::string::npos) << log;
  EXPECT_NE(log.find("1 corrections dropped out of sequence, 1 held beyond the entity's uncertainty; "
                     "1 global map samples of another map id refused"),
            std::string::npos) << log;
}

}  // namespace
}  // namespace pena::services
