// The place choice of the reference (odometry::internal::LocalMap with PlaceChoice): keyframes
// are picked from a short pool by where they were taken, not only by how recent they are, so
// that an entity turning back on the spot matches the keyframe it made facing that way before.
#include "pena/odometry/internal/local_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pena/odometry/laser_odometry.hpp"
#include "team_entity.hpp"

namespace pena::odometry::internal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A keyframe at (x, 0) facing heading_deg, taken at stamp_s, with one marker point whose x
// coordinate tells the keyframe apart in the reference.
Keyframe Marked(double x_m, double heading_deg, double stamp_s, double marker) {
  return {geometry::Pose2{x_m, 0.0, heading_deg * kDeg}, {{marker, 100.0}}, stamp_s};
}

bool HasMarker(const scan_matching::Points2& reference, double marker) {
  for (const auto& point : reference) {
    if (std::abs(point.x() - marker) < 1e-9 && std::abs(point.y() - 100.0) < 1e-9) return true;
  }
  return false;
}

// On the spot: keyframes every 15 deg from 0 to 150 deg (markers 0..10), then a turn back.
void TurnOnTheSpot(LocalMap& map) {
  for (int k = 0; k <= 10; ++k) map.Add(Marked(0.0, 15.0 * k, k, static_cast<double>(k)));
}

PlaceChoice Place() {
  PlaceChoice place;
  place.pool_keyframes = 40;
  place.pool_age_s = 60.0;
  place.recent_keyframes = 2;
  place.radius_m = 2.0;
  return place;
}

TEST(PlaceChoice, RecencyKeepsOnlyTheLastKeyframes) {
  LocalMap map(4, 0.12, false);
  TurnOnTheSpot(map);
  const scan_matching::Points2 reference = map.Reference();
  EXPECT_EQ(reference.size(), 4u);
  EXPECT_TRUE(HasMarker(reference, 10.0));
  EXPECT_FALSE(HasMarker(reference, 0.0));
  EXPECT_FALSE(map.ChooseAgain(geometry::Pose2{0.0, 0.0, 0.0}, 11.0));  // no choice to make
  EXPECT_FALSE(map.Covers(geometry::Pose2{0.0, 0.0, 0.0}, 0.5, 15.0 * kDeg));
}

TEST(PlaceChoice, TurningBackChoosesTheKeyframeFacingThatWay) {
  LocalMap map(4, 0.12, false, Place());
  TurnOnTheSpot(map);
  // After the latest keyframe (150 deg): the two latest plus the two nearest in heading.
  scan_matching::Points2 reference = map.Reference();
  EXPECT_EQ(reference.size(), 4u);
  for (double marker : {7.0, 8.0, 9.0, 10.0}) EXPECT_TRUE(HasMarker(reference, marker)) << marker;
  // Turned back to 5 deg: the keyframe made at 0 deg is chosen again (with 15 deg's), the two
  // latest stay; a new keyframe is not needed there.
  const geometry::Pose2 back{0.02, 0.0, 5.0 * kDeg};
  EXPECT_FALSE(map.Covers(back, 0.5, 15.0 * kDeg));
  EXPECT_TRUE(map.ChooseAgain(back, 12.0));
  reference = map.Reference();
  EXPECT_EQ(reference.size(), 4u);
  for (double marker : {0.0, 1.0, 9.0, 10.0}) EXPECT_TRUE(HasMarker(reference, marker)) << marker;
  EXPECT_TRUE(map.Covers(back, 0.5, 15.0 * kDeg));
  EXPECT_FALSE(map.ChooseAgain(back, 12.5));  // already chosen: the matcher is kept
}

TEST(PlaceChoice, OldAndFarKeyframesAreNotChosen) {
  PlaceChoice place = Place();
  place.pool_age_s = 30.0;
  LocalMap map(4, 0.12, false, place);
  TurnOnTheSpot(map);  // stamps 0..10 s
  // 35 s later at 0 deg: keyframes 0..4 are older than 30 s, 5 and 6 are not.
  EXPECT_TRUE(map.ChooseAgain(geometry::Pose2{0.0, 0.0, 0.0}, 35.0));
  scan_matching::Points2 reference = map.Reference();
  for (double marker : {5.0, 6.0, 9.0, 10.0}) EXPECT_TRUE(HasMarker(reference, marker)) << marker;
  // 3 m away nothing but the latest two is near enough.
  map.Add(Marked(3.0, 0.0, 36.0, 11.0));
  reference = map.Reference();
  EXPECT_EQ(reference.size(), 2u);
  EXPECT_TRUE(HasMarker(reference, 10.0));
  EXPECT_TRUE(HasMarker(reference, 11.0));
}

