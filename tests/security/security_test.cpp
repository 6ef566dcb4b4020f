// DDS Security (docs/security.md): the identity checks that stop a daemon before it joins, and a
// rogue participant against a secured lockstep team on loopback (pena-fusion and two
// pena-entity processes): (a) without a certificate, (b) with a certificate of another CA,
// (c) with a valid entity identity of the mission trying to write a fusion correction, an
// operator correction, a global map snapshot and another entity's pose. None of its samples
// reaches a receiver, and the team's trajectories are the same with and without it. And what
// an entity identity may read.
#include <gtest/gtest.h>

#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "dds_endpoints.hpp"
#include "dds_security.hpp"
#include "pena/sim/mission_writer.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"
#include "pena_dds/sensorsPubSubTypes.h"
#include "process_support.hpp"
#include "security_support.hpp"
#include "sensor_topics.hpp"
#include "service_test_support.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

namespace fs = std::filesystem;
using namespace security_testing;  // NOLINT: the shared identities, rogue and probe

// Two robots in two rooms off a corridor, about 12 s of mission time.
constexpr const char* kTeamScenario = R"scn(pena-scenario 1
name security_test
ceiling 2.7
rect 0 0 24 8
wall 0 4 5 4
wall 6 4 13 4
wall 14 4 24 4
wall 12 4 12 8
entity robot1 robot 2 2 0 speed=0.8
waypoint robot1 11 2
entity robot2 robot 21 6 3.14159 speed=0.6
waypoint robot2 15 6
)scn";

// A copy of identity directory `from` to tamper with.
fs::path CopyIdentity(const fs::path& from, const std::string& name) {
  const fs::path to = testing::ScratchDir(name);
  fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  return to;
}

std::string ErrorOf(const SecurityFiles& files) {
  try {
    CheckSecurityFiles(files);
  } catch (const DdsError& error) {
    return error.what();
  }
  return "";
}

TEST(SecurityFiles, AcceptsAnIdentityOfTheMissionAndNamesItsSubject) {
  const CheckedIdentity identity =
      CheckSecurityFiles(SecurityFilesIn(MissionIdentities().mission / "robot1"));
  EXPECT_EQ(identity.subject, "CN=robot1,OU=entity,O=PeNa");
  EXPECT_EQ(identity.common_name, "robot1");
}

TEST(SecurityFiles, NamesAMissingFile) {
  const fs::path dir = CopyIdentity(MissionIdentities().mission / "robot1", "missing-cert");
  fs::remove(dir / "cert.pem");
  const std::string error = ErrorOf(SecurityFilesIn(dir));
  EXPECT_NE(error.find((dir / "cert.pem").string() + " (identity certificate): no such file"),
            std::string::npos) << error;
}

TEST(SecurityFiles, RefusesACertificateOfAnotherCa) {
  const fs::path dir = CopyIdentity(MissionIdentities().mission / "robot1", "foreign-cert");
  fs::copy_file(MissionIdentities().foreign / "robot1" / "cert.pem", dir / "cert.pem",
                fs::copy_options::overwrite_existing);
  fs::copy_file(MissionIdentities().foreign / "robot1" / "key.pem", dir / "key.pem",
                fs::copy_options::overwrite_existing);
  const std::string error = ErrorOf(SecurityFilesIn(dir));
  EXPECT_NE(error.find("cert.pem (identity certificate): not signed by the identity CA"),
            std::string::npos) << error;
}

TEST(SecurityFiles, RefusesAKeyThatIsNotTheCertificates) {
  const fs::path dir = CopyIdentity(MissionIdentities().mission / "robot1", "other-key");
  fs::copy_file(MissionIdentities().mission / "robot2" / "key.pem", dir / "key.pem",
                fs::copy_options::overwrite_existing);
  const std::string error = ErrorOf(SecurityFilesIn(dir));
  EXPECT_NE(error.find("key.pem (private key): does not belong to"), std::string::npos) << error;
}

