#include "pena/localisation/localisation_chain.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "office_plan.hpp"
#include "pena/dead_reckoning/human_dead_reckoning.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::localisation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The simulated office mission (seed 1), as bench_global_localisation runs it.
const sim::SimulationResult& OfficeMission() {
  static const sim::SimulationResult mission = [] {
    sim::SimulationOptions options;
    options.seed = 1;
    return sim::Simulator(options).Run(testing::OfficeScenario());
  }();
  return mission;
}

// Index of the ground truth record right before the first scan at or after `stamp_s`.
std::size_t StartAt(const sim::EntityRecording& entity, double stamp_s) {
  for (std::size_t i = 0; i + 1 < entity.records.size(); ++i) {
    const auto* truth = std::get_if<sensors::GroundTruth>(&entity.records[i]);
    if (truth && truth->stamp_s >= stamp_s && std::holds_alternative<sensors::LaserScan>(entity.records[i + 1])) return i;
  }
  throw std::runtime_error("no scan after the stamp");
}

LocalisationChainOptions UnknownStart(double compass_tolerance_rad) {
  LocalisationChainOptions options;
  options.global_start = true;
  options.compass_tolerance_rad = compass_tolerance_rad;
  return options;
}

// Runs the log from `start` with an unknown start until the chain anchors (at most `max_scans`);
// returns the anchored pose and the true pose then.
struct Anchor {
  std::optional<geometry::Pose2> estimate;
  geometry::Pose2 truth;
};
Anchor RunUntilAnchored(const LocalisationChainOptions& options, sensors::EntityKind kind, std::size_t start,
                        int max_scans) {
  const sim::EntityRecording& entity = OfficeMission().entities.front();
  const sim::Scenario office = testing::OfficeScenario();
  const auto& first = std::get<sensors::GroundTruth>(entity.records[start]);
  LocalisationChain chain(options, kind, *office.apriori, geometry::Pose2{}, first.stamp_s);
  Anchor anchor;
  int scans = 0;
  for (std::size_t i = start; i < entity.records.size() && scans < max_scans; ++i) {
    if (const auto* t = std::get_if<sensors::GroundTruth>(&entity.records[i])) {
      anchor.truth = t->world_from_body;
      continue;
    }
    const auto pose = chain.Add(entity.records[i]);
    if (!pose) continue;
    ++scans;
    if (pose->anchored) {
      anchor.estimate = pose->map_from_body;
      break;
    }
  }
  return anchor;
}

// The unknown phase's odometry frame starts at the compass heading, so the odometry heading is
// the mission frame's (walking west: 180 deg); without the compass tolerance it starts at 0.
TEST(LocalisationChain, UnknownStartWithACompassStartsAtTheCompassHeading) {
  const sim::EntityRecording& entity = OfficeMission().entities.front();
  const sim::Scenario office = testing::OfficeScenario();
  const std::size_t start = StartAt(entity, 3.0);
  const auto& first = std::get<sensors::GroundTruth>(entity.records[start]);
  for (const double tolerance_rad : {0.0, 30.0 * kDeg}) {
    LocalisationChain chain(UnknownStart(tolerance_rad), entity.kind, *office.apriori, geometry::Pose2{}, first.stamp_s);
    std::optional<LocalisedPose> pose;
    for (std::size_t i = start + 1; i < entity.records.size() && !pose; ++i) pose = chain.Add(entity.records[i]);
    ASSERT_TRUE(pose.has_value());
    const double expected_rad = tolerance_rad > 0.0 ? first.world_from_body.theta_rad : 0.0;
    EXPECT_NEAR(geometry::NormalizeAngle(pose->odometry.world_from_body.theta_rad - expected_rad), 0.0, 6.0 * kDeg)
        << "tolerance " << tolerance_rad;
  }
}

