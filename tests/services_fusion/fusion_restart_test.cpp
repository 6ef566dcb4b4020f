// pena-fusion killed with kill -9 and restarted: it publishes the operator's marks again, so a
// console that connects afterwards sees every mark (and every retraction) although the console
// that made them has left the domain; and it knows when each wall was mapped, so an operator's
// rotation moves only the walls mapped after its origin, as it would have before the restart.
// And a placed entity's rotation (start unknown) moves only its walls mapped after the origin.
// Every participant uses deploy/dds/pena-loopback.xml and a domain of its own.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <set>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>
#include <mutex>
#include <thread>

#include "dds_endpoints.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"
#include "to_dds.hpp"
#include "process_support.hpp"
#include "service_test_support.hpp"

namespace pena::services {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

pid_t SpawnFusion(int domain, const fs::path& run) {
  testing::UseLoopbackByDefault();  // the fusion inherits FASTRTPS_DEFAULT_PROFILES_FILE
  const fs::path dds = fs::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  return testing::Spawn({PENA_FUSION_BIN, "--state-dir", (run / "state").string(), "--out",
                         (run / "fusion").string(), "--no-corrections", "--domain",
                         std::to_string(domain), "--profiles-file",
                         (dds / "pena-loopback.xml").string(), "--profiles-file",
                         (dds / "pena-qos.xml").string()},
                        run / "fusion.log");
}

// A console's view of pena/annotation: the last sample of each mark, and who wrote it.
struct MarkReader {
  explicit MarkReader(int domain, const char* name)
      : participant(testing::LoopbackUdpDds(domain), name),
        reader(participant, topics::kAnnotation,
               [this](pena_dds::Annotation&& sample, const SampleMeta& meta) {
                 const std::lock_guard<std::mutex> lock(mutex);
                 const std::string id = sample.annotation_id().to_string();
                 const std::string writer(reinterpret_cast<const char*>(meta.publication.data()), 12);
                 by_writer[writer][id] = sample;
                 marks[id] = std::move(sample);
               }) {}