TEST(SecurityFiles, RefusesPermissionsEditedAfterSigning) {
  const fs::path dir = CopyIdentity(MissionIdentities().mission / "robot1", "edited-permissions");
  std::string text = testing::ReadFile(dir / "permissions.p7s");
  const std::size_t at = text.find("<partition>robot1</partition>");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 29, "<partition>*</partition>     ");
  std::ofstream(dir / "permissions.p7s") << text;
  const std::string error = ErrorOf(SecurityFilesIn(dir));
  EXPECT_NE(error.find("permissions.p7s (permissions): its signature does not verify against the "
                       "permissions CA"),
            std::string::npos) << error;
  // And permissions of another mission.
  fs::copy_file(MissionIdentities().foreign / "robot1" / "permissions.p7s",
                dir / "permissions.p7s", fs::copy_options::overwrite_existing);
  EXPECT_NE(ErrorOf(SecurityFilesIn(dir)).find("does not verify"), std::string::npos);
}

TEST(SecurityFiles, AParticipantWithABrokenIdentityIsNeverCreated) {
  const int domain = testing::TestDomain(31);
  const fs::path dir = CopyIdentity(MissionIdentities().mission / "robot1", "broken-participant");
  fs::remove(dir / "key.pem");
  try {
    Participant participant(Secured(domain, dir), "broken");
    FAIL() << "a participant was created without its private key";
  } catch (const DdsError& error) {
    EXPECT_NE(std::string(error.what()).find((dir / "key.pem").string()), std::string::npos)
        << error.what();
  }
}

TEST(SecurityFiles, TheDaemonStopsAndNamesTheFile) {
  const fs::path out = testing::ScratchDir("daemon-no-identity");
  const fs::path missing = out / "nowhere";
  const pid_t pid = testing::Spawn({PENA_FUSION_BIN, "--state-dir", (out / "state").string(),
                                    "--domain", std::to_string(testing::TestDomain(32)),
                                    "--security", missing.string()},
                                   out / "fusion.log");
  ASSERT_GT(pid, 0);
  EXPECT_NE(testing::WaitExit(pid, 30.0), 0);
  const std::string log = testing::ReadFile(out / "fusion.log");
  EXPECT_NE(log.find((missing / "identity_ca.pem").string() + " (identity CA): no such file"),
            std::string::npos) << log;
}

// An entity reads the sensor topics in its own partition only (its driver's): access control
// refuses it a reader of them in another entity's partition or in all ("*"), while it reads the
// fusion's topics from the default partition.
TEST(Permissions, AnEntityReadsOnlyItsOwnSensors) {
  namespace dds = eprosima::fastdds::dds;
  DdsOptions options = Secured(testing::TestDomain(36), MissionIdentities().mission / "ff9");
  options.own_partition = true;
  Participant ff9(options, "ff9");
  // Its own sensors, and the fusion's corrections: allowed.
  Reader<pena_dds::SensorStreamStatusPubSubType> own(ff9, topics::kSensorStatus,
                                                    [](pena_dds::SensorStreamStatus&&, const SampleMeta&) {});
  Reader<pena_dds::CorrectionPubSubType> corrections(ff9, topics::kCorrection,
                                                     [](pena_dds::Correction&&, const SampleMeta&) {});
  // A modified participant that asks for robot1's partition, or for all, is refused a reader.
  for (const char* partition : {"robot1", "*"}) {
    dds::SubscriberQos qos = dds::SUBSCRIBER_QOS_DEFAULT;
    qos.partition().push_back(partition);
    dds::Subscriber* subscriber = ff9.get()->create_subscriber(qos);
    ASSERT_NE(subscriber, nullptr) << partition;
    dds::DataReader* reader = subscriber->create_datareader(
        ff9.GetTopic<pena_dds::SensorStreamStatusPubSubType>(topics::kSensorStatus.name),
        dds::DATAREADER_QOS_DEFAULT);
    EXPECT_EQ(reader, nullptr) << "ff9 got a reader of the sensors in partition " << partition;
    if (reader != nullptr) subscriber->delete_datareader(reader);
    ff9.get()->delete_subscriber(subscriber);
  }
  // The monitor's identity reads no sensors at all.
  Participant monitor(Secured(testing::TestDomain(36), MissionIdentities().mission / "monitor"),
                      "monitor");
  EXPECT_THROW(Reader<pena_dds::SensorStreamStatusPubSubType>(
                   monitor, topics::kSensorStatus,
                   [](pena_dds::SensorStreamStatus&&, const SampleMeta&) {}),
               DdsError);
}