// A robot has no compass: the tolerance changes nothing (same estimates scan by scan).
TEST(LocalisationChain, RobotWithoutCompassIsUnchangedByTheCompassTolerance) {
  const sim::EntityRecording& entity = OfficeMission().entities.front();
  const sim::Scenario office = testing::OfficeScenario();
  const std::size_t start = StartAt(entity, 3.0);
  const double stamp_s = std::get<sensors::GroundTruth>(entity.records[start]).stamp_s;
  LocalisationChain without(UnknownStart(0.0), sensors::EntityKind::kRobot, *office.apriori, {}, stamp_s);
  LocalisationChain with(UnknownStart(30.0 * kDeg), sensors::EntityKind::kRobot, *office.apriori, {}, stamp_s);
  int scans = 0;
  for (std::size_t i = start + 1; i < entity.records.size() && scans < 12; ++i) {
    const auto a = without.Add(entity.records[i]);
    const auto b = with.Add(entity.records[i]);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) continue;
    ++scans;
    EXPECT_EQ(a->map_from_body.x_m, b->map_from_body.x_m);
    EXPECT_EQ(a->map_from_body.theta_rad, b->map_from_body.theta_rad);
    EXPECT_EQ(a->global.has_value(), b->global.has_value());
    if (a->global && b->global) {
      EXPECT_EQ(a->global->hypotheses.size(), b->global->hypotheses.size());
    }
  }
  EXPECT_EQ(scans, 12);
}

// The walk from the entrance west along the corridor anchors on the true pose with the compass
// start (a plain corridor start: the bound must not lose what every heading finds). From 2 s:
// a start at 3 s walks into a 2 s stand at x 36.9 and anchors on the look-alike 6 m along in
// front of the archive (as some of bench_global_localisation's misses do).
TEST(LocalisationChain, CompassStartAnchorsTheWalkFromTheEntrance) {
  const sim::EntityRecording& entity = OfficeMission().entities.front();
  const Anchor anchor = RunUntilAnchored(UnknownStart(30.0 * kDeg), entity.kind, StartAt(entity, 2.0), 400);
  ASSERT_TRUE(anchor.estimate.has_value());
  EXPECT_NEAR(anchor.estimate->x_m, anchor.truth.x_m, 0.3);
  EXPECT_NEAR(anchor.estimate->y_m, anchor.truth.y_m, 0.3);
  EXPECT_NEAR(geometry::NormalizeAngle(anchor.estimate->theta_rad - anchor.truth.theta_rad), 0.0, 3.0 * kDeg);
}

// Walking south down the passage at x 22 into the annex the plan lacks (office seed 1 from
// 40.25 s, bench_global_localisation's start #89): the true place agrees with nothing there, and a
// whole-plan search finds the north-east room (x 34-42, y 15-22), which looks like the annex room
// the walker is in. Its evidence on the keyframes before it was found is the odometry's replay.
// Followed over 2 keyframes of its own it would be decided, 25 m off; over min_keyframes (6, the
// default) it is refuted first, and the walk is anchored right once back in the corridor.
TEST(LocalisationChain, AWalkIntoTheAnnexIsNotDecidedOnTheNorthEastRoom) {
  const sim::EntityRecording& entity = OfficeMission().entities.front();
  const std::size_t start = StartAt(entity, 40.25);
  LocalisationChainOptions options = UnknownStart(30.0 * kDeg);
  const Anchor anchor = RunUntilAnchored(options, entity.kind, start, 400);
  ASSERT_TRUE(anchor.estimate.has_value());
  EXPECT_NEAR(anchor.estimate->x_m, anchor.truth.x_m, 0.3);
  EXPECT_NEAR(anchor.estimate->y_m, anchor.truth.y_m, 0.3);
  EXPECT_NEAR(geometry::NormalizeAngle(anchor.estimate->theta_rad - anchor.truth.theta_rad), 0.0, 3.0 * kDeg);
  options.tracker.min_followed_keyframes = 2;
  const Anchor early = RunUntilAnchored(options, entity.kind, start, 400);
  ASSERT_TRUE(early.estimate.has_value());
  EXPECT_GT(std::hypot(early.estimate->x_m - early.truth.x_m, early.estimate->y_m - early.truth.y_m), 10.0);
}

