// The per-entity chain on simulated missions (ground truth known) and on broken input.
#include "pena/odometry/laser_odometry.hpp"
#include "expect_refused.hpp"
#include "team_entity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::odometry {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The team scenario's robot (level laser, wheel odometry) and its first firefighter.
const sim::EntityRecording& Entity(const std::string& id) { return testing::TeamEntity(id); }

struct Replayed {
  std::vector<OdometryEstimate> estimates;
  OdometryCounts counts;
};

Replayed Replay(const sim::EntityRecording& entity, const LaserOdometryOptions& options = {}) {
  const sensors::GroundTruth& start = entity.truth.front();
  LaserOdometry odometry(options, entity.kind, start.world_from_body, entity.start_s);
  Replayed run;
  for (const auto& record : entity.records) {
    if (auto estimate = odometry.Add(record)) run.estimates.push_back(*estimate);
  }
  run.counts = odometry.counts();
  return run;
}

double FinalErrorM(const sim::EntityRecording& entity, const Replayed& run) {
  const geometry::Pose2& truth = entity.truth.back().world_from_body;
  const geometry::Pose2& estimate = run.estimates.back().world_from_body;
  return std::hypot(truth.x_m - estimate.x_m, truth.y_m - estimate.y_m);
}

TEST(LaserOdometry, RobotWithLevelLaserEndsWithinHalfAPercent) {
  const auto& robot = Entity("robot1");
  const Replayed matched = Replay(robot);
  LaserOdometryOptions odometry_only;
  odometry_only.match_scans = false;
  const Replayed unmatched = Replay(robot, odometry_only);
  ASSERT_EQ(matched.estimates.size(), robot.truth.size());
  EXPECT_EQ(matched.counts.failed, 0);
  // 79 m driven: scan matching removes the wheel odometry's scale error and slip.
  EXPECT_LT(FinalErrorM(robot, matched), 0.4);
  EXPECT_LT(FinalErrorM(robot, matched), 0.2 * FinalErrorM(robot, unmatched));
}

TEST(LaserOdometry, OnePoseAtEveryScanStamp) {
  const auto& firefighter = Entity("ff1");
  const Replayed run = Replay(firefighter);
  ASSERT_EQ(run.estimates.size(), firefighter.truth.size());
  for (std::size_t i = 0; i < run.estimates.size(); ++i) {
    EXPECT_EQ(run.estimates[i].stamp_s, firefighter.truth[i].stamp_s);
  }
  EXPECT_GT(run.counts.keyframes, 10);
}

// A stream with every fault the issue lists, in between good scans: the chain reports each and
// carries on from dead reckoning; it never throws.
TEST(LaserOdometry, CarriesOnThroughBadInput) {
  const auto& firefighter = Entity("ff1");
  LaserOdometry odometry({}, firefighter.kind, firefighter.truth.front().world_from_body,
                         firefighter.start_s);
  std::vector<MatchStatus> statuses;
  int scans = 0;
  bool long_stride_sent = false;
  for (const auto& record : firefighter.records) {
    sensors::SensorRecord fed = record;
    if (auto* scan = std::get_if<sensors::LaserScan>(&fed)) {
      ++scans;
      if (scans == 40) scan->ranges_m.clear();                                        // empty
      if (scans == 41) std::fill(scan->ranges_m.begin(), scan->ranges_m.end(),
                                 sensors::LaserScan::kNoReturn);                     // all no-returns
      if (scans == 42) {
        for (std::size_t i = 0; i < scan->ranges_m.size(); i += 3) {
          scan->ranges_m[i] = std::numeric_limits<float>::quiet_NaN();               // NaNs
        }
      }
    }
    if (auto* stride = std::get_if<sensors::StrideSample>(&fed); stride && scans >= 50 && !long_stride_sent) {
      stride->length_m = 40.0;                                                        // 40 m stride
      long_stride_sent = true;
    }
    if (std::holds_alternative<sensors::GyroSample>(fed) && scans >= 60 && scans < 80) continue;  // 5 s gap
    std::optional<OdometryEstimate> estimate;
    ASSERT_NO_THROW(estimate = odometry.Add(fed));
    if (estimate) statuses.push_back(estimate->status);
  }
  ASSERT_EQ(statuses.size(), firefighter.truth.size());
  EXPECT_EQ(statuses[39], MatchStatus::kNoPoints);
  EXPECT_EQ(statuses[40], MatchStatus::kNoPoints);
  EXPECT_NE(statuses[41], MatchStatus::kNoPoints);  // two thirds of the beams still match
  EXPECT_GE(odometry.dead_reckoning_counts().strides_rejected, 1u);
  EXPECT_GE(odometry.dead_reckoning_counts().gyro_gaps, 1u);
  EXPECT_EQ(odometry.counts().no_points, 2);
}

