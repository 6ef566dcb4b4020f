#include "pena/localisation/map_localiser.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include "office_plan.hpp"

namespace pena::localisation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

class MapLocaliserTest : public ::testing::Test {
 protected:
  MapLocaliserTest()
      : office_(testing::OfficeScenario()), truth_scanner_(office_.walls) {}

  // A perfect scan of the true building at `truth` and an odometry estimate `error` (body frame)
  // off it.
  std::pair<sensors::LaserScan, odometry::OdometryEstimate> At(const geometry::Pose2& truth,
                                                               const geometry::Pose2& error = {},
                                                               bool reference_changed = true) {
    stamp_s_ += 1.0;
    sensors::LaserScan scan = truth_scanner_.Scan(truth, testing::OfficeLaser(), 361, stamp_s_);
    odometry::OdometryEstimate estimate;
    estimate.stamp_s = stamp_s_;
    estimate.world_from_body = geometry::Compose(truth, error);  // error in the body frame
    estimate.reference_changed = reference_changed;
    return {scan, estimate};
  }

  std::vector<double> AlongErrors(const MapLocaliserOptions& options, double jump_at, bool round_at_jump);

  sim::Scenario office_;
  VirtualScanner truth_scanner_;
  double stamp_s_ = 0.0;
};

void ExpectNear(const geometry::Pose2& got, const geometry::Pose2& expected, double tol_m,
                double tol_rad) {
  EXPECT_NEAR(got.x_m, expected.x_m, tol_m);
  EXPECT_NEAR(got.y_m, expected.y_m, tol_m);
  EXPECT_NEAR(geometry::NormalizeAngle(got.theta_rad - expected.theta_rad), 0.0, tol_rad);
}

TEST_F(MapLocaliserTest, CorrectsAnOffsetPoseInAMappedRoom) {
  MapLocaliser localiser({}, *office_.apriori, {});
  const geometry::Pose2 truth{7.0, 18.5, -90.0 * kDeg};
  const auto [scan, estimate] = At(truth, {0.15, -0.12, 2.5 * kDeg});
  const auto round = localiser.Update(scan, estimate);
  ASSERT_TRUE(round.has_value());
  EXPECT_TRUE(round->accepted);
  EXPECT_EQ(round->status, MapStatus::kInMap);
  EXPECT_GT(round->confidence, 0.5);
  ExpectNear(localiser.MapFromBody(estimate.world_from_body), truth, 0.03, 0.5 * kDeg);
  ExpectNear(round->map_from_body_after, truth, 0.03, 0.5 * kDeg);
}

// In a mapped room with the odometry 0.24 m off, beyond the paper's window (+-0.2 m): the search's
// best grid position lies on the window's edge, so the round is not taken (require_interior) and
// the next one, in a window grown by window_growth, finds the place inside it.
TEST_F(MapLocaliserTest, AnOptimumOnTheWindowsEdgeWaitsForAWiderWindow) {
  const geometry::Pose2 truth{7.0, 18.5, -90.0 * kDeg};
  MapLocaliser localiser({}, *office_.apriori, {});
  auto [scan, estimate] = At(truth, {0.24, 0.0, 0.0});
  const auto edge = localiser.Update(scan, estimate);
  ASSERT_TRUE(edge.has_value());
  EXPECT_FALSE(edge->accepted);
  EXPECT_FALSE(edge->recast);
  std::tie(scan, estimate) = At(truth, {0.24, 0.0, 0.0});
  const auto wider = localiser.Update(scan, estimate);
  ASSERT_TRUE(wider.has_value());
  EXPECT_GT(wider->window_xy_m, edge->window_xy_m);
  EXPECT_TRUE(wider->accepted);
  ExpectNear(wider->map_from_body_after, truth, 0.05, 0.5 * kDeg);
  MapLocaliserOptions off;
  off.require_interior = false;
  MapLocaliser taken(off, *office_.apriori, {});
  const auto first = taken.Update(scan, estimate);
  ASSERT_TRUE(first.has_value());
  EXPECT_TRUE(first->accepted);
}