// "N corrections, M global deltas received" of pena-entity's summary.
std::string Received(const std::string& log) {
  const std::size_t end = log.find(" global deltas received");
  if (end == std::string::npos) return "";
  const std::size_t begin = log.rfind(';', end);
  return begin == std::string::npos ? "" : log.substr(begin + 1, end - begin - 1);
}

fs::path TeamMission() {
  static const fs::path mission = [] {
    const sim::Scenario scenario = sim::ParseScenario(kTeamScenario, "test:security");
    const sim::SimulationResult result = sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
    const fs::path dir = testing::ScratchDir("security-mission");
    sim::WriteMission(scenario, result, dir, "security_test");
    return dir;
  }();
  return mission;
}

// One secured lockstep run of the team (pena-fusion, robot1, robot2) into `out`, with `during`
// called once the fusion is up; returns when every process has stopped.
void RunTeam(int domain, const fs::path& out, const std::function<void()>& during) {
  const fs::path dds = kRepo / "deploy" / "dds";
  const fs::path ids = MissionIdentities().mission;
  const std::vector<std::string> profiles{"--profiles-file", (dds / "pena-loopback.xml").string(),
                                          "--profiles-file", (dds / "pena-qos.xml").string()};
  std::vector<std::string> fusion{PENA_FUSION_BIN, "--state-dir", (out / "state").string(),
                                  "--out", (out / "fusion").string(), "--domain",
                                  std::to_string(domain), "--security", (ids / "fusion").string(),
                                  "--lockstep", "--lockstep-entities", "robot1,robot2",
                                  "--correction-interval", "2"};
  const pid_t fusion_pid = testing::Spawn(fusion, out / "fusion.log");
  ASSERT_GT(fusion_pid, 0);
  during();
  std::vector<pid_t> entities;
  for (const std::string id : {"robot1", "robot2"}) {
    std::vector<std::string> args{PENA_ENTITY_BIN, "--input", (TeamMission() / id).string(),
                                  "--rate", "3", "--out", (out / id).string(), "--domain",
                                  std::to_string(domain), "--security", (ids / id).string(),
                                  "--wait-for-readers", "20", "--linger", "2",
                                  "--await-corrections", "2"};
    args.insert(args.end(), profiles.begin(), profiles.end());
    entities.push_back(testing::Spawn(args, out / (id + ".log")));
    ASSERT_GT(entities.back(), 0);
  }
  for (std::size_t i = 0; i < entities.size(); ++i) {
    EXPECT_EQ(testing::WaitExit(entities[i], 120.0), 0)
        << testing::ReadFile(out / (i == 0 ? "robot1.log" : "robot2.log"));
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  kill(fusion_pid, SIGTERM);
  EXPECT_EQ(testing::WaitExit(fusion_pid, 30.0), 0) << testing::ReadFile(out / "fusion.log");
}

TEST(RoguePeer, NoSampleOfARogueReachesTheTeamAndTheTrajectoriesAreUnchanged) {
  const int domain = testing::TestDomain(33);
  const Identities& ids = MissionIdentities();
  const fs::path clean = testing::ScratchDir("team-clean");
  const fs::path attacked = testing::ScratchDir("team-attacked");
  RunTeam(domain, clean, [] {});

  // The receivers: a secured one that may read all three topics (the monitor's identity)
  // beside the team's own services.
  Probe probe(Secured(domain, ids.mission / "monitor"), "probe");
  std::vector<std::unique_ptr<Rogue>> rogues;
  // (a) no certificate: an open participant on the secured domain.
  rogues.push_back(std::make_unique<Rogue>(testing::LoopbackDds(domain), "rogue-open", "robot1"));
  // (b) a consistent identity of another mission (its own CAs, its own fusion's permissions).
  rogues.push_back(
      std::make_unique<Rogue>(Secured(domain, ids.foreign / "fusion"), "rogue-foreign", "robot1"));
  // (c) ff9, an entity of this mission: in its own partition, writing robot1's pose ...
  DdsOptions ff9 = Secured(domain, ids.mission / "ff9");
  ff9.own_partition = true;
  rogues.push_back(std::make_unique<Rogue>(ff9, "rogue-ff9", "robot1"));
  // ... and claiming robot1's partition.
  DdsOptions ff9_as_robot1 = Secured(domain, ids.mission / "ff9");
  ff9_as_robot1.publish_partition = "robot1";
  rogues.push_back(std::make_unique<Rogue>(ff9_as_robot1, "rogue-ff9-as-robot1", "robot1"));

  RunTeam(domain, attacked, [] {});
  const int probe_team = probe.team.load();
  const int probe_rogue = probe.rogue.load();
  std::vector<int> written;
  for (const auto& rogue : rogues) written.push_back(rogue->written());
  const std::vector<std::string> ff9_refused = rogues[2]->refused();
  const std::vector<std::string> ff9_as_robot1_refused = rogues[3]->refused();
  const std::uint64_t refused_by_probe = probe.participant.refused_samples();
  rogues.clear();
  std::printf("[figures] rogues wrote %d (open), %d (another CA), %d (ff9), %d (ff9 as robot1) "
              "samples; the probe heard %d of the team's and %d of theirs, refused %llu by key\n",
              written[0], written[1], written[2], written[3], probe_team, probe_rogue,
              static_cast<unsigned long long>(refused_by_probe));

  // (c) Access control refused ff9 the fusion's and the operators' topics, and robot1's
  // partition; it could write only robot1's pose in its own partition.
  EXPECT_EQ(ff9_refused, (std::vector<std::string>{"correction", "operator correction",
                                                   "global map snapshot"}));
  EXPECT_EQ(ff9_as_robot1_refused, (std::vector<std::string>{"pose", "correction",
                                                             "operator correction",
                                                             "global map snapshot"}));
  // Every rogue that had a writer wrote (else this test would prove nothing) ...
  EXPECT_GT(written[0], 100);
  EXPECT_GT(written[1], 100);
  EXPECT_GT(written[2], 30);
  // ... and no sample of theirs reached the probe, which heard the team.
  EXPECT_GT(probe_team, 50);
  EXPECT_EQ(probe_rogue, 0);
  // ff9's forged poses reached it as DDS samples and were refused there, by key.
  EXPECT_GT(refused_by_probe, 0U);

  // At the team's services: the fusion heard no pose but the team's, and the entities' logs
  // hold no correction but the fusion's. The received poses and the trajectories are the same
  // with and without the rogues.
  for (const std::string id : {"robot1", "robot2"}) {
    const std::string a = testing::ReadFile(clean / id / "trajectory.tum");
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, testing::ReadFile(attacked / id / "trajectory.tum")) << id;
    // Every pose the fusion received with the rogues present it received without them too
    // (poses are volatile: one published before the fusion's reader matched is not resent).
    const std::string heard_clean =
        testing::ReadFile(clean / "fusion" / "poses" / (id + "_world.tum"));
    std::istringstream heard_attacked(
        testing::ReadFile(attacked / "fusion" / "poses" / (id + "_world.tum")));
    int poses = 0;
    for (std::string line; std::getline(heard_attacked, line); ++poses) {
      EXPECT_NE(heard_clean.find(line + "\n"), std::string::npos) << id << ": " << line;
    }
    EXPECT_GT(poses, 40) << id;
    // The entity took the same corrections and global deltas, and dropped or held none.
    const std::string log = testing::ReadFile(attacked / (id + ".log"));
    EXPECT_EQ(log.find("corrections dropped out of sequence"), std::string::npos) << log;
    EXPECT_EQ(Received(log), Received(testing::ReadFile(clean / (id + ".log")))) << log;
    EXPECT_GT(std::atoi(Received(log).c_str()), 0) << log;  // the fusion's corrections came
  }
  std::vector<std::string> heard;
  for (const auto& entry : fs::directory_iterator(attacked / "fusion" / "poses")) {
    heard.push_back(entry.path().filename().string());
  }
  std::sort(heard.begin(), heard.end());
  EXPECT_EQ(heard, (std::vector<std::string>{"robot1_odom.tum", "robot1_world.tum",
                                             "robot2_odom.tum", "robot2_world.tum"}));
  const std::string fusion_log = testing::ReadFile(attacked / "fusion.log");
  EXPECT_EQ(fusion_log.find("rogue"), std::string::npos) << fusion_log;
  // Its permissions let it read and answer the operators (console corrections and marks).
  EXPECT_EQ(fusion_log.find("operator corrections are"), std::string::npos) << fusion_log;
  EXPECT_NE(testing::ReadFile(attacked / "fusion.log").find("refused a sample about entity "
                                                            "'robot1' from a writer in partition "
                                                            "'ff9'"),
            std::string::npos);
}