// Office seed 2 from its known start, as `pena localise` reads it (strides spread over their
// scans), until 104 s: the RMS position error while it walks back into the plan up the south
// passage at x 22 (96-103 s; single scans jump with the odometry, hence not the largest). At 95.75 s, after 25 s in the annex on an odometry within 0.06 m of
// the truth, a round's best grid pose lay on the edge of the grown window (3.2 m) and its
// refinement finished 1.66 m up the passage on a look-alike (score 0.94, pinned).
double ErrorReenteringUpTheSouthPassageM(bool require_interior) {
  static const sim::SimulationResult mission = [] {
    sim::SimulationOptions options;
    options.seed = 2;
    return sim::Simulator(options).Run(testing::OfficeScenario());
  }();
  const sim::EntityRecording& entity = mission.entities.front();
  const sim::Scenario office = testing::OfficeScenario();
  // The known start: the ground truth before the first scan, as `pena localise` takes it.
  const auto first = std::find_if(entity.records.begin(), entity.records.end(), [](const sensors::SensorRecord& r) {
    return std::holds_alternative<sensors::GroundTruth>(r);
  });
  const geometry::Pose2 start = std::get<sensors::GroundTruth>(*first).world_from_body;
  LocalisationChainOptions options;
  options.map.require_interior = require_interior;
  LocalisationChain chain(options, entity.kind, *office.apriori, start, sensors::StampOf(entity.records.front()));
  const std::vector<sensors::SensorRecord> records =
      dead_reckoning::SpreadStrides(entity.records, dead_reckoning::SpreadOptionsOf(options.odometry.dead_reckoning));
  geometry::Pose2 truth = start;
  double sum_squared_m2 = 0.0;
  int scans = 0;
  for (const sensors::SensorRecord& record : records) {
    if (const auto* t = std::get_if<sensors::GroundTruth>(&record)) {
      truth = t->world_from_body;
      continue;
    }
    const auto pose = chain.Add(record);
    if (!pose) continue;
    if (pose->stamp_s > 104.0) break;
    if (pose->stamp_s < 96.0 || pose->stamp_s > 103.0) continue;
    sum_squared_m2 += std::pow(pose->map_from_body.x_m - truth.x_m, 2) + std::pow(pose->map_from_body.y_m - truth.y_m, 2);
    ++scans;
  }
  return scans > 0 ? std::sqrt(sum_squared_m2 / scans) : 1e9;
}

TEST(LocalisationChain, AReentryIsNotTakenOnALookAlikeFoundBeyondTheWindow) {
  EXPECT_LT(ErrorReenteringUpTheSouthPassageM(true), 0.15);
  EXPECT_GT(ErrorReenteringUpTheSouthPassageM(false), 0.6);  // the look-alike, as before the rule
}

// Runs the log from `start` with the chain started at `offset` from the true start pose (body
// frame) for `scans` scans; returns the last estimate, the true pose then and whether a round
// reported the entity relocalised.
struct OffStart {
  geometry::Pose2 estimate;
  geometry::Pose2 truth;
  bool relocalised = false;
  double sum_squared_m2 = 0.0;  // position error from the relocalisation on
  int scans_since_relocalised = 0;
  double RmsSinceRelocalisedM() const {
    return scans_since_relocalised > 0 ? std::sqrt(sum_squared_m2 / scans_since_relocalised) : 1e9;
  }
};
OffStart RunFromWrongStart(int relocalise_after_rounds, bool lost_and_found, const geometry::Pose2& offset,
                           double start_stamp_s, int scans) {
  const sim::EntityRecording& entity = OfficeMission().entities.front();
  const sim::Scenario office = testing::OfficeScenario();
  const std::size_t start = StartAt(entity, start_stamp_s);
  const auto& first = std::get<sensors::GroundTruth>(entity.records[start]);
  LocalisationChainOptions options;
  options.relocalise_after_rounds = relocalise_after_rounds;
  options.lost.enabled = lost_and_found;
  LocalisationChain chain(options, entity.kind, *office.apriori, geometry::Compose(first.world_from_body, offset),
                          first.stamp_s);
  OffStart out;
  for (std::size_t i = start + 1; i < entity.records.size() && scans > 0; ++i) {
    if (const auto* t = std::get_if<sensors::GroundTruth>(&entity.records[i])) {
      out.truth = t->world_from_body;
      continue;
    }
    const auto pose = chain.Add(entity.records[i]);
    if (!pose) continue;
    --scans;
    out.estimate = pose->map_from_body;
    out.relocalised = out.relocalised || pose->status == MapStatus::kRelocalised;
    if (out.relocalised) {
      const double dx = out.estimate.x_m - out.truth.x_m;
      const double dy = out.estimate.y_m - out.truth.y_m;
      out.sum_squared_m2 += dx * dx + dy * dy;
      ++out.scans_since_relocalised;
    }
  }
  return out;
}