TEST_F(MapLocaliserTest, RunsOnlyWhenTheReferenceChanges) {
  MapLocaliser localiser({}, *office_.apriori, {});
  const auto [scan, estimate] = At({7.0, 18.5, -90.0 * kDeg}, {0.15, 0.0, 0.0}, false);
  EXPECT_FALSE(localiser.Update(scan, estimate).has_value());
  EXPECT_EQ(localiser.status(), MapStatus::kUnknown);
  EXPECT_NEAR(localiser.MapFromBody(estimate.world_from_body).y_m, estimate.world_from_body.y_m, 1e-12);
  EXPECT_TRUE(localiser.Update(scan, estimate, /*force=*/true).has_value());
}

TEST_F(MapLocaliserTest, RobustToAShiftedWall) {
  std::vector<geometry::Segment2> plan = *office_.apriori;
  for (auto& s : plan) {  // the room's east wall x = 10 drawn 0.3 m too far east
    if (s.start_m.x() == 10.0 && s.end_m.x() == 10.0) s.start_m.x() = s.end_m.x() = 10.3;
  }
  MapLocaliser localiser({}, plan, {});
  // Facing north: the shifted east wall is about a quarter of the returns.
  const geometry::Pose2 truth{7.0, 18.5, 90.0 * kDeg};
  const auto [scan, estimate] = At(truth, {-0.12, 0.1, -2.0 * kDeg});
  const auto round = localiser.Update(scan, estimate);
  ASSERT_TRUE(round && round->accepted);
  ExpectNear(round->map_from_body_after, truth, 0.05, 0.5 * kDeg);
}

TEST_F(MapLocaliserTest, GoesOutsideTheMapAndIsReacquired) {
  MapLocaliser localiser({}, *office_.apriori, {});
  auto [scan, estimate] = At({8.0, 14.0, 180.0 * kDeg});
  EXPECT_EQ(localiser.Update(scan, estimate)->status, MapStatus::kInMap);
  // The west wing is not on the plan: rounds there fail and the entity is judged outside.
  std::tie(scan, estimate) = At({2.0, 14.0, 180.0 * kDeg});
  EXPECT_FALSE(localiser.Update(scan, estimate)->accepted);
  std::tie(scan, estimate) = At({2.0, 11.0, -90.0 * kDeg});
  const auto outside = localiser.Update(scan, estimate);
  EXPECT_FALSE(outside->accepted);
  EXPECT_EQ(outside->status, MapStatus::kOutsideMap);
  EXPECT_GT(outside->window_xy_m, MapLocaliserOptions{}.window.size_x_m);
  // Back in the corridor with 0.3 m of lateral drift and 1.5 deg: the grown window finds the
  // plan again (along the corridor the odometry is kept, so no along-corridor error is made).
  const geometry::Pose2 truth{7.0, 14.0, 0.0};
  std::tie(scan, estimate) = At(truth, {0.0, 0.3, 1.5 * kDeg});
  const auto back = localiser.Update(scan, estimate);
  ASSERT_TRUE(back->accepted);
  EXPECT_EQ(back->status, MapStatus::kReacquired);
  ExpectNear(back->map_from_body_after, truth, 0.05, 0.5 * kDeg);
}

// The office corridor with the odometry 0.6 m ahead along it. Seen from the expected pose the
// plan looks different through the doors, so the right correction scores low there; judged again
// from where it puts the entity, it scores as a match should.
TEST_F(MapLocaliserTest, ALargeCorrectionIsJudgedFromWhereItPutsTheEntity) {
  MapLocaliserOptions options;
  options.window.size_x_m = options.window.size_y_m = 1.6;
  const geometry::Pose2 truth{20.46, 14.0, 0.0};
  const auto [scan, estimate] = At(truth, {0.6, 0.0, 0.0});
  MapLocaliser localiser(options, *office_.apriori, {});
  const auto round = localiser.Update(scan, estimate);
  ASSERT_TRUE(round.has_value());
  EXPECT_TRUE(round->accepted);
  EXPECT_TRUE(round->recast);
  EXPECT_GT(round->score, round->first_score + 0.1);
  ExpectNear(round->map_from_body_after, truth, 0.05, 0.5 * kDeg);
  // Without the re-cast the same search is judged on the first score alone.
  options.recast_min_m = 1e9;
  options.recast_min_rad = 1e9;
  MapLocaliser plain(options, *office_.apriori, {});
  const auto first = plain.Update(scan, estimate);
  ASSERT_TRUE(first.has_value());
  EXPECT_FALSE(first->recast);
  EXPECT_NEAR(first->score, round->first_score, 1e-12);
}

