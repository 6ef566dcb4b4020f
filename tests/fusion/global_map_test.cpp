// The global map: walls of different entities merge with provenance, ids stay stable, corrections
// move contributions, a late joiner's snapshot plus deltas equals the map.
#include <gtest/gtest.h>

#include <cmath>

#include "fusion_test_util.hpp"
#include "pena/fusion/fusion_state.hpp"

namespace pena::fusion {
namespace {

using test::Moved;
using test::Wall;

bool Has(const std::vector<std::string>& list, const std::string& entry) {
  return std::find(list.begin(), list.end(), entry) != list.end();
}

// Two entities with known starts, each reporting its own part of one wall in its own frame.
struct TwoEntities {
  FusionState fusion;
  line_map::LineMap ff1_map, ff2_map;
  const geometry::Pose2 ff2_start{10.0, 0.0, 0.0};  // ff2's frame starts 10 m along x
  explicit TwoEntities(const FusionOptions& options = {}) : fusion(options) {
    fusion.Handle(EntityJoin{0.0, "ff1", geometry::Pose2{}});
    fusion.Handle(EntityJoin{0.0, "ff2", ff2_start});
  }
};

TEST(GlobalMap, TwoEntitiesSeeingOneWallGiveOneSegmentWithBothInProvenance) {
  TwoEntities team;
  // ff1 sees y = 2 from x = 0..8; ff2 sees x = 5..14 in the map, i.e. -5..4 in its frame.
  team.fusion.Handle(LocalDelta{1.0, "ff1", team.ff1_map.Integrate({Wall(0, 2, 8, 2)}, "ff1")});
  const FusionOutput out = team.fusion.Handle(
      LocalDelta{1.5, "ff2", team.ff2_map.Integrate({Wall(-5, 2.03, 4, 2.03)}, "ff2")});
  ASSERT_TRUE(out.problem.empty()) << out.problem;
  ASSERT_TRUE(out.global_delta.has_value());
  const line_map::MapSnapshot global = team.fusion.GlobalSnapshot();
  ASSERT_EQ(global.segments.size(), 1u);
  const line_map::LineSegment& wall = global.segments.front();
  EXPECT_TRUE(Has(wall.provenance, "ff1:1"));
  EXPECT_TRUE(Has(wall.provenance, "ff2:1"));
  EXPECT_NEAR(std::min(wall.segment.start_m.x(), wall.segment.end_m.x()), 0.0, 0.01);
  EXPECT_NEAR(std::max(wall.segment.start_m.x(), wall.segment.end_m.x()), 14.0, 0.01);
  EXPECT_LT(geometry::DistanceToSegment(wall.segment, {7.0, 2.015}), 0.02);
}

TEST(GlobalMap, KeepsTheIdOfAWallWhileItsSupportGrows) {
  TwoEntities team;
  team.fusion.Handle(LocalDelta{1.0, "ff1", team.ff1_map.Integrate({Wall(0, 2, 8, 2)}, "ff1")});
  const std::int64_t id = team.fusion.GlobalSnapshot().segments.at(0).id;
  const FusionOutput out = team.fusion.Handle(
      LocalDelta{2.0, "ff2", team.ff2_map.Integrate({Wall(-5, 2, 4, 2), Wall(4, 0, 4, 2)}, "ff2")});
  ASSERT_TRUE(out.global_delta.has_value());
  EXPECT_EQ(out.global_delta->changed.size(), 1u);
  EXPECT_EQ(out.global_delta->changed.at(0).id, id);
  EXPECT_EQ(out.global_delta->added.size(), 1u);  // ff2's cross wall at x = 14
  EXPECT_TRUE(out.global_delta->removed.empty());
}

TEST(GlobalMap, AlignmentCorrectionMovesAnEntitysWalls) {
  TwoEntities team;
  team.fusion.Handle(LocalDelta{1.0, "ff1", team.ff1_map.Integrate({Wall(0, 2, 8, 2)}, "ff1")});
  // ff2's far wall at x = 20 in the map (10 in its frame); then its alignment is found 0.5 m off.
  team.fusion.Handle(LocalDelta{1.0, "ff2", team.ff2_map.Integrate({Wall(10, 0, 10, 3)}, "ff2")});
  const std::int64_t id = team.fusion.GlobalSnapshot().segments.at(1).id;
  const FusionOutput out = team.fusion.Handle(
      AlignmentCorrection{2.0, "ff2", geometry::Pose2{10.5, 0.0, 0.0}, 0.9});
  ASSERT_TRUE(out.global_delta.has_value());
  ASSERT_EQ(out.global_delta->changed.size(), 1u);
  EXPECT_EQ(out.global_delta->changed.at(0).id, id);
  EXPECT_NEAR(out.global_delta->changed.at(0).segment.start_m.x(), 20.5, 1e-3);
  // An operator correction (section 4.1) composes on top: 0.5 m back.
  const FusionOutput back = team.fusion.Handle(
      OperatorCorrection{3.0, "ff2", geometry::Pose2{-0.5, 0.0, 0.0}, "operator"});
  ASSERT_TRUE(back.global_delta.has_value());
  EXPECT_NEAR(back.global_delta->changed.at(0).segment.start_m.x(), 20.0, 1e-3);
}

TEST(GlobalMap, LateJoinerSnapshotPlusDeltasEqualsTheFullMap) {
  TwoEntities team;
  line_map::LineMap late_joiner;
  bool joined = false;
  for (int step = 0; step < 12; ++step) {
    const double x = 2.0 * step;
    // Alternating entities extend a corridor and revisit earlier walls; ff2 works in its frame.
    FusionOutput out =
        step % 2 == 0
            ? team.fusion.Handle(LocalDelta{1.0 * step, "ff1",
                                            team.ff1_map.Integrate({Wall(x, 0, x + 2.5, 0),
                                                                    Wall(x, 2, x + 1.5, 2)}, "ff1")})
            : team.fusion.Handle(LocalDelta{1.0 * step, "ff2",
                                            team.ff2_map.Integrate(
                                                Moved(geometry::Inverse(team.ff2_start),
                                                      {Wall(x, 0.02, x + 2.2, 0.02),
                                                       Wall(x + 1, 2, x + 2.5, 2)}), "ff2")});
    if (step == 5) {  // the late joiner gets the snapshot here, then the deltas that follow
      late_joiner = line_map::LineMap::FromSnapshot(team.fusion.GlobalSnapshot());
      joined = true;
    } else if (joined && out.global_delta) {
      ASSERT_TRUE(late_joiner.Apply(*out.global_delta).ok());
    }
  }
  const line_map::MapSnapshot full = team.fusion.GlobalSnapshot();
  EXPECT_TRUE(line_map::SameMap(late_joiner.Snapshot(), full));
  EXPECT_GT(full.version, 6u);
  // Both entities' pieces of the south wall overlap: one wall. The north pieces leave 1.5 m gaps.
  const auto south = std::count_if(full.segments.begin(), full.segments.end(), [](const auto& s) {
    return std::abs(s.segment.start_m.y()) < 0.05 && std::abs(s.segment.end_m.y()) < 0.05;
  });
  EXPECT_EQ(south, 1);
}

TEST(GlobalMap, WithholdsALoneDottedWallUntilAnotherEntityCorroboratesIt) {
  TwoEntities team;
  line_map::LineSegment dotted = Wall(0, 5, 10, 5);
  dotted.support_cells = 50;  // 5 cells per metre: floor reflections, not a wall
  team.fusion.Handle(LocalDelta{1.0, "ff1", team.ff1_map.Integrate({dotted, Wall(0, 0, 5, 0)}, "ff1")});
  EXPECT_EQ(team.fusion.GlobalSnapshot().segments.size(), 1u);
  // ff2 sees the same line: two entities agree, so it is published.
  team.fusion.Handle(LocalDelta{2.0, "ff2", team.ff2_map.Integrate({Wall(-8, 5, -4, 5)}, "ff2")});
  EXPECT_EQ(team.fusion.GlobalSnapshot().segments.size(), 2u);
}

TEST(GlobalMap, LeavesOutALoneDriftedCopyOfACorroboratedWall) {
  // Both see y = 2 (x 0..14 in the map); ff1 also saw it 0.4 m off from a drifted pose, and a
  // real wall 2 m away that nobody else saw.
  const auto run = [](const FusionOptions& options) {
    TwoEntities team(options);
    team.fusion.Handle(LocalDelta{
        1.0, "ff1",
        team.ff1_map.Integrate({Wall(0, 2, 8, 2), Wall(1, 2.4, 7, 2.4), Wall(0, 4, 8, 4)}, "ff1")});
    team.fusion.Handle(LocalDelta{2.0, "ff2", team.ff2_map.Integrate({Wall(-5, 2, 4, 2)}, "ff2")});
    return team.fusion.GlobalSnapshot();
  };
  const line_map::MapSnapshot global = run(FusionOptions{});
  ASSERT_EQ(global.segments.size(), 2u);
  for (const line_map::LineSegment& wall : global.segments) {
    EXPECT_GT(std::abs(wall.segment.start_m.y() - 2.4), 0.1) << "the drifted copy is out";
  }
  // With the rule off the copy is published.
  FusionOptions off;
  off.global.lone_duplicate_distance_m = 0.0;
  EXPECT_EQ(run(off).segments.size(), 3u);
}

TEST(GlobalMap, PublishesTheLoneWallsOfAnEntityThatDisagreesWithTheOthers) {
  // ff1 drifted: of its walls along y = 2, which ff2 also saw, 8 m merged and 6 m are a copy
  // 0.4 m off. The copy is withheld, but its wall at y = 4 that nobody else saw contradicts
  // nothing: published, with a larger estimated error than ff2's lone wall at y = -3.
  TwoEntities team;
  team.fusion.Handle(LocalDelta{
      1.0, "ff1",
      team.ff1_map.Integrate({Wall(0, 2, 8, 2), Wall(1, 2.4, 7, 2.4), Wall(0, 4, 8, 4)}, "ff1")});
  team.fusion.Handle(LocalDelta{
      2.0, "ff2", team.ff2_map.Integrate({Wall(-10, 2, 2, 2), Wall(-10, -3, -4, -3)}, "ff2")});
  const line_map::MapSnapshot map = team.fusion.GlobalSnapshot();
  const auto at_y = [&](double y) {
    return std::find_if(map.segments.begin(), map.segments.end(), [y](const auto& s) {
      return std::abs(s.segment.start_m.y() - y) < 0.05 && std::abs(s.segment.end_m.y() - y) < 0.05;
    });
  };
  ASSERT_NE(at_y(2.0), map.segments.end());
  EXPECT_EQ(at_y(2.4), map.segments.end()) << "the drifted copy";
  ASSERT_NE(at_y(4.0), map.segments.end()) << "ff1's lone wall";
  ASSERT_NE(at_y(-3.0), map.segments.end()) << "ff2's lone wall";
  const auto& support = team.fusion.GlobalSupport();
  ASSERT_EQ(support.size(), 3u);
  const WallSupport& both = support.at(at_y(2.0)->id);
  EXPECT_EQ(both.seen_by, (std::vector<std::string>{"ff1", "ff2"}));
  const WallSupport& ff1_alone = support.at(at_y(4.0)->id);
  const WallSupport& ff2_alone = support.at(at_y(-3.0)->id);
  EXPECT_EQ(ff1_alone.seen_by, std::vector<std::string>{"ff1"});
  EXPECT_EQ(ff2_alone.seen_by, std::vector<std::string>{"ff2"});
  // ff1's walls around y = 4: 8 m agree, 6 m are 0.4 m off, over the 5 m prior at 0.05 m.
  EXPECT_NEAR(ff1_alone.error_sd_m, std::sqrt((5 * 0.0025 + 6 * 0.16) / 19.0), 0.02);
  EXPECT_LT(ff2_alone.error_sd_m, 0.06);
  EXPECT_LT(both.error_sd_m, ff2_alone.error_sd_m);
  // The published walls carry it (what the gateway and the console get): the entities counted,
  // the sd on 1 cm quanta.
  for (const auto& [wall, seen] : {std::pair{at_y(2.0), 2u}, std::pair{at_y(4.0), 1u},
                                   std::pair{at_y(-3.0), 1u}}) {
    EXPECT_EQ(wall->seen_by_entities, seen) << "wall " << wall->id;
    EXPECT_EQ(wall->error_sd_m,
              line_map::Quantise(support.at(wall->id).error_sd_m, line_map::kErrorSdQuantumM));
  }
  EXPECT_GT(at_y(4.0)->error_sd_m, 0.0);
  // The agreement behind it.
  GlobalMap global;
  line_map::LineMap ff1_map, ff2_map;
  ff1_map.Integrate({Wall(0, 2, 8, 2), Wall(1, 2.4, 7, 2.4), Wall(0, 4, 8, 4)}, "ff1");
  ff2_map.Integrate({Wall(0, 2, 12, 2), Wall(0, -3, 6, -3)}, "ff2");
  global.Rebuild({{"ff1", ff1_map.segments()}, {"ff2", ff2_map.segments()}});
  ASSERT_EQ(global.agreement().size(), 2u);
  EXPECT_NEAR(global.agreement().at("ff1").agree_m, 8.0, 1e-6);
  EXPECT_NEAR(global.agreement().at("ff1").disagree_m, 6.0, 1e-6);
  EXPECT_NEAR(global.agreement().at("ff1").rms_offset_m(), 0.4 * std::sqrt(6.0 / 14.0), 1e-3);
  EXPECT_NEAR(global.agreement().at("ff2").ratio(), 1.0, 1e-9);
  FusionOptions bad;
  bad.global.error_radius_m = 0.0;
  EXPECT_THROW(FusionState{bad}, std::invalid_argument);
}

TEST(GlobalMap, KeepsTheCopyOfTheEntityWhoseWallsAgreeAroundItAndCreditsTheOther) {
  // All three saw y = 0; ff1 and ff3 saw y = 3 where ff2 put it at 3.3 (its walls are off here).
  // ff1 and ff2 alone saw the wall at y = 6, 0.25 m apart: ff1's is published, seen by both.
  FusionState fusion;
  for (const char* id : {"ff1", "ff2", "ff3"}) fusion.Handle(EntityJoin{0.0, id, geometry::Pose2{}});
  line_map::LineMap ff1_map, ff2_map, ff3_map;
  fusion.Handle(LocalDelta{1.0, "ff1",
                           ff1_map.Integrate({Wall(0, 0, 10, 0), Wall(0, 3, 10, 3), Wall(0, 6, 10, 6)},
                                             "ff1")});
  fusion.Handle(LocalDelta{2.0, "ff2",
                           ff2_map.Integrate({Wall(0, 0, 10, 0), Wall(0, 3.3, 10, 3.3),
                                              Wall(0, 6.25, 10, 6.25)},
                                             "ff2")});
  fusion.Handle(LocalDelta{3.0, "ff3", ff3_map.Integrate({Wall(0, 0, 10, 0), Wall(0, 3, 10, 3)}, "ff3")});
  const line_map::MapSnapshot map = fusion.GlobalSnapshot();
  ASSERT_EQ(map.segments.size(), 3u) << "one wall each at y = 0, 3, 6";
  const auto& support = fusion.GlobalSupport();
  for (const line_map::LineSegment& wall : map.segments) {
    const double y = wall.segment.start_m.y();
    EXPECT_TRUE(std::abs(y) < 0.01 || std::abs(y - 3.0) < 0.01 || std::abs(y - 6.0) < 0.01) << y;
    const std::vector<std::string> seen_by = support.at(wall.id).seen_by;
    EXPECT_TRUE(Has(seen_by, "ff1") && Has(seen_by, "ff2")) << y;
    if (std::abs(y - 6.0) < 0.01) {
      EXPECT_EQ(wall.provenance.size(), 1u) << "ff1's geometry";
    }
  }
}

TEST(GlobalMap, WithholdsAWallTwoUntrustedEntitiesSawAlongAPlanWallTheyDoNotConfirm) {
  // Plan walls y = 0 and y = 5. ff1 and ff2 each confirm y = 0 but also left a copy of it
  // 0.4 m off (agreement 20 m of 28 m; estimated wall error 0.2 m: untrusted). Both saw y = 5 at
  // 5.2, drifted alike.
  const auto run = [](const FusionOptions& options) {
    FusionState fusion(options);
    std::vector<line_map::LineSegment> plan = {Wall(0, 0, 10, 0, 0), Wall(0, 5, 10, 5, 0)};
    plan[0].id = 1;
    plan[1].id = 2;
    fusion.Handle(SetPlan{0.0, plan});
    for (const auto& [id, copy_y] : {std::pair{"ff1", 0.4}, std::pair{"ff2", -0.4}}) {
      fusion.Handle(EntityJoin{0.0, id, geometry::Pose2{}});
      line_map::LineMap local;
      fusion.Handle(LocalDelta{
          1.0, id,
          local.Integrate({Wall(0, 0, 10, 0), Wall(1, copy_y, 9, copy_y), Wall(0, 5.2, 10, 5.2)}, id)});
    }
    const line_map::MapSnapshot map = fusion.GlobalSnapshot();
    return std::count_if(map.segments.begin(), map.segments.end(), [](const auto& s) {
      return std::abs(s.segment.start_m.y() - 5.2) < 0.05 && s.provenance.size() >= 2;
    });
  };
  EXPECT_EQ(run(FusionOptions{}), 0);
  FusionOptions off;
  off.global.max_lone_error_m = 10.0;
  EXPECT_EQ(run(off), 1);
}

TEST(GlobalMap, LaysThePlanUnderTheObservationsAndKeepsItsUnseenParts) {
  FusionState fusion;
  // Plan: a wall y = 0 (right) and a wall y = 5 that is really at y = 5.4 (shifted 0.4 m).
  std::vector<line_map::LineSegment> plan = {Wall(0, 0, 10, 0, 0), Wall(0, 5, 10, 5, 0)};
  plan[0].id = 1;
  plan[1].id = 2;
  ASSERT_TRUE(fusion.Handle(SetPlan{0.0, plan}).problem.empty());
  EXPECT_EQ(fusion.GlobalSnapshot().segments.size(), 2u);
  line_map::LineMap ff1;
  fusion.Handle(EntityJoin{0.0, "ff1", geometry::Pose2{}});
  fusion.Handle(LocalDelta{1.0, "ff1", ff1.Integrate({Wall(1, 0.03, 6, 0.03), Wall(0, 5.4, 10, 5.4)}, "ff1")});
  const line_map::MapSnapshot global = fusion.GlobalSnapshot();
  ASSERT_EQ(global.segments.size(), 4u);
  int plan_only = 0;
  for (const line_map::LineSegment& wall : global.segments) {
    if (Has(wall.provenance, "ff1:1")) {  // observed geometry, confirmed by the plan
      EXPECT_TRUE(Has(wall.provenance, "plan:1"));
      EXPECT_NEAR(wall.segment.start_m.y(), 0.03, 1e-9);
    } else if (Has(wall.provenance, "ff1:2")) {  // the shifted plan wall is replaced
      EXPECT_EQ(wall.provenance.size(), 1u);
      EXPECT_NEAR(wall.segment.start_m.y(), 5.4, 1e-9);
    } else {  // the unseen parts of plan wall 1: x 0..1 and 6..10
      EXPECT_EQ(wall.provenance, std::vector<std::string>{"plan:1"});
      ++plan_only;
    }
  }
  EXPECT_EQ(plan_only, 2);
}

}  // namespace
}  // namespace pena::fusion

