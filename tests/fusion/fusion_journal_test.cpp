// Persistence: the codec is exact, a journal replay rebuilds the state bit for bit, a torn last
// record is dropped with a message, corruption elsewhere is an error naming file and byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "fusion_test_util.hpp"
#include "pena/fusion/fusion_codec.hpp"
#include "pena/fusion/fusion_store.hpp"
#include "pena/io/input_error.hpp"
#include "scoped_temp_dir.hpp"

namespace pena::fusion {
namespace {

namespace fs = std::filesystem;
using test::Moved;
using test::Wall;

// A path `name` in this test's own temporary directory, not yet created.
fs::path FreshDir(const std::string& name) {
  const fs::path dir = pena::testing::ProcessTempDir() / name;
  fs::remove_all(dir);
  return dir;
}

// A dangerous area drawn as a polygon (the console's "Area..." gesture).
Annotation DangerArea() {
  Annotation area;
  area.kind = AnnotationKind::kDangerousArea;
  area.outline_m = {{10.0, 1.0}, {14.5, 1.25}, {14.0, 4.75}, {10.125, 4.0}};
  area.position_m = {12.15625, 2.75};
  area.radius_m = 2.9;
  area.text = "gas";
  area.author = "op";
  return area;
}

// A mission's worth of varied inputs: plan, joins, deltas with a gap and a snapshot, corrections,
// annotations, ticks that mark an entity lost.
std::vector<FusionInput> Mission() {
  std::vector<FusionInput> inputs;
  std::vector<line_map::LineSegment> plan = {Wall(0, 0, 30, 0, 0), Wall(0, 6, 30, 6, 0)};
  plan[0].id = 1;
  plan[1].id = 2;
  inputs.push_back(SetPlan{0.0, plan});
  inputs.push_back(EntityJoin{0.0, "ff1", geometry::Pose2{}});
  inputs.push_back(EntityJoin{0.5, "robot1", geometry::Pose2{5.0, 1.0, 0.1}});
  line_map::LineMap ff1, robot1;
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (int step = 0; step < 20; ++step) {
    const double x = 1.5 * step, t = 1.0 + step;
    inputs.push_back(LocalDelta{t, "ff1", ff1.Integrate({Wall(x, noise(random), x + 2, noise(random)),
                                                         Wall(x, 6 + noise(random), x + 1.5, 6)},
                                                        "ff1")});
    const line_map::MapDelta d = robot1.Integrate(
        Moved(geometry::Inverse(geometry::Pose2{5.0, 1.0, 0.1}),
              {Wall(x + 0.5, 3 + noise(random), x + 0.5, 4 + noise(random))}), "robot1");
    if (step != 9) inputs.push_back(LocalDelta{t + 0.2, "robot1", d});  // step 9 lost: a gap
    if (step == 12) inputs.push_back(LocalSnapshot{t + 0.3, "robot1", robot1.Snapshot()});
    if (step % 5 == 0) inputs.push_back(Tick{t + 0.4});
  }
  inputs.push_back(AlignmentCorrection{22.0, "robot1", geometry::Pose2{5.02, 0.97, 0.102}, 0.8});
  Annotation elevator;
  elevator.kind = AnnotationKind::kElevator;
  elevator.position_m = {12.0, 5.5};
  elevator.text = "lift B";
  elevator.author = "op";
  inputs.push_back(PutAnnotation{23.0, elevator});
  inputs.push_back(PutAnnotation{23.5, DangerArea()});
  inputs.push_back(OperatorCorrection{24.0, "ff1", geometry::Pose2{0.0, 0.01, 0.0}, "op"});
  inputs.push_back(MoveEntityWalls{24.5, "ff1", geometry::Pose2{0.5, -0.25, 0.1}, {3, 4, 77}, "op"});
  inputs.push_back(Tick{40.0});  // everyone silent: lost
  return inputs;
}

TEST(FusionCodec, RoundTripsEveryInputAndACheckpointExactly) {
  FusionState state;
  for (const FusionInput& input : Mission()) {
    const std::string bytes = EncodeInput(input);
    EXPECT_EQ(EncodeInput(DecodeInput(bytes)), bytes);
    state.Handle(input);
  }
  const std::string checkpoint = EncodeCheckpoint(state.Checkpoint());
  EXPECT_EQ(EncodeCheckpoint(DecodeCheckpoint(checkpoint)), checkpoint);
  // The global map keeps its walls' support (a restarted fusion would else re-send every wall).
  const line_map::MapSnapshot global = DecodeCheckpoint(checkpoint).global;
  EXPECT_TRUE(line_map::SameMap(global, state.GlobalSnapshot()));
  EXPECT_TRUE(std::any_of(global.segments.begin(), global.segments.end(),
                          [](const auto& wall) { return wall.seen_by_entities > 0; }));
  EXPECT_THROW(DecodeCheckpoint(checkpoint.substr(0, checkpoint.size() - 3)), io::InputError);
  EXPECT_THROW(DecodeInput("\x02garbage"), io::InputError);
}

TEST(FusionStore, ReplayAfterATornTailEqualsTheStateBeforeIt) {
  const fs::path dir = FreshDir("torn");
  const std::vector<FusionInput> inputs = Mission();
  std::string state_before_last;
  {
    FusionStore store(dir, FusionStoreOptions{{}, {}, 1000});  // no checkpoint: journal only
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      if (i + 1 == inputs.size()) state_before_last = EncodeCheckpoint(store.state().Checkpoint());
      store.Handle(inputs[i]);
    }
  }  // "kill -9": the store goes away without a checkpoint
  const fs::path journal = fs::directory_iterator(dir)->path();
  fs::resize_file(journal, fs::file_size(journal) - 5);  // the last record torn mid-write
  FusionStore recovered(dir);
  EXPECT_NE(recovered.recovery().torn_tail.find("torn record at byte"), std::string::npos)
      << recovered.recovery().torn_tail;
  EXPECT_EQ(EncodeCheckpoint(recovered.state().Checkpoint()), state_before_last);
  // The torn bytes are cut, so appending again and reopening is clean and complete.
  recovered.Handle(inputs.back());
  const std::string after = EncodeCheckpoint(recovered.state().Checkpoint());
  FusionStore again(dir);
  EXPECT_TRUE(again.recovery().torn_tail.empty());
  EXPECT_EQ(EncodeCheckpoint(again.state().Checkpoint()), after);
  fs::remove_all(dir);
}

TEST(FusionStore, CheckpointPlusJournalRebuildsTheUninterruptedState) {
  const fs::path dir = FreshDir("checkpoint");
  const std::vector<FusionInput> inputs = Mission();
  FusionState uninterrupted;
  for (const FusionInput& input : inputs) uninterrupted.Handle(input);
  {
    FusionStore first(dir, FusionStoreOptions{{}, {}, 7});  // checkpoints every 7 records
    for (std::size_t i = 0; i < inputs.size() / 2; ++i) first.Handle(inputs[i]);
  }  // crash
  FusionStore second(dir, FusionStoreOptions{{}, {}, 7});
  EXPECT_TRUE(second.recovery().from_checkpoint);
  EXPECT_GT(second.recovery().checkpoint_sequence, 0u);
  for (std::size_t i = inputs.size() / 2; i < inputs.size(); ++i) second.Handle(inputs[i]);
  EXPECT_EQ(EncodeCheckpoint(second.state().Checkpoint()),
            EncodeCheckpoint(uninterrupted.Checkpoint()));
  // Global versions are contiguous: the late state's map is the same version and bits.
  EXPECT_TRUE(line_map::SameMap(second.state().GlobalSnapshot(), uninterrupted.GlobalSnapshot()));
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_LE(files, 4u);  // old generations deleted
  fs::remove_all(dir);
}

TEST(FusionStore, DangerAreaPolygonSurvivesAKillAndARestart) {
  for (const std::size_t checkpoint_every : {std::size_t{1000}, std::size_t{1}}) {
    const fs::path dir = FreshDir("polygon");
    {
      FusionStore store(dir, FusionStoreOptions{{}, {}, checkpoint_every});
      store.Handle(PutAnnotation{1.0, DangerArea()});
      Annotation moved = store.state().annotations().at(0);  // moved by the operator
      for (Eigen::Vector2d& corner : moved.outline_m) corner += Eigen::Vector2d(0.5, -0.25);
      store.Handle(PutAnnotation{2.0, moved});
    }  // "kill -9": no checkpoint at exit
    FusionStore recovered(dir, FusionStoreOptions{{}, {}, checkpoint_every});
    ASSERT_EQ(recovered.state().annotations().size(), 1u);
    const Annotation area = recovered.state().annotations().at(0);
    const Annotation drawn = DangerArea();
    ASSERT_EQ(area.outline_m.size(), drawn.outline_m.size()) << "every " << checkpoint_every;
    for (std::size_t i = 0; i < drawn.outline_m.size(); ++i) {
      EXPECT_EQ(area.outline_m[i], drawn.outline_m[i] + Eigen::Vector2d(0.5, -0.25)) << i;
    }
    EXPECT_EQ(area.kind, AnnotationKind::kDangerousArea);
    EXPECT_EQ(area.text, "gas");
    fs::remove_all(dir);
  }
}

TEST(FusionCodec, ReadsAnAnnotationWrittenBeforeOutlinesWereKept) {
  Annotation exit;
  exit.kind = AnnotationKind::kLandmark;
  exit.position_m = {3.0, 4.0};
  exit.text = "exit";
  exit.author = "op";
  std::string bytes = EncodeInput(PutAnnotation{5.0, exit});
  ASSERT_EQ(bytes.substr(bytes.size() - 8), std::string(8, '\0'));  // the empty outline's count
  bytes.resize(bytes.size() - 8);  // version 1 ends before it
  bytes[0] = 1;
  const auto input = std::get<PutAnnotation>(DecodeInput(bytes));
  EXPECT_EQ(input.annotation.position_m, exit.position_m);
  EXPECT_EQ(input.annotation.text, "exit");
  EXPECT_TRUE(input.annotation.outline_m.empty());
  bytes[0] = static_cast<char>(kFusionCodecVersion + 1);
  EXPECT_THROW(DecodeInput(bytes), io::InputError);
}

TEST(FusionStore, JournalsTicksOnlyWhenTheyChangeSomething) {
  const fs::path dir = FreshDir("ticks");
  FusionStore store(dir);
  store.Handle(EntityJoin{0.0, "ff1", geometry::Pose2{}});
  const std::uint64_t after_join = store.next_sequence();
  for (int i = 1; i <= 4; ++i) store.Handle(Tick{1.0 * i});  // within silent_after_s: no change
  EXPECT_EQ(store.next_sequence(), after_join);
  EXPECT_EQ(store.Handle(Tick{10.0}).lifecycle.size(), 1u);  // ff1 lost: journaled
  EXPECT_EQ(store.next_sequence(), after_join + 1);
  fs::remove_all(dir);
}

TEST(FusionStore, CorruptionBeforeTheTailIsAnErrorNamingTheFileAndByte) {
  const fs::path dir = FreshDir("corrupt");
  {
    FusionStore store(dir);
    for (const FusionInput& input : Mission()) store.Handle(input);
  }
  const fs::path journal = fs::directory_iterator(dir)->path();
  {
    std::fstream file(journal, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(200);
    file.put('\x5a');
  }
  try {
    FusionStore broken(dir);
    FAIL() << "expected an InputError";
  } catch (const io::InputError& error) {
    EXPECT_NE(std::string(error.what()).find(journal.filename().string()), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("corrupt record"), std::string::npos) << error.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pena::fusion