// A keyframe the odometry placed along the corridor by its motion prior alone (degenerate) and
// 0.5 m off: the places along the corridor are each judged from where they are and the one the
// door frames pin down is taken. A matched keyframe keeps the odometry along it as before, unless
// the plan's wall ends (the door jambs) see it off.
TEST_F(MapLocaliserTest, AnOdometryKeyframeOnItsPriorIsSearchedAlongTheCorridor) {
  const geometry::Pose2 truth{21.07, 14.0, 0.0};
  auto [scan, estimate] = At(truth, {0.5, 0.0, 0.0});
  // The plan's wall ends off: the jambs of the doors ahead would move the round back by
  // themselves (below).
  MapLocaliserOptions no_ends;
  no_ends.plan_adaptation.ends.enabled = false;
  MapLocaliser matched(no_ends, *office_.apriori, {});
  const auto kept = matched.Update(scan, estimate);
  ASSERT_TRUE(kept.has_value());
  EXPECT_TRUE(kept->accepted);
  EXPECT_TRUE(kept->degenerate);
  EXPECT_FALSE(kept->recast);
  EXPECT_NEAR(kept->map_from_body_after.x_m - truth.x_m, 0.5, 0.05);
  MapLocaliser with_ends({}, *office_.apriori, {});
  const auto held = with_ends.Update(scan, estimate);
  ASSERT_TRUE(held.has_value());
  EXPECT_TRUE(held->ends_corrected);
  EXPECT_NEAR(held->map_from_body_after.x_m - truth.x_m, 0.0, 0.1);
  estimate.status = odometry::MatchStatus::kDegenerate;
  MapLocaliser doubted({}, *office_.apriori, {});
  const auto round = doubted.Update(scan, estimate);
  ASSERT_TRUE(round.has_value());
  EXPECT_TRUE(round->accepted);
  EXPECT_FALSE(round->degenerate);
  EXPECT_TRUE(round->recast);
  EXPECT_GT(round->score, round->first_score + MapLocaliserOptions{}.along_min_drop);
  ExpectNear(round->map_from_body_after, truth, 0.05, 0.5 * kDeg);
  // Without the search along the corridor the odometry is kept as for a matched keyframe.
  MapLocaliserOptions off = no_ends;
  off.along_search_m = 0.0;
  MapLocaliser plain(off, *office_.apriori, {});
  EXPECT_NEAR(plain.Update(scan, estimate)->map_from_body_after.x_m - truth.x_m, 0.5, 0.05);
}

// A keyframe the odometry matched 0.8 m ahead along the corridor (its own match slid): from there
// the plan fits too badly for a round to pass, and the places along the corridor are searched as
// for a keyframe on the prior. Outside the plan (the west wing) the same search finds nothing.
TEST_F(MapLocaliserTest, AFailedRoundInTheCorridorIsSearchedAlongIt) {
  const geometry::Pose2 truth{17.0, 14.0, 0.0};
  auto [scan, estimate] = At(truth, {0.8, 0.0, 0.0});
  estimate.status = odometry::MatchStatus::kMatched;
  MapLocaliser localiser({}, *office_.apriori, {});
  const auto round = localiser.Update(scan, estimate);
  ASSERT_TRUE(round.has_value());
  EXPECT_TRUE(round->accepted);
  EXPECT_FALSE(round->degenerate);
  EXPECT_TRUE(round->recast);
  EXPECT_LT(round->first_score, MapLocaliserOptions{}.min_score);
  ExpectNear(round->map_from_body_after, truth, 0.05, 0.5 * kDeg);
  MapLocaliserOptions off;
  off.along_search_failed = false;
  MapLocaliser plain(off, *office_.apriori, {});
  const auto failed = plain.Update(scan, estimate);
  ASSERT_TRUE(failed.has_value());
  EXPECT_FALSE(failed->accepted);
  EXPECT_TRUE(failed->degenerate);
  const auto [outside_scan, outside_estimate] = At({2.0, 11.0, -90.0 * kDeg});
  MapLocaliser west_wing({}, *office_.apriori, {});
  EXPECT_FALSE(west_wing.Update(outside_scan, outside_estimate)->accepted);
}

