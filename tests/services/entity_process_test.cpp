// pena-entity as a real process on loopback DDS, with this test as its subscriber: poses and
// line-map deltas arrive, the deltas applied in order rebuild the entity's final map, SIGTERM
// stops it cleanly, a bad config exits non-zero naming file and line.
#include <gtest/gtest.h>

#include <fcntl.h>

#include <chrono>
#include <map>
#include <regex>

#include "dds_endpoints.hpp"
#include "from_dds.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/mission_log.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena/sim/mission_writer.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "corridor_scenario.hpp"
#include "process_support.hpp"
#include "service_test_support.hpp"
#include "work_queue.hpp"

namespace pena::services {
namespace {

using std::chrono::milliseconds;

constexpr const char* kScenario = pena::testing::kCorridorScenario;

struct Mission {
  std::filesystem::path entity_dir;
  std::size_t scans = 0;
};

const Mission& TestMission() {
  static const Mission mission = [] {
    const sim::Scenario scenario = sim::ParseScenario(kScenario, "test:services");
    const sim::SimulationResult result = sim::Simulator{sim::SimulationOptions{}}.Run(scenario);
    const std::filesystem::path dir = testing::ScratchDir("mission");
    sim::WriteMission(scenario, result, dir, "entity_process_test");
    return Mission{dir / "robot1", result.entities.front().scans};
  }();
  return mission;
}

std::vector<std::string> EntityArgs(int domain, const std::filesystem::path& out, double rate) {
  const std::filesystem::path dds = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  return {PENA_ENTITY_BIN, "--input", TestMission().entity_dir.string(), "--rate",
          std::to_string(rate), "--domain", std::to_string(domain), "--out", out.string(),
          "--profiles-file", (dds / "pena-loopback.xml").string(), "--profiles-file",
          (dds / "pena-qos.xml").string(), "--wait-for-readers", "20", "--linger", "5"};
}

// What this test subscribes to.
struct Listener {
  explicit Listener(const DdsOptions& dds)
      : participant(dds, "test-listener"),
        poses(participant, topics::kPose,
              [this](pena_dds::EntityPose&& s, const SampleMeta&) { pose_queue.Push(std::move(s)); }),
        deltas(participant, topics::kLineMapDelta,
               [this](pena_dds::LineMapDelta&& s, const SampleMeta&) {
                 delta_queue.Push(std::move(s));
               }),
        snapshots(participant, topics::kLineMapSnapshot,
                  [this](pena_dds::LineMapSnapshot&& s, const SampleMeta&) {
                    snapshot_queue.Push(std::move(s));
                  }) {}