// One entity walking or driving from x 0 to end_x along a 2 m wide, 200 m long corridor (its ends
// beyond the laser's range).
sim::EntityRecording CorridorRun(const std::string& kind, double speed_m_s, double end_x_m,
                                 std::uint64_t seed = 1) {
  const std::string id = kind == "robot" ? "robot1" : "ff1";
  const sim::Scenario scenario = sim::ParseScenario(
      "pena-scenario 1\nname corridor\nwall -100 0 100 0\nwall -100 2 100 2\nentity " + id + " " +
          kind + " 0 1 0 speed=" + std::to_string(speed_m_s) + "\nwaypoint " + id + " " +
          std::to_string(end_x_m) + " 1\n",
      "test:corridor");
  sim::SimulationOptions options;
  options.seed = seed;
  return sim::Simulator{options}.Run(scenario).entities.front();
}

// A straight featureless corridor longer than the laser's range: matching cannot see motion
// along it. The chain must say so and keep the odometry's along-track motion instead of sliding.
TEST(LaserOdometry, FeaturelessCorridorTakesAlongTrackMotionFromOdometry) {
  const sim::EntityRecording robot = CorridorRun("robot", 0.5, 20.0);
  const Replayed run = Replay(robot);
  long degenerate = 0;
  for (const auto& estimate : run.estimates) {
    degenerate += estimate.status == MatchStatus::kDegenerate ? 1 : 0;
  }
  EXPECT_GT(degenerate, static_cast<long>(run.estimates.size()) / 2);
  const geometry::Pose2& truth = robot.truth.back().world_from_body;
  const geometry::Pose2& end = run.estimates.back().world_from_body;
  EXPECT_NEAR(end.y_m, truth.y_m, 0.05);                 // across: the walls constrain it
  EXPECT_NEAR(end.theta_rad, truth.theta_rad, 0.5 * kDeg);
  // Along: the wheel odometry's few-percent error (it ends at 19.6 m of 19.9 m), no slide back
  // (the chain ended at 18.6 m when only 2 % eigenvalue ratios counted as degenerate).
  EXPECT_NEAR(end.x_m, truth.x_m, 0.05 * 20.0);
  EXPECT_GT(end.x_m, 15.0);
}

// RMS change from scan to scan of the along-track (x) error.
double AlongTrackJitterM(const sim::EntityRecording& entity, const Replayed& run) {
  double sum_m2 = 0.0;
  for (std::size_t i = 1; i < run.estimates.size(); ++i) {
    const double before = run.estimates[i - 1].world_from_body.x_m - entity.truth[i - 1].world_from_body.x_m;
    const double now = run.estimates[i].world_from_body.x_m - entity.truth[i].world_from_body.x_m;
    sum_m2 += (now - before) * (now - before);
  }
  return std::sqrt(sum_m2 / static_cast<double>(run.estimates.size() - 1));
}