// A corridor with door posts every metre and a keyframe the odometry placed 0.5 m along it on its
// prior: the places 1 m apart along it fit the plan equally well, so the search along the
// corridor takes neither (along_search_unique) and the odometry is kept; without the rule the
// best of the equal scores is taken.
MapCorrection RoundBetweenLookAlikePosts(const MapLocaliserOptions& options) {
  std::vector<geometry::Segment2> plan{{{0.0, 0.0}, {40.0, 0.0}}, {{0.0, 2.0}, {40.0, 2.0}}};
  for (int k = 0; k <= 20; ++k) {
    const double x = 10.0 + k;
    plan.push_back({{x, 0.0}, {x, 0.15}});
    plan.push_back({{x, 2.0}, {x, 1.85}});
  }
  const geometry::Pose2 truth{20.3, 1.0, 0.0};
  odometry::OdometryEstimate estimate;
  estimate.stamp_s = 1.0;
  estimate.world_from_body = geometry::Compose(truth, {0.5, 0.0, 0.0});
  estimate.reference_changed = true;
  estimate.status = odometry::MatchStatus::kDegenerate;
  MapLocaliser localiser(options, plan, {});
  return *localiser.Update(VirtualScanner(plan).Scan(truth, testing::OfficeLaser(), 361, 1.0), estimate);
}

TEST(MapLocaliserAlongSearch, TakesNoPlaceAmongLookAlikes) {
  const MapCorrection kept = RoundBetweenLookAlikePosts({});
  EXPECT_TRUE(kept.accepted);
  EXPECT_TRUE(kept.degenerate);
  EXPECT_FALSE(kept.recast);
  EXPECT_NEAR(kept.map_from_body_after.x_m, 20.8, 0.05);  // the odometry along the corridor
  MapLocaliserOptions off;
  off.along_search_unique = false;
  const MapCorrection taken = RoundBetweenLookAlikePosts(off);
  EXPECT_TRUE(taken.accepted);
  EXPECT_TRUE(taken.recast);
  EXPECT_FALSE(taken.degenerate);
  EXPECT_GT(std::abs(taken.map_from_body_after.x_m - 20.8), 0.4);  // moved to one of the two
}

// Walking east along the office corridor at 1 m/s, one scan a second; the odometry is right except
// at `jump_at` (x), where its single scan lies 0.4 m ahead along the corridor (a scan matched near
// its reference keyframe). Returns the error along the corridor of the pose on the plan at every
// scan. Plan rounds run at the first scan and, with `round_at_jump`, at the jumped one.
std::vector<double> MapLocaliserTest::AlongErrors(const MapLocaliserOptions& options, double jump_at,
                                                  bool round_at_jump) {
  MapLocaliser localiser(options, *office_.apriori, {});
  std::vector<double> errors;
  for (double x = 14.46; x < 24.0; x += 1.0) {
    const geometry::Pose2 truth{x, 14.0, 0.0};
    const double jump_m = std::abs(x - jump_at) < 0.1 ? 0.4 : 0.0;
    const bool keyframe = errors.empty() || (round_at_jump && jump_m > 0.0);
    const auto [scan, estimate] = At(truth, {jump_m, 0.0, 0.0}, keyframe);
    localiser.Update(scan, estimate);
    errors.push_back(localiser.map_from_body().x_m - truth.x_m);
  }
  return errors;
}

// Known limit (docs/localisation.md, "Alternatives measured and not adopted"): a single-scan
// jump of the odometry is output as it is.
TEST_F(MapLocaliserTest, ASingleScanJumpOfTheOdometryIsOutput) {
  const std::vector<double> errors = AlongErrors({}, 18.46, /*round_at_jump=*/false);
  ASSERT_EQ(errors.size(), 10u);
  EXPECT_NEAR(errors[4], 0.4, 1e-9);
  EXPECT_NEAR(errors[5], 0.0, 1e-9);
}

