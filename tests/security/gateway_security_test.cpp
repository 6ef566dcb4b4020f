// The gateway path with DDS Security on (docs/security.md, "The gateway"): a pena-gateway pair
// (DdsDomain "building" <-> LinkSession == in-memory link == LinkSession <-> DdsDomain
// "command-post", the classes pena-gateway runs) whose participants hold the gateway identity,
// between two secured domains. In the building, robot1 (its own identity) publishes poses and
// the fusion (its identity) the global map; at the command post, pena-monitor's service (the
// monitor identity) logs what arrives and an operator sends a correction back. Rogues on both
// domains, (a) without a certificate, (b) with another mission's, (c) ff9, a valid entity of the
// mission, write forged poses of robot1, corrections, operator corrections and global map
// snapshots the whole time. The team's traffic crosses; none of the rogues' does.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include <fastrtps/xmlparser/XMLProfileManager.h>

#include "map_digest.hpp"
#include "monitor_service.hpp"
#include "pena/gateway/dds_convert.hpp"
#include "pena/gateway/dds_domain.hpp"
#include "pena/gateway/link_session.hpp"
#include "process_support.hpp"
#include "security_support.hpp"

namespace pena::services {
namespace {

using namespace security_testing;  // NOLINT: the shared identities, rogue and probe

double WallS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Both gateways of a link and the link between them: frames cross at once when pumped.
class GatewayPair {
 public:
  GatewayPair(const DdsOptions& building, const DdsOptions& post)
      : building_(Options(building, "building")),
        post_(Options(post, "command-post")),
        near_(Link(1), building_),
        far_(Link(2), post_) {}

  void Pump() {
    const double now_s = WallS();
    building_.set_clock(now_s);
    post_.set_clock(now_s);
    for (const std::string& frame : near_.Poll(now_s)) EXPECT_TRUE(far_.OnFrame(frame, now_s).ok());
    for (const std::string& frame : far_.Poll(now_s)) EXPECT_TRUE(near_.OnFrame(frame, now_s).ok());
  }
  gateway::DdsDomain& building() { return building_; }
  gateway::DdsDomain& post() { return post_; }

 private:
  static gateway::DdsDomainOptions Options(const DdsOptions& dds, const std::string& role) {
    gateway::DdsDomainOptions options;
    options.dds = dds;
    options.name = "pena-gateway-" + role;
    options.role = *gateway::ParseDdsRole(role);
    options.snapshot_grace_s = 0.5;
    return options;
  }
  static gateway::LinkOptions Link(std::uint64_t session) {
    gateway::LinkOptions options;
    options.session = session;
    options.budget_bit_s = 256000.0;
    options.burst_bits = 8.0 * 4000.0;
    options.packet_bytes = 1400;
    return options;
  }