// A person in a featureless corridor (its ends beyond the laser's range): along it the position is
// the dead reckoning's. The stride sensor reports each stride when it ends; moving the prior only
// then makes a saw tooth of up to a stride at 4 Hz scans, which carrying it forward at the last
// pace removes. Floor hits across the corridor move with the person and pull "matched" scans back
// towards the keyframe; degenerate_slide_ratio catches those.
TEST(LaserOdometry, PersonInACorridorHasNoStrideSawTooth) {
  const sim::EntityRecording person = CorridorRun("human", 1.0, 20.0);
  LaserOdometryOptions at_reports;
  at_reports.match_scans = false;  // the default: the position moves at stride reports only
  LaserOdometryOptions prior_only = at_reports;
  prior_only.dead_reckoning.stride_interpolation.enabled = false;
  prior_only.dead_reckoning.max_stride_period_s = 1.5;  // carried forward between reports
  const double carried_m = AlongTrackJitterM(person, Replay(person, prior_only));
  const double stepped_m = AlongTrackJitterM(person, Replay(person, at_reports));
  EXPECT_LT(carried_m, 0.5 * stepped_m) << "carried " << carried_m << " m, at reports " << stepped_m << " m";
  LaserOdometryOptions matched;
  matched.dead_reckoning.stride_interpolation.enabled = false;
  matched.dead_reckoning.max_stride_period_s = 1.5;
  LaserOdometryOptions slide = matched;
  slide.degenerate_slide_ratio = 0.2;  // on the raw stride stream the auto default is off
  slide.degenerate_slide_backward_only = false;  // both ways: the matches here slide both ways
  slide.degenerate_max_slide_m = 0.1;
  slide.degenerate_slide_max_across_m = 0.0;
  slide.degenerate_slide_prior_agreed_m = 0.0;
  const double matched_m = AlongTrackJitterM(person, Replay(person, matched));
  const double slide_m = AlongTrackJitterM(person, Replay(person, slide));
  EXPECT_LT(slide_m, 0.6 * matched_m) << "slide check " << slide_m << " m, without " << matched_m << " m";
  // Counting only the slides back against the direction of travel (degenerate_slide_backward_only)
  // keeps part of that: 0.15 m against 0.19 m without and 0.11 m both ways (the matches here are
  // pulled both ways).
  LaserOdometryOptions backward = slide;
  backward.degenerate_slide_backward_only = true;
  const double backward_m = AlongTrackJitterM(person, Replay(person, backward));
  EXPECT_LT(backward_m, 0.9 * matched_m) << "backward only " << backward_m << " m, without " << matched_m << " m";
  EXPECT_GT(backward_m, slide_m) << "backward only " << backward_m << " m, both ways " << slide_m << " m";
}

// The pace check (pace_check_*, on by default with spread strides): in a 60 m corridor whose only
// returns across it are the walker's own floor hits, matches slide back towards the keyframes;
// the walk's pace over the last 4 m holds them to the dead reckoning along the corridor. Which
// walks slide, and how far, is down to the draw: one walk can go either way (seed 1 is worse with
// the check since the simulated stride sensor reports the step that ends at a stop), so the test
// takes ten walks.
TEST(LaserOdometry, PaceCheckHoldsCorridorSlidesBack) {
  LaserOdometryOptions off;
  off.pace_check_tolerance = 0.0;
  double checked_sum_m = 0.0, unchecked_sum_m = 0.0;
  long held = 0;
  constexpr int kWalks = 10;
  for (std::uint64_t seed = 1; seed <= kWalks; ++seed) {
    const sim::EntityRecording person = CorridorRun("human", 1.0, 60.0, seed);
    const Replayed checked = Replay(person);
    const Replayed unchecked = Replay(person, off);
    auto along_rms_m = [&](const Replayed& run) {
      double sum_m2 = 0.0;
      for (std::size_t i = 0; i < run.estimates.size(); ++i) {
        const double e = run.estimates[i].world_from_body.x_m - person.truth[i].world_from_body.x_m;
        sum_m2 += e * e;
      }
      return std::sqrt(sum_m2 / static_cast<double>(run.estimates.size()));
    };
    EXPECT_EQ(unchecked.counts.pace_held, 0);
    held += checked.counts.pace_held;
    checked_sum_m += along_rms_m(checked);
    unchecked_sum_m += along_rms_m(unchecked);
  }
  EXPECT_GT(held, 0);
  EXPECT_LT(checked_sum_m, 0.95 * unchecked_sum_m)
      << "mean with " << checked_sum_m / kWalks << " m, without " << unchecked_sum_m / kWalks << " m";
  std::printf("[ figures  ] corridor along-track RMS, mean of %d walks: pace check %.3f m, without %.3f m (%ld held)\n",
              kWalks, checked_sum_m / kWalks, unchecked_sum_m / kWalks, held);
}

using testing::ExpectRefused;

TEST(LaserOdometry, RefusesAPaceCheckOutOfRangeNamingTheField) {
  LaserOdometryOptions options;
  options.pace_check_tolerance = 1.0;
  ExpectRefused(options, "pace_check_tolerance");
  options = {};
  options.pace_check_window_m = 0.0;
  ExpectRefused(options, "pace_check_window_m");
  options = {};
  options.pace_check_weak_ratio = -0.1;
  ExpectRefused(options, "pace_check_weak_ratio");
}