// Known limit: a round at the jumped keyframe next to a door (x 20.46: the plan pins the pose down
// along the corridor there) corrects that scan, and the correction carries the jump into
// map_from_odom, so every scan after it is 0.4 m behind (office seed 1 at 3.25 s and 152.75 s).
TEST_F(MapLocaliserTest, ARoundAtAJumpedKeyframeCarriesTheJumpIntoLaterScans) {
  MapLocaliserOptions options;  // a window that reaches the jump (0.4 m beyond the default's)
  options.window.size_x_m = options.window.size_y_m = 1.2;
  const std::vector<double> errors = AlongErrors(options, 20.46, /*round_at_jump=*/true);
  ASSERT_EQ(errors.size(), 10u);
  EXPECT_NEAR(errors[6], 0.0, 0.05);   // the jumped keyframe, corrected
  EXPECT_NEAR(errors[7], -0.4, 0.05);  // the jump carried
}

TEST(MapLocaliserOptions, RejectsBadValues) {
  MapLocaliserOptions options;
  options.min_score = 0.0;
  EXPECT_THROW(MapLocaliser(options, {}, {}), std::invalid_argument);
  options = {};
  options.window.step_xy_m = 0.03;  // not a multiple of the 0.02 m grid
  EXPECT_THROW(MapLocaliser(options, {}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation

namespace pena::localisation {
namespace {

// A 2 m wide, 40 m long corridor, both ends beyond the localiser's 15 m range; with `doors`, a
// 1 m opening every 5 m in both walls with a 0.4 m deep door frame on its far side. (With doors,
// along_drop came out 0.017 like the featureless corridor's: no positive-case test yet.)
std::vector<geometry::Segment2> Corridor(bool doors) {
  std::vector<geometry::Segment2> walls;
  for (const double y : {0.0, 2.0}) {
    if (!doors) {
      walls.push_back({{0.0, y}, {40.0, y}});
      continue;
    }
    const double out = y > 1.0 ? 0.4 : -0.4;
    for (double x = 0.0; x < 40.0; x += 5.0) {
      walls.push_back({{x, y}, {x + 4.0, y}});
      walls.push_back({{x + 5.0, y}, {x + 5.0, y + out}});
    }
  }
  return walls;
}

// The along-corridor error of the odometry after one round, scan taken looking down the corridor.
std::pair<MapCorrection, double> AlongError(bool doors, const MapLocaliserOptions& options = {},
                                            odometry::MatchStatus odometry_status = odometry::MatchStatus::kMatched) {
  const std::vector<geometry::Segment2> walls = Corridor(doors);
  const VirtualScanner scanner(walls);
  MapLocaliser localiser(options, walls, {});
  const geometry::Pose2 truth{20.3, 1.0, 0.0};
  odometry::OdometryEstimate estimate;
  estimate.stamp_s = 1.0;
  estimate.world_from_body = {truth.x_m + 0.2, truth.y_m, 0.0};  // 0.2 m ahead along the corridor
  estimate.reference_changed = true;
  estimate.status = odometry_status;
  const auto round = localiser.Update(scanner.Scan(truth, testing::OfficeLaser(), 361, 1.0), estimate);
  const geometry::Pose2 corrected = localiser.MapFromBody(estimate.world_from_body);
  return {round.value_or(MapCorrection{}), corrected.x_m - truth.x_m};
}

TEST(MapLocaliserAlongDrop, AFeaturelessCorridorKeepsTheOdometryAlongIt) {
  const auto [round, along_error_m] = AlongError(false);
  EXPECT_TRUE(round.accepted);
  EXPECT_LT(round.along_drop, MapLocaliserOptions{}.along_min_drop);
  EXPECT_TRUE(round.degenerate);
  EXPECT_NEAR(along_error_m, 0.2, 0.03);
}

// Where nothing pins the pose down along the corridor, searching along it (the odometry's keyframe
// on its motion prior) finds no place better than another: the odometry is kept.
TEST(MapLocaliserAlongDrop, AFeaturelessCorridorKeepsTheOdometryEvenOnItsPrior) {
  const auto [round, along_error_m] = AlongError(false, {}, odometry::MatchStatus::kDegenerate);
  EXPECT_TRUE(round.accepted);
  EXPECT_TRUE(round.degenerate);
  EXPECT_FALSE(round.recast);
  EXPECT_NEAR(along_error_m, 0.2, 0.03);
}

}  // namespace
}  // namespace pena::localisation