TEST(PlaceChoice, ThePoolIsBounded) {
  PlaceChoice place = Place();
  place.pool_keyframes = 6;
  LocalMap map(4, 0.12, false, place);
  TurnOnTheSpot(map);  // only keyframes 5..10 are kept
  EXPECT_TRUE(map.ChooseAgain(geometry::Pose2{0.0, 0.0, 0.0}, 11.0));
  const scan_matching::Points2 reference = map.Reference();
  EXPECT_FALSE(HasMarker(reference, 0.0));
  for (double marker : {5.0, 6.0, 9.0, 10.0}) EXPECT_TRUE(HasMarker(reference, marker)) << marker;
}

// The fill on demand (local_map_place_fill_below_score, local_map_place_fill_frozen_scans):
// FilledReference offers the filled reference without changing the choice, FillFreeSlots takes
// it until the next keyframe chooses again.
TEST(PlaceChoice, TheFillOnDemandLastsUntilTheNextChoice) {
  LocalMap map(4, 0.12, false, Place());
  for (int k = 0; k <= 10; ++k) map.Add(Marked(1.5 * k, 0.0, k, static_cast<double>(k)));
  const std::optional<scan_matching::Points2> filled = map.FilledReference();
  ASSERT_TRUE(filled.has_value());
  EXPECT_EQ(filled->size(), 4u);
  for (double marker : {7.0, 8.0, 9.0, 10.0}) EXPECT_TRUE(HasMarker(*filled, marker)) << marker;
  EXPECT_EQ(map.Reference().size(), 2u);  // offered, not taken
  EXPECT_TRUE(map.FillFreeSlots());
  EXPECT_EQ(map.Reference().size(), 4u);
  EXPECT_FALSE(map.FillFreeSlots());  // already full
  EXPECT_FALSE(map.FilledReference().has_value());
  map.Add(Marked(16.5, 0.0, 11.0, 11.0));  // the next keyframe chooses by place again
  EXPECT_EQ(map.Reference().size(), 2u);
}

// Without the place choice there is nothing to fill.
TEST(PlaceChoice, RecencyHasNoFillOnDemand) {
  LocalMap map(4, 0.12, false);
  for (int k = 0; k <= 10; ++k) map.Add(Marked(1.5 * k, 0.0, k, static_cast<double>(k)));
  EXPECT_FALSE(map.FilledReference().has_value());
  EXPECT_FALSE(map.FillFreeSlots());
}

struct RobotRun {
  geometry::Pose2 end;
  long keyframes = 0;
};

RobotRun ReplayRobot(const LaserOdometryOptions& options) {
  const sim::EntityRecording& robot = testing::TeamEntity("robot1");
  LaserOdometry odometry(options, robot.kind, robot.truth.front().world_from_body, robot.start_s);
  RobotRun run;
  for (const auto& record : robot.records) {
    if (auto estimate = odometry.Add(record)) run.end = estimate->world_from_body;
  }
  run.keyframes = odometry.counts().keyframes;
  return run;
}

// The whole chain with the place choice on the simulated team robot (level laser, wheel
// odometry): it ends where the truth does.
TEST(PlaceChoice, TeamRobotEndsOnTheTruth) {
  LaserOdometryOptions place;
  place.local_map_pool_keyframes = 40;
  const RobotRun chosen = ReplayRobot(place);
  const geometry::Pose2& truth = testing::TeamEntity("robot1").truth.back().world_from_body;
  EXPECT_LT(std::hypot(truth.x_m - chosen.end.x_m, truth.y_m - chosen.end.y_m), 0.5);
  EXPECT_LT(std::abs(geometry::NormalizeAngle(truth.theta_rad - chosen.end.theta_rad)), 2.0 * kDeg);
}