  WorkQueue<pena_dds::EntityPose> pose_queue;
  WorkQueue<pena_dds::LineMapDelta> delta_queue;
  WorkQueue<pena_dds::LineMapSnapshot> snapshot_queue;
  Participant participant;
  Reader<pena_dds::EntityPosePubSubType> poses;
  Reader<pena_dds::LineMapDeltaPubSubType> deltas;
  Reader<pena_dds::LineMapSnapshotPubSubType> snapshots;
};

TEST(EntityProcess, PublishesPosesAndDeltasThatRebuildItsMap) {
  const int domain = testing::TestDomain(10);
  Listener listener(testing::LoopbackDds(domain));
  const std::filesystem::path out = testing::ScratchDir("run");
  const pid_t pid = testing::Spawn(EntityArgs(domain, out, 20.0), out / "entity.log");
  ASSERT_GT(pid, 0);
  std::vector<pena_dds::EntityPose> poses;
  line_map::LineMap rebuilt;
  long deltas = 0;
  std::optional<pena_dds::LineMapSnapshot> final_snapshot;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(90);
  while (!final_snapshot && std::chrono::steady_clock::now() < until) {
    while (auto pose = listener.pose_queue.TryPop()) poses.push_back(std::move(*pose));
    while (auto delta = listener.delta_queue.TryPop()) {
      const line_map::ApplyResult applied = rebuilt.Apply(FromDds(*delta));
      ASSERT_TRUE(applied.ok()) << applied.message;
      ++deltas;
    }
    // The final snapshot comes after the last delta, but on another topic: once it is here,
    // keep applying deltas until the rebuilt map reaches its version (or 10 s pass).
    if (auto snapshot = listener.snapshot_queue.PopFor(milliseconds(20))) {
      const auto patience = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (rebuilt.version() < snapshot->version() &&
             std::chrono::steady_clock::now() < patience) {
        if (auto delta = listener.delta_queue.PopFor(milliseconds(50))) {
          ASSERT_TRUE(rebuilt.Apply(FromDds(*delta)).ok());
          ++deltas;
        }
      }
      final_snapshot = std::move(snapshot);
    }
  }
  const int code = testing::WaitExit(pid, 30.0);
  const std::string log = testing::ReadFile(out / "entity.log");
  ASSERT_EQ(code, 0) << log;
  ASSERT_TRUE(final_snapshot.has_value()) << log;
  while (auto pose = listener.pose_queue.TryPop()) poses.push_back(std::move(*pose));
  // Poses are best effort: nearly all arrive on loopback, in order, for every scan.
  ASSERT_GE(poses.size(), TestMission().scans * 8 / 10) << log;
  for (std::size_t i = 1; i < poses.size(); ++i) EXPECT_GT(poses[i].seq(), poses[i - 1].seq());
  EXPECT_EQ(poses.front().entity_id().to_string(), "robot1");
  EXPECT_GE(deltas, 2);
  const line_map::MapSnapshot snapshot = FromDds(*final_snapshot);
  EXPECT_EQ(rebuilt.version(), snapshot.version);
  EXPECT_TRUE(line_map::SameMap(rebuilt.Snapshot(), snapshot));
  EXPECT_GE(snapshot.segments.size(), 4u);
  // The files the entity wrote agree with what it sent.
  EXPECT_EQ(io::ReadTum(out / "trajectory.tum").size(), TestMission().scans);
  EXPECT_EQ(io::ReadLineCsv(out / "line_map.csv").size(), snapshot.segments.size());
}

// pena-entity at rate 1 into `out` (with `extra_args`), once its first pose reached `listener`;
// -1 (with a failure naming the log) if it did not start or sent no pose within 30 s.
pid_t SpawnRunning(Listener& listener, int domain, const std::filesystem::path& out,
                   const std::vector<std::string>& extra_args = {}) {
  std::vector<std::string> args = EntityArgs(domain, out, 1.0);
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  const pid_t pid = testing::Spawn(args, out / "entity.log");
  if (pid <= 0) return -1;
  if (!listener.pose_queue.PopFor(std::chrono::seconds(30)).has_value()) {
    ADD_FAILURE() << "no pose within 30 s\n" << testing::ReadFile(out / "entity.log");
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    return -1;
  }
  return pid;
}

TEST(EntityProcess, StopsCleanlyOnSigterm) {
  const int domain = testing::TestDomain(20);
  Listener listener(testing::LoopbackDds(domain));
  const std::filesystem::path out = testing::ScratchDir("sigterm");
  const pid_t pid = SpawnRunning(listener, domain, out);
  ASSERT_GT(pid, 0);
  kill(pid, SIGTERM);
  const int code = testing::WaitExit(pid, 20.0);
  const std::string log = testing::ReadFile(out / "entity.log");
  EXPECT_EQ(code, 0) << log;
  EXPECT_NE(log.find("stopped by a signal"), std::string::npos) << log;
  EXPECT_TRUE(std::filesystem::exists(out / "trajectory.tum"));
  EXPECT_LT(io::ReadTum(out / "trajectory.tum").size(), TestMission().scans);
}

// A crash leaves a report: the signal and a backtrace on stderr (crash_report.hpp), and the
// process still dies of the signal, as without the handler. No shared memory between the two:
// a survivor's shared-memory teardown after its peer died of SIGSEGV sometimes crashed this test
// inside Fast DDS 2.9.1 (service_test_support.hpp, LoopbackUdpDds).
TEST(EntityProcess, ACrashWritesTheSignalAndABacktraceAndStillDiesOfIt) {
  const int domain = testing::TestDomain(24);
  Listener listener(testing::LoopbackUdpDds(domain));
  const std::filesystem::path out = testing::ScratchDir("crash");
  const pid_t pid = SpawnRunning(listener, domain, out, {"--profile", "pena_loopback_udp"});
  ASSERT_GT(pid, 0);
  kill(pid, SIGSEGV);
  const int code = testing::WaitExit(pid, 20.0);
  const std::string log = testing::ReadFile(out / "entity.log");
  EXPECT_EQ(code, 128 + SIGSEGV) << log;
  EXPECT_NE(log.find("pena-entity: fatal signal Segmentation fault; backtrace"), std::string::npos)
      << log;
  EXPECT_NE(log.find("pena-entity(+0x"), std::string::npos) << log;  // frames addr2line resolves
}

// --record: what the entity received from its sensors is a native mission log that `pena info`
// and the log readers open, record for record the input; what it sent is beside it.
TEST(EntityProcess, RecordsItsInputAsANativeLogThatPenaInfoReads) {
  const int domain = testing::TestDomain(30);
  Listener listener(testing::LoopbackDds(domain));
  const std::filesystem::path out = testing::ScratchDir("record");
  std::vector<std::string> args = EntityArgs(domain, out, 0.0);
  args.push_back("--record");
  const pid_t pid = testing::Spawn(args, out / "entity.log");
  ASSERT_GT(pid, 0);
  ASSERT_EQ(testing::WaitExit(pid, 90.0), 0) << testing::ReadFile(out / "entity.log");
  const std::filesystem::path recording = out / "recording" / "sensors.penalog";
  ASSERT_TRUE(io::IsMissionLog(recording));
  const pid_t info = testing::Spawn({PENA_CLI_BIN, "info", recording.string()}, out / "info.txt");
  ASSERT_EQ(testing::WaitExit(info, 30.0), 0) << testing::ReadFile(out / "info.txt");
  const std::string summary = testing::ReadFile(out / "info.txt");
  EXPECT_NE(summary.find("pena-log"), std::string::npos) << summary;
  EXPECT_NE(summary.find("robot1 (robot)"), std::string::npos) << summary;
  EXPECT_TRUE(std::regex_search(
      summary, std::regex("laser +" + std::to_string(TestMission().scans) + " ")))
      << summary;
  // Record for record the input (same kinds and stamps, in the same order).
  io::MissionLogReader recorded(recording);
  std::unique_ptr<io::LogSource> input = io::OpenLog(TestMission().entity_dir / "sensors.penalog");
  long records = 0;
  while (auto expected = input->Next()) {
    const std::optional<sensors::SensorRecord> got = recorded.Next();
    ASSERT_TRUE(got.has_value()) << "recording ends after " << records << " records";
    ASSERT_EQ(got->index(), expected->index()) << "record " << records;
    ASSERT_EQ(sensors::StampOf(*got), sensors::StampOf(*expected)) << "record " << records;
    ++records;
  }
  EXPECT_FALSE(recorded.Next().has_value());
  EXPECT_EQ(recorded.header().entity_id, "robot1");
  EXPECT_GT(std::filesystem::file_size(out / "recording" / "sent_line_map_deltas.pbs"), 0u);
}

TEST(EntityProcess, BadConfigInputOrDdsFailureExitsNonZeroNamingTheCause) {
  testing::UseLoopbackByDefault();
  const std::filesystem::path dir = testing::ScratchDir("badconfig");
  std::ofstream(dir / "entity.conf") << "input: \"x\"\nrat: 10\n";
  const pid_t pid =
      testing::Spawn({PENA_ENTITY_BIN, "--config", (dir / "entity.conf").string()}, dir / "log");
  EXPECT_EQ(testing::WaitExit(pid, 20.0), 1);
  EXPECT_NE(testing::ReadFile(dir / "log").find("entity.conf:2"), std::string::npos)
      << testing::ReadFile(dir / "log");
  const pid_t missing = testing::Spawn({PENA_ENTITY_BIN, "--input", "/nonexistent/sensors.penalog"},
                                       dir / "log2");
  EXPECT_EQ(testing::WaitExit(missing, 20.0), 1);
  EXPECT_NE(testing::ReadFile(dir / "log2").find("/nonexistent/sensors.penalog"),
            std::string::npos);
  // A DDS failure (no such participant profile) exits 2 naming the profile.
  const pid_t dds = testing::Spawn({PENA_ENTITY_BIN, "--input", TestMission().entity_dir.string(),
                                    "--profile", "no_such_profile"},
                                   dir / "log3");
  EXPECT_EQ(testing::WaitExit(dds, 20.0), 2);
  EXPECT_NE(testing::ReadFile(dir / "log3").find("no_such_profile"), std::string::npos);
}

}  // namespace
}  // namespace pena::services