  gateway::DdsDomain building_;
  gateway::DdsDomain post_;
  gateway::LinkSession near_;
  gateway::LinkSession far_;
};

// Walls of the fusion's map: `count` from row `row0`.
std::vector<line_map::LineSegment> Walls(int count, int row0) {
  std::vector<line_map::LineSegment> walls;
  for (int i = 0; i < count; ++i) {
    line_map::LineSegment wall;
    wall.segment.start_m = {4.0 * (i % 10), 0.5 * (row0 + i / 10)};
    wall.segment.end_m = {4.0 * (i % 10) + 3.0, 0.5 * (row0 + i / 10)};
    wall.support_cells = 60;
    wall.observations = 10;
    walls.push_back(wall);
  }
  return walls;
}

// What one run saw.
struct GatewayRun {
  MonitorSummary monitor;
  int probe_team = 0;   // the team's poses and corrections heard by the probe at the post
  int probe_rogue = 0;  // the rogues' samples heard there
  std::set<std::string> probe_rogue_ids;  // entity ids of the rogues' poses heard there
  std::string poses_csv;
  std::string map_csv;
  std::uint64_t source_version = 0;
  std::uint64_t source_digest = 0;
  int operator_team = 0;  // the operator's correction, received by the fusion in the building
  std::map<std::string, int> operator_rogue;  // rogues' operator corrections there, by target
  std::uint64_t building_refused = 0;  // samples the building gateway refused by key
  std::vector<int> written;
  std::vector<std::vector<std::string>> refused;
};

// The team across the gateway pair on domains `building` and `post`, with `rogues(a, b)` made
// once the pair is up (a: the building's domain, b: the post's); `secured` gives every team
// participant its identity.
GatewayRun RunThroughGateways(
    bool secured,
    const std::function<std::vector<std::unique_ptr<Rogue>>(int building, int post)>& make_rogues) {
  // A dozen participants in one process: Fast DDS 2.9.1 delivers between them in-process, and
  // there its liveliness messages can deadlock with a reader being deleted (seen in the open
  // run's teardown). Deployed, every process holds one participant, so the test delivers
  // through the transport as they do.
  eprosima::fastrtps::LibrarySettingsAttributes library;
  library.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(library);
  const Identities& ids = MissionIdentities();
  const int building = testing::TestDomain(37);
  const int post = testing::TestDomain(38);
  EXPECT_NE(building, post);
  const auto dds = [&](int domain, const std::string& identity) {
    return secured ? Secured(domain, ids.mission / identity) : testing::LoopbackDds(domain);
  };
  GatewayPair pair(dds(building, "gateway"), dds(post, "gateway"));

  // The command post: pena-monitor's service, and an operator.
  const fs::path out = testing::ScratchDir(secured ? "gateway-secured" : "gateway-open");
  MonitorOptions monitor_options;
  monitor_options.dds = dds(post, "monitor");
  monitor_options.output_dir = out / "monitor";
  monitor_options.duration_s = 14.0;  // from when its worker starts, once the team is matched
  auto monitor = std::make_unique<MonitorService>(monitor_options);
  GatewayRun run;
  // A probe beside it (the monitor's identity) tells the rogues' samples by their marks, which
  // the gateway carries (positions) where pena-monitor's log has only sequence numbers, which
  // the gateway renumbers.
  Probe probe(dds(post, "monitor"), "probe");
  Participant operator_participant(dds(post, "operator"), "operator");
  // A writer access control admits (the fusion's identity) sending a snapshot of another map id
  // than the monitor's: refused by map id.
  Participant other_map(dds(post, "fusion"), "other-map");
  Writer<pena_dds::GlobalMapSnapshotPubSubType> other_map_writer(other_map, topics::kGlobalMapSnapshot);
  Writer<pena_dds::OperatorCorrectionPubSubType> operator_writer(operator_participant,
                                                                 topics::kOperatorCorrection);

  // The building: robot1 and the fusion.
  DdsOptions robot1_dds = dds(building, "robot1");
  robot1_dds.own_partition = true;
  Participant robot1(robot1_dds, "robot1");
  Writer<pena_dds::EntityPosePubSubType> pose_writer(robot1, topics::kPose);
  Participant fusion(dds(building, "fusion"), "fusion");
  Writer<pena_dds::GlobalMapSnapshotPubSubType> snapshot_writer(fusion, topics::kGlobalMapSnapshot);
  Writer<pena_dds::GlobalMapDeltaPubSubType> delta_writer(fusion, topics::kGlobalMapDelta);
  std::atomic<int> operator_team{0};
  std::mutex mutex;
  Reader<pena_dds::OperatorCorrectionPubSubType> operator_reader(
      fusion, topics::kOperatorCorrection,
      [&](pena_dds::OperatorCorrection&& s, const SampleMeta&) {
        if (IsRogueX(s.world_from_body().x_m())) {
          const std::lock_guard<std::mutex> lock(mutex);
          ++run.operator_rogue[s.target_entity_id().to_string()];
        } else if (s.operator_id().to_string() == "operator") {
          ++operator_team;
        }
      });

  const auto pump_until = [&](double timeout_s, const std::function<bool()>& done,
                              const std::function<void()>& each) {
    const double until_s = WallS() + timeout_s;
    while (WallS() < until_s) {
      pair.Pump();
      each();
      if (done()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  };
  std::uint64_t pose_seq = 0;
  double next_pose_s = 0.0;
  const auto write_pose = [&] {
    if (WallS() < next_pose_s) return;
    next_pose_s = WallS() + 0.1;
    pena_dds::EntityPose sample =
        gateway::PoseToDds(gateway::PoseUpdate{"robot1", {1.0 + 0.01 * static_cast<double>(pose_seq), 2.0, 0.5}, WallS()},
                           ++pose_seq);
    pose_writer.Write(sample);
  };
  EXPECT_TRUE(pump_until(
      30.0,
      [&] {
        return pose_writer.matched() > 0 && snapshot_writer.matched() > 0 &&
               delta_writer.matched() > 0 && operator_writer.matched() > 0 &&
               operator_reader.matched() > 0 && pair.post().matched_readers() > 0 &&
               probe.poses.matched() > 0 &&
               // The probe's reader and the monitor's: it is written once, and a loaded machine's
               // secured discovery can pair the monitor later than its 14 s run lasts.
               other_map_writer.matched() >= 2;
      },
      [] {}))
      << "the team's endpoints and the gateways did not match";
  std::thread monitor_thread([&] { run.monitor = monitor->Run(); });

  std::vector<std::unique_ptr<Rogue>> rogues = make_rogues(building, post);
  const double rogues_from_s = WallS();

  // The fusion's map: a snapshot, then a delta; the operator's correction from the post.
  line_map::LineMap source;
  source.Integrate(Walls(40, 0), kGlobalMapId);
  pena_dds::GlobalMapSnapshot snapshot = ToDdsGlobalMapSnapshot(source.Snapshot(), kGlobalMapId, 1.0);
  EXPECT_TRUE(snapshot_writer.Write(snapshot));
  const line_map::MapDelta delta = source.Integrate(Walls(5, 40), kGlobalMapId);
  bool delta_sent = false;
  pena_dds::OperatorCorrection move;
  SetBounded(move.correction_id(), std::string("operator/1"), "correction_id");
  SetBounded(move.operator_id(), std::string("operator"), "operator_id");
  SetBounded(move.target_entity_id(), std::string("robot1"), "target_entity_id");
  move.schema_version(pena_dds::SCHEMA_VERSION);
  move.kind(pena_dds::OPERATOR_SET_POSE);
  move.world_from_body().x_m(3.0);
  move.stamp_s(WallS());
  EXPECT_TRUE(operator_writer.Write(move));
  line_map::LineMap elsewhere;
  elsewhere.Integrate(Walls(3, 0), "elsewhere");
  pena_dds::GlobalMapSnapshot other = ToDdsGlobalMapSnapshot(elsewhere.Snapshot(), "elsewhere", 1.0);
  other.version(1000000);  // newer than the fusion's, unmarked (the probe counts marked ones)
  EXPECT_TRUE(other_map_writer.Write(other));
  // Run at least 8 s with the rogues writing, until the map and the correction crossed.
  pump_until(
      12.0,
      [&] { return WallS() - rogues_from_s > 8.0 && delta_sent && operator_team.load() > 0; },
      [&] {
        write_pose();
        if (!delta_sent && WallS() - rogues_from_s > 2.0) {
          pena_dds::GlobalMapDelta sample = ToDdsGlobalMapDelta(delta, kGlobalMapId, 2.0);
          delta_sent = delta_writer.Write(sample);
        }
      });
  for (const auto& rogue : rogues) {
    run.written.push_back(rogue->written());
    run.refused.push_back(rogue->refused());
  }
  rogues.clear();
  run.building_refused = pair.building().stats().samples_refused;
  monitor_thread.join();
  monitor.reset();
  run.operator_team = operator_team.load();
  run.probe_team = probe.team.load();
  run.probe_rogue = probe.rogue.load();
  {
    const std::lock_guard<std::mutex> lock(probe.mutex);
    run.probe_rogue_ids = probe.rogue_ids;
  }
  run.source_version = source.version();
  run.source_digest = MapDigest(source.segments());
  run.poses_csv = testing::ReadFile(out / "monitor" / "poses.csv");
  run.map_csv = testing::ReadFile(out / "monitor" / "map.csv");
  return run;
}

// Field `index` (from 0) of each data row of a CSV text.
std::vector<std::string> Column(const std::string& csv, int index) {
  std::istringstream in(csv);
  std::vector<std::string> column;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string field;
    for (int i = 0; i <= index; ++i) std::getline(fields, field, ',');
    column.push_back(field);
  }
  return column;
}

// Rows of pena-monitor's poses.csv (recv_ns,entity,seq,...) with a rogue's sequence number
// (written on the post's domain: the gateway renumbers what it carries).
int RoguePoses(const std::string& poses_csv) {
  int rogue = 0;
  for (const std::string& seq : Column(poses_csv, 2)) rogue += std::stoull(seq) >= kRogueSeq;
  return rogue;
}

// Rows of pena-monitor's map.csv (recv_ns,kind,from_version,to_version,...) of a rogue's
// snapshot version.
int RogueMaps(const std::string& map_csv) {
  int rogue = 0;
  for (const std::string& version : Column(map_csv, 3)) rogue += std::stoull(version) >= kRogueSeq;
  return rogue;
}

int Sum(const std::map<std::string, int>& counts) {
  int sum = 0;
  for (const auto& [key, count] : counts) sum += count;
  return sum;
}

TEST(GatewaySecured, TheTeamCrossesAndNoRogueInjectsThroughTheGateways) {
  const Identities& ids = MissionIdentities();
  const GatewayRun run = RunThroughGateways(true, [&](int building, int post) {
    std::vector<std::unique_ptr<Rogue>> rogues;
    for (const int domain : {building, post}) {
      // (a) no certificate, (b) another mission's, (c) ff9 of this mission in its partition.
      rogues.push_back(std::make_unique<Rogue>(testing::LoopbackDds(domain), "rogue-open", "robot1"));
      rogues.push_back(
          std::make_unique<Rogue>(Secured(domain, ids.foreign / "fusion"), "rogue-foreign", "robot1"));
      DdsOptions ff9 = Secured(domain, ids.mission / "ff9");
      ff9.own_partition = true;
      rogues.push_back(std::make_unique<Rogue>(ff9, "rogue-ff9", "robot1"));
    }
    return rogues;
  });
  // Every rogue wrote on the topics it had writers for, the whole time.
  for (std::size_t i = 0; i < run.written.size(); ++i) EXPECT_GT(run.written[i], 100) << "rogue " << i;
  // ff9 was refused every writer but its own partition's poses.
  for (const std::size_t i : {2U, 5U}) {
    EXPECT_EQ(run.refused[i], (std::vector<std::string>{"correction", "operator correction",
                                                       "global map snapshot"}));
  }
  // The team crossed: robot1's poses, the fusion's map (snapshot and delta) to the monitor, the
  // operator's correction to the fusion.
  EXPECT_GT(run.monitor.poses, 20);
  EXPECT_GT(run.probe_team, 20);
  EXPECT_EQ(run.monitor.map_version, run.source_version);
  EXPECT_EQ(run.monitor.map_digest, run.source_digest);
  EXPECT_EQ(run.monitor.deltas_invalid, 0);
  EXPECT_EQ(run.monitor.global_maps_refused, 1);  // the snapshot of map id "elsewhere"
  EXPECT_GE(run.operator_team, 1);
  // None of the rogues' samples did: no forged pose or snapshot at the monitor (their sequence
  // numbers and versions start at kRogueSeq), no forged operator correction at the fusion.
  EXPECT_EQ(run.probe_rogue, 0);
  EXPECT_EQ(RoguePoses(run.poses_csv), 0);
  EXPECT_EQ(RogueMaps(run.map_csv), 0);
  EXPECT_EQ(Sum(run.operator_rogue), 0);
  // ff9's forged poses of robot1 reached the building gateway as DDS samples and were refused
  // there, by key.
  EXPECT_GT(run.building_refused, 0U);
  int written = 0;
  for (const int count : run.written) written += count;
  std::printf("[figures] 6 rogues wrote %d samples; at the post %ld poses logged by the monitor, "
              "%d team samples and %d rogue samples heard by the probe; map version %llu equal "
              "to the fusion's: %s; the building gateway refused %llu samples by key\n",
              written, run.monitor.poses, run.probe_team, run.probe_rogue,
              static_cast<unsigned long long>(run.monitor.map_version),
              run.monitor.map_digest == run.source_digest ? "yes" : "no",
              static_cast<unsigned long long>(run.building_refused));
}

// The control: on open domains the same rogues' samples cross the gateway pair, so the counts
// above can see them: the building rogue's forged poses of robot1 reach the post's probe, the
// post rogue's operator corrections for robot2 reach the building's fusion.
TEST(GatewaySecured, OnOpenDomainsTheSameRoguesCrossTheGateways) {
  const GatewayRun run = RunThroughGateways(false, [](int building, int post) {
    std::vector<std::unique_ptr<Rogue>> rogues;
    rogues.push_back(std::make_unique<Rogue>(testing::LoopbackDds(building), "rogue-building", "robot1"));
    rogues.push_back(std::make_unique<Rogue>(testing::LoopbackDds(post), "rogue-post", "robot2"));
    return rogues;
  });
  EXPECT_EQ(run.probe_rogue_ids, (std::set<std::string>{"robot1", "robot2"}));
  EXPECT_GT(run.probe_rogue, 10);
  EXPECT_GT(run.operator_rogue.count("robot2") ? run.operator_rogue.at("robot2") : 0, 10);
  EXPECT_GT(RogueMaps(run.map_csv), 0);  // and a forged snapshot was adopted
}

}  // namespace
}  // namespace pena::services
