// pena-entity --input dds fed by pena-sensor-replay, all real processes on loopback DDS: a short
// mission with a firefighter and a robot is replayed onto the live sensor topics (both entities
// in one domain, so each entity sees and ignores the other's samples), and each entity's
// trajectory.tum is compared with a pena-entity run reading the same log from its file. Open,
// and secured with DDS Security (each entity's driver and pena-entity with the entity's
// identity: an entity then reads only its own driver's sensors, docs/security.md).
#include <gtest/gtest.h>

#include <csignal>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>
#include <map>
#include <regex>

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

// The corridor of the entity process tests with a firefighter walking it and a robot behind:
// about 25 s of mission time, so every sensor topic (gyro, compass, stride; wheel odometry;
// scans) carries samples.
constexpr const char* kScenario = R"scn(pena-scenario 1
name live_input_test
ceiling 2.7
rect 0 0 24 8
wall 0 4 5 4
wall 6 4 13 4
wall 14 4 24 4
wall 12 4 12 8
entity ff1 human 2 2 0 speed=0.9
waypoint ff1 20 2
waypoint ff1 20 1.5
entity robot1 robot 2 1.5 0 speed=0.8
waypoint robot1 14 1.5
)scn";

const std::filesystem::path& MissionDir() {
  static const std::filesystem::path dir = [] {
    const sim::Scenario scenario = sim::ParseScenario(kScenario, "test:live_input");
    const sim::SimulationResult result = sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
    const std::filesystem::path out = testing::ScratchDir("live-mission");
    sim::WriteMission(scenario, result, out, "live_input_test");
    return out;
  }();
  return dir;
}

std::vector<std::string> DdsArgs(int domain) {
  const std::filesystem::path dds = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  return {"--domain", std::to_string(domain), "--profiles-file",
          (dds / "pena-loopback.xml").string(), "--profiles-file", (dds / "pena-qos.xml").string()};
}

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

struct Process {
  std::filesystem::path out;
  pid_t pid = -1;
};

// pena-entity on the entity's log file, as fast as it runs.
Process StartFileEntity(const std::string& id, int domain, const std::filesystem::path& root) {
  Process run{root / ("file-" + id)};
  std::filesystem::create_directories(run.out);
  run.pid = testing::Spawn(Concat({PENA_ENTITY_BIN, "--input", (MissionDir() / id).string(),
                                   "--rate", "0", "--out", run.out.string(), "--linger", "0"},
                                  DdsArgs(domain)),
                           run.out / "entity.log");
  return run;
}

// pena-entity on the live topics. The reorder window is 1 s of sensor time (0.25 s of wall
// time at the replay's rate 4): wider than the default 0.2 s so a loaded CI machine delaying
// one topic cannot make a record late and the comparison with the file run exact.
Process StartLiveEntity(const std::string& id, std::vector<std::string> extra, int domain,
                        const std::filesystem::path& root) {
  Process run{root / ("live-" + id)};
  std::filesystem::create_directories(run.out);
  std::vector<std::string> args = {PENA_ENTITY_BIN, "--input", "dds", "--entity-id", id,
                                   "--out", run.out.string(), "--reorder-window", "1.0",
                                   "--idle-timeout", "60", "--linger", "0"};
  args.insert(args.end(), extra.begin(), extra.end());
  run.pid = testing::Spawn(Concat(args, DdsArgs(domain)), run.out / "entity.log");
  return run;
}

Process StartReplay(const std::string& id, std::vector<std::string> extra, int domain,
                    const std::filesystem::path& root) {
  Process run{root / ("replay-" + id)};
  std::filesystem::create_directories(run.out);
  std::vector<std::string> args = {PENA_SENSOR_REPLAY_BIN, "--input", (MissionDir() / id).string(),
                                   "--rate", "4", "--wait-for-readers", "30"};
  args.insert(args.end(), extra.begin(), extra.end());
  run.pid = testing::Spawn(Concat(args, DdsArgs(domain)), run.out / "replay.log");
  return run;
}