// The direction flag is a mode of the slide check: with the check off (ratio 0) it changes
// nothing, so turning the check off takes one setting.
TEST(LaserOdometry, BackwardOnlySlideIsAModeOfTheSlideCheck) {
  const sim::EntityRecording person = CorridorRun("human", 1.0, 20.0);
  LaserOdometryOptions off;
  off.degenerate_slide_ratio = 0.0;
  LaserOdometryOptions off_both_ways = off;
  off_both_ways.degenerate_slide_backward_only = false;
  const Replayed a = Replay(person, off);
  const Replayed b = Replay(person, off_both_ways);
  ASSERT_EQ(a.estimates.size(), b.estimates.size());
  for (std::size_t i = 0; i < a.estimates.size(); ++i) {
    EXPECT_EQ(a.estimates[i].world_from_body.x_m, b.estimates[i].world_from_body.x_m) << i;
  }
}

TEST(LaserOdometry, RefusesASlideCheckOutOfRangeNamingTheField) {
  LaserOdometryOptions options;
  options.degenerate_slide_ratio = -0.5;  // -1 is auto, other negatives are errors
  ExpectRefused(options, "degenerate_slide_ratio");
  options = {};
  options.degenerate_slide_max_across_m = -0.1;
  ExpectRefused(options, "degenerate_slide_max_across_m");
  options = {};
  options.degenerate_slide_prior_agreed_m = -0.1;
  ExpectRefused(options, "degenerate_slide_prior_agreed_m");
}

TEST(LaserOdometry, ScanGoingBackInTimeIsIgnored) {
  LaserOdometry odometry({}, sensors::EntityKind::kRobot, {}, 0.0);
  sensors::LaserScan scan;
  scan.geometry = {-std::numbers::pi / 2, std::numbers::pi / 360, 30.0};
  scan.ranges_m.assign(361, 3.0f);
  scan.stamp_s = 1.0;
  EXPECT_TRUE(odometry.Add(scan).has_value());
  scan.stamp_s = 0.5;
  EXPECT_FALSE(odometry.Add(scan).has_value());
  EXPECT_EQ(odometry.counts().records_ignored, 1);
}

// A person's dead reckoning starts at the start pose, and a first scan taken later is moved by
// what it measured since: here a 0.5 rad turn (1 rad/s from the start at 0 s to the first scan at
// 0.5 s). It was taken as no motion, and the odometry, which takes only increments after that,
// stayed 0.5 rad off for good (an unknown start waits for the compass, office seed 1 at 97.8 s:
// 31 deg). A scan at the start stamp is at the start pose.
TEST(LaserOdometry, ATurnBetweenTheStartAndTheFirstScanIsKept) {
  sensors::LaserScan scan;
  scan.geometry = {-std::numbers::pi / 2, std::numbers::pi / 360, 30.0};
  scan.ranges_m.assign(361, 3.0f);
  const geometry::Pose2 start{2.0, 1.0, 0.3};
  LaserOdometry later({}, sensors::EntityKind::kHuman, start, 10.0);
  for (int tick = 1; tick <= 50; ++tick) later.Add(sensors::GyroSample{10.0 + 0.01 * tick, 1.0});
  scan.stamp_s = 10.5;
  const auto turned = later.Add(scan);
  ASSERT_TRUE(turned.has_value());
  EXPECT_NEAR(turned->world_from_body.theta_rad, 0.8, 0.01);
  EXPECT_NEAR(turned->world_from_body.x_m, 2.0, 1e-9);  // no stride: no step
  LaserOdometry at_start({}, sensors::EntityKind::kHuman, start, 10.0);
  scan.stamp_s = 10.0;
  const auto first = at_start.Add(scan);
  ASSERT_TRUE(first.has_value());
  EXPECT_DOUBLE_EQ(first->world_from_body.theta_rad, 0.3);
  EXPECT_DOUBLE_EQ(first->world_from_body.x_m, 2.0);
}

TEST(LaserOdometry, InvalidOptionNamesField) {
  LaserOdometryOptions options;
  options.min_score = 1.5;
  try {
    LaserOdometry odometry(options, sensors::EntityKind::kHuman, {}, 0.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("laser_odometry.min_score"), std::string::npos);
  }
}

}  // namespace
}  // namespace pena::odometry