  // Waits until `done` holds of the marks (under the lock), at most timeout_s.
  template <class Predicate>
  bool WaitFor(Predicate done, double timeout_s) {
    const auto until = Clock::now() + std::chrono::milliseconds(static_cast<long>(timeout_s * 1000));
    while (Clock::now() < until) {
      {
        const std::lock_guard<std::mutex> lock(mutex);
        if (done(marks)) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  std::mutex mutex;
  std::map<std::string, pena_dds::Annotation> marks;
  // Per writer (its participant's GUID prefix): the last sample of each mark it wrote.
  std::map<std::string, std::map<std::string, pena_dds::Annotation>> by_writer;
  Participant participant;
  Reader<pena_dds::AnnotationPubSubType> reader;
};

pena_dds::Annotation Mark(const std::string& id, pena_dds::AnnotationKind kind, double x_m,
                          double stamp_s, const std::string& text) {
  pena_dds::Annotation mark;
  mark.annotation_id(id);
  mark.schema_version(pena_dds::SCHEMA_VERSION);
  mark.author_id("op");
  mark.kind(kind);
  mark.position().x_m(x_m);
  mark.position().y_m(2.5);
  mark.stamp_s(stamp_s);
  mark.text(text);
  return mark;
}

TEST(FusionRestart, MarksArePublishedAgainAfterKillNine) {
  const int domain = testing::TestDomain(47);
  const fs::path run = testing::ScratchDir("restart_marks");
  pid_t fusion = SpawnFusion(domain, run);
  ASSERT_GT(fusion, 0);
  {
    // The operator's console: marks a victim and an exit, retracts the exit, and leaves.
    Participant operator_console(testing::LoopbackUdpDds(domain), "test-operator");
    Writer<pena_dds::AnnotationPubSubType> writer(operator_console, topics::kAnnotation);
    MarkReader relay(domain, "test-relay");
    std::vector<pena_dds::Annotation> sent = {
        Mark("op/1", pena_dds::ANNOTATION_VICTIM_FOUND, 4.0, 12.0, "two people"),
        Mark("op/2", pena_dds::ANNOTATION_EXIT, 9.0, 13.0, "exit east")};
    for (pena_dds::Annotation& mark : sent) ASSERT_TRUE(writer.Write(mark));
    sent[1].retracted(true);
    ASSERT_TRUE(writer.Write(sent[1]));
    // Relayed by the fusion (a writer that is not the operator's): journalled by then.
    const auto& own = operator_console.get()->guid().guidPrefix.value;
    const std::string operator_prefix(reinterpret_cast<const char*>(own), 12);
    ASSERT_TRUE(relay.WaitFor(
        [&](const auto& /*marks*/) {
          for (const auto& [prefix, marks] : relay.by_writer) {
            if (prefix != operator_prefix && marks.size() == 2 && marks.at("op/2").retracted()) {
              return true;
            }
          }
          return false;
        },
        30.0))
        << testing::ReadFile(run / "fusion.log");
  }
  kill(fusion, SIGKILL);
  ASSERT_EQ(testing::WaitExit(fusion, 10.0), 128 + SIGKILL);
  fusion = SpawnFusion(domain, run);
  ASSERT_GT(fusion, 0);
  // A console that connects now: the marks, as last relayed, from the restarted fusion alone.
  MarkReader console(domain, "test-late-console");
  const bool seen = console.WaitFor(
      [](const auto& marks) { return marks.size() == 2 && marks.at("op/2").retracted(); }, 30.0);
  kill(fusion, SIGTERM);
  const int exit_code = testing::WaitExit(fusion, 20.0);
  const std::string log = testing::ReadFile(run / "fusion.log");
  ASSERT_TRUE(seen) << console.marks.size() << " marks seen\n" << log;
  const pena_dds::Annotation& victim = console.marks.at("op/1");
  EXPECT_EQ(victim.kind(), pena_dds::ANNOTATION_VICTIM_FOUND);
  EXPECT_DOUBLE_EQ(victim.position().x_m(), 4.0);
  EXPECT_EQ(victim.text().to_string(), "two people");
  EXPECT_FALSE(victim.retracted());
  EXPECT_EQ(console.marks.at("op/2").kind(), pena_dds::ANNOTATION_EXIT);
  EXPECT_NE(log.find("2 operator marks published again from the journal"), std::string::npos) << log;
  EXPECT_EQ(exit_code, 0) << log;
}

// A vertical wall of the fake entity at x_m, from y 0 to 4 m, well supported.
line_map::LineSegment Wall(std::int64_t id, double x_m) {
  line_map::LineSegment wall;
  wall.id = id;
  wall.segment = {Eigen::Vector2d(x_m, 0.0), Eigen::Vector2d(x_m, 4.0)};
  wall.support_cells = 200.0;
  wall.observations = 400.0;
  wall.rms_error_m = 0.01;
  wall.provenance = {"ff9"};
  return wall;
}

// Where the fusion's global map (OUT/global_map.csv, written at a clean stop) has the wall whose
// provenance names the fake entity's segment `id`.
std::optional<geometry::Segment2> GlobalWall(const fs::path& csv, std::int64_t id) {
  for (const io::LineRow& row : io::ReadLineCsv(csv)) {
    std::stringstream keys(row.extra.substr(row.extra.rfind(',') + 1));
    for (std::string key; keys >> key;) {
      if (key == "ff9:" + std::to_string(id)) return row.segment;
    }
  }
  return std::nullopt;
}

TEST(FusionRestart, ARotationAfterKillNineMovesOnlyTheWallsMappedAfterItsOrigin) {
  const int domain = testing::TestDomain(48);
  const fs::path run = testing::ScratchDir("restart_walls");
  pid_t fusion = SpawnFusion(domain, run);
  ASSERT_GT(fusion, 0);
  // A fake entity with a known start: wall 1 mapped at 10 s, wall 2 at 20 s of mission time.
  pena_dds::EntityStatus status;
  status.entity_id("ff9");
  status.schema_version(pena_dds::SCHEMA_VERSION);
  status.kind(pena_dds::ENTITY_HUMAN);
  status.state(pena_dds::ENTITY_RUNNING);
  pena_dds::EntityPose pose;
  pose.entity_id("ff9");
  pose.schema_version(pena_dds::SCHEMA_VERSION);
  pose.seq(1);
  pose.stamp_s(21.0);
  pose.world_from_body(ToDds(geometry::Pose2{8.0, 4.0, 0.0}));
  pose.odom_from_body(ToDds(geometry::Pose2{8.0, 4.0, 0.0}));  // map_from_odom = identity
  {
    Participant entity(testing::LoopbackUdpDds(domain), "test-entity-ff9");
    Writer<pena_dds::EntityStatusPubSubType> status_writer(entity, topics::kStatus);
    Writer<pena_dds::LineMapDeltaPubSubType> delta_writer(entity, topics::kLineMapDelta);
    ASSERT_TRUE(status_writer.Write(status));
    std::uint64_t version = 0;
    for (const auto& [id, x_m, stamp_s] : {std::tuple{1, 2.0, 10.0}, std::tuple{2, 8.0, 20.0}}) {
      line_map::MapDelta delta;
      delta.from_version = version;
      delta.to_version = ++version;
      delta.added = {Wall(id, x_m)};
      pena_dds::LineMapDelta sample = ToDdsLineMapDelta(delta, "ff9", stamp_s);
      ASSERT_TRUE(delta_writer.Write(sample));
    }
    // Both walls journalled (their stamps are written before the deltas are applied).
    const fs::path stamps = run / "state" / "wall_stamps.csv";
    for (const auto until = Clock::now() + std::chrono::seconds(30);
         Clock::now() < until && testing::ReadFile(stamps).find("ff9,2,20") == std::string::npos;) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ASSERT_NE(testing::ReadFile(stamps).find("ff9,2,20"), std::string::npos)
        << testing::ReadFile(run / "fusion.log");
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  kill(fusion, SIGKILL);
  ASSERT_EQ(testing::WaitExit(fusion, 10.0), 128 + SIGKILL);
  fusion = SpawnFusion(domain, run);
  ASSERT_GT(fusion, 0);
  // The entity comes back with writers of no history (its old deltas are not delivered again,
  // as in a mission longer than their transient-local depth): the restarted fusion knows when
  // its walls were mapped from the journal alone. Then an operator rotates it by 90 deg about the
  // map origin from 15 s on.
  Participant entity(testing::LoopbackUdpDds(domain), "test-entity-ff9-again");
  Writer<pena_dds::EntityStatusPubSubType> status_writer(entity, topics::kStatus);
  Writer<pena_dds::EntityPosePubSubType> pose_writer(entity, topics::kPose);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ASSERT_TRUE(status_writer.Write(status));
  ASSERT_TRUE(pose_writer.Write(pose));
  std::this_thread::sleep_for(std::chrono::seconds(1));
  Participant operator_console(testing::LoopbackUdpDds(domain), "test-operator");
  Writer<pena_dds::OperatorCorrectionPubSubType> correction_writer(operator_console,
                                                                   topics::kOperatorCorrection);
  std::mutex mutex;
  std::optional<pena_dds::OperatorCorrection> answer;
  Reader<pena_dds::OperatorCorrectionPubSubType> answers(
      operator_console, topics::kOperatorCorrection,
      [&](pena_dds::OperatorCorrection&& sample, const SampleMeta&) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (sample.applied() || !sample.refusal().to_string().empty()) answer = std::move(sample);
      });
  pena_dds::OperatorCorrection rotation;
  rotation.correction_id("op/1");
  rotation.schema_version(pena_dds::SCHEMA_VERSION);
  rotation.operator_id("op");
  rotation.kind(pena_dds::OPERATOR_ROTATE);
  rotation.target_entity_id("ff9");
  rotation.stamp_s(15.0);
  rotation.wrong_point().x_m(1.0);
  rotation.correct_point().y_m(1.0);
  ASSERT_TRUE(correction_writer.Write(rotation));
  bool answered = false;
  for (const auto until = Clock::now() + std::chrono::seconds(30); Clock::now() < until && !answered;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const std::lock_guard<std::mutex> lock(mutex);
    answered = answer.has_value();
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  kill(fusion, SIGTERM);
  const int exit_code = testing::WaitExit(fusion, 20.0);
  const std::string log = testing::ReadFile(run / "fusion.log");
  ASSERT_TRUE(answered) << log;
  ASSERT_TRUE(answer->applied()) << answer->refusal().to_string() << "\n" << log;
  EXPECT_NE(log.find("2 wall stamps recovered from the journal"), std::string::npos) << log;
  ASSERT_EQ(exit_code, 0) << log;
  const fs::path csv = run / "fusion" / "global_map.csv";
  const std::optional<geometry::Segment2> before = GlobalWall(csv, 1);
  const std::optional<geometry::Segment2> after = GlobalWall(csv, 2);
  ASSERT_TRUE(before && after) << testing::ReadFile(csv) << log;
  // Wall 1 (mapped at 10 s, before the origin's 15 s) stays at x = 2 m; wall 2 (20 s) is turned
  // by 90 deg about the origin: from x = 8 m to y = 8 m.
  EXPECT_NEAR(std::min(before->start_m.x(), before->end_m.x()), 2.0, 0.01) << testing::ReadFile(csv);
  EXPECT_NEAR(std::max(before->start_m.x(), before->end_m.x()), 2.0, 0.01);
  EXPECT_NEAR(after->start_m.y(), 8.0, 0.01) << testing::ReadFile(csv);
  EXPECT_NEAR(after->end_m.y(), 8.0, 0.01);
}

// A placed entity (start unknown): a rotation from 15 s moves its walls mapped at 20 s and leaves
// those mapped at 10 s where placement put them, on the plan. The plan: a corridor along x with
// side corridors at x = 10, 20 and 30 (tests/fusion/placement_test.cpp); the entity sees it from
// a frame 30 deg turned and shifted, first 15.5-24.5 m along it (10 s), then 24.5-40 m (20 s),
// which places it.
std::vector<line_map::LineSegment> Corridor(double from_x, double to_x) {
  std::vector<line_map::LineSegment> walls;
  const auto clip = [&](double x1, double y1, double x2, double y2) {
    const double a = std::max(std::min(x1, x2), from_x);
    const double b = std::min(std::max(x1, x2), to_x);
    if (b - a > 0.05 || (x1 == x2 && x1 >= from_x && x1 <= to_x)) {
      line_map::LineSegment wall;
      wall.segment = {Eigen::Vector2d(x1 == x2 ? x1 : a, y1), Eigen::Vector2d(x1 == x2 ? x2 : b, y2)};
      wall.support_cells = 40.0 * geometry::Length(wall.segment) + 10.0;
      wall.observations = 2.0 * wall.support_cells;
      wall.rms_error_m = 0.01;
      walls.push_back(wall);
    }
  };
  clip(0, 0, 40, 0);
  double x = 0.0;
  for (const double junction : {10.0, 20.0, 30.0}) {
    clip(x, 2, junction - 0.75, 2);
    clip(junction - 0.75, 2, junction - 0.75, 6);
    clip(junction + 0.75, 2, junction + 0.75, 6);
    x = junction + 0.75;
  }
  clip(x, 2, 40, 2);
  clip(40, 0, 40, 2);
  return walls;
}

TEST(FusionOperator, APlacedEntitysRotationMovesOnlyTheWallsMappedAfterItsOrigin) {
  const int domain = testing::TestDomain(49);
  const fs::path run = testing::ScratchDir("placed_rotation");
  {
    std::ofstream plan(run / "plan.csv");
    plan << "id,x1,y1,x2,y2\n";
    int id = 0;
    for (const line_map::LineSegment& wall : Corridor(0, 40)) {
      plan << id++ << ',' << wall.segment.start_m.x() << ',' << wall.segment.start_m.y() << ','
           << wall.segment.end_m.x() << ',' << wall.segment.end_m.y() << '\n';
    }
  }
  testing::UseLoopbackByDefault();
  const fs::path dds = fs::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  const pid_t fusion = testing::Spawn(
      {PENA_FUSION_BIN, "--state-dir", (run / "state").string(), "--out", (run / "fusion").string(),
       "--plan", (run / "plan.csv").string(), "--no-corrections", "--domain", std::to_string(domain),
       "--profiles-file", (dds / "pena-loopback.xml").string(), "--profiles-file",
       (dds / "pena-qos.xml").string()},
      run / "fusion.log");
  ASSERT_GT(fusion, 0);
  const geometry::Pose2 map_from_entity{20.3, -1.7, M_PI / 6.0};
  const auto seen = [&](double from_x, double to_x) {
    std::vector<line_map::LineSegment> walls = Corridor(from_x, to_x);
    for (line_map::LineSegment& wall : walls) {
      const geometry::Pose2 entity_from_map = geometry::Inverse(map_from_entity);
      for (Eigen::Vector2d* p : {&wall.segment.start_m, &wall.segment.end_m}) {
        const geometry::Pose2 moved = geometry::Compose(entity_from_map, geometry::Pose2{p->x(), p->y(), 0.0});
        *p = Eigen::Vector2d(moved.x_m, moved.y_m);
      }
    }
    return walls;
  };
  Participant entity(testing::LoopbackUdpDds(domain), "test-entity-ff8");
  Writer<pena_dds::EntityStatusPubSubType> status_writer(entity, topics::kStatus);
  Writer<pena_dds::LineMapDeltaPubSubType> delta_writer(entity, topics::kLineMapDelta);
  pena_dds::EntityStatus status;
  status.entity_id("ff8");
  status.schema_version(pena_dds::SCHEMA_VERSION);
  status.kind(pena_dds::ENTITY_HUMAN);
  status.state(pena_dds::ENTITY_RUNNING);
  status.start_unknown(true);
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_TRUE(status_writer.Write(status));
  std::this_thread::sleep_for(std::chrono::seconds(1));
  line_map::LineMap local;
  std::set<std::int64_t> early, late;
  for (const auto& [from_x, to_x, stamp_s] : {std::tuple{15.5, 24.5, 10.0}, std::tuple{24.5, 40.0, 20.0}}) {
    const line_map::MapDelta delta = local.Integrate(seen(from_x, to_x), "ff8");
    for (const line_map::LineSegment& wall : delta.added) (stamp_s < 15.0 ? early : late).insert(wall.id);
    pena_dds::LineMapDelta sample = ToDdsLineMapDelta(delta, "ff8", stamp_s);
    ASSERT_TRUE(delta_writer.Write(sample));
  }
  // Placed (the fusion says so in its log), then rotated by 10 deg about the map origin.
  for (const auto until = Clock::now() + std::chrono::seconds(30);
       Clock::now() < until && testing::ReadFile(run / "fusion.log").find("ff8: placed at") == std::string::npos;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_NE(testing::ReadFile(run / "fusion.log").find("ff8: placed at"), std::string::npos)
      << testing::ReadFile(run / "fusion.log");
  Participant operator_console(testing::LoopbackUdpDds(domain), "test-operator");
  Writer<pena_dds::OperatorCorrectionPubSubType> correction_writer(operator_console,
                                                                   topics::kOperatorCorrection);
  pena_dds::OperatorCorrection rotation;
  rotation.correction_id("op/1");
  rotation.schema_version(pena_dds::SCHEMA_VERSION);
  rotation.operator_id("op");
  rotation.kind(pena_dds::OPERATOR_ROTATE);
  rotation.target_entity_id("ff8");
  rotation.stamp_s(15.0);
  rotation.wrong_point().x_m(1.0);
  rotation.correct_point().x_m(std::cos(10.0 * M_PI / 180.0));
  rotation.correct_point().y_m(std::sin(10.0 * M_PI / 180.0));
  ASSERT_TRUE(correction_writer.Write(rotation));
  for (const auto until = Clock::now() + std::chrono::seconds(30);
       Clock::now() < until && testing::ReadFile(run / "fusion.log").find("op/1 of ff8 by") == std::string::npos;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  kill(fusion, SIGTERM);
  const int exit_code = testing::WaitExit(fusion, 20.0);
  const std::string log = testing::ReadFile(run / "fusion.log");
  ASSERT_EQ(exit_code, 0) << log;
  ASSERT_NE(log.find("op/1 of ff8 by"), std::string::npos) << log;
  // A wall of ff8 on the plan still merges with its plan wall; one turned by 10 deg does not.
  std::map<std::int64_t, bool> on_plan;
  for (const io::LineRow& row : io::ReadLineCsv(run / "fusion" / "global_map.csv")) {
    std::stringstream keys(row.extra.substr(row.extra.rfind(',') + 1));
    std::vector<std::int64_t> ids;
    bool plan = false;
    for (std::string key; keys >> key;) {
      if (key.rfind("plan:", 0) == 0) plan = true;
      if (key.rfind("ff8:", 0) == 0) ids.push_back(std::stoll(key.substr(4)));
    }
    for (const std::int64_t id : ids) on_plan[id] = plan;
  }
  int early_on_plan = 0, late_on_plan = 0, early_seen = 0, late_seen = 0;
  for (const auto& [id, plan] : on_plan) {
    if (early.contains(id)) { ++early_seen; early_on_plan += plan ? 1 : 0; }
    if (late.contains(id)) { ++late_seen; late_on_plan += plan ? 1 : 0; }
  }
  EXPECT_GT(early_seen, 3) << log;
  EXPECT_EQ(early_on_plan, early_seen) << "walls mapped before the origin moved\n" << log;
  EXPECT_GT(late_seen, 3) << log;
  EXPECT_EQ(late_on_plan, 0) << "walls mapped after the origin did not move\n" << log;
}

}  // namespace
}  // namespace pena::services