std::vector<geometry::Pose2> Poses(const std::string& entity, const LaserOdometryOptions& options) {
  const sim::EntityRecording& recording = testing::TeamEntity(entity);
  std::vector<geometry::Pose2> poses;
  for (const auto& estimate : testing::ReplayRecords(recording, recording.records, options)) {
    poses.push_back(estimate.world_from_body);
  }
  return poses;
}

bool Same(const std::vector<geometry::Pose2>& a, const std::vector<geometry::Pose2>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].x_m != b[i].x_m || a[i].y_m != b[i].y_m || a[i].theta_rad != b[i].theta_rad) {
      return false;
    }
  }
  return true;
}

// The defaults: a robot's reference is chosen by place from a pool of 40 (chosen on the
// Freiburg logs), a person's by recency.
TEST(PlaceChoice, RobotsChooseByPlaceAndPeopleByRecencyByDefault) {
  LaserOdometryOptions place;
  place.local_map_pool_keyframes = 40;
  LaserOdometryOptions recency;
  recency.local_map_pool_keyframes = 0;
  const std::vector<geometry::Pose2> robot = Poses("robot1", {});
  EXPECT_TRUE(Same(robot, Poses("robot1", place)));
  EXPECT_FALSE(Same(robot, Poses("robot1", recency)));
  const std::vector<geometry::Pose2> person = Poses("ff1", {});
  EXPECT_TRUE(Same(person, Poses("ff1", recency)));
  EXPECT_FALSE(Same(person, Poses("ff1", place)));
}

// local_map_place_fill_below_score on the whole chain (the team robot, a bar it does not always
// reach): the runs agree up to the first match below the bar whose reference has free slots;
// there the match against the filled reference scored higher and was kept.
TEST(PlaceChoice, APoorMatchIsSearchedAgainAgainstTheFilledReference) {
  const sim::EntityRecording& robot = testing::TeamEntity("robot1");
  LaserOdometryOptions refill;
  refill.local_map_place_fill_below_score = 0.95;
  LaserOdometryOptions place_only;
  place_only.local_map_place_fill_below_score = 0.0;
  const std::vector<OdometryEstimate> plain =
      testing::ReplayRecords(robot, robot.records, place_only);
  const std::vector<OdometryEstimate> again =
      testing::ReplayRecords(robot, robot.records, refill);
  ASSERT_EQ(plain.size(), again.size());
  std::size_t first = 0;
  while (first < plain.size() && plain[first].score == again[first].score) ++first;
  ASSERT_LT(first, plain.size()) << "the rule never acted";
  EXPECT_LT(plain[first].score, refill.local_map_place_fill_below_score);
  EXPECT_GT(again[first].score, plain[first].score);
  const geometry::Pose2& truth = robot.truth.back().world_from_body;
  const geometry::Pose2& end = again.back().world_from_body;
  EXPECT_LT(std::hypot(truth.x_m - end.x_m, truth.y_m - end.y_m), 0.5);
  EXPECT_LT(std::abs(geometry::NormalizeAngle(truth.theta_rad - end.theta_rad)), 2.0 * kDeg);
  // On by default, at keyframe_min_score (chosen on the Freiburg start-frame means).
  EXPECT_EQ(LaserOdometryOptions{}.local_map_place_fill_below_score,
            LaserOdometryOptions{}.keyframe_min_score);
}

TEST(PlaceChoice, OptionsAreChecked) {
  const auto throws = [](const LaserOdometryOptions& options) {
    EXPECT_THROW(LaserOdometry(options, sensors::EntityKind::kRobot, {}, 0.0),
                 std::invalid_argument);
  };
  LaserOdometryOptions options;
  options.local_map_pool_keyframes = -2;
  throws(options);
  options = {};
  options.local_map_recent_keyframes = options.local_map_keyframes + 1;
  throws(options);
  options = {};
  options.local_map_place_radius_m = 0.0;
  throws(options);
  options = {};
  options.local_map_pool_age_s = 0.0;
  throws(options);
  options = {};
  options.local_map_place_fill_below_score = 1.5;
  throws(options);
  options = {};
  options.local_map_place_fill_below_score = -0.1;
  throws(options);
  options = {};
  options.local_map_place_fill_frozen_scans = -1;
  throws(options);
}

}  // namespace
}  // namespace pena::odometry::internal
