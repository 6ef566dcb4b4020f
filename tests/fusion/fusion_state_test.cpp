// The fusion's bookkeeping: version gaps, lifecycle, annotations, refused inputs.
#include <gtest/gtest.h>

#include <cmath>

#include "fusion_test_util.hpp"
#include "pena/fusion/fusion_state.hpp"

namespace pena::fusion {
namespace {

using test::Wall;

TEST(FusionState, AsksForASnapshotOnAVersionGapAndRecoversFromIt) {
  FusionState fusion;
  fusion.Handle(EntityJoin{0.0, "ff1", geometry::Pose2{}});
  line_map::LineMap sender;
  const line_map::MapDelta first = sender.Integrate({Wall(0, 0, 5, 0)}, "ff1");
  ASSERT_FALSE(fusion.Handle(LocalDelta{1.0, "ff1", first}).snapshot_request);
  sender.Integrate({Wall(0, 3, 5, 3)}, "ff1");  // lost on the way
  const FusionOutput gap =
      fusion.Handle(LocalDelta{2.0, "ff1", sender.Integrate({Wall(7, 0, 7, 3)}, "ff1")});
  ASSERT_TRUE(gap.snapshot_request.has_value());
  EXPECT_EQ(*gap.snapshot_request, "ff1");
  EXPECT_TRUE(gap.problem.empty());
  EXPECT_TRUE(fusion.entity("ff1")->awaiting_snapshot);
  EXPECT_EQ(fusion.local_map("ff1").version(), 1u);  // unchanged by the refused delta
  const FusionOutput resync = fusion.Handle(LocalSnapshot{2.5, "ff1", sender.Snapshot()});
  EXPECT_TRUE(resync.problem.empty());
  EXPECT_FALSE(fusion.entity("ff1")->awaiting_snapshot);
  EXPECT_TRUE(line_map::SameMap(fusion.local_map("ff1").Snapshot(), sender.Snapshot()));
  EXPECT_EQ(fusion.GlobalSnapshot().segments.size(), 3u);
  // A delta that was in flight before the snapshot is stale: ignored, no new request.
  const FusionOutput stale = fusion.Handle(LocalDelta{2.6, "ff1", first});
  EXPECT_FALSE(stale.snapshot_request);
  EXPECT_TRUE(stale.problem.empty());
  EXPECT_EQ(fusion.local_map("ff1").version(), 3u);
}

// True if the global map holds a wall from a to b (either way round) within 1 mm.
bool HoldsWall(const FusionState& fusion, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  for (const line_map::LineSegment& wall : fusion.GlobalSnapshot().segments) {
    const geometry::Segment2& s = wall.segment;
    if (((s.start_m - a).norm() < 1e-3 && (s.end_m - b).norm() < 1e-3) ||
        ((s.start_m - b).norm() < 1e-3 && (s.end_m - a).norm() < 1e-3)) {
      return true;
    }
  }
  return false;
}

TEST(FusionState, OperatorWallMoveRotatesOnlyTheWallsMappedInTheWrongFrame) {
  FusionState fusion;
  fusion.Handle(EntityJoin{0.0, "ff1", geometry::Pose2{}});  // a known start
  line_map::LineMap sender;
  // Before the heading went wrong: a wall along x. After: a wall mapped 20 deg askew about
  // (5, 0), the rotation origin.
  fusion.Handle(LocalDelta{1.0, "ff1", sender.Integrate({Wall(0, 0, 5, 0)}, "ff1")});
  const double angle_rad = 20.0 * M_PI / 180.0;
  const geometry::Pose2 about_origin_wrong =
      geometry::Compose(geometry::Pose2{5.0, 0.0, angle_rad}, geometry::Pose2{-5.0, 0.0, 0.0});
  const std::vector<line_map::LineSegment> askew =
      test::Moved(about_origin_wrong, {Wall(6, 1, 6, 4)});
  const line_map::MapDelta wrong = sender.Integrate(askew, "ff1");
  fusion.Handle(LocalDelta{2.0, "ff1", wrong});
  ASSERT_EQ(wrong.added.size(), 1u);
  // The operator's three-point rotation: corrected_from_wrong turns it back about (5, 0).
  const geometry::Pose2 corrected_from_wrong = geometry::Inverse(about_origin_wrong);
  const FusionOutput moved = fusion.Handle(
      MoveEntityWalls{3.0, "ff1", corrected_from_wrong, {wrong.added[0].id, 999}, "op"});
  ASSERT_TRUE(moved.problem.empty()) << moved.problem;
  EXPECT_TRUE(moved.global_delta.has_value());
  EXPECT_TRUE(HoldsWall(fusion, {0, 0}, {5, 0}));  // mapped before the origin: stays
  EXPECT_TRUE(HoldsWall(fusion, {6, 1}, {6, 4}));  // mapped askew: back where it belongs
  EXPECT_EQ(fusion.GlobalSnapshot().segments.size(), 2u);
  // Walls mapped after the entity took the corrected frame arrive right and are not moved.
  fusion.Handle(LocalDelta{4.0, "ff1", sender.Integrate({Wall(8, 0, 8, 4)}, "ff1")});
  EXPECT_TRUE(HoldsWall(fusion, {8, 0}, {8, 4}));
  // The moves are part of the state: a checkpoint keeps them.
  const FusionState restored = FusionState::FromCheckpoint(fusion.Checkpoint());
  EXPECT_TRUE(line_map::SameMap(restored.GlobalSnapshot(), fusion.GlobalSnapshot()));
  EXPECT_EQ(restored.entity("ff1")->moved_walls.size(), 1u);
  // Undone (the inverse on the same walls): the askew wall is back where ff1 mapped it.
  fusion.Handle(MoveEntityWalls{5.0, "ff1", about_origin_wrong, {wrong.added[0].id}, "op"});
  EXPECT_TRUE(HoldsWall(fusion, askew[0].segment.start_m, askew[0].segment.end_m));
  EXPECT_TRUE(HoldsWall(fusion, {0, 0}, {5, 0}));
  // Refused without change: an unknown entity, a transform that is not finite.
  EXPECT_FALSE(fusion.Handle(MoveEntityWalls{6.0, "nobody", {}, {1}, "op"}).problem.empty());
  EXPECT_FALSE(
      fusion.Handle(MoveEntityWalls{6.0, "ff1", geometry::Pose2{NAN, 0, 0}, {1}, "op"})
          .problem.empty());
}

TEST(FusionState, MarksASilentEntityLostAndKeepsItsWalls) {
  FusionOptions options;
  options.silent_after_s = 5.0;
  FusionState fusion(options);
  fusion.Handle(EntityJoin{0.0, "robot1", geometry::Pose2{}});
  EXPECT_EQ(fusion.entity("robot1")->lifecycle, EntityLifecycle::kJoined);
  line_map::LineMap sender;
  fusion.Handle(LocalDelta{1.0, "robot1", sender.Integrate({Wall(0, 0, 5, 0)}, "robot1")});
  EXPECT_EQ(fusion.entity("robot1")->lifecycle, EntityLifecycle::kActive);
  EXPECT_TRUE(fusion.Handle(Tick{5.9}).lifecycle.empty());  // 4.9 s of silence: still active
  const FusionOutput lost = fusion.Handle(Tick{6.1});
  ASSERT_EQ(lost.lifecycle.size(), 1u);
  EXPECT_EQ(lost.lifecycle[0].entity_id, "robot1");
  EXPECT_EQ(lost.lifecycle[0].to, EntityLifecycle::kLost);
  EXPECT_EQ(fusion.entity("robot1")->lifecycle, EntityLifecycle::kLost);
  EXPECT_EQ(fusion.GlobalSnapshot().segments.size(), 1u);  // its wall stays
  EXPECT_EQ(fusion.local_map("robot1").size(), 1u);
  // It comes back: a heartbeat makes it active again; leaving keeps the walls too.
  const FusionOutput back = fusion.Handle(EntityHeartbeat{8.0, "robot1"});
  ASSERT_EQ(back.lifecycle.size(), 1u);
  EXPECT_EQ(back.lifecycle[0].to, EntityLifecycle::kActive);
  fusion.Handle(EntityLeave{9.0, "robot1"});
  EXPECT_EQ(fusion.entity("robot1")->lifecycle, EntityLifecycle::kLeft);
  EXPECT_TRUE(fusion.Handle(Tick{100.0}).lifecycle.empty());  // a left entity is not "lost"
  EXPECT_EQ(fusion.GlobalSnapshot().segments.size(), 1u);
}

TEST(FusionState, VersionsAnnotationsAndRefusesBadOnes) {
  FusionState fusion;
  Annotation victim;
  victim.kind = AnnotationKind::kVictimFound;
  victim.position_m = {12.5, 3.0};
  victim.text = "conscious, leg trapped";
  victim.author = "operator";
  victim.stamp_s = 40.0;
  const FusionOutput added = fusion.Handle(PutAnnotation{40.0, victim});
  ASSERT_TRUE(added.annotation.has_value());
  EXPECT_EQ(added.annotation->annotation.id, 1);
  EXPECT_EQ(added.annotation->version, 1u);
  Annotation area = victim;
  area.kind = AnnotationKind::kDangerousArea;
  area.radius_m = 3.0;
  area.text = "ceiling collapse";
  EXPECT_EQ(fusion.Handle(PutAnnotation{41.0, area}).annotation->annotation.id, 2);
  area.id = 2;
  area.radius_m = 4.0;  // the operator widens it
  EXPECT_EQ(fusion.Handle(PutAnnotation{42.0, area}).annotation->version, 3u);
  const FusionOutput removed = fusion.Handle(RemoveAnnotation{43.0, 1, "operator"});
  ASSERT_TRUE(removed.annotation.has_value());
  EXPECT_TRUE(removed.annotation->removed);
  ASSERT_EQ(fusion.annotations().size(), 1u);
  EXPECT_EQ(fusion.annotations()[0].radius_m, 4.0);
  EXPECT_EQ(fusion.annotation_version(), 4u);
  // Refused: unknown id, negative radius, no author; nothing changes.
  area.id = 7;
  EXPECT_NE(fusion.Handle(PutAnnotation{44.0, area}).problem.find("unknown"), std::string::npos);
  area.id = 0;
  area.radius_m = -1.0;
  EXPECT_NE(fusion.Handle(PutAnnotation{44.0, area}).problem.find("radius_m"), std::string::npos);
  EXPECT_FALSE(fusion.Handle(RemoveAnnotation{45.0, 1, "operator"}).problem.empty());
  EXPECT_EQ(fusion.annotation_version(), 4u);
}

TEST(FusionState, RefusesBadInputWithAMessageAndChangesNothing) {
  FusionState fusion;
  fusion.Handle(EntityJoin{0.0, "ff1", geometry::Pose2{}});
  line_map::MapDelta bad{0, 1, {Wall(0, 0, std::nan(""), 0)}, {}, {}};
  bad.added[0].id = 1;
  const FusionOutput out = fusion.Handle(LocalDelta{1.0, "ff1", bad});
  EXPECT_NE(out.problem.find("delta of ff1: segment 1"), std::string::npos) << out.problem;
  EXPECT_EQ(fusion.local_map("ff1").version(), 0u);
  EXPECT_FALSE(fusion.Handle(EntityJoin{0.0, "a:b", std::nullopt}).problem.empty());
  EXPECT_FALSE(fusion.Handle(AlignmentCorrection{1.0, "nobody", {}, 1.0}).problem.empty());
  EXPECT_FALSE(fusion.Handle(AlignmentCorrection{1.0, "ff1", {}, 1.5}).problem.empty());
  EXPECT_EQ(fusion.global_version(), 0u);
}

TEST(FusionState, CorrectionMapLeavesOutWallsOnlyTheEntityItselfSaw) {
  FusionState fusion;
  fusion.Handle(EntityJoin{0.0, "ff1", geometry::Pose2{}});
  fusion.Handle(EntityJoin{0.0, "ff2", geometry::Pose2{}});
  line_map::LineMap ff1, ff2;
  fusion.Handle(LocalDelta{1.0, "ff1", ff1.Integrate({Wall(0, 0, 5, 0), Wall(0, 4, 5, 4)}, "ff1")});
  fusion.Handle(LocalDelta{1.0, "ff2", ff2.Integrate({Wall(0, 0, 5, 0)}, "ff2")});
  EXPECT_EQ(fusion.CorrectionMap("ff1").size(), 1u);  // the shared wall only
  EXPECT_EQ(fusion.CorrectionMap("ff2").size(), 2u);
}

}  // namespace
}  // namespace pena::fusion
