// Lost and found (LostAndFound): judged lost from the plan's evidence, found again by a search in
// a growing region and then over the whole plan, on a synthetic floor with perfect scans.
#include "pena/localisation/lost_and_found.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "office_plan.hpp"
#include "pena/localisation/global_localiser.hpp"
#include "pena/localisation/virtual_scanner.hpp"

namespace pena::localisation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A 20 m x 12 m floor of rooms of different sizes with doors, a pillar and a few stubs, so that no
// two places look alike.
std::vector<geometry::Segment2> Floor() {
  return {{{0, 0}, {20, 0}},    {{20, 0}, {20, 12}},  {{20, 12}, {0, 12}},   {{0, 12}, {0, 0}},
          {{6, 0}, {6, 5}},     {{6, 7}, {6, 12}},    {{13, 0}, {13, 3}},    {{13, 4.5}, {13, 12}},
          {{13, 8}, {17, 8}},   {{18.2, 8}, {20, 8}}, {{0, 8}, {3, 8}},      {{9, 9}, {10, 9}},
          {{10, 9}, {10, 10}},  {{10, 10}, {9, 10}},  {{9, 10}, {9, 9}},     {{16, 2}, {18, 2}},
          {{16, 2}, {16, 3.5}}, {{2, 3}, {3.5, 3}},   {{8.5, 3.5}, {11, 3.5}}};
}

// The walk: a circle of 1.2 m radius in the north-east room, one keyframe every 0.48 m, facing
// along it. The odometry is perfect in its own frame (the odometry frame is the plan's).
geometry::Pose2 Walk(int k) {
  const double a = 0.4 * k;
  return {16.5 + 1.2 * std::cos(a), 10.0 + 1.2 * std::sin(a), geometry::NormalizeAngle(a + std::numbers::pi / 2)};
}

// Believed in the south-west room, turned by 30 deg: the walk's centre put at (4, 4) on the plan.
geometry::Pose2 FarKidnap() {
  return geometry::Compose({4.0, 4.0, 30.0 * kDeg}, {-16.5, -10.0, 0.0});
}

MapCorrection FailedRound() {
  MapCorrection round;
  round.accepted = false;
  return round;
}

struct Outcome {
  int became_lost_at = -1;
  int found_at = -1;
  std::optional<geometry::Pose2> found;
  std::vector<double> searched_radii_m;
};

// Runs `keyframes` keyframes on which every plan round fails (the chain believes the entity at
// `map_from_odom` * odometry pose, the scans are taken where it truly is).
Outcome RunKidnapped(const LostAndFoundOptions& options, const geometry::Pose2& map_from_odom, int keyframes,
                     double sigma_m = 0.0) {
  const std::vector<geometry::Segment2> plan = Floor();
  const GlobalLocaliser global(plan);
  const VirtualScanner walls(plan);
  LostAndFound watch(options, global);
  Outcome outcome;
  for (int k = 0; k < keyframes; ++k) {
    const geometry::Pose2 truth = Walk(k);
    const sensors::LaserScan scan = walls.Scan(truth, testing::OfficeLaser(), 361, 1.0 + k);
    const geometry::Pose2 believed = geometry::Compose(map_from_odom, truth);
    const LostStep step = watch.Update(scan, FailedRound(), truth, believed, sigma_m);
    if (step.became_lost) outcome.became_lost_at = k;
    if (step.searched_radius_m) outcome.searched_radii_m.push_back(*step.searched_radius_m);
    if (step.found) {
      outcome.found_at = k;
      outcome.found = step.found;
      // Where it was found, relative to where it truly is.
      outcome.found = geometry::Between(truth, *step.found);
      break;
    }
  }
  return outcome;
}