std::string ExpectExitZero(const Process& run, const char* log_name) {
  const int code = testing::WaitExit(run.pid, 120.0);
  const std::string log = testing::ReadFile(run.out / log_name);
  EXPECT_EQ(code, 0) << log;
  return log;
}

// The live run (with `security`: each process with its entity's identity) against the file run.
void ExpectLiveEqualsFile(bool secured) {
  const int file_domain = testing::TestDomain(40);
  const int live_domain = testing::TestDomain(50);
  testing::UseLoopbackByDefault();
  const std::filesystem::path root = testing::ScratchDir(secured ? "live-secured" : "live-input");
  MissionDir();
  std::map<std::string, std::vector<std::string>> security;
  if (secured) {
    const std::filesystem::path ids = root / "identities";
    const std::string script =
        (std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "security" / "make-identities.sh").string();
    ASSERT_EQ(std::system((script + " " + ids.string() + " ff1 robot1 > /dev/null").c_str()), 0);
    for (const char* id : {"ff1", "robot1"}) security[id] = {"--security", (ids / id).string()};
  }
  // The live entities first: the replays wait until every sensor topic has their readers.
  // ff1's kind comes from the start marker (human: not the default, robot), robot1's is given.
  const Process live_ff1 = StartLiveEntity("ff1", security["ff1"], live_domain, root);
  const Process live_robot =
      StartLiveEntity("robot1", Concat({"--kind", "robot"}, security["robot1"]), live_domain, root);
  ASSERT_GT(live_ff1.pid, 0);
  ASSERT_GT(live_robot.pid, 0);
  const Process replay_ff1 = StartReplay("ff1", security["ff1"], live_domain, root);
  const Process replay_robot = StartReplay("robot1", security["robot1"], live_domain, root);
  const std::string replay_log = ExpectExitZero(replay_ff1, "replay.log");
  ExpectExitZero(replay_robot, "replay.log");
  const std::string ff1_log = ExpectExitZero(live_ff1, "entity.log");
  const std::string robot_log = ExpectExitZero(live_robot, "entity.log");
  // The file runs after, so the two pairs do not share the two cores.
  const Process file_ff1 = StartFileEntity("ff1", file_domain, root);
  const Process file_robot = StartFileEntity("robot1", file_domain, root);
  ExpectExitZero(file_ff1, "entity.log");
  ExpectExitZero(file_robot, "entity.log");

  // Every topic of the entity's kind arrived whole, nothing was late or refused, and the other
  // entity's samples were ignored (open) or never reached it (secured: it reads its own
  // partition only).
  EXPECT_NE(ff1_log.find("live input ended (end marker)"), std::string::npos) << ff1_log;
  EXPECT_NE(ff1_log.find("(human)"), std::string::npos) << ff1_log;
  EXPECT_NE(robot_log.find("(robot)"), std::string::npos) << robot_log;
  EXPECT_NE(ff1_log.find("start pose from ground truth"), std::string::npos) << ff1_log;
  for (const char* topic : {"gyro", "compass", "stride", "scan"}) {
    EXPECT_NE(ff1_log.find(std::string("pena/sensors/") + topic), std::string::npos)
        << topic << "\n" << ff1_log;
  }
  EXPECT_NE(robot_log.find("pena/sensors/wheel_odometry"), std::string::npos) << robot_log;
  for (const std::string& log : {ff1_log, robot_log}) {
    EXPECT_EQ(log.find("late on this topic"), std::string::npos) << log;
    EXPECT_EQ(log.find("never arrived"), std::string::npos) << log;
    EXPECT_EQ(log.find("arrived twice"), std::string::npos) << log;
    EXPECT_FALSE(std::regex_search(log, std::regex("[1-9][0-9]* refused"))) << log;
    EXPECT_EQ(log.find(" 0 samples of other entities ignored") != std::string::npos, secured)
        << log;
  }
  EXPECT_NE(replay_log.find("and the end marker"), std::string::npos) << replay_log;

  // The same records in the same order through the same deterministic chain: the same poses.
  testing::ExpectSameTrajectory("ff1", io::ReadTum(file_ff1.out / "trajectory.tum"),
                                io::ReadTum(live_ff1.out / "trajectory.tum"), "live vs file", 0.0,
                                0.0);
  testing::ExpectSameTrajectory("robot1", io::ReadTum(file_robot.out / "trajectory.tum"),
                                io::ReadTum(live_robot.out / "trajectory.tum"), "live vs file", 0.0,
                                0.0);
}

