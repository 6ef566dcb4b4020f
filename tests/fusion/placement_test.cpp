// Placement of an entity with an unknown start: several hypotheses, accepted only by a margin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fusion_test_util.hpp"
#include "pena/fusion/fusion_state.hpp"
#include "pena/fusion/placement.hpp"

namespace pena::fusion {
namespace {

using test::Moved;
using test::Wall;

// A 2 m wide corridor along x from 0 to 40 with identical side corridors (1.5 m openings, 4 m
// deep) going up at x = 10, 20 and 30, and a dead end at x = 40. The west end stays open.
std::vector<line_map::LineSegment> Corridor(double from_x, double to_x) {
  std::vector<line_map::LineSegment> walls;
  const auto clip = [&](double x1, double y1, double x2, double y2) {
    const double a = std::max(std::min(x1, x2), from_x);
    const double b = std::min(std::max(x1, x2), to_x);
    if (b - a > 0.05 || (x1 == x2 && x1 >= from_x && x1 <= to_x)) {
      walls.push_back(Wall(x1 == x2 ? x1 : a, y1, x1 == x2 ? x2 : b, y2));
    }
  };
  clip(0, 0, 40, 0);  // south wall, unbroken
  double x = 0.0;
  for (const double junction : {10.0, 20.0, 30.0}) {
    clip(x, 2, junction - 0.75, 2);
    clip(junction - 0.75, 2, junction - 0.75, 6);
    clip(junction + 0.75, 2, junction + 0.75, 6);
    x = junction + 0.75;
  }
  clip(x, 2, 40, 2);
  clip(40, 0, 40, 2);  // the dead end
  for (std::size_t i = 0; i < walls.size(); ++i) walls[i].id = static_cast<std::int64_t>(i + 1);
  return walls;
}

// The entity's frame: 30 deg turned and shifted against the map.
const geometry::Pose2 kMapFromEntity{20.3, -1.7, std::numbers::pi / 6.0};

std::vector<line_map::LineSegment> SeenFrom(double from_x, double to_x) {
  return Moved(geometry::Inverse(kMapFromEntity), Corridor(from_x, to_x));
}

TEST(Placement, KeepsSeveralHypothesesWhileTheCorridorAliases) {
  // The entity saw the junction at x = 20 and 4.5 m either side: junctions 10 and 30 look the same.
  const PlacementResult result = PlaceLocalMap(SeenFrom(15.5, 24.5), Corridor(0, 40), {});
  EXPECT_FALSE(result.placed);
  ASSERT_GE(result.hypotheses.size(), 3u);
  EXPECT_LT(result.margin_m, 1.5);
  EXPECT_NE(result.reason.find("aliased"), std::string::npos) << result.reason;
  // The truth is among the equally good hypotheses.
  const bool truth_kept = std::any_of(result.hypotheses.begin(), result.hypotheses.end(),
                                      [](const PlacementHypothesis& h) {
    return std::hypot(h.map_from_entity.x_m - kMapFromEntity.x_m,
                      h.map_from_entity.y_m - kMapFromEntity.y_m) < 0.1;
  });
  EXPECT_TRUE(truth_kept);
}

TEST(Placement, AcceptsOnceTheGrownMapWinsByTheMargin) {
  const PlacementResult early = PlaceLocalMap(SeenFrom(15.5, 24.5), Corridor(0, 40), {});
  // Walking on east, it sees the junction at 30 and the dead end at 40: only one place fits.
  const PlacementResult later = PlaceLocalMap(SeenFrom(15.5, 40), Corridor(0, 40), early.hypotheses);
  ASSERT_TRUE(later.placed) << later.reason;
  EXPECT_GE(later.margin_m, 1.5);
  EXPECT_NEAR(later.map_from_entity.x_m, kMapFromEntity.x_m, 0.05);
  EXPECT_NEAR(later.map_from_entity.y_m, kMapFromEntity.y_m, 0.05);
  EXPECT_NEAR(later.map_from_entity.theta_rad, kMapFromEntity.theta_rad, 0.01);
}

// The entity saw two places: near its start an L of two 6 m walls, farther on a staircase of six
// 3-3.5 m walls. The global map holds the L where it truly is (kRight) but not the staircase
// there; it holds a staircase of the same shape elsewhere, turned by 100 deg (kWrong): the wrong
// pose explains 20 of the 32 m (62 %, 8 m more than the right pose), other walls than the right
// pose does. Were the two equally good, that margin's sd wall by wall would be 11.8 m.
const geometry::Pose2 kRight{12.0, -3.0, 0.4};
const geometry::Pose2 kWrong{-30.0, 25.0, 0.4 + 1.7453292519943295};

std::vector<line_map::LineSegment> StartL() { return {Wall(0, 0, 6, 0), Wall(0, 0, 0, 6)}; }

std::vector<line_map::LineSegment> Staircase() {
  return {Wall(20, 0, 23.5, 0),   Wall(23.5, 0, 23.5, 3), Wall(23.5, 3, 20.5, 3),
          Wall(20.5, 3, 20.5, 6.5), Wall(20.5, 6.5, 24, 6.5), Wall(24, 6.5, 24, 10)};
}

TEST(Placement, RefusesAWrongPoseThatExplainsOtherWallsThanTheRightOne) {
  std::vector<line_map::LineSegment> local = StartL();
  for (const line_map::LineSegment& wall : Staircase()) local.push_back(wall);
  for (std::size_t i = 0; i < local.size(); ++i) local[i].id = static_cast<std::int64_t>(i + 1);
  std::vector<line_map::LineSegment> global = Moved(kRight, StartL());
  for (const line_map::LineSegment& wall : Moved(kWrong, Staircase())) global.push_back(wall);
  for (std::size_t i = 0; i < global.size(); ++i) global[i].id = static_cast<std::int64_t>(i + 1);

  const PlacementResult result = PlaceLocalMap(local, global, {});
  ASSERT_GE(result.hypotheses.size(), 2u);
  const geometry::Pose2& best = result.hypotheses.front().map_from_entity;
  EXPECT_NEAR(best.x_m, kWrong.x_m, 0.05);  // the wrong pose explains the most wall ...
  EXPECT_NEAR(best.y_m, kWrong.y_m, 0.05);
  EXPECT_GE(result.hypotheses.front().score, 0.6);
  EXPECT_GE(result.margin_m, 1.5);
  EXPECT_FALSE(result.placed);  // ... but not by more than chance would
  EXPECT_NE(result.reason.find("chance alone"), std::string::npos) << result.reason;
  const bool right_kept = std::any_of(result.hypotheses.begin(), result.hypotheses.end(),
                                      [](const PlacementHypothesis& h) {
    return std::hypot(h.map_from_entity.x_m - kRight.x_m, h.map_from_entity.y_m - kRight.y_m) < 0.1;
  });
  EXPECT_TRUE(right_kept);

  // Score and margin in metres alone would have placed it there.
  PlacementOptions metres_only;
  metres_only.min_margin_sd = 0.0;
  const PlacementResult wrong = PlaceLocalMap(local, global, {}, metres_only);
  ASSERT_TRUE(wrong.placed) << wrong.reason;
  EXPECT_NEAR(wrong.map_from_entity.x_m, kWrong.x_m, 0.05);
}

TEST(Placement, WaitsForEnoughWalls) {
  const PlacementResult result = PlaceLocalMap(SeenFrom(19.5, 20.5), Corridor(0, 40), {});
  EXPECT_FALSE(result.placed);
  EXPECT_NE(result.reason.find("placement needs"), std::string::npos) << result.reason;
}

TEST(Placement, FusionPlacesAnEntityWithUnknownStartAndMergesItsWalls) {
  FusionState fusion;
  std::vector<line_map::LineSegment> plan = Corridor(0, 40);
  fusion.Handle(SetPlan{0.0, plan});
  fusion.Handle(EntityJoin{0.0, "ff3", std::nullopt});
  line_map::LineMap sender;
  const FusionOutput first =
      fusion.Handle(LocalDelta{1.0, "ff3", sender.Integrate(SeenFrom(15.5, 24.5), "ff3")});
  ASSERT_TRUE(first.placement.has_value());
  EXPECT_FALSE(first.placement->placed);
  EXPECT_FALSE(first.global_delta.has_value());  // unplaced walls stay out of the global map
  const FusionOutput second =
      fusion.Handle(LocalDelta{2.0, "ff3", sender.Integrate(SeenFrom(24.5, 40), "ff3")});
  ASSERT_TRUE(second.placement.has_value());
  ASSERT_TRUE(second.placement->placed) << second.placement->reason;
  ASSERT_TRUE(fusion.entity("ff3")->map_from_entity.has_value());
  EXPECT_NEAR(fusion.entity("ff3")->map_from_entity->x_m, kMapFromEntity.x_m, 0.05);
  ASSERT_TRUE(second.global_delta.has_value());
  // Every wall ff3 saw lies on its plan wall (placed within the merge distance), so none is
  // duplicated: 9 observed walls confirm the plan, 5 plan pieces ff3 did not see remain.
  int confirmed = 0, plan_only = 0;
  for (const line_map::LineSegment& wall : fusion.GlobalSnapshot().segments) {
    const bool seen = std::any_of(wall.provenance.begin(), wall.provenance.end(),
                                  [](const std::string& key) { return key.rfind("ff3:", 0) == 0; });
    const bool planned = std::any_of(wall.provenance.begin(), wall.provenance.end(),
                                     [](const std::string& key) { return key.rfind("plan:", 0) == 0; });
    EXPECT_TRUE(planned);
    confirmed += seen ? 1 : 0;
    plan_only += seen ? 0 : 1;
  }
  EXPECT_EQ(confirmed, 9);
  EXPECT_EQ(plan_only, 5);
}

}  // namespace
}  // namespace pena::fusion