TEST(LostAndFound, KidnappedFarAcrossTheFloorIsFoundAsTheRegionGrowsToTheWholePlan) {
  const Outcome o = RunKidnapped({}, FarKidnap(), 60);
  ASSERT_EQ(o.became_lost_at, 2);  // lost_after_rounds failed rounds where the plan explains little
  ASSERT_TRUE(o.found.has_value()) << "not found in 60 keyframes";
  EXPECT_LT(std::hypot(o.found->x_m, o.found->y_m), 0.1);
  EXPECT_LT(std::abs(o.found->theta_rad), 1.0 * kDeg);
  // The region around where it was believed, doubling search by search, then the whole plan (0).
  ASSERT_GE(o.searched_radii_m.size(), 3u);
  EXPECT_DOUBLE_EQ(o.searched_radii_m.front(), 3.0);
  for (std::size_t i = 1; i + 1 < o.searched_radii_m.size(); ++i) {
    EXPECT_DOUBLE_EQ(o.searched_radii_m[i], 2.0 * o.searched_radii_m[i - 1]);
  }
  EXPECT_DOUBLE_EQ(o.searched_radii_m.back(), 0.0);
}

TEST(LostAndFound, ARegionCoveringThePlanIsAWholePlanSearch) {
  LostAndFoundOptions wide;
  wide.region_start_m = 50.0;
  const Outcome o = RunKidnapped(wide, FarKidnap(), 60);
  ASSERT_TRUE(o.found.has_value());
  EXPECT_LT(std::hypot(o.found->x_m, o.found->y_m), 0.1);
  ASSERT_FALSE(o.searched_radii_m.empty());
  EXPECT_DOUBLE_EQ(o.searched_radii_m.front(), 0.0);  // 0: over the whole plan
}

TEST(LostAndFound, KidnappedNearbyIsFoundInTheFirstRegion) {
  const Outcome o = RunKidnapped({}, {1.2, -0.9, 0.0}, 30);  // 1.5 m off, inside the first region
  ASSERT_GE(o.became_lost_at, 0);
  ASSERT_TRUE(o.found.has_value());
  EXPECT_LT(std::hypot(o.found->x_m, o.found->y_m), 0.1);
  EXPECT_LT(std::abs(o.found->theta_rad), 1.0 * kDeg);
  // Found in the first region, by the search and the confirming keyframes after it.
  ASSERT_FALSE(o.searched_radii_m.empty());
  EXPECT_DOUBLE_EQ(o.searched_radii_m.front(), 3.0);
  EXPECT_LE(o.found_at, o.became_lost_at + 4) << "lost at " << o.became_lost_at << ", searches "
                                               << o.searched_radii_m.size();
}

TEST(LostAndFound, BelievedOutsideThePlansBoxIsNotLost) {
  // Believed 25 m east of the floor: off the plan, where it does not have to explain the scan.
  const Outcome o = RunKidnapped({}, {25.0, 0.0, 0.0}, 20);
  EXPECT_EQ(o.became_lost_at, -1);
}

TEST(LostAndFound, FailedRoundsWhereThePlanExplainsTheScanAreNotLost) {
  const Outcome o = RunKidnapped({}, {}, 20);  // believed where it is; only the rounds fail
  EXPECT_EQ(o.became_lost_at, -1);
  EXPECT_FALSE(o.found.has_value());
}

TEST(LostAndFound, OdometrySpreadPastTheBoundOnAFailedRoundIsLost) {
  const Outcome o = RunKidnapped({}, {}, 3, 2.5);  // lost_sigma_m 2
  EXPECT_EQ(o.became_lost_at, 0);
  EXPECT_FALSE(o.found.has_value());  // where it is is no better place than where it is believed
}

TEST(LostAndFound, DisabledNeverJudgesLost) {
  LostAndFoundOptions off;
  off.enabled = false;
  const Outcome o = RunKidnapped(off, FarKidnap(), 20);
  EXPECT_EQ(o.became_lost_at, -1);
}

TEST(LostAndFound, RefusesBadOptionsNamingTheField) {
  const GlobalLocaliser global(Floor());
  LostAndFoundOptions bad;
  bad.region_growth = 0.5;
  try {
    LostAndFound watch(bad, global);
    FAIL() << "accepted region_growth 0.5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lost_and_found.region_growth must be >= 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pena::localisation