TEST(LiveInput, ReplayedSensorTopicsGiveTheTrajectoryOfTheFileRun) { ExpectLiveEqualsFile(false); }

TEST(LiveInput, SecuredEachEntityReadsOnlyItsOwnDriverAndGetsTheSameTrajectory) {
  ExpectLiveEqualsFile(true);
}

TEST(LiveInput, EndsOnTheIdleTimeoutAndRefusesAMissingEntityId) {
  testing::UseLoopbackByDefault();
  const int domain = testing::TestDomain(60);
  const std::filesystem::path root = testing::ScratchDir("live-idle");
  // No publisher: the idle timeout ends the input before any record, a clear error, exit 1.
  const pid_t idle = testing::Spawn(
      Concat({PENA_ENTITY_BIN, "--input", "dds", "--entity-id", "ff9", "--idle-timeout", "1"},
             DdsArgs(domain)),
      root / "idle.log");
  EXPECT_EQ(testing::WaitExit(idle, 30.0), 1);
  const std::string idle_log = testing::ReadFile(root / "idle.log");
  EXPECT_NE(idle_log.find("no sensor record for ff9"), std::string::npos) << idle_log;
  EXPECT_NE(idle_log.find("idle timeout"), std::string::npos) << idle_log;
  // Without --entity-id the live input does not know whose samples to take.
  const pid_t anonymous =
      testing::Spawn(Concat({PENA_ENTITY_BIN, "--input", "dds"}, DdsArgs(domain)),
                     root / "anonymous.log");
  EXPECT_EQ(testing::WaitExit(anonymous, 30.0), 1);
  EXPECT_NE(testing::ReadFile(root / "anonymous.log").find("--entity-id"), std::string::npos)
      << testing::ReadFile(root / "anonymous.log");
  const pid_t window = testing::Spawn(
      Concat({PENA_ENTITY_BIN, "--input", "dds", "--entity-id", "ff1", "--reorder-window", "-1"},
             DdsArgs(domain)),
      root / "window.log");
  EXPECT_EQ(testing::WaitExit(window, 30.0), 1);
  EXPECT_NE(testing::ReadFile(root / "window.log").find("reorder_window_s"), std::string::npos)
      << testing::ReadFile(root / "window.log");
}

TEST(LiveInput, ASignalBeforeTheFirstRecordIsACleanStop) {
  testing::UseLoopbackByDefault();
  const int domain = testing::TestDomain(61);
  const std::filesystem::path root = testing::ScratchDir("live-signal");
  // No publisher and no idle timeout: the entity waits for its first record until SIGTERM.
  const pid_t waiting = testing::Spawn(
      Concat({PENA_ENTITY_BIN, "--input", "dds", "--entity-id", "ff9"}, DdsArgs(domain)),
      root / "signal.log");
  ASSERT_GT(waiting, 0);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ASSERT_EQ(kill(waiting, SIGTERM), 0);
  EXPECT_EQ(testing::WaitExit(waiting, 30.0), 0) << testing::ReadFile(root / "signal.log");
  EXPECT_NE(testing::ReadFile(root / "signal.log").find("stopped by a signal before the first record"),
            std::string::npos)
      << testing::ReadFile(root / "signal.log");
}

}  // namespace
}  // namespace pena::services