// A revoked identity: the captured device still holds its certificate, key, permissions and the
// old revocation list, so it starts; every participant that holds the new list refuses it.
TEST(RoguePeer, ARevokedIdentityIsNotHeardByParticipantsThatHoldTheNewList) {
  const fs::path root = testing::ScratchDir("revocation");
  const std::string script = (kRepo / "deploy" / "security" / "make-identities.sh").string();
  Shell(script + " " + (root / "mission").string() + " robot1 ff9 > /dev/null");
  const fs::path captured = CopyIdentity(root / "mission" / "ff9", "captured-ff9");
  Shell(script + " --revoke ff9 " + (root / "mission").string() + " robot1 > /dev/null");
  EXPECT_FALSE(fs::exists(root / "mission" / "ff9"));
  // With the new list its own check names the revocation.
  SecurityFiles revoked = SecurityFilesIn(captured);
  revoked.identity_crl = root / "mission" / "monitor" / "identity_crl.pem";
  EXPECT_NE(ErrorOf(revoked).find("cert.pem (identity certificate): revoked"), std::string::npos)
      << ErrorOf(revoked);

  const int domain = testing::TestDomain(35);
  Probe probe(Secured(domain, root / "mission" / "monitor"), "probe");
  int written = 0;
  {
    DdsOptions ff9 = Secured(domain, captured);
    ff9.own_partition = true;
    Rogue rogue(ff9, "captured-ff9", "ff9");
    // The control: a valid entity of the same mission is heard meanwhile.
    DdsOptions robot1 = Secured(domain, root / "mission" / "robot1");
    robot1.own_partition = true;
    Rogue valid(robot1, "robot1", "robot1");
    for (int i = 0; i < 100 && probe.rogue.load() < 60; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    std::this_thread::sleep_for(std::chrono::seconds(2));
    written = rogue.written();
  }
  EXPECT_GT(written, 30);
  // Every marked pose the probe heard is robot1's: none of ff9's.
  EXPECT_GE(probe.rogue.load(), 60);
  EXPECT_EQ(probe.rogue_ids.count("ff9"), 0U);
  EXPECT_EQ(probe.rogue_ids.count("robot1"), 1U);
}

// The control: on an open domain the same rogue's samples do reach the probe, so the count
// above can see them.
TEST(RoguePeer, OnAnOpenDomainTheSameRogueIsHeard) {
  const int domain = testing::TestDomain(34);
  Probe probe(testing::LoopbackDds(domain), "probe");
  {
    Rogue rogue(testing::LoopbackDds(domain), "rogue-open", "robot1");
    for (int i = 0; i < 100 && probe.rogue.load() < 30; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  EXPECT_GE(probe.rogue.load(), 30);
}

}  // namespace
}  // namespace pena::services