namespace pena::fusion {
namespace {

using test::Wall;

TEST(GlobalMap, RebuildOnPublishGivesOneDeltaForManyChangesAndTheSameWalls) {
  FusionOptions batched_options;
  batched_options.rebuild_on_publish = true;
  FusionState each, batched(batched_options);
  line_map::LineMap ff1, ff2;
  std::vector<FusionInput> inputs = {EntityJoin{0.0, "ff1", geometry::Pose2{}},
                                     EntityJoin{0.0, "ff2", geometry::Pose2{}}};
  for (int step = 0; step < 5; ++step) {
    const double x = 3.0 * step;
    inputs.push_back(LocalDelta{1.0 + step, "ff1", ff1.Integrate({Wall(x, 0, x + 3.2, 0)}, "ff1")});
    inputs.push_back(LocalDelta{1.5 + step, "ff2", ff2.Integrate({Wall(x, 2, x + 1, 2)}, "ff2")});
  }
  for (const FusionInput& input : inputs) {
    each.Handle(input);
    EXPECT_FALSE(batched.Handle(input).global_delta.has_value());
  }
  const FusionOutput published = batched.Handle(Publish{10.0});
  ASSERT_TRUE(published.global_delta.has_value());
  EXPECT_EQ(batched.global_version(), 1u);
  EXPECT_GT(each.global_version(), 5u);
  const auto a = each.GlobalSnapshot().segments;
  const auto b = batched.GlobalSnapshot().segments;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].segment.start_m, b[i].segment.start_m);
    EXPECT_EQ(a[i].segment.end_m, b[i].segment.end_m);
    EXPECT_EQ(a[i].provenance, b[i].provenance);
  }
  EXPECT_FALSE(batched.Handle(Publish{11.0}).changed);  // nothing new: nothing to publish
}

}  // namespace
}  // namespace pena::fusion