// An entity put 3 m off across the mapped corridor and 30 deg off in heading is beyond the plan
// window (3.2 m x 20 deg at most): the plan rounds fail for good. With relocalisation the whole
// plan is searched after a few lost rounds and the walk east along the main corridor (office
// seed 1 from 152 s) finds it again, and keeps it: judged over every scan from the relocalisation
// to the end, not at the last one alone (along the east end of the corridor, where the plan's
// wall is drawn 0.3 m off, single scans are 0.2-0.6 m ahead with or without the pace check).
TEST(LocalisationChain, ALostEntityInAMappedCorridorIsRelocalised) {
  const geometry::Pose2 offset{0.0, 3.0, 30.0 * kDeg};
  const OffStart lost = RunFromWrongStart(0, false, offset, 152.0, 150);
  EXPECT_GT(std::hypot(lost.estimate.x_m - lost.truth.x_m, lost.estimate.y_m - lost.truth.y_m), 1.0);
  EXPECT_FALSE(lost.relocalised);
  const OffStart found = RunFromWrongStart(3, false, offset, 152.0, 150);
  EXPECT_TRUE(found.relocalised);
  EXPECT_GT(found.scans_since_relocalised, 50);
  EXPECT_LT(found.RmsSinceRelocalisedM(), 0.3);
  EXPECT_NEAR(found.estimate.x_m, found.truth.x_m, 0.6);
  EXPECT_NEAR(found.estimate.y_m, found.truth.y_m, 0.3);
  EXPECT_NEAR(geometry::NormalizeAngle(found.estimate.theta_rad - found.truth.theta_rad), 0.0, 3.0 * kDeg);
}

// The same entity with the chain's defaults: judged lost from the plan's evidence (rounds failing
// where the plan explains little of the scan), searched for around where it was thought to be and
// found again (LostAndFoundOptions), with no compass and no relocalisation option.
TEST(LocalisationChain, AKidnappedEntityInAMappedCorridorIsFoundByDefault) {
  const OffStart found = RunFromWrongStart(0, true, {0.0, 3.0, 30.0 * kDeg}, 152.0, 150);
  EXPECT_TRUE(found.relocalised);
  EXPECT_GT(found.scans_since_relocalised, 50);
  EXPECT_LT(found.RmsSinceRelocalisedM(), 0.3);
  EXPECT_NEAR(found.estimate.x_m, found.truth.x_m, 0.6);
  EXPECT_NEAR(found.estimate.y_m, found.truth.y_m, 0.3);
  EXPECT_NEAR(geometry::NormalizeAngle(found.estimate.theta_rad - found.truth.theta_rad), 0.0, 3.0 * kDeg);
}

TEST(LocalisationChainOptions, RejectsBadValues) {
  const sim::Scenario office = testing::OfficeScenario();
  LocalisationChainOptions options = UnknownStart(-0.1);
  EXPECT_THROW(LocalisationChain(options, sensors::EntityKind::kHuman, *office.apriori, {}, 0.0),
               std::invalid_argument);
  options = UnknownStart(0.5);
  options.compass_wait_s = -1.0;
  EXPECT_THROW(LocalisationChain(options, sensors::EntityKind::kHuman, *office.apriori, {}, 0.0),
               std::invalid_argument);
  options = LocalisationChainOptions{};
  options.relocalise_after_rounds = -1;
  EXPECT_THROW(LocalisationChain(options, sensors::EntityKind::kHuman, *office.apriori, {}, 0.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace pena::localisation
